"""roughcontact.io (issue 29): a netCDF write that fails on a full disk says so, naming the file
(netCDF reports only "NetCDF: HDF error"), and leaves nothing under the file's name."""

from __future__ import annotations

import errno
import os
import shutil

import numpy as np
import pytest
import xarray as xr

from roughcontact import io


def _dataset(n=1000):
    s = np.linspace(1.0, 3.5, n)
    return xr.Dataset({"pressure": ("s", 100.0 * np.exp(-s), {"units": "N/mm^2"})},
                      coords={"s": ("s", s, {"units": "1", "long_name": "separation"})})


def _fail_writing(monkeypatch, exc):
    """Dataset.to_netcdf writes part of the file, then fails with ``exc`` (as netCDF4 does)."""
    def to_netcdf(self, path, *args, **kwargs):
        with open(path, "wb") as f:
            f.write(b"\x89HDF\r\n\x1a\n partial")
        raise exc

    monkeypatch.setattr(xr.Dataset, "to_netcdf", to_netcdf)


def _free(monkeypatch, free):
    usage = shutil.disk_usage(os.getcwd())
    monkeypatch.setattr(shutil, "disk_usage", lambda path: usage._replace(free=free))


def test_hdf_error_on_a_full_disk_says_the_disk_is_full(tmp_path, monkeypatch):
    """netCDF4 raises RuntimeError('NetCDF: HDF error') on ENOSPC; the free space tells."""
    out = tmp_path / "m00_psi.nc"
    out.write_bytes(b"an earlier result")
    _fail_writing(monkeypatch, RuntimeError("NetCDF: HDF error"))
    _free(monkeypatch, 4096)
    with pytest.raises(io.WriteError) as info:
        io.write_netcdf(_dataset(), out, timestamp=False)
    message = str(info.value)
    assert isinstance(info.value, ValueError) and "\n" not in message
    assert message.startswith(f"netCDF file {out}: cannot write it (NetCDF: HDF error); the disk is full"), message
    assert "0.00391 MB free" in message and "nothing written" in message  # 4096 B = 0.00390625 MB
    assert out.read_bytes() == b"an earlier result"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m00_psi.nc"]  # the partial file removed


def test_free_space_below_the_data_size_counts_as_full(tmp_path, monkeypatch):
    ds = _dataset(200_000)  # 3.2 MB of data, above the 1 MiB floor
    _fail_writing(monkeypatch, RuntimeError("NetCDF: HDF error"))
    _free(monkeypatch, ds.nbytes - 1)
    with pytest.raises(io.WriteError, match="the disk is full"):
        io.write_netcdf(ds, tmp_path / "x.nc", timestamp=False)


def test_enospc_is_a_full_disk_whatever_the_free_space(tmp_path, monkeypatch):
    _fail_writing(monkeypatch, OSError(errno.ENOSPC, os.strerror(errno.ENOSPC)))
    _free(monkeypatch, 10 ** 12)
    with pytest.raises(io.WriteError, match=r"cannot write it \(No space left on device\); the disk is full: free") as info:
        io.write_netcdf(_dataset(), tmp_path / "x.nc", timestamp=False)
    assert "MB free" not in str(info.value)  # the free space is stated only where it is low
    assert list(tmp_path.iterdir()) == []


def test_a_quota_is_named_as_such(tmp_path, monkeypatch):
    _fail_writing(monkeypatch, OSError(errno.EDQUOT, os.strerror(errno.EDQUOT)))
    _free(monkeypatch, 10 ** 12)
    with pytest.raises(io.WriteError, match="your disk quota is exceeded") as info:
        io.write_netcdf(_dataset(), tmp_path / "x.nc", timestamp=False)
    assert "MB free" not in str(info.value)


def test_another_failure_is_not_called_a_full_disk(tmp_path, monkeypatch):
    _fail_writing(monkeypatch, RuntimeError("NetCDF: HDF error"))
    _free(monkeypatch, 10 ** 12)
    with pytest.raises(io.WriteError) as info:
        io.write_netcdf(_dataset(), tmp_path / "x.nc", timestamp=False)
    assert "disk is full" not in str(info.value) and str(tmp_path / "x.nc") in str(info.value)
    assert list(tmp_path.iterdir()) == []


def test_a_real_write_still_round_trips(tmp_path):
    path = io.write_netcdf(_dataset(10), tmp_path / "x.nc", timestamp=False)
    np.testing.assert_array_equal(io.read_netcdf(path)["pressure"].values, _dataset(10)["pressure"].values)
