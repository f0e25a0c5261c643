"""Reading and writing results: xarray → netCDF with units and provenance, atomic writes, logs.

Every netCDF file the workflow writes carries in its global attributes

* ``roughcontact_version`` — the installed package version,
* ``git_commit`` — the commit of the source tree (``"unknown"`` outside a git checkout or
  before the first commit) and ``git_dirty`` (``"true"``/``"false"``/``"unknown"``),
* ``config_json`` / ``config_sha256`` — the configuration that produced it (canonical JSON),
* ``settings_json`` — the creation settings (method, accuracy preset, dps, ...),
* library versions (python, numpy, scipy, mpmath, numba, xarray) and ``created_utc``,
* the CF global attributes ``title`` (the dataset's own, else one naming the paper),
  ``history``, ``references`` (the paper and its DOI), ``institution``-free ``source`` and
  ``Conventions = "CF-1.8"``.

Variables follow CF (checked by tests/test_cf.py on every file the workflow writes): numeric
variables and coordinates carry UDUNITS ``units`` ("1" for pure numbers), meanings go in
``long_name``, every coordinate has a ``long_name``, string variables carry no ``units``.

The data are deterministic; only ``created_utc`` (and the commit) change between two runs
of the same configuration. Files are written to a temporary name and renamed into place, so
a job killed midway never leaves a half-written result for Snakemake to trust.
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import hashlib
import json
import logging
import math
import os
import platform
import subprocess
import sys
from pathlib import Path
from typing import Any, Iterator, Mapping

from .files import atomic_path
from .write_errors import WriteError, write_error

__all__ = [
    "git_commit",
    "git_dirty",
    "canonical_json",
    "config_sha256",
    "provenance_attrs",
    "write_netcdf",
    "WriteError",
    "write_error",
    "read_netcdf",
    "read_provenance",
    "REFERENCES",
    "check_cf_metadata",
    "write_text",
    "atomic_path",
    "log_to",
    "PROGRESS",
]

#: the logger of progress messages of long jobs: inside :func:`log_to` they go to the rule's
#: log *and* to the console (the terminal that runs Snakemake), one line each
PROGRESS = "roughcontact.progress"

_LIBRARIES = ("numpy", "scipy", "mpmath", "numba", "xarray", "netCDF4")

#: the CF ``references`` attribute of every file: the paper reproduced
REFERENCES = ("R. Buczkowski, M. Kleiber (2009), Statistical Models of Rough Surfaces for Finite Element "
              "3D-Contact Analysis, Arch. Comput. Methods Eng. 16:399-424, doi:10.1007/s11831-009-9037-2")
_TITLE = "roughcontact: statistical contact of anisotropic rough surfaces (Buczkowski & Kleiber 2009)"


def _git(args: list[str], cwd: str | os.PathLike | None) -> str | None:
    try:
        out = subprocess.run(
            ["git", *args],
            cwd=cwd,
            capture_output=True,
            text=True,
            timeout=10,
            check=True,
        )
    except (OSError, subprocess.SubprocessError):
        return None
    return out.stdout.strip()


def _source_dir() -> Path:
    return Path(__file__).resolve().parent


def git_commit(cwd: str | os.PathLike | None = None) -> str:
    """The full commit hash of the checkout containing ``cwd`` (default: this package's
    source), or ``"unknown"`` (no git, not a repository, no commit yet)."""
    sha = _git(["rev-parse", "--verify", "--quiet", "HEAD"], cwd or _source_dir())
    return sha if sha else "unknown"


def git_dirty(cwd: str | os.PathLike | None = None) -> str:
    """``"true"`` if tracked files differ from HEAD, ``"false"`` if clean, else ``"unknown"``."""
    if git_commit(cwd) == "unknown":
        return "unknown"
    status = _git(["status", "--porcelain", "--untracked-files=no"], cwd or _source_dir())
    if status is None:
        return "unknown"
    return "true" if status else "false"


def _jsonable(obj: Any) -> Any:
    """Plain JSON types for config objects (Snakemake's Namedlist/OrderedDict, numpy scalars)."""
    if isinstance(obj, Mapping):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, (str, bool)) or obj is None:
        return obj
    if isinstance(obj, int):
        return int(obj)
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else str(obj)
    try:  # numpy scalars and arrays
        import numpy as np

        if isinstance(obj, np.generic):
            return _jsonable(obj.item())
        if isinstance(obj, np.ndarray):
            return _jsonable(obj.tolist())
    except ImportError:  # pragma: no cover
        pass
    return str(obj)


