"""Issue 29 (A1): reads that went silently wrong or ended in a traceback. Each map is constructed
with known spacing, units and heights, so the expected values are the construction's."""

from __future__ import annotations

import os
import time

import numpy as np
import pytest

from roughcontact.readers import HeightMap, read_height_map, unit_warning
from roughcontact.readers.lengths import in_metres, likely_unit

RNG = np.random.default_rng(29)
Z = RNG.normal(size=(12, 16))  # z[i, j]: 12 rows along y, 16 columns along x


def write_gsf(path, header_lines, nx=16, ny=12):
    """A Gwyddion Simple Field file with the given header lines (after the magic line)."""
    header = ("Gwyddion Simple Field 1.0\n" + "".join(f"{line}\n" for line in header_lines)).encode()
    path.write_bytes(header + b"\0" * (4 - len(header) % 4) + np.zeros(nx * ny, dtype="<f4").tobytes())


def xyz_text(x, y, z, header):
    return header + "\n" + "\n".join(f"{a:.17g}, {b:.17g}, {c:.17g}" for a, b, c in zip(x, y, z)) + "\n"


# --- 1. units that go silently wrong ---------------------------------------------------------

def test_a_map_in_metres_read_as_micrometres_is_named_with_the_unit_meant(tmp_path):
    """An XYZ export in metres (dx = 1.25 µm, heights ~0.1 µm) read without a unit: dx = 1.25e-6
    "µm" = 1.25 pm, no instrument samples that finely: the warning says metres and the options."""
    y, x = np.mgrid[0:12, 0:16]
    path = tmp_path / "metres.xyz"
    path.write_text(xyz_text(x.ravel() * 1.25e-6, y.ravel() * 1.25e-6, Z.ravel() * 1e-7, "x, y, z"))
    m = read_height_map(path)
    assert m.dx == pytest.approx(1.25e-6) and m.xy_unit is None
    text = unit_warning(m, "um", "um", path)
    assert text is not None and str(path) in text and "\n" not in text
    assert "metres" in text and "--xy-unit m --z-unit m" in text and "1.25 pm" in text
    # the same map stated in metres, or its numbers in µm, is plausible: no warning
    assert unit_warning(m, "m", "m", path) is None
    um = HeightMap(m.heights * 1e6, m.dx * 1e6, m.dy * 1e6, "um", "um", "xyz")
    assert unit_warning(um, "um", "um", path) is None


def test_heights_in_picometre_counts_read_as_micrometres_suggest_a_finer_unit():
    """rms ~1e5 "µm" = 10 cm of roughness: no instrument; 1e5 nm = 100 µm is plausible."""
    m = HeightMap(Z * 9e4, 0.5, 0.5, "um", None, "npy")
    text = unit_warning(m, "um", "um", "scan.npy")
    rms = np.std(Z * 9e4)
    assert f"an rms height of {rms:.3g} um ({rms * 1e-3:.3g} mm)" in text and text.endswith("pass --z-unit nm")
    assert "a sampling interval of" not in text
    assert likely_unit(1.25e-6, "um", "sampling interval") == "m"
    assert likely_unit(0.5, "um", "sampling interval") is None  # plausible: nothing to suggest
    assert in_metres(1e-10) == "0.1 nm" and in_metres(1.25e-12) == "1.25 pm" and in_metres(1e-2) == "10 mm"


# --- 2. vendor CSV headers -------------------------------------------------------------------

def vendor_csv(z, lines):
    return "".join(f"{line}\n" for line in lines) + "\n".join(",".join(f'"{v:.6f}"' for v in row) for row in z) + "\n"


def test_vendor_csv_header_gives_the_spacing_and_the_units(tmp_path):
    path = tmp_path / "vendor.csv"
    path.write_text(vendor_csv(Z, ['"Instrument","Profiler 3000"', '"XY calibration","1.25","um/pixel"',
                                   '"Z unit","nm"']))
    m = read_height_map(path)
    assert (m.dx, m.dy, m.xy_unit, m.z_unit) == (1.25, 1.25, "um", "nm") and m.source == "grid"
    np.testing.assert_allclose(m.heights, Z, atol=5e-7)
    assert any("XY calibration 1.25 um/pixel" in n for n in m.notes)
    um = m.in_unit("um")
    np.testing.assert_allclose(um.heights, Z * 1e-3, atol=1e-9)


