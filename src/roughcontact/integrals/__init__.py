"""The summit integrals of the statistical model (docs/derivation.md): how they are computed.

* :mod:`.polar` — the polar form (θ, r, t): θ-geometry, break points, dimensional prefactors;
* :mod:`.rules` — integration rules and the accuracy presets;
* :mod:`.kernels` — the numba production kernels (elastic and elasto-plastic);
* :mod:`.production` — their Python API (array layout, presets, threads);
* :mod:`.normal_moments` — J_ν(a) = E[(Z + a)₊^ν] as Chebyshev tables (the inner t-integral);
* :mod:`.reference`, :mod:`.reference_functions` — the mpmath reference of the elastic
  integrals (the slow twin of the elastic kernels);
* :mod:`.reference_elastoplastic` — the scipy slow twin of the elasto-plastic kernel.

Totals per nominal area (with θ-weights, prefactors, D_sum) are :mod:`roughcontact.contact`'s.
"""
