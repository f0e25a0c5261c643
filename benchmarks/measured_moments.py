"""Errors of the moment estimators on windows of known moments (issue 20's closing note).

Windows of 400 x 512 points cut from 1201 x 1201 periodic synthetic surfaces (dx = 0.25, across-lay
rms wavenumber 1, alpha1 = alpha2 = 3) at lays 0, 30, 45, 75 deg and m02/m20 = 10, 100; the
reference is the window's own exact moments (statistics.synthetic.window_moments: the parent's
derivative fields from its spectrum, cropped). Rows: the Hann periodogram (the old default, code
unchanged), the derivative-field estimator (the new default), and the latter with ~3 % dropouts
(40 patches + 1 % single points; the old estimators refused such maps).

    .venv/bin/python benchmarks/measured_moments.py [--out results/benchmarks/measured_moments.md]
"""

from __future__ import annotations

import argparse
import time
import warnings

import numpy as np

from roughcontact.statistics import SpectralMoments
from roughcontact.statistics.measure import measure_heights
from roughcontact.statistics.synthetic import dropout_mask, synthetic_surface, window_moments

FIVE = ("m00", "m20", "m02", "m40", "m04")
DX, ROWS, COLS = 0.25, slice(300, 700), slice(250, 762)


def rows():
    for anisotropy in (10, 100):
        for lay in (0.0, 30.0, 45.0, 75.0):
            m = SpectralMoments(1.0, 1.0 / anisotropy, 1.0, 3.0 / anisotropy**2, 3.0)
            parent = synthetic_surface(m, (1201, 1201), DX, seed=7, lay_angle_deg=lay)
            z = parent[ROWS, COLS]
            ref = window_moments(parent, DX, rows=ROWS, cols=COLS)
            hole = dropout_mask(z.shape, seed=int(lay) + anisotropy)
            holed = np.where(hole, np.nan, z)
            ref_holed = window_moments(parent, DX, rows=ROWS, cols=COLS, mask=~hole)
            for name, zz, r, options in (("Hann periodogram (old default)", z, ref, {"estimator": "spectral"}),
                                         ("derivative fields (new default)", z, ref, {}),
                                         (f"derivative fields, {100 * hole.mean():.1f} % dropouts", holed, ref_holed, {})):
                t0 = time.perf_counter()
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    got = measure_heights(zz, DX, **options)
                seconds = time.perf_counter() - t0
                lay_error = (got.lay_angle_deg - r["lay_angle_deg"] + 90.0) % 180.0 - 90.0
                yield anisotropy, lay, name, {k: got.values[k] / r[k] - 1.0 for k in FIVE}, lay_error, seconds


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=None, help="also write the table (Markdown) to this file")
    args = parser.parse_args()
    lines = ["| m02/m20 | lay | estimator | " + " | ".join(FIVE) + " | lay error | time |",
             "|---|---|---|" + "---|" * len(FIVE) + "---|---|"]
    for anisotropy, lay, name, errors, lay_error, seconds in rows():
        lines.append(f"| {anisotropy} | {lay:g}° | {name} | " + " | ".join(f"{100 * errors[k]:+.2f} %" for k in FIVE)
                     + f" | {lay_error:+.3f}° | {seconds:.2f} s |")
        print(lines[-1], flush=True)
    if args.out:
        from pathlib import Path

        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        Path(args.out).write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
