"""The geometry of example 9.2 (Buczkowski & Kleiber 2009): an elastic flat punch on an elastic
foundation (Figs 14, 15; contact points of Figs 18, 19), and its input deck.

A punch 20 × 20 × 10 mm stands on a foundation 100 × 100 × 50 mm. By symmetry a quarter is
meshed: punch x, y ∈ [0, 10], z ∈ [0, 10]; foundation x, y ∈ [0, 50], z ∈ [−50, 0]; the
contact plane is z = 0 and the symmetry planes are x = 0 and y = 0. Choices (the paper gives
only the element types and the contact-point counts):

* C3D20 elements; the deck reader turns the contact layers into transition elements: HEX21
  and 18-node interface elements ("quadratic"), HEX28 and 32-node ones ("cubic"). The
  foundation's contact surface is its whole top face (a HEX28 does not conform with a HEX20
  beside it); the interface covers the punch's face only (master = foundation, normal +z);
* ``n_punch`` elements across the quarter punch: 4 quadratic (9 × 9 = 81 interface nodes, the
  contact points of Fig. 18 under nodal integration) or 3 cubic (10 × 10 = 100, Fig. 19). The
  foundation's x/y grid under the punch IS the punch's grid (a node-matching interface);
* the foundation's elements grow geometrically away from the punch: outward over x, y
  (``n_outer``) and downward over the depth (``n_depth``). A ratio (size far away / size at the
  punch) of None makes the first element as large as the punch's element next to it (its
  outermost x/y element; its bottom layer for the depth), or uniform if that is already larger;
* the load: "a uniform load on one 20-noded element in the middle of the punch". Reading:
  ``load_patch`` [mm] is the side of a centred square on the WHOLE punch's top face, so the
  quarter carries [0, load_patch/2]²; by default it is the quarter's corner element (side
  10/n_punch), i.e. on the whole punch the 2 × 2 elements around the centre: 5 mm (quadratic),
  2 × 10/3 mm (cubic). A patch edge off the uniform grid gets an element edge inserted there:
  the punch keeps n_punch elements across (so the contact-point count does not change), spread
  as evenly as possible on either side of load_patch/2, hence unequal sizes.

Names in the deck (:func:`roughcontact.examples.punch.punch_deck`): elsets FOUNDATION, PUNCH,
PUNCHTOP, LOADPATCH; node sets :data:`SYMMETRY_X` (u_x = 0), :data:`SYMMETRY_Y` (u_y = 0),
:data:`BASE` (u_z = 0); surfaces FOUNDATIONTOP (master), PUNCHBOTTOM (slave). Lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..fe.mesh import graded
from ..validation import choice, positive
from .section9 import PUNCH
from ..limits import describe

__all__ = ["PunchGeometry", "SYMMETRY_X", "SYMMETRY_Y", "BASE", "FAMILIES", "figure_annotations"]

FAMILIES = ("quadratic", "cubic")
#: elements across the quarter punch giving the paper's 81 / 100 contact points
DEFAULT_N_PUNCH = {"quadratic": 4, "cubic": 3}
SYMMETRY_X = "XSYMMETRY"
SYMMETRY_Y = "YSYMMETRY"
BASE = "BASE"
_ON_GRID = 1e-9  # relative tolerance [–] for "load_patch/2 is already an element edge"


def _count(name: str, value) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise ValueError(f"{name} must be an integer >= 1, got {describe(value)}")
    return int(value)


def _first_size_ratio(length: float, n: int, first: float) -> float:
    """graded's ratio (last/first size) of n elements over ``length`` [mm] whose first is
    ``first`` [mm]; 1 (uniform) when n elements of that size already fill the length."""
    if n == 1 or n * first >= length:
        return 1.0
    # first·(1 + q + … + q^(n−1)) = length has one root q > 1 (the sum grows with q), found by
    # bisection in plain floats: the eigenvalues of np.roots come from LAPACK, whose last bits
    # differ between BLAS builds and processors, and moved the shipped decks' nodes by ulps
    def excess(q: float) -> float:
        total = 0.0
        for _ in range(n):  # Horner: 1 + q(1 + q(…))
            total = total * q + 1.0
        return first * total - length

    lo, hi = 1.0, length / first  # excess(1) = n·first − length < 0 <= excess(length/first)
    while True:
        mid = 0.5 * (lo + hi)
        if not lo < mid < hi:
            break
        lo, hi = (mid, hi) if excess(mid) < 0.0 else (lo, mid)
    return hi ** (n - 1)


@dataclass(frozen=True)
class PunchGeometry:
    """Quarter model of the punch on the foundation: sizes [mm], element family and counts, the
    loaded patch [mm, side on the whole punch]. None fields take the defaults of the module
    docstring at construction (so a built geometry states every number it meshes)."""

    punch_half_width: float = PUNCH["punch_width"] / 2.0
    punch_height: float = PUNCH["punch_height"]
    foundation_half_width: float = PUNCH["foundation_width"] / 2.0
    foundation_depth: float = PUNCH["foundation_depth"]
    family: str = "quadratic"
    n_punch: int | None = None
    n_punch_z: int | None = None
    n_outer: int = 4
    outer_ratio: float | None = None
    n_depth: int = 4
    depth_ratio: float | None = None
    load_patch: float | None = None

    def __post_init__(self):
        for name in ("punch_half_width", "punch_height", "foundation_half_width", "foundation_depth"):
            object.__setattr__(self, name, positive(name, getattr(self, name)))
        choice("family", self.family, FAMILIES)
        if self.foundation_half_width <= self.punch_half_width:
            raise ValueError("foundation_half_width must exceed punch_half_width")
        n_punch = DEFAULT_N_PUNCH[self.family] if self.n_punch is None else _count("n_punch", self.n_punch)
        object.__setattr__(self, "n_punch", n_punch)
        n_z = n_punch if self.n_punch_z is None else _count("n_punch_z", self.n_punch_z)
        object.__setattr__(self, "n_punch_z", n_z)
        for name in ("n_outer", "n_depth"):
            _count(name, getattr(self, name))
        for name, n in (("outer_ratio", self.n_outer), ("depth_ratio", self.n_depth)):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, positive(name, getattr(self, name)))
                if n == 1 and getattr(self, name) != 1.0:
                    raise ValueError(f"{name} needs at least two elements to grade over")
        if self.load_patch is None:
            object.__setattr__(self, "load_patch", 2.0 * self.punch_half_width / n_punch)
        patch = positive("load_patch", self.load_patch)
        object.__setattr__(self, "load_patch", patch)
        if patch > 2.0 * self.punch_half_width * (1 + _ON_GRID):
            raise ValueError(f"load_patch {describe(patch)} mm is wider than the punch")
        if n_punch == 1 and not self._patch_on_uniform_grid():
            raise ValueError("load_patch must cover the whole punch when n_punch = 1 (no edge to insert)")

    @property
    def load_half(self) -> float:
        """Half side of the loaded patch [mm]: the quarter carries [0, load_half]²."""
        return min(self.load_patch / 2.0, self.punch_half_width)

    def _patch_on_uniform_grid(self) -> bool:
        k = self.load_half / (self.punch_half_width / self.n_punch)
        return abs(k - round(k)) < _ON_GRID * self.n_punch and round(k) >= 1

    def punch_edges(self) -> np.ndarray:
        """x (= y) element edges of the quarter punch [mm], n_punch + 1 values: uniform, or with
        an inserted edge at load_half (k elements inside the patch, n_punch − k outside)."""
        w, n, a = self.punch_half_width, self.n_punch, self.load_half
        if self._patch_on_uniform_grid():
            edges = np.linspace(0.0, w, n + 1)
            edges[int(round(a / (w / n)))] = a  # the patch edge exactly (not 1 ulp off)
            return edges
        # k elements inside, n − k outside (one at least each), the sizes as even as possible
        k = min(range(1, n), key=lambda j: max(a / j, (w - a) / (n - j)) / min(a / j, (w - a) / (n - j)))
        return np.concatenate([np.linspace(0.0, a, k + 1), np.linspace(a, w, n - k + 1)[1:]])

    def punch_z_edges(self) -> np.ndarray:
        """z element edges of the punch [mm], uniform from the contact plane up."""
        return np.linspace(0.0, self.punch_height, self.n_punch_z + 1)

    def foundation_xy_edges(self) -> np.ndarray:
        """x (= y) edges of the foundation [mm]: the punch's, then n_outer growing outward."""
        inner = self.punch_edges()
        length = self.foundation_half_width - self.punch_half_width
        ratio = self.outer_ratio or _first_size_ratio(length, self.n_outer, inner[-1] - inner[-2])
        return np.concatenate([inner, graded(self.punch_half_width, self.foundation_half_width,
                                             self.n_outer, ratio)[1:]])

    def foundation_z_edges(self) -> np.ndarray:
        """z edges of the foundation [mm], from −depth to 0: n_depth layers growing downward."""
        first = self.punch_height / self.n_punch_z
        ratio = self.depth_ratio or _first_size_ratio(self.foundation_depth, self.n_depth, first)
        return graded(-self.foundation_depth, 0.0, self.n_depth, 1.0 / ratio)  # graded's "first" is the bottom


