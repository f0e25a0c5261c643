"""Can concurrent processes (Snakemake jobs) corrupt numba's on-disk cache or race on it?

    .venv/bin/python benchmarks/numba_cache_experiment.py [--procs 4] [--rounds 3] [--json out.json]

Each round starts ``--procs`` processes at the same moment on one EMPTY cache directory
(NUMBA_CACHE_DIR), as a Snakemake run on a fresh checkout does: each imports roughcontact and
calls the elastic and elasto-plastic integrators (every production kernel, serial and
threaded) at its own separations. Then one more process runs on the now-populated cache. It
records per process the time of the first calls (compile or cache load) and of repeated calls,
and checks:

* every process's numbers equal, bit for bit, those of a process with a private cache;
* the cache directory holds one index (.nbi) per kernel, each index with exactly one entry
  (one signature), every data file it names exists, and no temporary file is left behind;
* the last process compiled nothing (its first call is a cache load).

Why this is expected to hold (numba 0.68, numba/core/caching.py): index and data files are
written to a temporary name and os.replace'd into place (atomic on POSIX); the index records a
content hash of the defining source file; the index key is (signature, target CPU, bytecode
hash). Concurrent writers of the SAME key write equivalent data, so the last rename wins
harmlessly. What would not be safe is two processes adding DIFFERENT keys to one index at the
same time: each reads the index, picks the first free data-file number and rewrites the
index, so one entry can be lost (a recompile) or, worse, two keys can be given the same data
file name and one key's index entry end up naming the other key's code. Hence the rules in
docs/performance.md: one signature per kernel (no read-only arrays, C-contiguous float64 and
int64 only; tests/integrals/test_kernels.py checks it), and no kernel calls a kernel of another file
(the cache is invalidated per defining file only).
"""

from __future__ import annotations

import argparse
import json
import os
import pickle
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

WORKER = textwrap.dedent(
    """
    import hashlib, json, sys, time
    start = float(sys.argv[1]); offset = float(sys.argv[2])
    while time.time() < start:
        time.sleep(0.001)
    t0 = time.perf_counter()
    import numpy as np
    from roughcontact import SpectralMoments
    from roughcontact.contact import elastic_contact
    from roughcontact.contact import elastoplastic_contact
    from roughcontact.asperity import AsperityMaterial, yield_strength_for_plasticity_index
    import roughcontact.integrals.kernels as Q
    t_import = time.perf_counter() - t0
    surf = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
    mat = AsperityMaterial(1.14e5, yield_strength_for_plasticity_index(1.0, surf, 1.14e5))
    s1 = np.array([1.0 + offset]); s16 = np.linspace(0.0, 3.0, 16) + offset
    times = {}
    digest = hashlib.sha256()
    for name, fn in (("elastic_1", lambda: elastic_contact(surf, s1, 1.14e5)),
                     ("elastic_16", lambda: elastic_contact(surf, s16, 1.14e5)),
                     ("ep_1", lambda: elastoplastic_contact(surf, s1, mat, accuracy="plot")),
                     ("ep_16", lambda: elastoplastic_contact(surf, s16, mat, accuracy="plot"))):
        t0 = time.perf_counter(); c = fn(); times[name + "_first"] = time.perf_counter() - t0
        t0 = time.perf_counter(); c = fn(); times[name + "_again"] = time.perf_counter() - t0
        for q in ("area_fraction", "pressure", "stiffness"):
            digest.update(np.ascontiguousarray(getattr(c, q)).tobytes())
    sigs = {k: len(v.signatures) for k, v in vars(Q).items() if hasattr(v, "signatures") and v.signatures}
    print(json.dumps({"import": t_import, "times": times, "digest": digest.hexdigest(), "signatures": sigs}))
    """
)


def _launch(n: int, cache_dir: str, offsets) -> list[dict]:
    start = time.time() + 2.0
    env = dict(os.environ, NUMBA_CACHE_DIR=cache_dir)
    procs = [subprocess.Popen([sys.executable, "-c", WORKER, repr(start), repr(off)], env=env,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for off in offsets[:n]]
    out = []
    for p in procs:
        stdout, stderr = p.communicate(timeout=3600)
        if p.returncode:
            raise RuntimeError(stderr)
        out.append(json.loads(stdout.strip().splitlines()[-1]))
    return out


def _inspect(cache_dir: Path) -> dict:
    """Index files, their entries, missing data files, leftover temporaries."""
    indexes = list(cache_dir.rglob("*.nbi"))
    entries, missing = {}, []
    for idx in indexes:
        with open(idx, "rb") as fh:
            pickle.load(fh)  # numba version
            _stamp, overloads = pickle.loads(fh.read())
        entries[idx.name] = len(overloads)
        for data_name in overloads.values():
            if not (idx.parent / data_name).exists():
                missing.append(data_name)
    return {
        "index_files": len(indexes),
        "data_files": len(list(cache_dir.rglob("*.nbc"))),
        "indexes_with_more_than_one_entry": {k: v for k, v in entries.items() if v != 1},
        "missing_data_files": missing,
        "leftover_temporaries": [p.name for p in cache_dir.rglob("*.tmp.*")],
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--procs", type=int, default=4)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--json", help="write the record here")
    args = ap.parse_args(argv)
    offsets = [0.0, 0.001, 0.002, 0.003, 0.004, 0.005, 0.006, 0.007]
    rounds = []
    for r in range(args.rounds):
        with tempfile.TemporaryDirectory(prefix="numba-race-") as shared, \
                tempfile.TemporaryDirectory(prefix="numba-private-") as private:
            t0 = time.time()
            concurrent = _launch(args.procs, shared, offsets)
            wall = time.time() - t0
            after = _launch(1, shared, offsets)[0]
            private_runs = [_launch(1, private, [off])[0] for off in offsets[:args.procs]]
            state = _inspect(Path(shared))
        identical = all(c["digest"] == p["digest"] for c, p in zip(concurrent, private_runs))
        rounds.append({
            "round": r,
            "concurrent_wall_seconds": wall,
            "first_call_seconds": [sum(v for k, v in c["times"].items() if k.endswith("_first")) for c in concurrent],
            "warm_cache_first_call_seconds": sum(v for k, v in after["times"].items() if k.endswith("_first")),
            "repeat_call_seconds": sum(v for k, v in after["times"].items() if k.endswith("_again")),
            "results_identical_to_private_cache": identical,
            "warm_process_identical": after["digest"] == private_runs[0]["digest"],
            "signatures_per_kernel": sorted(set(after["signatures"].values())),
            "cache": state,
        })
        print(json.dumps(rounds[-1], indent=1), flush=True)
    ok = all(r["results_identical_to_private_cache"] and r["warm_process_identical"]
             and not r["cache"]["missing_data_files"] and not r["cache"]["leftover_temporaries"]
             and not r["cache"]["indexes_with_more_than_one_entry"] for r in rounds)
    record = {"procs": args.procs, "rounds": rounds, "ok": ok,
              "numba": __import__("numba").__version__, "loadavg": os.getloadavg()}
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(record, indent=1))
    print("OK" if ok else "PROBLEM", flush=True)
    return 0 if ok else 1


if __name__ == "__main__":
    raise SystemExit(main())
