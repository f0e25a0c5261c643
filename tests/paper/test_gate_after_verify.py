"""Issue 22's acceptance, end to end: a 5 % scale of the beam results, with ``ccx`` hidden, turns
``snakemake verify`` red.

It needs a finished ``snakemake verify`` in this checkout (CI runs it after its step 3; marker
``after_verify``, deselected otherwise). In a scratch copy of the checkout (tracked files, results,
figures, logs and Snakemake's metadata, modification times kept) every written beam deflection is
multiplied by 1.05 — what the audit did inside the engine's beam run (then fe/beam.py, now
roughcontact.examples.beam.run_beam), applied to the results the gate reads, so
that only the rules downstream of the beam runs run again instead of the twelve beam runs — and
``snakemake verify`` is run with a PATH that lacks ccx. The gate must fail, and fail on the
anchors of roughcontact.paper.fe_anchors, which need no optional tool.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCALE = 1.05

pytestmark = pytest.mark.after_verify


def _path_without(program: str, bin_dir: Path) -> str:
    """A PATH of one directory of symlinks to every program on today's PATH except ``program``."""
    bin_dir.mkdir()
    for d in os.environ.get("PATH", "").split(os.pathsep):
        if not d or not Path(d).is_dir():
            continue
        for entry in Path(d).iterdir():
            target = bin_dir / entry.name
            if entry.name != program and not target.exists() and os.access(entry, os.X_OK):
                target.symlink_to(entry)
    return str(bin_dir)


def _copy_checkout(dest: Path) -> None:
    """Tracked files and the workflow's state, modification times kept (Snakemake's mtime trigger)."""
    files = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, check=True, capture_output=True).stdout
    for rel in filter(None, files.decode().split("\0")):
        src = ROOT / rel
        if src.is_file():
            (dest / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dest / rel)
    for state in ("results", "paper_figures", "logs", ".snakemake"):
        if (ROOT / state).exists():
            shutil.copytree(ROOT / state, dest / state, symlinks=True,
                            ignore=shutil.ignore_patterns("locks", "incomplete", "shadow", "conda"))


def _scale_beam_results(results: Path) -> int:
    """Every beam run's deflections (the variables and attributes the checks read) times SCALE."""
    import xarray as xr

    n = 0
    for path in sorted((results / "fe" / "beam").glob("*/*.nc")):
        with xr.open_dataset(path) as ds:
            ds = ds.load()
        for name in ("u_N_um", "point_u_N_um"):
            ds[name] = ds[name] * SCALE
        for name in ("u_N_centre_um", "u_N_end_um"):
            ds.attrs[name] = ds.attrs[name] * SCALE
        ds.to_netcdf(path.with_suffix(".part"))
        path.with_suffix(".part").replace(path)
        n += 1
    for stamp in (results / "fe" / "beam").glob("*/.snakemake_timestamp"):
        stamp.touch()  # how Snakemake dates a directory output: as if the beam jobs had just run
    return n


def _reference_dps(results: Path) -> int:
    """The precision the finished run used (CI's profile: 12; the default: 20)."""
    return int(json.loads((results / "verify" / "summary.json").read_text())["provenance"]["reference dps"])


def test_a_five_percent_beam_scale_turns_snakemake_verify_red_without_ccx(tmp_path):
    if not (ROOT / "results" / "verify" / "passed").exists():
        pytest.skip("needs a finished `snakemake verify` in this checkout")
    repo = tmp_path / "repo"
    _copy_checkout(repo)
    assert _scale_beam_results(repo / "results") >= 12
    env = {**os.environ, "PATH": _path_without("ccx", tmp_path / "bin")}
    snakemake = Path(sys.executable).parent / "snakemake"
    cmd = [str(snakemake), "--snakefile", str(repo / "Snakefile"), "--directory", str(repo), "--cores", "2",
           "--workflow-profile", "none", "--config", f"reference_dps={_reference_dps(ROOT / 'results')}",
           # only what is downstream of the scaled files runs again, not what the finished run's
           # profile set otherwise (CI's benchmark_mode: the benchmark's params would differ)
           "--rerun-triggers", "mtime", "--keep-going", "verify"]
    proc = subprocess.run(cmd, cwd=repo, env=env, capture_output=True, text=True, timeout=1200)
    out = proc.stdout + proc.stderr
    assert proc.returncode != 0, out[-3000:]
    summary = json.loads((repo / "results" / "verify" / "summary.json").read_text())
    assert not summary["passed"]
    red = [i for i in summary["regression_ids"] if i.startswith("numerics:fe_beam_anchor/")]
    # the centre, the end and the profile of every anchored run (the equilibrium of the
    # pressures is blind to a deflection error)
    assert red and {i.split("/")[2] for i in red} >= {"u_N_centre", "u_N_end", "u_N_profile"}, red
    assert "verification FAILED" in out and "REGRESSION numerics:fe_beam_anchor/" in out
    # ccx was hidden: the CalculiX scene was skipped, not run
    assert "ccx" in (repo / "paper_figures" / "calculix.md").read_text()
    assert not (repo / "results" / "verify" / "calculix.checks.csv").read_text().strip().splitlines()[1:]
