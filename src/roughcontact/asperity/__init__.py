"""One asperity (sections 3, 5, 6 of Buczkowski & Kleiber 2009).

* :mod:`.ellipse` — complete elliptic integrals K, E (exact and the paper's polynomials),
  the curvature ratio λ ↔ eccentricity inversion, the Hertz factors f1 … f4 (Fig. 4);
* :mod:`.material` — E* (42), K_Y (63)–(64), Tabor's H (68), :class:`AsperityMaterial`;
* :mod:`.laws` — one elliptic asperity against a flat: Hertz, first yield, the ZMC/Jeng–Wang
  transition, the CEB/Horng plastic branch, the plasticity index (69), (74), (86)–(87).

The public names of :mod:`.material` and :mod:`.laws` are available here.
"""

from . import ellipse
from .laws import *  # noqa: F401,F403
from .laws import __all__ as _laws
from .material import *  # noqa: F401,F403
from .material import __all__ as _material

__all__ = ["ellipse", *_material, *_laws]