def test_vendor_csv_x_and_y_calibration_in_different_units(tmp_path):
    path = tmp_path / "vendor.csv"
    path.write_text(vendor_csv(Z, ['"X calibration","1.25","µm/px"', '"Y calibration","500","nm/pixel"',
                                   '"Z unit","um"']))
    m = read_height_map(path)
    assert (m.dx, m.dy, m.xy_unit, m.z_unit) == (1.25, pytest.approx(0.5), "um", "um")


@pytest.mark.parametrize("line, match", [('"XY calibration","abc","um/pixel"',
                                          r"line 1: 'XY calibration' needs a number"),
                                         ('"XY calibration","1.25","furlong/pixel"', r"line 1: unknown length unit"),
                                         ('"XY calibration","-1","um/pixel"', r"line 1: .* must be positive"),
                                         ('"Z unit","volts"', r"line 1: unknown length unit")])
def test_vendor_header_that_cannot_be_read_is_one_line_naming_it(tmp_path, line, match):
    path = tmp_path / "vendor.csv"
    path.write_text(vendor_csv(Z, [line]))
    with pytest.raises(ValueError, match=match) as info:
        read_height_map(path)
    assert "\n" not in str(info.value)


# --- 3. silently wrong reads -----------------------------------------------------------------

def test_a_corrupt_x3p_is_refused_not_read_as_another_format(tmp_path):
    """Random bytes named .x3p were read as 'hgt' (heights of 1e8, exit 0)."""
    pytest.importorskip("SurfaceTopography")
    path = tmp_path / "scan.x3p"
    path.write_bytes(np.random.default_rng(3).bytes(5000))
    with pytest.raises(ValueError, match=r"not a readable \.x3p file .*x3p: ") as info:
        read_height_map(path)
    assert "\n" not in str(info.value) and "hgt" not in str(info.value)


def test_an_extension_no_reader_claims_is_detected_and_said(tmp_path):
    st = pytest.importorskip("SurfaceTopography")
    st.Topography(Z.T.copy(), physical_sizes=(16 * 0.5, 12 * 0.25), unit="um").to_x3p(str(tmp_path / "a.x3p"))
    (tmp_path / "a.scan").write_bytes((tmp_path / "a.x3p").read_bytes())
    m = read_height_map(tmp_path / "a.scan")
    assert m.source == "x3p" and any("detected from the content" in n for n in m.notes)
    np.testing.assert_allclose(m.in_unit("um").heights, Z, rtol=1e-6)


def test_xyz_header_with_x_in_mm_and_y_in_um(tmp_path):
    """x [mm], y [um]: the y unit was ignored (dy taken in mm, 1000x too large)."""
    y, x = np.mgrid[0:12, 0:16]
    path = tmp_path / "mixed.xyz"
    path.write_text(xyz_text(x.ravel() * 0.0005, y.ravel() * 0.25, Z.ravel(), "x [mm], y [um], z [nm]"))
    m = read_height_map(path)
    assert (m.xy_unit, m.z_unit) == ("um", "nm") and (m.dx, m.dy) == (pytest.approx(0.5), pytest.approx(0.25))
    np.testing.assert_allclose(m.heights, Z)
    assert any("x in mm, y in um: both taken in um" in n for n in m.notes)
    spaced = tmp_path / "spaced.xyz"  # space-separated, the units after the names
    spaced.write_text(path.read_text().replace(",", "").replace("x [mm] y [um] z [nm]", "x [mm]  y [um]  z [nm]"))
    assert (read_height_map(spaced).dx, read_height_map(spaced).dy) == (pytest.approx(0.5), pytest.approx(0.25))
    path.write_text(xyz_text(x.ravel() * 0.0005, y.ravel(), Z.ravel(), "x [mm], y [px], z [nm]"))
    with pytest.raises(ValueError, match="cannot be reconciled: mm and 'px'"):
        read_height_map(path)


