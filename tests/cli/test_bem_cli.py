"""``roughcontact bem SCAN`` (issue 32): against an independent BEM written here (numpy only) on a
periodic map with Table 1's moments and anisotropic pixels, stored as a .gsf; the statistical
model's numbers beside it; the free boundary stated; the law table; one line per bad input;
one line without the extra [bem]."""

import json
import math
import sys

import numpy as np
import pytest

from roughcontact.bem.compare import model_at_pressures
from roughcontact.bem.law_table import read_law_table
from roughcontact.bem.solver import SKIP_MESSAGE, available
from roughcontact.bem.surfaces import BandLimitedSurface
from roughcontact.statistics.surface import SpectralMoments

requires_bem = pytest.mark.skipif(not available(), reason=SKIP_MESSAGE)
TABLE1 = SpectralMoments(m00=0.0625, m20=8.0e-5, m02=8.0e-4, m40=1.04e-6, m04=1.04e-4)  # config/config.yaml, section bem, family table1
E_STAR = 114000.0  # N/mm^2, Tables 1-2
#: the issue's acceptance: area fraction within 1 %, mean gap within 0.3 % of an independent BEM
AREA_RTOL, GAP_RTOL = 0.01, 0.003


def write_gsf(path, z, dx, dy, unit="um"):
    """A Gwyddion Simple Field file (gwyddion.net, "GSF file format"): header, NUL padding to a
    multiple of 4 bytes, little-endian float32 heights row by row. Returns the heights as stored."""
    ny, nx = z.shape
    header = (f"Gwyddion Simple Field 1.0\nXRes = {nx}\nYRes = {ny}\nXReal = {nx * dx!r}\nYReal = {ny * dy!r}\n"
              f"XYUnits = {unit}\nZUnits = {unit}\n").encode()
    stored = np.asarray(z, dtype="<f4")
    path.write_bytes(header + b"\0" * (4 - len(header) % 4) + stored.tobytes())
    return stored.astype(float)


def independent_bem(z, dx, dy, E_star, mean_pressure, *, rtol=1e-12, maxiter=20000):
    """Frictionless contact of the periodic rigid map z[i, j] (x = j·dx, y = i·dy) with an elastic
    half-space under the nominal pressure ``mean_pressure``: (A/A0, mean gap).

    Green's function (Stanley & Kato 1997, J. Tribol. 119, 481): the surface deflection of a
    periodic pressure field is û(q) = 2 p̂(q)/(E*|q|), q = 2π(k_x/L_x, k_y/L_y), the q = 0 term
    left out (a uniform shift, absorbed by the approach). Constrained conjugate gradients at
    prescribed load (Polonsky & Keer 1999, Wear 231, 206, section 3): gap g = s0 + u − δ with
    s0 = max z − z, δ fixed by the mean of g over the contact, p ≥ 0, Σp = N·p̄."""
    ny, nx = z.shape
    qx = 2 * np.pi * np.fft.fftfreq(nx, d=dx)
    qy = 2 * np.pi * np.fft.fftfreq(ny, d=dy)
    q = np.hypot(qx[np.newaxis, :], qy[:, np.newaxis])
    kernel = np.zeros_like(q)
    kernel[q > 0] = 2.0 / (E_star * q[q > 0])

    def deflection(p):
        return np.fft.ifft2(kernel * np.fft.fft2(p)).real

    s0 = z.max() - z
    total = mean_pressure * z.size
    p = np.full(z.shape, mean_pressure)
    t = np.zeros_like(p)
    G_old, conjugate = 1.0, False
    for _ in range(maxiter):
        contact = p > 0
        g = s0 + deflection(p)
        g -= g[contact].mean()
        G = float(np.sum(g[contact] ** 2))
        t = np.where(contact, g + (G / G_old) * t if conjugate else g, 0.0)
        G_old = G
        r = deflection(t)
        r -= r[contact].mean()
        tau = float(np.sum(g[contact] * t[contact]) / np.sum(r[contact] * t[contact]))
        p_old = p.copy()
        p = np.where(contact, p - tau * t, 0.0)
        p[p < 0] = 0.0
        overlap = (p == 0) & (g < 0)  # penetrating points outside the contact: enter it
        conjugate = not overlap.any()
        p[overlap] -= tau * g[overlap]
        p *= total / p.sum()
        if np.sqrt(np.sum((p - p_old) ** 2) / np.sum(p**2)) < rtol and conjugate:
            break
    else:
        raise AssertionError("the independent BEM did not converge")
    g = s0 + deflection(p)
    g -= g[p > 0].mean()
    return float((p > 0).mean()), float(g.mean())


