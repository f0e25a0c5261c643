"""roughcontact: statistical contact of strongly anisotropic rough surfaces.

Reproduces and extends Buczkowski & Kleiber (2009), "Statistical Models of Rough Surfaces
for Finite Element 3D-Contact Analysis", Arch. Comput. Methods Eng. 16:399-424.
"""

from importlib.metadata import PackageNotFoundError, version as _version

from .statistics import SpectralMoments, gaussian_bearing_area

try:
    __version__ = _version("roughcontact")
except PackageNotFoundError:  # running from a source tree without installation
    __version__ = "0+unknown"

__all__ = ["SpectralMoments", "gaussian_bearing_area", "__version__"]