def coordinate_grid(z, xs, ys, corner=""):
    head = corner + "," + ",".join(f"{v:g}" for v in xs)
    return head + "\n" + "\n".join(f"{b:g}," + ",".join(f"{v:.17g}" for v in row) for b, row in zip(ys, z)) + "\n"


@pytest.mark.parametrize("corner", ["", "y\\x"])
def test_a_grid_with_coordinates_in_its_first_row_and_column(tmp_path, corner):
    path = tmp_path / "coords.csv"
    path.write_text(coordinate_grid(Z, 10 + 0.5 * np.arange(16), 0.25 * np.arange(12), corner))
    m = read_height_map(path)
    assert m.heights.shape == (12, 16) and (m.dx, m.dy) == (pytest.approx(0.5), pytest.approx(0.25))
    np.testing.assert_allclose(m.heights, Z)
    assert any("first row and column are coordinates" in n for n in m.notes)


def test_coordinates_decreasing_along_y_flip_the_map(tmp_path):
    path = tmp_path / "coords.csv"
    path.write_text(coordinate_grid(Z[::-1], 0.5 * np.arange(16), 0.25 * np.arange(12)[::-1]))
    m = read_height_map(path)
    np.testing.assert_allclose(m.heights, Z)  # row i at y = i dy again
    assert m.dy == pytest.approx(0.25) and "flipped along y" in m.notes[-1]


def test_row_and_column_numbers_are_dropped_without_a_spacing(tmp_path):
    """pandas' to_csv: a header of column numbers, an index column: not coordinates."""
    path = tmp_path / "index.csv"
    path.write_text(coordinate_grid(Z, np.arange(16), np.arange(12)))
    m = read_height_map(path)
    assert m.heights.shape == (12, 16) and m.dx is None and "row and column numbers" in m.notes[-1]
    np.testing.assert_allclose(m.heights, Z)


# --- 4. bounds and tracebacks ----------------------------------------------------------------

def test_npy_empty_truncated_object_and_too_large(tmp_path, monkeypatch):
    (tmp_path / "empty.npy").write_bytes(b"")
    with pytest.raises(ValueError, match="empty.npy: not a .npy array"):
        read_height_map(tmp_path / "empty.npy")
    with open(tmp_path / "big.npy", "wb") as f:  # a header declaring 10^8 points, 1 KB of data
        np.lib.format.write_array_header_1_0(f, {"descr": "<f8", "fortran_order": False, "shape": (10000, 10000)})
        f.write(b"\0" * 1024)
    start = time.perf_counter()
    with pytest.raises(ValueError, match=r"10000 x 10000 points: 100000000 exceed the limit of 67108864 .*"
                                         "ROUGHCONTACT_MAX_CELLS"):
        read_height_map(tmp_path / "big.npy")
    assert time.perf_counter() - start < 1.0
    monkeypatch.setenv("ROUGHCONTACT_MAX_CELLS", str(10 ** 9))
    with pytest.raises(ValueError, match="truncated: the header declares 10000 x 10000 values of 8 bytes"):
        read_height_map(tmp_path / "big.npy")
    np.save(tmp_path / "obj.npy", np.array([[1, "a"]], dtype=object), allow_pickle=True)
    with pytest.raises(ValueError, match="expected a 2-d numeric map"):
        read_height_map(tmp_path / "obj.npy")
    np.save(tmp_path / "ok.npy", Z)
    np.testing.assert_array_equal(read_height_map(tmp_path / "ok.npy").heights, Z)


