"""Height maps from text grids, XYZ points, .gsf and instrument files (SurfaceTopography, present
and absent), with their units; moment files."""

from __future__ import annotations

import json
import sys

import numpy as np
import pytest

from roughcontact.readers import HeightMap, load_moments, moments_from_mapping, moments_in_unit, read_height_map
from roughcontact.readers.lengths import factor, normalise
from roughcontact.statistics import SpectralMoments

RNG = np.random.default_rng(0)
Z = RNG.normal(size=(7, 9))  # z[i, j]: 7 rows along y, 9 columns along x


def write_gsf(path, z, dx, dy, xy_unit="um", z_unit="nm"):
    """A Gwyddion Simple Field file, written as its specification says (header, NUL padding to a
    multiple of 4, little-endian float32 row by row)."""
    ny, nx = z.shape
    header = (f"Gwyddion Simple Field 1.0\nXRes = {nx}\nYRes = {ny}\nXReal = {nx * dx!r}\nYReal = {ny * dy!r}\n"
              f"XYUnits = {xy_unit}\nZUnits = {z_unit}\nTitle = test\n").encode()
    path.write_bytes(header + b"\0" * (4 - len(header) % 4) + np.asarray(z, dtype="<f4").tobytes())


def test_length_units():
    assert normalise("µm") == normalise("micron") == normalise("μm") == "um"
    assert factor("nm", "um") == pytest.approx(1e-3) and factor("m", "um") == pytest.approx(1e6)
    with pytest.raises(ValueError, match="unknown length unit"):
        normalise("furlong")


def test_csv_grid_with_quoted_header_comments_and_missing_values(tmp_path):
    z = Z.copy()
    z[2, 3] = np.nan
    rows = [",".join("" if np.isnan(v) else repr(float(v)) for v in row) for row in z]
    path = tmp_path / "map.csv"
    path.write_text("# exported by an instrument\n" + ",".join(f'"c{j}"' for j in range(9)) + "\n" + "\n".join(rows))
    m = read_height_map(path)
    assert m.source == "grid" and m.dx is None and m.z_unit is None
    np.testing.assert_array_equal(np.isnan(m.heights), np.isnan(z))
    np.testing.assert_allclose(m.heights[~np.isnan(z)], z[~np.isnan(z)])


def test_semicolon_grid_with_decimal_comma(tmp_path):
    path = tmp_path / "map.txt"
    path.write_text("\n".join(";".join(f"{v:.6f}".replace(".", ",") for v in row) for row in Z))
    np.testing.assert_allclose(read_height_map(path).heights, Z, atol=1e-6)


def test_gwyddion_text_export_gives_size_and_units(tmp_path):
    path = tmp_path / "gwy.txt"
    path.write_text("# Channel: Height\n# Width: 4.5 µm\n# Height: 1.75 µm\n# Value units: nm\n"
                    + "\n".join("\t".join(repr(float(v)) for v in row) for row in Z))
    m = read_height_map(path)
    assert (m.dx, m.dy, m.xy_unit, m.z_unit) == (pytest.approx(0.5), pytest.approx(0.25), "um", "nm")
    um = m.in_unit("um")
    np.testing.assert_allclose(um.heights, Z * 1e-3)
    assert um.dx == pytest.approx(0.5)


def test_xyz_points_in_any_order_with_units_and_absent_nodes(tmp_path):
    y, x = np.mgrid[0:7, 0:9]
    pts = np.column_stack([x.ravel() * 0.5 + 10.0, y.ravel() * 0.25 - 3.0, Z.ravel()])
    order = RNG.permutation(len(pts))[:-2]  # shuffled, two nodes absent
    path = tmp_path / "pts.xyz"
    path.write_text("x [um], y [um], z [nm]\n" + "\n".join(f"{a:.17g}, {b:.17g}, {c:.17g}" for a, b, c in pts[order]))
    m = read_height_map(path)
    assert m.source == "xyz" and (m.dx, m.dy) == (pytest.approx(0.5), pytest.approx(0.25))
    assert (m.xy_unit, m.z_unit) == ("um", "nm") and np.isnan(m.heights).sum() == 2
    ok = ~np.isnan(m.heights)
    np.testing.assert_allclose(m.heights[ok], Z[ok])


def test_a_tall_table_is_points_or_a_clear_error(tmp_path):
    """A 50000 x 6 table was read as a 50000 x 6 height map: now x y z (+ extra columns, ignored
    with a note) on a lattice, or refused saying why (the 50000 x 6 case itself:
    tests/cli/test_moments_command.py)."""
    y, x = np.mgrid[0:60, 0:80]
    z = np.sin(0.1 * x) * np.cos(0.07 * y)
    extra = RNG.normal(size=(x.size, 3))
    table = np.column_stack([x.ravel() * 0.2, y.ravel() * 0.2, z.ravel(), extra])
    path = tmp_path / "cloud.txt"
    np.savetxt(path, table)
    m = read_height_map(path)
    assert m.heights.shape == (60, 80) and m.dx == pytest.approx(0.2) and "ignored" in m.notes[0]
    np.testing.assert_allclose(m.heights, z, atol=1e-12)
    scattered = tmp_path / "scattered.txt"
    np.savetxt(scattered, RNG.random((3000, 6)))
    with pytest.raises(ValueError, match="neither a height grid .* nor x y z points on a grid"):
        read_height_map(scattered)
    grid = read_height_map(scattered, layout="grid")  # stated: a grid it is
    assert grid.heights.shape == (3000, 6)


