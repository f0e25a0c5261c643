"""Surface statistics from five spectral moments (section 2 of Buczkowski & Kleiber 2009).

* :mod:`.surface` — :class:`SpectralMoments`: validation, bandwidth parameters α, β, μ, summit
  density D_sum (17), mean summit curvature, summit-height standard deviation (71)–(72), the
  offset δ (73), the summit pdf (18), Nayak's extremum densities (12), the bearing area A_B;
* :mod:`.measure` — the moments of a measured window (derivative fields, or the periodogram for
  periodic maps), the lay angle, scales, uncertainty, the distance from strong anisotropy, the
  noise floor (height quantisation and a white spectral tail), form removal (plane, polynomial,
  sphere);
* :mod:`.derivatives` — finite-difference derivative fields around dropouts and edges;
* :mod:`.dropouts` — missing data: the fraction, the harmonic fill;
* :mod:`.synthetic` — seeded periodic Gaussian surfaces with a prescribed spectrum;
* :mod:`.gw` — McCool's equivalent isotropic Greenwood–Williamson surface (Tables 1–2).
"""

from .gw import EquivalentGW
from .measure import MeasuredMoments, MeasurementWarning, measure_heights, measure_profiles
from .surface import SpectralMoments, gaussian_bearing_area

__all__ = ["SpectralMoments", "gaussian_bearing_area", "EquivalentGW", "MeasuredMoments",
           "MeasurementWarning", "measure_heights", "measure_profiles"]