@pytest.mark.parametrize("lines, match", [
    (["XRes = 0", "YRes = 12"], "XRes = 0: the number of points must be at least 1"),
    (["XRes = -64", "YRes = 12"], "XRes = -64: the number of points must be at least 1"),
    (["XRes = abc", "YRes = 12"], "XRes = 'abc' is not an integer"),
    (["YRes = 12"], "the header has no XRes"),
    (["XRes = 16", "YRes = 12", "XReal = 0"], "XReal = '0': the size must be positive"),
    (["XRes = 16", "YRes = 12", "XReal = nan"], "XReal = 'nan': the size must be positive"),
    (["XRes = 16", "YRes = 12", "XYUnits = furlong"], "XYUnits: unknown length unit 'furlong'"),
    (["XRes = 100000", "YRes = 100000"], "100000 x 100000 points: 10000000000 exceed the limit"),
])
def test_gsf_header_values_are_checked_naming_the_key(tmp_path, lines, match):
    write_gsf(tmp_path / "a.gsf", lines)
    with pytest.raises(ValueError, match=match) as info:
        read_height_map(tmp_path / "a.gsf")
    assert "\n" not in str(info.value)


def test_a_fifo_or_a_device_is_not_read(tmp_path):
    fifo = tmp_path / "scan.csv"
    os.mkfifo(fifo)  # opening it for reading would block until a writer comes
    with pytest.raises(ValueError, match="not a regular file"):
        read_height_map(fifo)
    with pytest.raises(ValueError, match="not a regular file"):
        read_height_map("/dev/zero", layout="grid")


def test_a_text_file_over_the_size_limit_is_refused(tmp_path, monkeypatch):
    path = tmp_path / "map.csv"
    path.write_text("\n".join(",".join(f"{v:.17g}" for v in row) for row in Z))  # ~4.5 KB
    monkeypatch.setenv("ROUGHCONTACT_MAX_INPUT_MB", "0.001")
    with pytest.raises(ValueError, match="exceed the limit of .*ROUGHCONTACT_MAX_INPUT_MB"):
        read_height_map(path)
    monkeypatch.setenv("ROUGHCONTACT_MAX_INPUT_MB", "1")
    monkeypatch.setenv("ROUGHCONTACT_MAX_CELLS", "100")  # the table's 192 fields, counted before parsing
    with pytest.raises(ValueError, match="12 data lines of 16 fields: 192 exceed the limit of 100"):
        read_height_map(path)


def test_an_xyz_lattice_with_one_far_point_names_it(tmp_path):
    """A 49 x 50 lattice with one point at x = 1e7: all x were merged into one ("2450 points
    repeat") or a grid of tens of GiB was allocated; now the point and its line are named."""
    y, x = np.mgrid[0:50, 0:49]
    z = RNG.normal(size=x.size)
    xs = x.ravel().astype(float)
    xs[5] = 1e7
    path = tmp_path / "outlier.xyz"
    path.write_text(xyz_text(xs, y.ravel(), z, "x, y, z"))
    with pytest.raises(ValueError, match=r"line 7: the point x = 1e\+07, y = 0 lies far off the lattice of the "
                                         r"others \(x 0 to 48, y 0 to 49\)"):
        read_height_map(path)