def figure_annotations(geometry: PunchGeometry, arrows: int = 3) -> dict:
    """Keyword arguments of :func:`roughcontact.paper.drawings.mesh_figure` for Figs 14/15 (data
    only): the supports, the load patch as ``arrows`` × ``arrows`` arrows [mm], a detail box
    [0, 1.6 w]² × [−w, h] on the contact zone (w the punch's half-width, h its height: the punch
    and the foundation's cells next to it), a lift of w/2 that explodes the detail, the
    transition layers shaded, and the view: from (+x, +y), off the diagonal, so that the
    symmetry planes are behind the bodies."""
    g, a = geometry, geometry.load_half
    grid = np.linspace(0.0, a, arrows)
    loads = [((x, y, g.punch_height), (0.0, 0.0, -1.0), "") for x in grid for y in grid]
    loads[len(loads) // 2] = (loads[len(loads) // 2][0], (0.0, 0.0, -1.0), "p on the load patch")
    w = g.punch_half_width
    return {"supports": [(SYMMETRY_X, "symmetry u_x = 0"), (SYMMETRY_Y, "symmetry u_y = 0"), (BASE, "base support")],
            "loads": loads, "detail": ((0.0, 0.0, -w), (1.6 * w, 1.6 * w, g.punch_height)), "lift": 0.5 * w,
            "elev": 26.0, "azim": 32.0, "figsize": (12.0, 6.5), "show_transition": True}
