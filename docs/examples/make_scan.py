"""Writes scan.npy, the height map of the README's first example: a 128 × 128 periodic Gaussian
surface with the moments of the paper's Table 1 (m00 = 0.0625 µm², m20 = 8e-5, m02 = 8e-4,
m40 = 1.04e-6, m04 = 1.04e-4 µm⁻²), sampled every 1 µm, the lay along x, seed 1, heights in µm
as float32 (64 KB). The same seed gives the same file (tests/test_readme_commands.py checks it):

    .venv/bin/python docs/examples/make_scan.py         # writes docs/examples/scan.npy
    roughcontact moments docs/examples/scan.npy --dx 1 --json > surface.json
"""

from pathlib import Path

import numpy as np

from roughcontact import SpectralMoments
from roughcontact.statistics.synthetic import synthetic_surface

TABLE1 = SpectralMoments(m00=0.0625, m20=8e-5, m02=8e-4, m40=1.04e-6, m04=1.04e-4)


def scan() -> np.ndarray:
    """z[i, j] [µm] at x = j·1 µm, y = i·1 µm."""
    return synthetic_surface(TABLE1, (128, 128), 1.0, seed=1).astype(np.float32)


if __name__ == "__main__":
    out = Path(__file__).resolve().parent / "scan.npy"
    np.save(out, scan())
    print(f"wrote {out.name}")