def test_the_grid_the_points_span_is_checked_before_it_is_allocated(tmp_path, monkeypatch):
    """2000 points scattered over a 1000 x 1000 lattice: a grid of 10^6 cells for 6000 numbers of
    text; with the limit at 10^5 it is refused before np.full allocates it."""
    rng = np.random.default_rng(1)
    flat = rng.choice(1000 * 1000, size=2000, replace=False)
    flat[:4] = [0, 999, 999 * 1000, 999 * 1000 + 999]  # the corners: the lattice spans 1000 x 1000
    path = tmp_path / "sparse.xyz"
    path.write_text(xyz_text(flat % 1000 * 0.5, flat // 1000 * 0.5, rng.normal(size=flat.size), "x, y, z"))
    sparse = read_height_map(path)
    assert sparse.heights.shape == (1000, 1000)
    assert "2000 points fill 0 % of the 1000 x 1000 lattice" in sparse.notes[-1]
    monkeypatch.setenv("ROUGHCONTACT_MAX_CELLS", "100000")
    with pytest.raises(ValueError, match=r"the points' lattice \(x step 0.5, y step 0.5\) spans 1000 x 1000 grid "
                                         r"points: 1e\+06 exceed the limit of 100000 .*ROUGHCONTACT_MAX_CELLS"):
        read_height_map(path)


def test_a_latin1_header_and_line_ends(tmp_path):
    """Latin-1 'µm' (Windows instrument software) is read as µm; only LF/CR LF end lines (a
    form feed inside a comment does not start a data line)."""
    y, x = np.mgrid[0:12, 0:16]
    text = "# exported\x0c1, 2, 3\r\n" + xyz_text(x.ravel() * 0.5, y.ravel() * 0.25, Z.ravel(),
                                                 "x [µm], y [µm], z [nm]").replace("\n", "\r\n")
    path = tmp_path / "latin.xyz"
    path.write_bytes(text.encode("latin-1"))
    m = read_height_map(path)
    assert (m.xy_unit, m.z_unit, m.dx) == ("um", "nm", pytest.approx(0.5)) and m.heights.shape == (12, 16)
    assert any("read as Latin-1" in n for n in m.notes)


def test_coordinates_and_a_header_spacing_must_agree(tmp_path):
    grid = coordinate_grid(Z, 0.5 * np.arange(16), 0.5 * np.arange(12))
    path = tmp_path / "both.csv"
    path.write_text('"XY calibration","0.5","um/pixel"\n' + grid)
    m = read_height_map(path)
    assert (m.dx, m.dy, m.xy_unit) == (0.5, 0.5, "um")
    np.testing.assert_allclose(m.heights, Z)
    path.write_text('"XY calibration","1.25","um/pixel"\n' + grid)
    with pytest.raises(ValueError, match=r"coordinates in the first row and column \(step 0.5, 0.5\) contradict "
                                         r"the header's spacing \(1.25, 1.25\)"):
        read_height_map(path)


def test_instrument_errors_are_printable_and_an_empty_map_is_named(tmp_path):
    """SurfaceTopography quoted a corrupt .plu's bytes (control characters) in its message; an
    empty file of an extension no reader claims was read as a 0 x 0 map."""
    pytest.importorskip("SurfaceTopography")
    (tmp_path / "scan.plu").write_bytes(b"PK\x03\x04D\x8c\x9a\xad" + bytes(range(256)) * 2)
    with pytest.raises(ValueError, match=r"not a readable \.plu file") as info:
        read_height_map(tmp_path / "scan.plu")
    assert str(info.value).isprintable()
    (tmp_path / "scan.bin").write_bytes(b"")
    with pytest.raises(ValueError, match=r"scan.bin: the map has no points"):
        read_height_map(tmp_path / "scan.bin")


def test_an_instrument_channel_is_checked_against_the_cell_limit_before_it_is_read(tmp_path, monkeypatch):
    st = pytest.importorskip("SurfaceTopography")
    st.Topography(Z.T.copy(), physical_sizes=(8.0, 3.0), unit="um").to_x3p(str(tmp_path / "a.x3p"))
    assert read_height_map(tmp_path / "a.x3p").heights.shape == (12, 16)
    monkeypatch.setenv("ROUGHCONTACT_MAX_CELLS", "100")
    with pytest.raises(ValueError, match=r"a.x3p: channel 0 declares 16 x 12 points: 192 exceed the limit of 100"):
        read_height_map(tmp_path / "a.x3p")


@pytest.mark.parametrize("dx, rms, unit", [(2.0, 0.5, "nm"),      # an AFM scan
                                           (0.1, 0.005, "mm"),    # stylus profilometry in mm
                                           (0.8, 0.02, "um"),     # an optical profiler
                                           (2e-9, 3e-10, "m")])   # an AFM scan in SI units
def test_maps_of_real_instruments_are_not_doubted(dx, rms, unit):
    m = HeightMap(Z / np.std(Z) * rms, dx, dx, unit, unit, "npy")
    assert unit_warning(m, unit, unit, "scan") is None