@pytest.fixture(scope="module")
def scan(tmp_path_factory):
    """Table 1's surface on a 256² periodic grid (16 pixels per shortest wavelength; pixels
    dx/dy = √(m02/m20) ≈ 3.2: anisotropic), in µm, as a .gsf."""
    surface = BandLimitedSurface.design(TABLE1, hurst=0.8, k_high=16)
    n = 256
    dx, dy = surface.spacing(n)
    path = tmp_path_factory.mktemp("bem") / "scan.gsf"
    z = write_gsf(path, surface.heights(n, 3), dx, dy)
    return path, z, dx, dy


def test_independent_bem_on_westergaards_wave():
    """The reference itself on a closed form (Westergaard 1939; Johnson 1985, (13.9)):
    p̄ = p* sin²(πa/λ), p* = πE*h0/λ."""
    n, lam, h0 = 512, 1.0, 1e-3
    x = np.arange(n) * lam / n
    z = np.tile(h0 * np.cos(2 * np.pi * x / lam), (8, 1))
    p_star = np.pi * h0 / lam
    area, _ = independent_bem(z, lam / n, lam / 8, 1.0, 0.25 * p_star)
    assert area == pytest.approx(2 / np.pi * np.arcsin(np.sqrt(0.25)), abs=1.5 / n)


@requires_bem
def test_periodic_scan_against_the_independent_bem(scan, cli_json):
    path, z, dx, dy = scan
    pressures = [1.0, 10.0, 100.0]
    out = cli_json("bem", path, "--periodic", "--E-star", E_STAR, "--pressure", *pressures, "--quiet")
    assert out["periodic"] is True and out["solver"]["boundary"] == "periodic"
    assert out["length_unit"] == "um" and out["pressure"] == pressures
    assert out["source"]["shape"] == [256, 256]
    assert out["source"]["dx"] == pytest.approx(dx, rel=1e-12) and out["source"]["dy"] == pytest.approx(dy, rel=1e-12)
    for i, p in enumerate(pressures):
        area, gap = independent_bem(z, dx, dy, E_STAR, p)
        assert out["area_fraction"][i] == pytest.approx(area, rel=AREA_RTOL)
        assert out["mean_gap"][i] == pytest.approx(gap, rel=GAP_RTOL)
    assert all(k > 0 for k in out["stiffness"]) and np.all(np.diff(out["mean_gap"]) < 0)
    assert max(out["residual"]["penetration"]) < out["solver"]["pentol"]
    assert max(out["residual"]["tensile_force"]) < out["solver"]["forcetol"]


@requires_bem
def test_the_model_beside_it_is_model_at_pressures(scan, cli_json):
    """The model's numbers are those of bem.compare.model_at_pressures on the moments the command
    reports (measured on the map), the mean gap h = s√m00, and the ratios BEM/model."""
    path, *_ = scan
    out = cli_json("bem", path, "--periodic", "--E-star", E_STAR, "--pressure", 10, 100, "--quiet")
    mo = out["moments"]
    ref = model_at_pressures(SpectralMoments(*(mo[k] for k in ("m00", "m20", "m02", "m40", "m04"))),
                             [10.0, 100.0], E_STAR)
    m = out["model"]
    np.testing.assert_allclose(m["area_fraction"], ref.area_fraction, rtol=1e-12)
    np.testing.assert_allclose(m["s"], ref.s, rtol=1e-12)
    np.testing.assert_allclose(m["mean_gap"], ref.s * math.sqrt(mo["m00"]), rtol=1e-12)
    np.testing.assert_allclose(m["stiffness"], ref.stiffness, rtol=1e-12)
    for k in ("area_fraction", "mean_gap", "stiffness"):
        np.testing.assert_allclose(out["ratio"][k], np.array(out[k]) / np.array(m[k]), rtol=1e-12)
    # the map is periodic: the mean is removed, not a plane; m00 is the map's variance
    assert out["source"]["detrend"] == "mean"
    assert mo["m00"] == pytest.approx(np.var(scan[1]), rel=1e-9)


@requires_bem
def test_non_periodic_runs_with_the_free_boundary(scan, cli_run):
    path, *_ = scan
    code, out, err = cli_run("bem", path, "--E-star", E_STAR, "--pressure", 10, 100)
    assert code == 0, err
    assert "BEM (free boundary (padded))" in out and "ratio BEM/model:" in out
    assert "bem: W/A0 = 10 (1/2)" in err and "bem: W/A0 = 100 (2/2)" in err  # progress on stderr
    code, out, err = cli_run("bem", path, "--E-star", E_STAR, "--pressure", 10, "--json", "--quiet")
    data = json.loads(out)
    assert data["periodic"] is False and data["solver"]["boundary"] == "free boundary (padded)"
    assert data["source"]["detrend"] == "plane" and "bem:" not in err


