"""The BEM on closed forms (rule bem_checks): Hertz (sphere, square pixels; elliptic paraboloid
on each family's pixels) and Westergaard's wave along x and y, on every grid of the scale."""

import csv
import io as _io
import logging

from roughcontact import io
from roughcontact.bem import checks
from roughcontact.bem.solver import SolverSettings
from roughcontact.bem.surfaces import BandLimitedSurface
from roughcontact.statistics.surface import SpectralMoments

FIELDS = ("case", "family", "n", "size", "size_exact", "p_max", "p_max_exact", "iterations", "pixels_across")


def run(grids, families, hurst, k_high, solver, output, log):
    settings = SolverSettings(**solver)
    rows = []
    with io.log_to(log):
        for n in grids:
            results = [("-", checks.hertz_sphere(n, settings=settings))]
            for fam, m in families.items():
                dx, dy = BandLimitedSurface.design(SpectralMoments(**m), hurst=hurst, k_high=k_high).spacing(n)
                results.append((fam, checks.hertz_elliptic(n, dx / dy, settings=settings)))
                for axis in ("x", "y"):
                    results.append((fam, checks.westergaard(n, dx=dx, dy=dy, axis=axis, settings=settings)))
            for fam, c in results:
                logging.getLogger(io.PROGRESS).info("%s (%s) %d^2: size %.5f, p_max %.5f of the closed form, %d iterations",
                                                    c.case, fam, n, c.size_ratio, c.p_max_ratio, c.iterations)
                rows.append({"case": c.case if fam == "-" else f"{c.case}_{fam}", "family": fam, "n": n,
                             "size": c.size, "size_exact": c.size_exact, "p_max": c.p_max,
                             "p_max_exact": c.p_max_exact, "iterations": c.iterations,
                             "pixels_across": c.pixels_across})
    buf = _io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=FIELDS, lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    io.write_text(output, buf.getvalue())


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.grids, sm.params.families, sm.params.hurst, sm.params.k_high, sm.params.solver, sm.output[0], sm.log[0])
