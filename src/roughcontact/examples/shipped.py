"""The decks and law files shipped in ``roughcontact/examples/decks/``, written by the examples'
own generators (tests/examples check that the files equal them; after changing a generator,
``python -m roughcontact.examples.shipped`` rewrites them).

* ``beam.inp``: example 9.1 with the paper's defaults (the main mesh, 25 × 6 elements);
  ``beam-case1.yaml`` … ``beam-case6.yaml``: the laws of Table 4's rows (free sliding);
* ``punch.inp``: example 9.2 on the mesh of Fig. 18 (4 × 4 elements across the quarter punch:
  81 contact points with ``--elements quadratic``), ``punch-fig19.inp`` on that of Fig. 19
  (3 × 3: 100 points with ``--elements cubic``); ``punch-a.yaml``, ``punch-b.yaml``,
  ``punch-c.yaml``: Fig. 18's friction cases, ``punch-frictionless.yaml`` the bound's problem.
"""

from __future__ import annotations

from pathlib import Path

from . import beam, punch
from .punch_geometry import PunchGeometry
from .section9 import BEAM_E_STAR, PUNCH_PSI, TABLE4_M00

__all__ = ["DECKS", "shipped_files", "write"]

#: the folder of the shipped files
DECKS = Path(__file__).with_name("decks")


def shipped_files() -> dict[str, str]:
    """{file name: text} of every shipped deck and law file."""
    out = {"beam.inp": beam.beam_deck(beam.BeamSpec())}
    for case, m00 in TABLE4_M00.items():
        law = "elastic" if int(case) <= 3 else "elastoplastic"
        run = beam.BeamRun(m00=m00, law=law, psi=PUNCH_PSI if law == "elastoplastic" else None, E_star=BEAM_E_STAR,
                           case=case)
        out[f"beam-case{case}.yaml"] = (f"# example 9.1, Table 4 case {case}: m00 = {m00} um^2, {law} law, free sliding "
                                        f"(roughcontact fe run beam.inp --interface beam-case{case}.yaml)\n"
                                        + run.law_file().to_yaml())
    out["punch.inp"] = punch.punch_deck(punch.PunchSpec())
    out["punch-fig19.inp"] = punch.punch_deck(punch.PunchSpec(geometry=PunchGeometry(family="cubic")))
    for case in punch.CASES:
        what = "the frictionless problem of the bound" if case == "frictionless" else f"Fig. 18 case ({case})"
        out[f"punch-{case}.yaml"] = (f"# example 9.2, {what} (roughcontact fe run punch.inp --interface punch-{case}.yaml)\n"
                                     + punch.PunchRun(case=case).law_file().to_yaml())
    return out


def write(folder: Path = DECKS) -> list[Path]:
    """Write every shipped file into ``folder``."""
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for name, text in shipped_files().items():
        (folder / name).write_text(text)
        paths.append(folder / name)
    return paths


if __name__ == "__main__":
    for path in write():
        print(path)
