"""Time the production presets of git revisions and of the working tree side by side (before/after).

    .venv/bin/python benchmarks/compare_revision.py --rev d6d5e4c --current [--rounds 3] [--repeat 5] \\
        [--references results/benchmarks/speed_vs_error/references.json] [--json out.json]

Each ``--rev`` is checked out into a temporary git worktree; ``--current`` is this tree's src/.
In a subprocess per tree (its src/ first on sys.path, its own numba cache) a probe times
elastic_contact and elastoplastic_contact (presets "table" and "plot", one separation per call,
median of --repeat after a warm-up call) at the points of speed_vs_error.py, the elastic batch
of 64 separations, and elasto-plastic curves of 200 separations (s = 0 … 4: one call; the
revisions since issue 13 build them from a verified interpolant in s). The trees are probed
in turn, --rounds times (A B A B …), and the median over rounds is reported, so a change of
the machine's load hits both alike; the ratio column is time(first tree)/time(each other).
Errors are against the references of that benchmark (its cache, else the committed seed
benchmarks/data/references.json); curves: the largest relative difference of A, W, K from the
first tree's curve.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import textwrap
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SEED = ROOT / "benchmarks" / "data" / "references.json"

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

    def timed(call, n_sep):
        c = call()
        ts = []
        for _ in range(repeat):
            t0 = time.perf_counter(); call(); ts.append((time.perf_counter() - t0) / n_sep)
        return c, statistics.median(ts)

    for p in points:
        surf = SpectralMoments(*p["moments"])
        s = np.asarray(p["s"], dtype=float)
        if p["model"] == "elastic":
            call = lambda acc: elastic_contact(surf, s, 1.0, accuracy=acc)
        else:
            mat = AsperityMaterial(1.14e5, yield_strength_for_plasticity_index(p["psi"], surf, 1.14e5))
            call = lambda acc: elastoplastic_contact(surf, s, mat, accuracy=acc)
        for acc in ("table", "plot"):
            c, sec = timed(lambda: call(acc), s.size)
            vals = np.array([c.area_fraction, c.pressure, c.stiffness], dtype=float)
            out["rows"].append({**{k: v for k, v in p.items() if k != "s"}, "s": p["s"] if s.size == 1 else
                                [float(s[0]), float(s[-1]), int(s.size)], "preset": acc, "seconds": sec,
                                "values": vals.tolist()})
    out["loadavg"] = os.getloadavg()
    print(json.dumps(out))
    """
)


def _points() -> list[dict]:
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from speed_vs_error import LOADS, PSI, SURFACES

    pts = []
    for name, loads in LOADS.items():
        moments = list(SURFACES[name].as_dict().values())
        for s in loads:
            pts.append({"model": "elastic", "surface": name, "moments": moments, "s": [s], "kind": "single"})
            pts.append({"model": "elastoplastic", "surface": name, "moments": moments, "s": [s], "psi": PSI,
                        "kind": "single"})
    t1 = list(SURFACES["table1"].as_dict().values())
    pts.append({"model": "elastic", "surface": "table1", "moments": t1, "s": [1.0] * 64, "kind": "batch of 64"})
    for psi in (PSI, 5.0):
        pts.append({"model": "elastoplastic", "surface": "table1", "moments": t1, "psi": psi,
                    "s": [float(x) for x in np.linspace(0.0, 4.0, 200)], "kind": "curve of 200"})
    return pts


def _reference(references: dict, r: dict):
    if r["kind"] != "single":
        return None
    key_surface = ",".join(repr(v) for v in r["moments"])
    s = r["s"][0]
    if r["model"] == "elastic":
        rec = references.get(f"elastic|{key_surface}|s={s!r}|exact|dps=20")
        return None if rec is None else rec["value"]
    for key, rec in references.items():
        if key.startswith(f"elastoplastic|{key_surface}|s={s!r}|psi={r['psi']!r}|exact|rtol=1e-10"):
            return rec["value"][:3]
    return None


