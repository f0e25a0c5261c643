"""CF conventions of the netCDF files (CF-1.8), checked with a real UDUNITS parser.

cfchecker (the CF checker of NCAS) needs the UDUNITS-2 C library from the system and downloads
the standard-name table at run time, so it cannot run offline from pip alone. What it would
check that applies to these files (no standard_name, no time axis, no grid mapping) is checked
here instead, each rule with its CF section:

* every numeric variable has ``units``, and the string parses as UDUNITS (cf-units bundles
  UDUNITS-2; CF 3.1) — "1 (h/sqrt(m00))" or "unit of p_N" do not;
* string variables carry no ``units`` (CF 3.1: units are for dimensional quantities);
* every numeric variable and every coordinate variable — a dimension's variable or one named
  in a ``coordinates`` attribute — has a ``long_name`` (CF 3.2 asks for a long_name or a
  standard_name; the project requires the long_name);
* the global attributes ``Conventions`` ("CF-1.8", CF 2.6.1), ``title``, ``history`` and
  ``references`` (with the paper's DOI; CF 2.6.2) are present.

``test_every_workflow_file`` runs on every file under results/ — a glob, so a file a new rule
writes is covered without being listed (marker ``cf``: CI runs it after ``snakemake verify``,
which writes them); the fast tier checks files written by the library's own writers, the FE
runs' among them (small runs, written as the workflow's scripts write them), so that a missing
long_name fails ``make test`` already.
"""

from pathlib import Path

import cf_units
import netCDF4
import numpy as np
import pytest

from roughcontact import SpectralMoments, elastic_contact, io
from roughcontact.contact.sweep import SweepSpec, run_sweep

ROOT = Path(__file__).resolve().parents[1]
DOI = "doi:10.1007/s11831-009-9037-2"
UNITS = {"length": "um", "stress": "N/mm^2"}


def cf_problems(path) -> list[str]:
    """What in ``path`` breaks the CF rules of the module docstring (empty: none)."""
    problems = []
    with netCDF4.Dataset(path) as nc:
        g = {k: nc.getncattr(k) for k in nc.ncattrs()}
        if not str(g.get("Conventions", "")).startswith("CF-1."):
            problems.append(f"Conventions = {g.get('Conventions')!r}")
        for key in ("title", "history", "references"):
            if not str(g.get(key, "")).strip():
                problems.append(f"no global {key}")
        if DOI not in str(g.get("references", "")):
            problems.append("references lack the paper's DOI")
        coords = set(nc.dimensions) & set(nc.variables)
        for var in nc.variables.values():
            coords |= set(getattr(var, "coordinates", "").split())
        for name, var in nc.variables.items():
            is_text = var.dtype == str or np.dtype(var.dtype).kind in "SUO"
            units = getattr(var, "units", None)
            if is_text and units is not None:
                problems.append(f"{name}: a string variable has units {units!r}")
            elif not is_text:
                if units is None:
                    problems.append(f"{name}: no units")
                else:
                    try:
                        cf_units.Unit(units)
                    except ValueError:
                        problems.append(f"{name}: units {units!r} are not UDUNITS")
            if name in coords and not str(getattr(var, "long_name", "")).strip():
                problems.append(f"{name}: a coordinate without long_name")
            elif not is_text and not str(getattr(var, "long_name", "")).strip():
                problems.append(f"{name}: no long_name")
    return problems


def test_checker_rejects_what_cf_forbids(tmp_path):
    import xarray as xr

    ds = xr.Dataset({"p": ("s", [1.0, 2.0], {"units": "unit of p_N"}),
                     "newton_iterations": ("s", [3, 4], {"units": "1"})},
                    coords={"s": ("s", [0.0, 1.0], {"units": "1 (h/sqrt(m00))", "long_name": "s"})})
    path = tmp_path / "bad.nc"
    ds.to_netcdf(path)
    problems = cf_problems(path)
    assert "p: units 'unit of p_N' are not UDUNITS" in problems
    assert "s: units '1 (h/sqrt(m00))' are not UDUNITS" in problems
    assert "newton_iterations: no long_name" in problems and "p: no long_name" in problems
    assert "no global references" in problems


def test_library_writers_are_cf(tmp_path):
    surface = SpectralMoments(m00=0.0625, m20=8e-5, m02=8e-4, m40=1.04e-6, m04=1.04e-4)
    curves = elastic_contact(surface, [1.0, 2.0], 1.14e5)
    sweep = run_sweep(SweepSpec(axes={"m00": [0.0625, 0.625], "psi": [0.5]}, s=[1.0, 2.0],
                                fixed={"m20": 8e-5, "m02": 8e-4, "m40": 1.04e-6, "m04": 1.04e-4, "E_star": 1.14e5},
                                units=UNITS))
    for name, ds in (("elastic", curves.to_dataset(units=UNITS)), ("sweep", sweep)):
        path = io.write_netcdf(ds, tmp_path / f"{name}.nc")
        assert cf_problems(path) == [], name
    with pytest.raises(ValueError, match="pressure: no units"):  # no unit system stated
        io.write_netcdf(curves.to_dataset(), tmp_path / "bare.nc")


WORKFLOW_FILES = sorted((ROOT / "results").rglob("*.nc"))


@pytest.mark.cf
@pytest.mark.skipif(not WORKFLOW_FILES, reason="no workflow results yet (run snakemake verify first)")
def test_every_workflow_file():
    bad = {str(p.relative_to(ROOT)): cf_problems(p) for p in WORKFLOW_FILES}
    bad = {k: v for k, v in bad.items() if v}
    assert not bad, f"{len(bad)} of {len(WORKFLOW_FILES)} files break CF: {bad}"


def test_fe_writers_are_cf(tmp_path):
    """Issue 22: the FE outputs (results/fe/**.nc, results/curves/fig18_point.nc) had 459 numeric
    variables without long_name (newton_iterations, t_x, p_N, point_*, cutbacks, ...). Small runs
    of the beam and the punch and the Fig. 18 material point, written as the workflow writes
    them."""
    from roughcontact.examples.beam import BeamRun, BeamSpec, run_beam
    from roughcontact.examples.punch import PunchRun, PunchSpec, run_punch, to_dataset
    from roughcontact.examples.punch_geometry import PunchGeometry
    from roughcontact.paper.scenes import fig18_paths

    surface = (("m20", 8e-5), ("m02", 8e-4), ("m40", 1.04e-6), ("m04", 1.04e-4))
    beam = run_beam(BeamRun(spec=BeamSpec(elements="quadratic", n_x=3, n_z=2, increments=2), m00=0.625,
                            law="elastic", E_star=1.1275e5, tangential="free", surface=surface))
    punch = run_punch(PunchRun(case="b", m00=0.625, surface=surface, law="elastic", psi=None,
                               spec=PunchSpec(geometry=PunchGeometry(family="quadratic", n_punch=2, n_outer=2, n_depth=2),
                                              load=1000.0, load_on="quarter", seating_pressure=0.1, increments=2,
                                              unload_increments=1)))
    point = fig18_paths(["a", "b"], k_N=1e3, p_N=1.0, angle_deg=30.0, u_max=1.0, steps=2)
    for name, ds in (("beam", beam.to_dataset()), ("punch", to_dataset(punch)), ("fig18_point", point)):
        path = io.write_netcdf(ds, tmp_path / f"{name}.nc", config={"test": name})
        assert cf_problems(path) == [], name
