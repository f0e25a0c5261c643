"""The data of section 9 of Buczkowski & Kleiber (2009) and its captions, in one place.

Lengths of the surfaces in µm (m00 [µm²], m20, m02 [–], m40, m04 [µm⁻²]), of the models in mm;
stresses in N/mm²; forces in N. Each number cites where the paper prints it.
"""

from __future__ import annotations

from ..validation import positive
from ..limits import describe

__all__ = ["SURFACE", "TABLE4_M00", "BEAM", "BEAM_E_STAR", "PUNCH", "PUNCH_M00", "PUNCH_PSI", "N_PER_MM",
           "FIG18_CASES", "FIG18_NU", "fig18_preset", "FIG13_MARKERS", "MESH_CAPTIONS"]

#: the surface of Fig. 13, Table 4 and Figs 18, 19 (captions), without m00 [µm units]
SURFACE = {"m20": 8.0e-5, "m02": 8.0e-4, "m40": 1.04e-6, "m04": 1.04e-4}
#: Table 4's m00 by case (rows 1-3 elastic, 4-6 elasto-plastic) [µm²]
TABLE4_M00 = {"1": 0.625, "2": 0.3125, "3": 0.0625, "4": 0.625, "5": 0.3125, "6": 0.0625}
#: example 9.1 (text): the beam 500 × 10 × 120 mm on its 500 × 10 face, E1, ν1 of the beam,
#: 1962 N at mid-length after an initial 4.9 N, sixteen increments
BEAM = {"length": 500.0, "width": 10.0, "height": 120.0, "E": 1.057e5, "nu": 0.25, "load": 1962.0,
        "initial_load": 4.9, "increments": 16}
#: E* of eq. (42) on a rigid base: E1/(1 − ν1²) (the text's 1.127e5; the caption prints 1.14e5)
BEAM_E_STAR = BEAM["E"] / (1.0 - BEAM["nu"] ** 2)
#: example 9.2 (text): punch 20 × 20 × 10 mm on a foundation 100 × 100 × 50 mm, E = 200 GPa and
#: ν = 0.25 for both, 1000 N, sixteen increments
PUNCH = {"punch_width": 20.0, "punch_height": 10.0, "foundation_width": 100.0, "foundation_depth": 50.0,
         "E": 2.0e5, "nu": 0.25, "load": 1000.0, "increments": 16}
#: Figs 18, 19 (captions): m00 [µm²] and the plasticity index of the elasto-plastic law
PUNCH_M00 = 0.625
PUNCH_PSI = 0.35
#: slip hardening n_x = n_y = 275 1/mm (section 9.2 text)
N_PER_MM = 275.0
#: Figs 18/19 cases (captions). ν_x = ν_y = 0.125 for all three: a circular slip potential, i.e.
#: k = 0 (only ν_y/ν_x matters). k_N is not given numerically (it comes from (95) for the
#: captions' surface), so stiffnesses are ratios.
FIG18_CASES = {
    "a": dict(mu_m=0.2, mu_o=1.0, kTx_over_kN=0.7, kTy_over_kN=0.7),
    "b": dict(mu_m=0.5, mu_o=0.5, kTx_over_kN=0.7, kTy_over_kN=0.7),
    "c": dict(mu_m=0.5, mu_o=0.5, kTx_over_kN=0.7, kTy_over_kN=1.0),
}
#: ν_x = ν_y of the slip potential, all three cases (captions of Figs 18, 19)
FIG18_NU = 0.125
#: the markers of Fig. 13 (caption): m00 = 0.0625 triangles, 0.3125 crosses, 0.625 squares
FIG13_MARKERS = {0.0625: "^", 0.3125: "x", 0.625: "s"}
#: Figs 14, 15 (captions) by element family
MESH_CAPTIONS = {"quadratic": "Fig. 14: punch on foundation with 21-node transition and 18-node interface elements",
                 "cubic": "Fig. 15: punch on foundation with 28-node transition and 32-node interface elements"}

_LENGTH_PER_MM = {"mm": 1.0, "um": 1e3, "µm": 1e3, "m": 1e-3}


class OnSurface:
    """What a run of an example on a surface shares (a mixin of frozen dataclasses with the
    fields ``m00`` [µm²] and ``surface``, the other moments as ((name, value), ...))."""

    def _freeze_surface(self):
        object.__setattr__(self, "surface", tuple((k, float(v)) for k, v in dict(self.surface).items()))

    @property
    def moments(self):
        """The surface's SpectralMoments [µm units]."""
        from ..statistics import SpectralMoments

        return SpectralMoments(m00=self.m00, **dict(self.surface))

    def to_dict(self) -> dict:
        """JSON-ready (provenance)."""
        from dataclasses import asdict

        return {**asdict(self), "surface": dict(self.surface)}


def fig18_preset(case, k_N, length_unit="mm"):
    """Orthotropic model and stiffnesses of Fig. 18/19 case 'a', 'b' or 'c'.

    ``k_N`` is the normal stiffness per unit area (user supplied; the paper gets it from (95)),
    ``length_unit`` the displacement unit used for u ('mm', 'um'/'µm', 'm'): n is converted
    from 275 1/mm. Returns (OrthotropicHardening, dict(k_N=..., k_Tx=..., k_Ty=...))."""
    from ..interface.friction import OrthotropicHardening  # here: the CLI reads this module's data without numba

    if case not in FIG18_CASES:
        raise ValueError(f"case must be one of {sorted(FIG18_CASES)}, got {describe(case)}")
    if length_unit not in _LENGTH_PER_MM:
        raise ValueError(f"length_unit must be one of {sorted(_LENGTH_PER_MM)}")
    k_N = positive("k_N", k_N)
    c = FIG18_CASES[case]
    n = N_PER_MM / _LENGTH_PER_MM[length_unit]
    model = OrthotropicHardening(c["mu_m"], c["mu_m"], c["mu_o"], c["mu_o"], n, n, k=0.0)
    return model, dict(k_N=k_N, k_Tx=c["kTx_over_kN"] * k_N, k_Ty=c["kTy_over_kN"] * k_N)
