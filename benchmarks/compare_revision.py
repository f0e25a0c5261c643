"""Time the production presets of another git revision on the benchmark points (before/after).

    .venv/bin/python benchmarks/compare_revision.py --rev 5c28df8 \\
        [--references results/benchmarks/speed_vs_error/references.json] [--json out.json]

Checks the revision out into a temporary git worktree, and in a subprocess with that tree's
src/ first on sys.path (its own numba cache) times elastic_contact and elastoplastic_contact
(presets "table" and "plot", one separation per call, median of --repeat after a warm-up call)
at the points of speed_vs_error.py; errors against the cached references of that benchmark
(run it first). Prints a markdown table and optionally writes JSON.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

PROBE = textwrap.dedent(
    """
    import json, sys, time, statistics, os
    import numpy as np
    from roughcontact import SpectralMoments
    from roughcontact.contact import elastic_contact
    try:  # the package layout since issue 9; older revisions have a flat module
        from roughcontact.contact import elastoplastic_contact
    except ImportError:
        from roughcontact.contact.elastoplastic import elastoplastic_contact
    from roughcontact.asperity import AsperityMaterial, yield_strength_for_plasticity_index
    import roughcontact
    points = json.loads(sys.argv[1]); repeat = int(sys.argv[2])
    out = {"module": roughcontact.__file__, "rows": []}
    for p in points:
        surf = SpectralMoments(*p["moments"])
        if p["model"] == "elastic":
            call = lambda acc: elastic_contact(surf, [p["s"]], 1.0, accuracy=acc)
        else:
            mat = AsperityMaterial(1.14e5, yield_strength_for_plasticity_index(p["psi"], surf, 1.14e5))
            call = lambda acc: elastoplastic_contact(surf, [p["s"]], mat, accuracy=acc)
        for acc in ("table", "plot"):
            c = call(acc)
            ts = []
            for _ in range(repeat):
                t0 = time.perf_counter(); call(acc); ts.append(time.perf_counter() - t0)
            out["rows"].append({**p, "preset": acc, "seconds": statistics.median(ts),
                                "values": [float(c.area_fraction[0]), float(c.pressure[0]), float(c.stiffness[0])]})
    out["loadavg"] = os.getloadavg()
    print(json.dumps(out))
    """
)


def _points(references: dict) -> list[dict]:
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from speed_vs_error import LOADS, PSI, SURFACES

    pts = []
    for name, loads in LOADS.items():
        moments = list(SURFACES[name].as_dict().values())
        for s in loads:
            pts.append({"model": "elastic", "surface": name, "moments": moments, "s": s})
            pts.append({"model": "elastoplastic", "surface": name, "moments": moments, "s": s, "psi": PSI})
    return pts


def _reference(references: dict, p: dict):
    key_surface = ",".join(repr(v) for v in p["moments"])
    if p["model"] == "elastic":
        rec = references.get(f"elastic|{key_surface}|s={p['s']!r}|exact|dps=20")
        return None if rec is None else rec["value"]
    for key, rec in references.items():
        if key.startswith(f"elastoplastic|{key_surface}|s={p['s']!r}|psi={p['psi']!r}|exact|rtol=1e-10"):
            return rec["value"][:3]
    return None


def run_revision(rev: str, points: list[dict], repeat: int) -> dict:
    with tempfile.TemporaryDirectory(prefix="rc-rev-") as tmp:
        tree = Path(tmp) / "tree"
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(tree), rev], check=True,
                       capture_output=True)
        try:
            res = subprocess.run([sys.executable, "-c", PROBE, json.dumps(points), str(repeat)],
                                 env={"PYTHONPATH": str(tree / "src"), "PATH": "/usr/bin:/bin"},
                                 capture_output=True, text=True, check=True, timeout=7200)
        finally:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(tree)], check=False,
                           capture_output=True)
    return json.loads(res.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rev", required=True)
    ap.add_argument("--references", default="results/benchmarks/speed_vs_error/references.json")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--json")
    args = ap.parse_args(argv)
    references = json.loads(Path(args.references).read_text())
    points = _points(references)
    out = run_revision(args.rev, points, args.repeat)
    lines = [f"revision {args.rev} ({out['module']}), load {out['loadavg']}", "",
             "| model | point | preset | time per separation | error A | error W | error K |",
             "| --- | --- | --- | --- | --- | --- | --- |"]
    for r in out["rows"]:
        ref = _reference(references, r)
        errs = ["–"] * 3 if ref is None else [f"{abs(v / x - 1):.1e}" for v, x in zip(r["values"], ref)]
        r["errors"] = None if ref is None else [abs(v / x - 1) for v, x in zip(r["values"], ref)]
        lines.append(f"| {r['model']} | {r['surface']} s={r['s']} | {r['preset']} | {r['seconds'] * 1e3:.2f} ms | "
                     + " | ".join(errs) + " |")
    print("\n".join(lines))
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
