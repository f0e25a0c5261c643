"""Compile (or load from numba's on-disk cache) every numba kernel of the package once.

For a workflow step that runs before parallel jobs, so that they do not all compile at the
same time on a cold cache (docs/performance.md, caching). It sits above the kernels it
compiles: it calls them through the public API of :mod:`.contact` and :mod:`.interface`.
"""

from __future__ import annotations

import numpy as np

from .asperity import AsperityMaterial
from .contact import elastic_contact, elastoplastic_contact
from .integrals.production import PARALLEL_MIN, asperity_law, elastic_inner_integrals
from .interface import friction
from .statistics import SpectralMoments

__all__ = ["warm_up"]


def warm_up() -> None:
    """Run every kernel, serial and threaded, on tiny inputs."""
    surface = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
    many = np.linspace(0.0, 1.0, PARALLEL_MIN)
    for s in ([1.0], many):
        # compiling, not computing results: no range-of-validity warnings (s = 0 is heavy load)
        elastic_contact(surface, s, 1.0, accuracy="plot", validity="off")
        elastoplastic_contact(surface, s, AsperityMaterial(1.0, 1e-3), accuracy="plot", validity="off")
    elastic_contact(surface, [1.0], 1.0, model="gw")
    elastic_inner_integrals([0.5], [1.0])
    asperity_law([1e-3], 2.0, 1.0, 1.0, 1.0, 1e-3, 1.0, 45.0, 1.0, 0.3)
    state = friction.initial_state(1, u_N=1.0, k_N=1.0)
    for model in (friction.OrthotropicHardening(0.5, 0.5, 0.5, 0.5, 1.0, 1.0),
                  friction.IsotropicHardening(0.5, 0.5, 1.0)):
        friction.update(model, state, [[1.0, 0.5, 0.1]], 1.0, 1.0, 1.0)
