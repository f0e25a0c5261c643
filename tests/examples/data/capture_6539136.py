"""How tests/examples/data/reference_6539136.json was made: example 9.1 and 9.2 runs of the
engine as it was at commit 6539136 (before the beam and the punch became input decks), stored
as references for tests/examples/test_reference_runs.py (the same runs through the deck reader
must give these numbers to 1e-9).

Run against that commit's source, e.g.

    git archive 6539136 src | tar -x -C /tmp/base
    PYTHONPATH=/tmp/base/src .venv/bin/python tests/examples/data/capture_6539136.py

It imports the modules fe/beam.py and fe/punch.py of that commit, which no longer exist after that commit: this file
is provenance, not a test (pytest does not collect it).
"""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np

import roughcontact
from roughcontact.fe.beam import beam_case
from roughcontact.fe.punch import _history, dissipation, frictionless_bound, mu_max, punch_case

SURFACE = {"m20": 8e-5, "m02": 8e-4, "m40": 1.04e-6, "m04": 1.04e-4}
E_STAR = 1.1274666666666667e5
COARSE_BEAM = {"n_x": 6, "n_z": 2, "z_ratio": 4.0, "increments": 16, "load": 1962.0, "initial_load": 4.9}
COARSE_PUNCH = {"n_punch": 2, "n_outer": 2, "n_depth": 2}


def beam(family, m00, law="elastic", tangential="free", mu=None, spec=None, **extra):
    run = {"family": family, "case": "-", "m00": m00, "law": law, "psi": 0.35, "E_star": E_STAR,
           "tangential": tangential, "mu": mu, "surface": SURFACE, "spec": {**COARSE_BEAM, **(spec or {})}, **extra}
    r = beam_case(run)
    f = r.solution.point_fields(-1, reference=0)
    pts = r.solution.model.points
    return {"kind": "beam", "run": run,
            "x_mm": r.x_mm.tolist(), "u_N_um": r.u_N_um.tolist(), "p_N": r.p_N.tolist(),
            "open_x_mm": r.open_x_mm.tolist(), "loads": r.loads.tolist(),
            "newton_iterations": r.newton_iterations.tolist(), "equilibrium_error": r.equilibrium_error,
            "dofs": r.n_dofs, "interface_points": r.n_points,
            "point_x": pts.x[:, 0].tolist(), "point_y": pts.x[:, 1].tolist(),
            "point_u_N_um": (-f["closure_mm"] * 1000.0).tolist(), "point_p_N": f["p_N"].tolist(),
            "point_t_x": f["traction"][:, 0].tolist(), "point_t_y": f["traction"][:, 1].tolist(),
            "point_status": f["status"].tolist()}


def punch(case, family="quadratic", law="elastic", geometry=None, keep=None, **spec):
    """``keep``: the load levels whose per-point history is stored (None: every level)."""
    run = {"case": case, "m00": 0.625, "surface": SURFACE, "law": law, "psi": 0.35,
           "geometry": {"family": family, **COARSE_PUNCH, **(geometry or {})}, **spec}
    r = punch_case(run)
    h = _history(r)
    kept = list(range(len(r.solution.increments))) if keep is None else [k % len(r.solution.increments) for k in keep]
    h = {k: np.asarray(v)[kept] for k, v in h.items()}
    out = {"kind": "punch", "run": run, "x": r.solution.model.points.x[:, 0].tolist(),
           "y": r.solution.model.points.x[:, 1].tolist(), "weights": r.solution.model.points.weights.tolist(),
           "levels": [float(i.level) for i in r.solution.increments], "kept_levels": kept,
           "newton_iterations": [int(i.iterations) for i in r.solution.increments],
           "dofs": r.n_dofs, "interface_points": r.n_points,
           **{k: np.asarray(v).tolist() for k, v in h.items()}}
    if case != "frictionless":
        free = punch_case({**run, "case": "frictionless"})
        out["D"] = {f"{at}_{w}": dissipation(r, at=at, weight=w) for at in ("max", "end") for w in ("area", "none", "work")}
        out["bound"] = frictionless_bound(r, free, mu_max(case))
    return out


CASES = {
    "beam-quadratic-1-free": lambda: beam("quadratic", 0.625),
    "beam-cubic-4-elastoplastic": lambda: beam("cubic", 0.625, law="elastoplastic"),
    "beam-quadratic-2-coulomb": lambda: beam("quadratic", 0.3125, tangential="coulomb", mu=0.1),
    "beam-quadratic-3-stick-patch": lambda: beam("quadratic", 0.0625, tangential="stick",
                                                 spec={"load_patch": 50.0, "x_ratio": 0.5, "increments": 4}),
    "beam-quadratic-6-printed-Y": lambda: beam("quadratic", 0.0625, law="elastoplastic", Y=2070.0),
    "punch-quadratic-b-quarter": lambda: punch("b", load=1000.0, load_on="quarter", seating_pressure=0.1,
                                               increments=4, unload_increments=4),
    "punch-cubic-c-secant": lambda: punch("c", family="cubic", law="elastoplastic", load=1000.0, load_on="whole",
                                          seating_pressure=0.1, increments=3, unload_increments=2,
                                          tangential_form="secant"),
    "punch-quadratic-a-patch-start": lambda: punch("a", geometry={"load_patch": 10.0}, load=2000.0, load_on="quarter",
                                                   seating_pressure=0.01, increments=3, unload_increments=3,
                                                   tangential_form="incremental-start"),
    "beam-quadratic-1-main": lambda: beam("quadratic", 0.625, spec={"n_x": 25, "n_z": 6}),
    "punch-quadratic-b-main": lambda: punch("b", law="elastoplastic", geometry={"n_punch": 4, "n_outer": 4, "n_depth": 4},
                                            load=1000.0, load_on="whole", seating_pressure=0.1, increments=16,
                                            unload_increments=16, keep=[0, 16, -1]),
}

if __name__ == "__main__":
    src = Path(roughcontact.__file__).resolve().parents[2]
    commit = subprocess.run(["git", "-C", str(Path(__file__).parent), "rev-parse", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    data = {"provenance": {"commit": "6539136", "roughcontact_source": str(src), "python": sys.version.split()[0],
                           "numpy": np.__version__, "written_from_checkout_at": commit,
                           "script": "tests/examples/data/capture_6539136.py"},
            "runs": {}}
    for name, make in CASES.items():
        print(name, flush=True)
        data["runs"][name] = make()
    out = Path(__file__).with_name("reference_6539136.json")
    out.write_text(json.dumps(data, indent=None, separators=(",", ":")) + "\n")
    print("wrote", out, out.stat().st_size, "bytes")