def canonical_json(obj: Any) -> str:
    """Deterministic JSON (sorted keys, no whitespace) of a config-like object."""
    return json.dumps(_jsonable(obj), sort_keys=True, separators=(",", ":"), ensure_ascii=False)


def config_sha256(obj: Any) -> str:
    """SHA-256 of :func:`canonical_json` — equal configs give equal hashes."""
    return hashlib.sha256(canonical_json(obj).encode("utf-8")).hexdigest()


def _library_versions() -> dict[str, str]:
    from importlib.metadata import PackageNotFoundError, version

    out = {"python": platform.python_version()}
    for name in _LIBRARIES:
        try:
            out[name] = version(name)
        except PackageNotFoundError:
            out[name] = "not installed"
    return out


def provenance_attrs(
    config: Any = None,
    settings: Mapping[str, Any] | None = None,
    *,
    timestamp: bool = True,
) -> dict[str, str]:
    """Global attributes recording what produced a result (all values are strings, as netCDF
    attributes must be plain)."""
    from . import __version__

    attrs = {
        "roughcontact_version": str(__version__),
        "git_commit": git_commit(),
        "git_dirty": git_dirty(),
        "config_json": canonical_json(config if config is not None else {}),
        "config_sha256": config_sha256(config if config is not None else {}),
        "settings_json": canonical_json(settings if settings is not None else {}),
        "software_versions": canonical_json(_library_versions()),
        "source": "roughcontact (Buczkowski & Kleiber 2009 reproduction)",
        "references": REFERENCES,
        "Conventions": "CF-1.8",
        "history": f"written by roughcontact {__version__} (roughcontact.io.write_netcdf)",
    }
    if timestamp:
        attrs["created_utc"] = _dt.datetime.now(_dt.timezone.utc).replace(microsecond=0).isoformat()
        attrs["history"] = f"{attrs['created_utc']} {attrs['history']}"
    return attrs


def _is_text(var) -> bool:
    return var.dtype.kind in "USO"


def check_cf_metadata(ds) -> list[str]:
    """What keeps ``ds`` from the CF metadata this project writes (empty if nothing): a numeric
    variable or coordinate without ``units``, a coordinate without ``long_name``, a string
    variable with ``units``. (Whether a units string is valid UDUNITS is checked by the tests
    with cf-units, which the library does not depend on.)"""
    problems = []
    for name in list(ds.data_vars) + list(ds.coords):
        var = ds[name]
        if _is_text(var):
            if "units" in var.attrs:
                problems.append(f"{name}: a string variable has units")
        elif "units" not in var.attrs:
            problems.append(f"{name}: no units")
        if name in ds.coords and "long_name" not in var.attrs:
            problems.append(f"{name}: a coordinate without long_name")
    return problems


def _netcdf_attr(value: Any):
    """netCDF attributes take strings and numbers: encode the rest as JSON / text."""
    if isinstance(value, bool) or value is None:
        return str(value).lower() if isinstance(value, bool) else "none"
    if isinstance(value, (str, int, float)):
        return value
    if isinstance(value, (Mapping, list, tuple)):
        return canonical_json(value)
    return str(value)