def _probe(tree_src: Path, points: list[dict], repeat: int) -> dict:
    res = subprocess.run([sys.executable, "-c", PROBE, json.dumps(points), str(repeat)],
                         env={"PYTHONPATH": str(tree_src), "PATH": "/usr/bin:/bin"},
                         capture_output=True, text=True, check=True, timeout=7200)
    return json.loads(res.stdout.strip().splitlines()[-1])


def run(revs: list[str], current: bool, points: list[dict], repeat: int, rounds: int) -> dict:
    """{label: probe result with per-row median seconds over rounds}; labels in the given order."""
    with tempfile.TemporaryDirectory(prefix="rc-rev-") as tmp:
        trees = {}
        try:
            for rev in revs:
                tree = Path(tmp) / rev
                subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(tree), rev], check=True,
                               capture_output=True)
                trees[rev] = tree / "src"
            if current:
                trees["working tree"] = ROOT / "src"
            runs = {label: [] for label in trees}
            for k in range(rounds):
                for label, src in trees.items():
                    runs[label].append(_probe(src, points, repeat))
                    print(f"round {k + 1}/{rounds}: {label} done", file=sys.stderr, flush=True)
        finally:
            for rev in revs:
                subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(Path(tmp) / rev)],
                               check=False, capture_output=True)
    out = {}
    for label, probes in runs.items():
        merged = probes[0]
        for i, row in enumerate(merged["rows"]):
            row["seconds_rounds"] = [p["rows"][i]["seconds"] for p in probes]
            row["seconds"] = statistics.median(row["seconds_rounds"])
        merged["loadavg_rounds"] = [p["loadavg"] for p in probes]
        out[label] = merged
    return out


def markdown(out: dict, references: dict) -> str:
    labels = list(out)
    head = (["model", "point", "preset"] + [f"time per separation, {lb}" for lb in labels]
            + [f"ratio {labels[0]} / {lb}" for lb in labels[1:]] + [f"max error A, W, K, {lb}" for lb in labels])
    trees = ", ".join(f"{lb} ({out[lb]['module']})" for lb in labels)
    loads = "; ".join(f"{lb} {[round(x[0], 2) for x in out[lb]['loadavg_rounds']]}" for lb in labels)
    lines = [f"trees: {trees}; load averages per round: {loads}", "",
             "| " + " | ".join(head) + " |", "|" + " --- |" * len(head)]
    first = out[labels[0]]["rows"]
    for i, r in enumerate(first):
        rows = [out[lb]["rows"][i] for lb in labels]
        ref = _reference(references, r)
        errs = []
        for row in rows:
            v = np.asarray(row["values"], dtype=float)
            if ref is not None:
                e = float(np.max(np.abs(v[:, 0] / np.asarray(ref) - 1.0)))
                errs.append(f"{e:.1e}")
            elif r["kind"] == "curve of 200":
                e = float(np.max(np.abs(v / np.asarray(r["values"]) - 1.0)))
                errs.append(f"{e:.1e} (vs {labels[0]})")
            else:
                errs.append("–")
            row["error"] = errs[-1]
        point = f"{r['surface']} " + (f"s={r['s'][0]}" if r["kind"] == "single" else
                                      f"s={r['s'][0]:g}…{r['s'][1]:g} ({r['kind']})")
        if r["model"] == "elastoplastic":
            point += f", ψ={r['psi']:g}"
        times = [f"{row['seconds'] * 1e3:.3f} ms" for row in rows]
        ratios = [f"{rows[0]['seconds'] / row['seconds']:.2f}" for row in rows[1:]]
        lines.append("| " + " | ".join([r["model"], point, r["preset"], *times, *ratios, *errs]) + " |")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rev", action="append", default=[], help="a git revision (repeatable)")
    ap.add_argument("--current", action="store_true", help="also the working tree (after the revisions)")
    ap.add_argument("--references", default="results/benchmarks/speed_vs_error/references.json")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--json")
    args = ap.parse_args(argv)
    if not args.rev and not args.current:
        ap.error("give --rev and/or --current")
    ref_path = Path(args.references)
    references = json.loads((ref_path if ref_path.exists() else SEED).read_text())
    out = run(args.rev, args.current, _points(), args.repeat, args.rounds)
    text = markdown(out, references)
    print(text)
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps({"trees": out, "markdown": text}, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
