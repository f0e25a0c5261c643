"""How tests/examples/data/ep_tables_6539136.json was made: the tabulated elasto-plastic normal
laws (NormalLawTable: nodes h and q, q', q'' there) that the elasto-plastic runs of
capture_6539136.py built at commit 6539136. Issue 24 changed how that law is integrated (its
τ = r t integrals), so today's tables of the same laws differ from these by up to 7.3e-10
relative; tests/examples/test_reference_runs.py gives the engine these tables to compare its
runs with 6539136's at the issue's 1e-9.

Run against that commit's source, as capture_6539136.py:

    git archive 6539136 src | tar -x -C /tmp/base
    PYTHONPATH=/tmp/base/src .venv/bin/python tests/examples/data/capture_6539136_ep_tables.py

Every run stops as soon as its first table is built (the solve is not needed); a run that builds
more than one elasto-plastic table (the punch's frictionless twin) shares it (one law). Provenance,
not a test (pytest does not collect it).
"""

import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))

import capture_6539136 as capture  # noqa: E402
from roughcontact.interface import NormalLawTable  # noqa: E402

EP_RUNS = ("beam-cubic-4-elastoplastic", "beam-quadratic-6-printed-Y", "punch-cubic-c-secant", "punch-quadratic-b-main")


class _Built(Exception):
    """Raised by the wrapped build: the table is recorded, the run is not needed."""


def record(table, pressure_range) -> dict:
    m = table.surface
    return {"moments": [m.m00, m.m20, m.m02, m.m40, m.m04], "E_star": table.material.E_star,
            "Y": table.material.Y, "pressure_range": list(pressure_range), "hertz": table.hertz,
            "accuracy": table.accuracy, "rtol": table.rtol,
            "max_error_pressure": table.max_error_pressure, "max_error_stiffness": table.max_error_stiffness,
            "n_evaluations": table.n_evaluations,
            **{k: getattr(table, k).tolist() for k in ("h", "q", "dq", "d2q")}}


if __name__ == "__main__":
    build = NormalLawTable.build.__func__
    tables = {}

    def wrapped(cls, surface, level, **kw):
        table = build(cls, surface, level, **kw)
        if level == "elastoplastic":
            tables[current] = record(table, kw["pressure_range"])
            raise _Built
        return table

    NormalLawTable.build = classmethod(wrapped)
    for current in EP_RUNS:
        print(current, flush=True)
        try:
            capture.CASES[current]()
        except _Built:
            pass
    data = {"provenance": {"commit": "6539136", "roughcontact_source": str(Path(capture.roughcontact.__file__).parents[1]),
                           "python": sys.version.split()[0], "numpy": np.__version__,
                           "script": "tests/examples/data/capture_6539136_ep_tables.py"},
            "tables": tables}
    out = Path(__file__).with_name("ep_tables_6539136.json")
    out.write_text(json.dumps(data, indent=None, separators=(",", ":")) + "\n")
    print("wrote", out, out.stat().st_size, "bytes")
