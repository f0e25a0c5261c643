"""The SLURM tier (`make test-slurm`; marker ``slurm``): a one-node SLURM cluster started here
(munged, slurmctld and slurmd on localhost, the configuration written by the test, no
cgroups), a small m00 × ψ sweep submitted through Snakemake's SLURM executor with the
project's profile (workflow/profiles/slurm), and the merged dataset compared with a local run's
to the last bit. Skips with one line where the scheduler cannot start (no Slurm, not root, a
daemon that does not come up).

Why these settings (Debian's slurm-wlm 22.05): ``proctrack/linuxproc``, ``task/none`` and
``jobacct_gather/none`` need no cgroups; ``accounting_storage/none`` (no slurmdbd) leaves
``sacct`` without data ("Slurm accounting storage is disabled"), so the executor is told to
poll ``squeue --states=all`` (``--slurm-status-command squeue``), which sees finished jobs
for ``MinJobAge`` = 300 s, and to submit without an account (``--slurm-no-account``: finding
one asks ``sacctmgr``/``sshare``, which need slurmdbd). Memory is not a consumable
(``CR_Core``): the profile's 2000 MB per job is a request, not a limit.
"""

import importlib.util
import os
import shutil
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import yaml

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("workflow_tests", ROOT / "tests" / "test_workflow.py")
workflow_tests = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(workflow_tests)

pytestmark = pytest.mark.slurm

DAEMONS = ("munged", "slurmctld", "slurmd", "sbatch", "srun", "squeue", "sinfo", "scontrol")

#: the sweep: 2 × 2 (m00 × ψ) × 5 separations, split into two SLURM jobs along m00
SWEEP = {**workflow_tests.TINY_SWEEP, "axes": {"m00": [0.0625, 0.3125], "psi": [0.5, 2.0]},
         "s": {"start": 0.0, "stop": 2.0, "num": 5}}


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _node_line() -> str:
    """This machine as a Slurm node (``slurmd -C``), addressed on the loopback."""
    out = subprocess.run(["slurmd", "-C"], capture_output=True, text=True, timeout=30).stdout.splitlines()[0]
    fields = dict(f.split("=", 1) for f in out.split())
    cpus = fields.get("CPUs", "1")
    return f"NodeName={fields['NodeName']} NodeAddr=127.0.0.1 CPUs={cpus} RealMemory=4000 State=UNKNOWN"


def slurm_conf(d: Path, node: str) -> str:
    name = node.split()[0].split("=", 1)[1]
    return "\n".join([
        "ClusterName=roughcontact-test",
        f"SlurmctldHost={name}(127.0.0.1)",
        "SlurmUser=root",
        "SlurmdUser=root",
        "AuthType=auth/munge",
        "CredType=cred/munge",
        f"AuthInfo=socket={d / 'munge.socket'}",
        "ProctrackType=proctrack/linuxproc",
        "TaskPlugin=task/none",
        "JobAcctGatherType=jobacct_gather/none",
        "AccountingStorageType=accounting_storage/none",
        "JobCompType=jobcomp/none",
        "SelectType=select/cons_tres",
        "SelectTypeParameters=CR_Core",
        "MpiDefault=none",
        "SwitchType=switch/none",
        "SchedulerType=sched/builtin",
        "MinJobAge=300",
        "ReturnToService=2",
        f"SlurmctldPort={_free_port()}",
        f"SlurmdPort={_free_port()}",
        f"StateSaveLocation={d / 'state'}",
        f"SlurmdSpoolDir={d / 'spool'}",
        f"SlurmctldPidFile={d / 'slurmctld.pid'}",
        f"SlurmdPidFile={d / 'slurmd.pid'}",
        f"SlurmctldLogFile={d / 'slurmctld.log'}",
        f"SlurmdLogFile={d / 'slurmd.log'}",
        node,
        f"PartitionName=test Nodes={name} Default=YES MaxTime=INFINITE State=UP",
        "",
    ])


def _stop(pid_file: Path) -> None:
    try:
        os.kill(int(pid_file.read_text().split()[0]), signal.SIGTERM)
    except (OSError, ValueError):
        pass


@pytest.fixture(scope="module")
def slurm_cluster(tmp_path_factory):
    """A running one-node cluster; yields the environment its commands need (SLURM_CONF)."""
    missing = [p for p in DAEMONS if shutil.which(p) is None]
    if missing:
        pytest.skip(f"SLURM tier: {', '.join(missing)} not installed (apt-get install slurmctld slurmd slurm-client munge)")
    if os.geteuid() != 0:
        pytest.skip("SLURM tier: slurmd must run as root here")
    d = tmp_path_factory.mktemp("slurm")
    for sub in ("state", "spool"):
        (d / sub).mkdir()
    d.chmod(0o700)
    key = d / "munge.key"
    key.write_bytes(os.urandom(1024))
    key.chmod(0o600)
    conf = d / "slurm.conf"
    env = {**os.environ, "SLURM_CONF": str(conf)}
    started = []
    try:
        subprocess.run(["munged", "--force", f"--key-file={key}", f"--socket={d / 'munge.socket'}",
                        f"--pid-file={d / 'munged.pid'}", f"--log-file={d / 'munged.log'}",
                        f"--seed-file={d / 'munged.seed'}"], check=True, capture_output=True, timeout=30)
        started.append(d / "munged.pid")
        conf.write_text(slurm_conf(d, _node_line()))
        for daemon, pid in (("slurmctld", "slurmctld.pid"), ("slurmd", "slurmd.pid")):
            subprocess.run([daemon, "-f", str(conf)], check=True, capture_output=True, env=env, timeout=60)
            started.append(d / pid)
        deadline = time.monotonic() + 60
        state = ""
        while time.monotonic() < deadline:
            state = subprocess.run(["sinfo", "-h", "-o", "%t"], capture_output=True, text=True, env=env).stdout.strip()
            if state in ("idle", "mix", "alloc"):
                break
            time.sleep(0.5)
        else:
            log = (d / "slurmctld.log").read_text()[-300:] if (d / "slurmctld.log").exists() else ""
            pytest.skip(f"SLURM tier: the node did not come up (sinfo: {state!r}) {log.splitlines()[-1:] }")
    except (subprocess.CalledProcessError, subprocess.TimeoutExpired, OSError) as exc:
        for pid in reversed(started):
            _stop(pid)
        err = getattr(exc, "stderr", b"") or b""
        first = err.decode(errors="replace").strip().splitlines()[:1] if isinstance(err, bytes) else []
        pytest.skip(f"SLURM tier: the scheduler could not start ({exc.__class__.__name__}: {' '.join(first)})")
    yield env
    subprocess.run(["scontrol", "shutdown"], capture_output=True, env=env, timeout=30)
    time.sleep(1)
    for pid in reversed(started):
        _stop(pid)


