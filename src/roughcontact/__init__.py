"""roughcontact: statistical contact of strongly anisotropic rough surfaces.

Reproduces and extends Buczkowski & Kleiber (2009), "Statistical Models of Rough Surfaces
for Finite Element 3D-Contact Analysis", Arch. Comput. Methods Eng. 16:399-424,
doi:10.1007/s11831-009-9037-2.

What docs/usage.md uses is importable from the top level::

    from roughcontact import SpectralMoments, elastic_contact, elastoplastic_contact, resolve_material
    from roughcontact import NormalLawTable, InterfaceLaw, friction, AsperityMaterial

The contact, interface and asperity names are loaded on first use (they pull in numba), so
``import roughcontact`` stays light.
"""

from importlib import import_module
from importlib.metadata import PackageNotFoundError, version as _version

from .statistics import SpectralMoments, gaussian_bearing_area

try:
    __version__ = _version("roughcontact")
except PackageNotFoundError:  # running from a source tree without installation
    __version__ = "0+unknown"

#: top-level name → the subpackage that defines it (loaded on first access, PEP 562)
_LAZY = {
    "elastic_contact": "contact",
    "elastoplastic_contact": "contact",
    "resolve_material": "contact",
    "ContactCurves": "contact",
    "ElastoPlasticCurves": "contact",
    "NormalLawTable": "interface",
    "InterfaceLaw": "interface",
    "friction": "interface",
    "AsperityMaterial": "asperity",
    "synthetic_surface": "statistics.synthetic",
}

__all__ = ["SpectralMoments", "gaussian_bearing_area", "__version__", *_LAZY]


def __getattr__(name: str):
    if name in _LAZY:
        value = getattr(import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'roughcontact' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY))
