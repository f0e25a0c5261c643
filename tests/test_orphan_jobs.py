"""Jobs left running by a Snakemake killed with SIGKILL are stopped before a resumed run starts
(roughcontact.orphan_jobs; issue 29: "kill -9 of snakemake leaves its job processes writing after
the parent died")."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from roughcontact.orphan_jobs import find_job_processes, stop_orphan_jobs

pytestmark = pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs Linux /proc")


def _job_script(workdir: Path, name: str = "tmpabc123.job.py") -> Path:
    """A stand-in for a Snakemake job script: ``<workdir>/.snakemake/scripts/tmp*.py`` that runs
    until stopped, with a child of its own (as fe_calculix's ccx run)."""
    scripts = workdir / ".snakemake" / "scripts"
    scripts.mkdir(parents=True, exist_ok=True)
    script = scripts / name
    script.write_text("import subprocess, sys, time\n"
                      "subprocess.Popen([sys.executable, '-c', 'import time; time.sleep(120)'])\n"
                      "time.sleep(120)\n")
    return script


def _wait_for(predicate, timeout: float = 10.0) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if predicate():
            return True
        time.sleep(0.05)
    return False


def _alive(pid: int) -> bool:
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def _children(pid: int) -> list[int]:
    out = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                if int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1]) == pid:
                    out.append(int(entry.name))
            except OSError:
                pass
    return out


def test_an_orphaned_job_and_its_child_are_stopped(tmp_path):
    script = _job_script(tmp_path)
    # started by a shell that exits at once: the job is re-parented, as after `kill -9 snakemake`
    pid = int(subprocess.run(["sh", "-c", f"'{sys.executable}' '{script}' >/dev/null 2>&1 & echo $!"],
                             capture_output=True, text=True, check=True).stdout)
    try:
        assert _wait_for(lambda: _children(pid))
        child = _children(pid)[0]
        jobs = find_job_processes(tmp_path)
        assert [(job.pid, job.orphan) for job in jobs] == [(pid, True)]
        lines = []
        stopped = stop_orphan_jobs(tmp_path, grace=5.0, report=lines.append)
        assert [job.pid for job in stopped] == [pid]
        assert len(lines) == 1 and f"pid {pid}" in lines[0] and str(script) in lines[0]
        assert _wait_for(lambda: not _alive(pid) and not _alive(child))
        assert find_job_processes(tmp_path) == []
    finally:
        for p in [pid, *_children(pid)]:
            try:
                os.kill(p, signal.SIGKILL)
            except ProcessLookupError:
                pass


def test_a_job_of_a_live_snakemake_is_reported_not_stopped(tmp_path):
    script = _job_script(tmp_path)
    # a parent whose program is called "snakemake", as the real one's console script
    parent = tmp_path / "bin" / "snakemake"
    parent.parent.mkdir()
    parent.write_text(f"#!{sys.executable}\nimport subprocess, sys\n"
                      f"subprocess.run([sys.executable, {str(script)!r}])\n")
    parent.chmod(0o755)
    run = subprocess.Popen([str(parent)])
    try:
        assert _wait_for(lambda: find_job_processes(tmp_path))
        (job,) = find_job_processes(tmp_path)
        assert not job.orphan
        lines = []
        assert stop_orphan_jobs(tmp_path, grace=0.5, report=lines.append) == []
        assert len(lines) == 1 and "another Snakemake" in lines[0]
        assert _alive(job.pid)
    finally:
        for p in _children(run.pid):
            for q in _children(p):
                os.kill(q, signal.SIGKILL)
            os.kill(p, signal.SIGKILL)
        run.kill()
        run.wait()


def test_snakemake_killed_hard_then_resumed_leaves_no_second_writer(tmp_path):
    """The real thing: a job of a Snakemake killed with SIGKILL keeps running; the resumed run
    (after --unlock) stops it in onstart and redoes the output."""
    snakemake = Path(sys.executable).parent / "snakemake"
    if not snakemake.exists():
        pytest.skip("snakemake (the workflow extra) is not installed")
    (tmp_path / "job.py").write_text(textwrap.dedent("""\
        import os, time
        # the killed run's job sleeps long; the resumed run's finishes at once
        time.sleep(float(os.environ.get("JOB_SLEEP", "0")))
        with open(snakemake.output[0], "w") as f:
            f.write(str(os.getpid()))
        """))
    (tmp_path / "Snakefile").write_text(textwrap.dedent("""\
        onstart:
            from roughcontact.orphan_jobs import stop_orphan_jobs
            stop_orphan_jobs(workflow.basedir, report=lambda line: print(line, flush=True))

        rule all:
            input: "out.txt"

        rule job:
            output: "out.txt"
            script: "job.py"
        """))
    env = {**os.environ, "JOB_SLEEP": "120"}
    first = subprocess.Popen([str(snakemake), "--cores", "1", "-q"], cwd=tmp_path, env=env,
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        assert _wait_for(lambda: find_job_processes(tmp_path), timeout=60)
        first.send_signal(signal.SIGKILL)
        first.wait()
        (orphan,) = find_job_processes(tmp_path)
        assert orphan.orphan
        subprocess.run([str(snakemake), "--unlock", "--cores", "1"], cwd=tmp_path, check=True,
                       capture_output=True)
        resumed = subprocess.run([str(snakemake), "--cores", "1", "--rerun-incomplete"], cwd=tmp_path,
                                 env={**os.environ, "JOB_SLEEP": "0"}, capture_output=True, text=True,
                                 timeout=120)
        assert resumed.returncode == 0, resumed.stderr[-2000:]
        assert f"pid {orphan.pid}" in resumed.stdout + resumed.stderr
        assert not _alive(orphan.pid)
        assert int((tmp_path / "out.txt").read_text()) != orphan.pid
    finally:
        for job in find_job_processes(tmp_path):
            os.kill(job.pid, signal.SIGKILL)
