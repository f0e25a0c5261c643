"""The zero-thickness interface law of section 8 (Buczkowski & Kleiber 2009), what an FE
engine evaluates at every interface point.

* :mod:`.normal_law` — :class:`NormalLawTable` (p_N, k_N of the elastic (53)/(55)/(95) or
  elasto-plastic (82) statistical model, tabulated once) and :class:`InterfaceLaw` (that law
  at a reference state, with k_T = a·k_N);
* :mod:`.tangential` — Mindlin's k_N/k_T for elliptical contacts, (96)/Table 3;
* :mod:`.friction` — orthotropic (8.1) and isotropic (8.2) hardening friction: the implicit
  return mapping and its consistent tangent, the owner of the sign convention of u_N;
* :mod:`.export` — the normal law as a pressure–overclosure table for Abaqus / CalculiX / CSV;
* :mod:`.kernels` — their numba kernels; :mod:`.reference` — the slow twins.
"""

from . import friction, tangential
from .normal_law import InterfaceLaw, NormalLawTable, mindlin_kT_over_kN
from .tangential import kn_over_kt

__all__ = ["friction", "tangential", "InterfaceLaw", "NormalLawTable", "mindlin_kT_over_kN", "kn_over_kt"]