def write_netcdf(
    ds,
    path: str | os.PathLike,
    *,
    config: Any = None,
    settings: Mapping[str, Any] | None = None,
    timestamp: bool = True,
) -> Path:
    """Write an ``xarray.Dataset`` to ``path`` (netCDF4) with provenance attributes.

    Existing dataset attributes are kept (provenance keys win; the dataset's ``title`` is
    kept, else a generic one is set); attribute values that netCDF cannot hold (dicts, lists,
    booleans, None) are stored as JSON/text. String variables lose a ``units`` attribute (CF:
    strings have none). A numeric variable without ``units`` or a coordinate without
    ``long_name`` is refused (ValueError naming them): every stored quantity says its unit.
    A failed write (a full disk, which netCDF reports only as "NetCDF: HDF error") is a
    :class:`WriteError` naming the file and saying whether the disk is full; the partial file is
    removed (files.atomic_path), nothing is left under ``path``.
    """
    path = Path(path)
    out = ds.copy()
    for name in list(out.data_vars) + list(out.coords):
        if _is_text(out[name]):
            out[name].attrs.pop("units", None)
    problems = check_cf_metadata(out)
    if problems:
        raise ValueError("not CF metadata: " + "; ".join(problems))
    attrs = {k: _netcdf_attr(v) for k, v in ds.attrs.items()}
    attrs.update(provenance_attrs(config, settings, timestamp=timestamp))
    attrs.setdefault("title", _TITLE)
    out.attrs = attrs
    for name in list(out.data_vars) + list(out.coords):
        out[name].attrs = {k: _netcdf_attr(v) for k, v in out[name].attrs.items()}
    with atomic_path(path) as tmp:
        try:
            out.to_netcdf(tmp, engine="netcdf4", format="NETCDF4")
        except (OSError, RuntimeError) as exc:  # netCDF4 raises RuntimeError for HDF errors
            # measured here, while the partial file still holds its blocks
            raise write_error(path, exc, "netCDF file", needed=int(out.nbytes)) from None
    return path


def read_netcdf(path: str | os.PathLike):
    """Load a netCDF file fully into memory and close it (no file handle left open)."""
    import xarray as xr

    with xr.open_dataset(path, engine="netcdf4") as ds:
        return ds.load()


def read_provenance(ds) -> dict[str, Any]:
    """The provenance attributes of a dataset, with the JSON ones decoded."""
    out: dict[str, Any] = {}
    for key in (
        "roughcontact_version",
        "git_commit",
        "git_dirty",
        "config_sha256",
        "created_utc",
    ):
        if key in ds.attrs:
            out[key] = ds.attrs[key]
    for key in ("config_json", "settings_json", "software_versions"):
        if key in ds.attrs:
            out[key.removesuffix("_json")] = json.loads(ds.attrs[key])
    return out


def write_text(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` to ``path`` atomically (temporary file + rename), creating parents."""
    path = Path(path)
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return path


@contextlib.contextmanager
def log_to(path: str | os.PathLike | None, level: int = logging.INFO) -> Iterator[logging.Logger]:
    """Send ``print`` output, warnings and ``logging`` records to ``path`` for the duration
    (a Snakemake rule's ``log:``); exceptions are logged with their traceback and re-raised.
    ``path=None`` logs to stderr. Records of the :data:`PROGRESS` logger also reach the
    console (the process's original stderr), tagged with the log's name, so a long job shows
    its progress where Snakemake runs, not only in ``logs/``."""
    logger = logging.getLogger("roughcontact.workflow")
    if path is None:
        handler: logging.Handler = logging.StreamHandler(sys.stderr)
        stream = None
    else:
        p = Path(path)
        p.parent.mkdir(parents=True, exist_ok=True)
        stream = open(p, "w", encoding="utf-8")
        handler = logging.StreamHandler(stream)
    handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(message)s"))
    root = logging.getLogger()
    old_level = root.level
    root.addHandler(handler)
    console = None
    if stream is not None:
        console = logging.StreamHandler(sys.__stderr__)
        console.setFormatter(logging.Formatter(f"%(asctime)s {Path(path).stem}: %(message)s", "%H:%M:%S"))
        console.addFilter(lambda record: record.name == PROGRESS)
        root.addHandler(console)
    root.setLevel(level)
    logging.captureWarnings(True)
    redirect = contextlib.ExitStack()
    if stream is not None:
        redirect.enter_context(contextlib.redirect_stdout(stream))
        redirect.enter_context(contextlib.redirect_stderr(stream))
    try:
        with redirect:
            try:
                yield logger
            except BaseException:
                logger.exception("failed")
                raise
    finally:
        logging.captureWarnings(False)
        root.removeHandler(handler)
        if console is not None:
            root.removeHandler(console)
        root.setLevel(old_level)
        handler.flush()
        if stream is not None:
            stream.close()
