"""The statistical model against a deterministic boundary-element solution on the same
surfaces (issue 21; docs/bem.md).

* :mod:`.surfaces` — periodic Gaussian maps with exactly five prescribed moments;
* :mod:`.solver` — load-controlled elastic contact with a rigid flat (ContactMechanics, the
  optional extra ``[bem]``; :data:`~.solver.SKIP_MESSAGE` where it is missing);
* :mod:`.checks` — the solver on Hertz and Westergaard closed forms;
* :mod:`.compare` — the model at the same loads, seed statistics, where the model holds.

Summit statistics of the maps are in :mod:`roughcontact.statistics.summits`.
"""

from .solver import SKIP_MESSAGE, BEMConvergenceError, BEMNotInstalled, SolverSettings, available
from .surfaces import BandLimitedSurface

__all__ = ["SKIP_MESSAGE", "BEMConvergenceError", "BEMNotInstalled", "SolverSettings", "available",
           "BandLimitedSurface"]