@requires_bem
def test_law_table_round_trip(scan, cli_json, tmp_path):
    path, *_ = scan
    table = tmp_path / "law.json"
    out = cli_json("bem", path, "--periodic", "--E-star", E_STAR, "--pressure-range", 5, 50, "--quiet",
                   "--law-table", table, "--stress-unit", "N/mm^2")
    assert len(out["pressure"]) == 5  # 4 per decade: ceil(4 * 1) + 1
    np.testing.assert_allclose(out["pressure"], np.geomspace(5, 50, 5), rtol=1e-12)
    law = read_law_table(table)
    np.testing.assert_array_equal(law.mean_gap, out["mean_gap"])
    np.testing.assert_array_equal(law.stiffness, out["stiffness"])
    assert law.periodic and law.stress_unit == "N/mm^2" and law.length_unit == "um" and law.E_star == E_STAR
    assert law.moments.m00 == out["moments"]["m00"] and law.source["sha256"] == out["source"]["sha256"]


@requires_bem
@pytest.mark.parametrize("args, message", [
    (["--pressure", "10", "1"], "--pressure: the pressures must be positive and increasing"),
    (["--pressure", "-1"], "--pressure: the pressures must be positive"),
    (["--pressure-range", "10", "1"], "--pressure-range: the pressure range needs 0 < LO < HI"),
    (["--pressure-range", "1", "10", "--n-pressures", "1"], "--pressure-range: the number of pressures"),
    (["--pressure", "1", "--n-pressures", "4"], "--n-pressures goes with --pressure-range"),
    (["--pressure", "1", "2", "4", "8", "--law-table", "{tmp}/t.json"], "--law-table needs at least 5 pressures"),
    (["--pressure", "1", "--stress-unit", "psi"], "--stress-unit psi: not one of Pa"),
])
def test_bad_pressures_one_line(scan, cli_run, tmp_path, args, message):
    path, *_ = scan
    code, out, err = cli_run("bem", path, "--E-star", E_STAR, *[a.format(tmp=tmp_path) for a in args])
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and message in err


@requires_bem
@pytest.mark.parametrize("E", ["-114000", "0", "inf"])
def test_bad_modulus_one_line(scan, cli_run, E):
    code, _, err = cli_run("bem", scan[0], "--E-star", E, "--pressure", 1)
    assert code == 2 and err.count("\n") == 1 and "--E-star: the contact modulus must be a positive" in err


@requires_bem
def test_missing_spacing_and_dropouts_one_line(cli_run, tmp_path):
    z = BandLimitedSurface.design(TABLE1, hurst=0.8, k_high=16).heights(64, 0)
    grid = tmp_path / "map.npy"
    np.save(grid, z)
    code, _, err = cli_run("bem", grid, "--E-star", E_STAR, "--pressure", 10)
    assert code == 2 and err.count("\n") == 1 and "does not give the sampling interval: pass --dx" in err
    z[3, 4] = z[10, 11] = np.nan
    np.save(grid, z)
    code, _, err = cli_run("bem", grid, "--E-star", E_STAR, "--pressure", 10, "--dx", 1)
    assert code == 2 and err.count("\n") == 1
    assert "2 of 4096 points are missing" in err and "--fill harmonic" in err
    code, out, err = cli_run("bem", grid, "--E-star", E_STAR, "--pressure", 10, "--dx", 1, "--fill", "harmonic",
                             "--quiet", "--json")
    assert code == 0, err
    assert json.loads(out)["source"]["missing_fraction"] == pytest.approx(2 / 4096)


@requires_bem
def test_the_size_is_checked_before_solving(scan, cli_run, monkeypatch):
    monkeypatch.setenv("ROUGHCONTACT_MAX_CELLS", str(256 * 256 * 2))
    code, _, err = cli_run("bem", scan[0], "--E-star", E_STAR, "--pressure", 10, "--periodic")
    assert code == 2 and err.count("\n") == 1 and "the BEM of a 256 x 256 map (periodic" in err
    assert "ROUGHCONTACT_MAX_CELLS" in err


def test_without_contact_mechanics_one_line(cli_run, monkeypatch, tmp_path):
    """ContactMechanics unimportable (None in sys.modules: `import` raises ImportError)."""
    for name in ("ContactMechanics", "ContactMechanics.Optimization"):
        monkeypatch.setitem(sys.modules, name, None)
    np.save(tmp_path / "z.npy", np.random.default_rng(0).normal(size=(16, 16)))
    code, out, err = cli_run("bem", tmp_path / "z.npy", "--dx", 1, "--E-star", 1, "--pressure", 0.1)
    assert code != 0 and out == ""
    assert err == f"roughcontact: error: {SKIP_MESSAGE}\n"
