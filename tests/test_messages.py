"""Values in the library's messages are quoted briefly and as plain numbers (roughcontact.limits
.describe; issue 29: NumPy reprs such as ``np.float64(0.0)`` leaked into messages)."""

from __future__ import annotations

import numpy as np
import pytest

from roughcontact.interface.friction import initial_state
from roughcontact.interface.tangential import kn_over_kt


@pytest.mark.parametrize("call, shown", [
    (lambda: initial_state(u_N=np.float64(np.nan)), "got nan"),
    (lambda: initial_state(k_N=np.float64(-2.5)), "got -2.5"),
    (lambda: kn_over_kt(np.float64(1.0), np.float64(0.7)), "got 0.7"),
])
def test_numpy_scalars_are_quoted_as_plain_numbers(call, shown):
    with pytest.raises(ValueError) as info:
        call()
    message = str(info.value)
    assert shown in message
    assert "np." not in message and "float64" not in message
