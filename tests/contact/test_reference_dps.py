"""The reference integrator's precision is validated (issue 22): ``dps=-5`` returned a value 15 %
off instead of refusing; mpmath takes any number of digits."""

import numpy as np
import pytest

from roughcontact import SpectralMoments, elastic_contact
from roughcontact.contact.elastic import REFERENCE_DPS, bearing_area

SURFACE = SpectralMoments(m00=0.0625, m20=8e-5, m02=8e-4, m40=1.04e-6, m04=1.04e-4)


@pytest.mark.parametrize("dps", [-5, 0, 7, 61, 12.0, 20.5, "20", True, None])
@pytest.mark.parametrize("model", ["bgk", "gw"])
def test_bad_dps_is_refused(dps, model):
    with pytest.raises(ValueError, match="dps"):
        elastic_contact(SURFACE, [1.0], 1.14e5, method="reference", dps=dps, model=model)
    with pytest.raises(ValueError, match="dps"):
        bearing_area(SURFACE, [1.0], method="reference", dps=dps)


@pytest.mark.mpmath
def test_the_smallest_dps_is_a_reference():
    """At the smallest accepted precision the reference is within 5e-9 of dps = 20 (measured
    1.2e-9 for GW, 5.7e-10 for BGK at s = 1, 3): inside the "plot" preset's 1e-8."""
    assert REFERENCE_DPS == (8, 60)
    for model in ("gw", "bgk"):
        low = elastic_contact(SURFACE, [1.0], 1.14e5, method="reference", dps=REFERENCE_DPS[0], model=model)
        high = elastic_contact(SURFACE, [1.0], 1.14e5, method="reference", dps=20, model=model)
        np.testing.assert_allclose(low.pressure, high.pressure, rtol=5e-9)
        np.testing.assert_allclose(low.area_fraction, high.area_fraction, rtol=5e-9)
    assert elastic_contact(SURFACE, [1.0], 1.14e5, method="reference", dps=np.int64(12), model="gw").pressure[0] > 0.0
