"""Contact of a rough surface with a rigid flat, per unit nominal area (sections 3–7 of
Buczkowski & Kleiber 2009): totals vs the separation s = h/√m00.

* :mod:`.elastic` — A/A0 (52), W/A0 (53), K/A0 (55) of the Bush–Gibson–Keogh model and of
  McCool's equivalent GW model; the bearing area A_G (22)/(24);
* :mod:`.elastoplastic` — totals and regime parts of (78)–(85), K = −dW/dh;
* :mod:`.at_pressure` — the same at a prescribed pressure (load control), warnings relayed;
* :mod:`.closures` — the named ways of fixing the material from ψ, E*, Y;
* :mod:`.sweep` — parameter sweeps as xarray Datasets, split into jobs and joined.
"""

from . import closures, sweep
from .at_pressure import ContactAtPressure, contact_at_pressure
from .closures import CLOSURES, default_closure, resolve_material
from .elastic import ContactCurves, bearing_area, bearing_area_ratio, elastic_contact
from .elastoplastic import ElastoPlasticCurves, elastoplastic_contact, elastoplastic_contact_many

__all__ = [
    "elastic_contact", "ContactCurves", "bearing_area", "bearing_area_ratio",
    "elastoplastic_contact", "elastoplastic_contact_many", "ElastoPlasticCurves", "contact_at_pressure",
    "ContactAtPressure",
    "resolve_material", "default_closure", "CLOSURES",
    "closures", "sweep",
]