def _clone(tmp_path, name):
    """A clone of the workflow with the sweep configured, its numba cache copied (the sources
    are identical: nothing recompiles)."""
    (tmp_path / name).mkdir()
    clone = workflow_tests.fresh_clone(tmp_path / name)
    for cache in (ROOT / "src").rglob("__pycache__"):
        dest = clone / "src" / cache.relative_to(ROOT / "src")
        if not dest.exists():
            shutil.copytree(cache, dest)
    cfg = yaml.safe_load((clone / "config" / "config.yaml").read_text())
    cfg["sweeps"] = {"tiny": SWEEP}
    # the gate samples the configured sweeps only (gate_anchors.curves.samples): none of this one
    cfg["gate_anchors"]["curves"]["samples"].pop("m00_psi")
    (clone / "config" / "config.yaml").write_text(yaml.safe_dump(cfg, sort_keys=False))
    return clone


def _srun_shim(tmp_path, env) -> Path:
    """A directory with an ``srun`` that sets SLURM_CONF and runs the real one. Inside a job,
    the executor's jobstep plugin (snakemake-executor-plugin-slurm-jobstep) starts the rule with
    ``srun`` after removing every SLURM_* variable but the job's identity, SLURM_CONF included;
    a site's slurm.conf sits in /etc/slurm, where srun finds it without the variable, but the
    test's cluster must not write there (the machine is shared), so srun is told where it is."""
    shim = tmp_path / "shim"
    shim.mkdir(exist_ok=True)
    srun = shim / "srun"
    srun.write_text(f"#!/bin/sh\nSLURM_CONF={env['SLURM_CONF']} exec {shutil.which('srun')} \"$@\"\n")
    srun.chmod(0o755)
    return shim


#: what the one-node test cluster needs on top of the project's profile (module docstring)
CLUSTER_OPTIONS = ("--slurm-status-command", "squeue", "--slurm-no-account",
                   "--slurm-init-seconds-before-status-checks", "2", "--latency-wait", "5")


def test_sweep_on_slurm_equals_the_local_run(slurm_cluster, tmp_path):
    """The local run first; then a copy of its tree without the sweep's outputs (the code
    hashes and the numba warm-up stamp kept, so only the sweep's jobs run again) runs the sweep
    on the cluster; the merged datasets agree to the last bit, and in every attribute but the
    time of writing."""
    from roughcontact import io

    env_path = f"{Path(sys.executable).parent}:{os.environ.get('PATH', '')}"
    local = _clone(tmp_path, "local")
    r = subprocess.run([sys.executable, "-m", "snakemake", "--cores", "2", "sweeps"], cwd=local,
                       capture_output=True, text=True, timeout=900, env={**os.environ, "PATH": env_path})
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]

    on_slurm = tmp_path / "slurm"
    shutil.copytree(local, on_slurm, ignore=shutil.ignore_patterns(".snakemake", "sweeps"))
    r = subprocess.run([sys.executable, "-m", "snakemake", "--profile", "workflow/profiles/slurm",
                        "--workflow-profile", "none", *CLUSTER_OPTIONS, "sweeps"],
                       cwd=on_slurm, capture_output=True, text=True, timeout=900,
                       env={**slurm_cluster, "PATH": f"{_srun_shim(tmp_path, slurm_cluster)}:{env_path}"})
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    # the parts ran as SLURM jobs (squeue keeps them for MinJobAge), the merge locally
    jobs = subprocess.run(["squeue", "--states=all", "-h", "-o", "%j|%T"], capture_output=True, text=True,
                          env=slurm_cluster).stdout.split()
    assert len(jobs) == SWEEP["split"]["jobs"] and all(j.endswith("|COMPLETED") for j in jobs), jobs
    assert "sweep_part" in r.stderr + r.stdout

    a = io.read_netcdf(on_slurm / "results/sweeps/tiny.nc")
    b = io.read_netcdf(local / "results/sweeps/tiny.nc")
    assert set(a.data_vars) == set(b.data_vars) and set(a.coords) == set(b.coords)
    for v in [*a.data_vars, *a.coords]:
        np.testing.assert_array_equal(a[v].values, b[v].values, err_msg=v)
    written = {"created_utc", "history"}  # when each file was written
    np.testing.assert_equal({k: v for k, v in a.attrs.items() if k not in written},  # NaN equals NaN here
                            {k: v for k, v in b.attrs.items() if k not in written})
