"""roughcontact.io: netCDF with units and provenance, atomic writes, logs."""

import json
import logging
import subprocess
import warnings

import numpy as np
import pytest
import xarray as xr

from roughcontact import __version__, io


def _dataset():
    s = np.linspace(1.0, 3.5, 6)
    return xr.Dataset(
        {"pressure": ("s", 100.0 * np.exp(-s), {"units": "N/mm^2"})},
        coords={"s": ("s", s, {"units": "1", "long_name": "separation"})},
        attrs={"model": "gw", "hertz": None, "flag": True, "surface": {"m00": 0.0625}},
    )


def test_round_trip_keeps_data_units_and_provenance(tmp_path):
    config = {"scene": "table1", "s": [1.0, 1.5], "nested": {"b": 2, "a": 1}}
    path = io.write_netcdf(_dataset(), tmp_path / "sub" / "x.nc", config=config,
                           settings={"method": "production", "dps": None})
    ds = io.read_netcdf(path)
    np.testing.assert_array_equal(ds["pressure"].values, _dataset()["pressure"].values)
    assert ds["pressure"].attrs["units"] == "N/mm^2" and ds["s"].attrs["units"] == "1"
    assert ds.attrs["model"] == "gw" and ds.attrs["hertz"] == "none" and ds.attrs["flag"] == "true"
    assert json.loads(ds.attrs["surface"]) == {"m00": 0.0625}
    prov = io.read_provenance(ds)
    assert prov["roughcontact_version"] == __version__
    assert prov["config"] == config
    assert prov["config_sha256"] == io.config_sha256(config)
    assert prov["settings"] == {"method": "production", "dps": None}
    assert set(prov["software_versions"]) >= {"python", "numpy", "xarray", "netCDF4"}
    assert prov["git_commit"] == "unknown" or len(prov["git_commit"]) == 40
    assert "created_utc" in prov
    assert not list((tmp_path / "sub").glob("*.part"))  # no temporary file left behind


def test_data_are_deterministic_without_timestamp(tmp_path):
    a = io.write_netcdf(_dataset(), tmp_path / "a.nc", config={"x": 1}, timestamp=False)
    b = io.write_netcdf(_dataset(), tmp_path / "b.nc", config={"x": 1}, timestamp=False)
    da, db = io.read_netcdf(a), io.read_netcdf(b)
    assert da.identical(db)
    assert "created_utc" not in da.attrs


def test_every_variable_needs_units(tmp_path):
    ds = _dataset()
    ds["area"] = ("s", np.ones(6))
    with pytest.raises(ValueError, match="area"):
        io.write_netcdf(ds, tmp_path / "x.nc")
    assert not (tmp_path / "x.nc").exists()


def test_cf_metadata_global_attributes_and_string_units(tmp_path):
    ds = _dataset().assign_coords(label=("s", [f"p{i}" for i in range(6)], {"units": "1", "long_name": "point"}))
    out = io.read_netcdf(io.write_netcdf(ds, tmp_path / "x.nc"))
    assert "units" not in out["label"].attrs  # CF: no units on strings
    assert out.attrs["Conventions"] == "CF-1.8" and "doi:10.1007/s11831-009-9037-2" in out.attrs["references"]
    assert out.attrs["title"] and out.attrs["history"].startswith(out.attrs["created_utc"])
    assert io.check_cf_metadata(out) == []


def test_coordinates_need_long_name(tmp_path):
    ds = _dataset()
    del ds["s"].attrs["long_name"]
    with pytest.raises(ValueError, match="s: a coordinate without long_name"):
        io.write_netcdf(ds, tmp_path / "x.nc")


def test_config_hash_is_canonical():
    assert io.config_sha256({"a": 1, "b": [1, 2]}) == io.config_sha256({"b": [1, 2], "a": 1})
    assert io.config_sha256({"a": 1}) != io.config_sha256({"a": 2})
    assert io.canonical_json({"x": np.float64(0.5), "y": (1, 2), "z": float("nan")}) == '{"x":0.5,"y":[1,2],"z":"nan"}'


def test_git_commit_outside_a_repository_is_unknown(tmp_path):
    assert io.git_commit(tmp_path) == "unknown"
    assert io.git_dirty(tmp_path) == "unknown"


def test_git_commit_of_a_repository(tmp_path):
    def git(*args):
        subprocess.run(["git", *args], cwd=tmp_path, check=True, capture_output=True)

    try:
        git("init", "-q")
        (tmp_path / "f").write_text("1")
        git("add", "f")
        git("-c", "user.name=t", "-c", "user.email=t@t", "commit", "-q", "-m", "x")
    except (OSError, subprocess.CalledProcessError):
        pytest.skip("git not available")
    sha = io.git_commit(tmp_path)
    assert len(sha) == 40
    assert io.git_dirty(tmp_path) == "false"
    (tmp_path / "f").write_text("2")
    assert io.git_dirty(tmp_path) == "true"


def test_write_text_is_atomic_and_creates_parents(tmp_path):
    p = io.write_text(tmp_path / "a" / "b.md", "hello\n")
    assert p.read_text() == "hello\n"
    assert [q.name for q in p.parent.iterdir()] == ["b.md"]


def test_log_to_captures_prints_logging_warnings_and_errors(tmp_path):
    log = tmp_path / "logs" / "x.log"
    with io.log_to(log) as logger:
        print("printed line")
        logger.info("logged line")
        warnings.warn("a warning")
    text = log.read_text()
    assert "printed line" in text and "logged line" in text and "a warning" in text
    with pytest.raises(RuntimeError):
        with io.log_to(log):
            raise RuntimeError("boom")
    assert "boom" in log.read_text() and "Traceback" in log.read_text()
    # handlers are removed afterwards
    assert all(getattr(h, "stream", None) is None or not h.stream.closed for h in logging.getLogger().handlers)


def test_progress_reaches_the_console_and_the_log(tmp_path, capfd):
    import logging

    with io.log_to(tmp_path / "rule.log") as logger:
        logger.info("detail only in the log")
        logging.getLogger(io.PROGRESS).info("part 1/2 done")
    err = capfd.readouterr().err
    assert "rule: part 1/2 done" in err and "detail only in the log" not in err
    text = (tmp_path / "rule.log").read_text()
    assert "part 1/2 done" in text and "detail only in the log" in text