def test_gsf_orientation_units_and_nan(tmp_path):
    z = Z.copy()
    z[0, 0] = np.nan
    write_gsf(tmp_path / "a.gsf", z, 0.5, 0.25)
    m = read_height_map(tmp_path / "a.gsf")
    assert (m.source, m.xy_unit, m.z_unit) == ("gsf", "um", "nm")
    assert (m.dx, m.dy) == (pytest.approx(0.5), pytest.approx(0.25))
    np.testing.assert_allclose(m.heights, z.astype(np.float32), equal_nan=True)
    (tmp_path / "b.gsf").write_bytes(b"not gsf")
    with pytest.raises(ValueError, match="not a Gwyddion Simple Field"):
        read_height_map(tmp_path / "b.gsf")


@pytest.mark.parametrize("fmt", ["x3p", "gwy", "nc"])
def test_instrument_formats_through_surfacetopography(tmp_path, fmt):
    """Files SurfaceTopography writes (ISO 25178-72 .x3p, Gwyddion .gwy, its NetCDF) read back with
    their orientation, spacing and units."""
    st = pytest.importorskip("SurfaceTopography")
    # SurfaceTopography's heights are h[ix, iy]; ours z[i, j] = h[j, i]
    topography = st.Topography(Z.T.copy(), physical_sizes=(9 * 0.5, 7 * 0.25), unit="um")
    getattr(topography, {"x3p": "to_x3p", "gwy": "to_gwy", "nc": "to_netcdf"}[fmt])(str(tmp_path / f"a.{fmt}"))
    m = read_height_map(tmp_path / f"a.{fmt}")
    assert m.source == fmt and m.z_unit in ("m", "um") and m.xy_unit == m.z_unit
    um = m.in_unit("um")
    np.testing.assert_allclose(um.heights, Z, rtol=1e-6)
    assert (um.dx, um.dy) == (pytest.approx(0.5), pytest.approx(0.25))


def test_without_surfacetopography_an_instrument_file_gets_one_line(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "SurfaceTopography", None)  # import fails as if not installed
    (tmp_path / "scan.x3p").write_bytes(b"PK\x03\x04")
    with pytest.raises(ValueError) as info:
        read_height_map(tmp_path / "scan.x3p")
    message = str(info.value)
    assert "pip install '.[measure]'" in message and "\n" not in message


@pytest.mark.parametrize("content, match", [(None, "no such file"), ("a,b\nc,d\n", "no numeric data"),
                                            ("1,2,3\n4,5\n", "line 2: 2 fields")])
def test_text_errors(tmp_path, content, match):
    path = tmp_path / "bad.csv"
    if content is not None:
        path.write_text(content)
    with pytest.raises(ValueError, match=match):
        read_height_map(path)


def test_moment_files(tmp_path):
    m = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
    # what `roughcontact moments --json` writes: the moments at the top level, units per moment
    (tmp_path / "cli.json").write_text(json.dumps({**m.as_dict(), "units": {"m00": "um^2", "m40": "1/um^2"}}))
    assert load_moments(tmp_path / "cli.json") == (m, "um")
    assert moments_from_mapping({"moments": {**m.as_dict(), "unit": "µm"}}) == (m, "um")
    assert moments_from_mapping(m.as_dict()) == (m, None)
    mm = moments_in_unit(m, "um", "mm")
    assert mm.m00 == pytest.approx(0.0625e-6) and mm.m20 == m.m20 and mm.m40 == pytest.approx(1.04)
    assert mm.mu == pytest.approx(m.mu) and moments_in_unit(mm, "mm", "um").m04 == pytest.approx(m.m04)
    with pytest.raises(ValueError, match="m40, m04 are missing"):
        moments_from_mapping({"m00": 1, "m20": 1, "m02": 1})
    with pytest.raises(ValueError, match="unknown length unit"):
        moments_from_mapping({**m.as_dict(), "unit": "parsec"})
    (tmp_path / "bad.json").write_text("{")
    with pytest.raises(ValueError, match="not a JSON file"):
        load_moments(tmp_path / "bad.json")


def test_heightmap_needs_its_units_to_convert():
    with pytest.raises(ValueError, match="units of the map are not known"):
        HeightMap(Z, 0.5, 0.5, None, None, "npy").in_unit("um")
