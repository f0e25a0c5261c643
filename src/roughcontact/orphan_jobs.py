"""The jobs of a Snakemake run that was killed hard (SIGKILL, the OOM killer, a closed terminal):
found and stopped before a new run starts in the same directory (no physics; Linux ``/proc``).

Snakemake runs each ``script:`` job as a child process ``python <workdir>/.snakemake/scripts/
tmpXXXX.<name>.py``. Killed with SIGKILL, Snakemake cannot stop its children: they are re-parented
(to init or a sub-reaper) and go on computing and writing into ``results/`` — beside the jobs of
the run that resumes after ``snakemake --unlock``, which redoes the same outputs. The workflow's
``onstart`` calls :func:`stop_orphan_jobs` first: every job process of this directory with no
live Snakemake among its ancestors is stopped (SIGTERM, then SIGKILL after a grace period), with
one line each. A job of another *live* Snakemake in the same directory (possible only after a
manual ``--unlock``) is not touched; it is reported, since two runs would write the same files.
"""

from __future__ import annotations

import os
import signal
import time
from dataclasses import dataclass
from pathlib import Path

__all__ = ["JobProcess", "find_job_processes", "stop_orphan_jobs"]

_PROC = Path("/proc")


@dataclass(frozen=True)
class JobProcess:
    """A process running a job script of the Snakemake directory ``workdir``."""

    pid: int
    command: str
    orphan: bool  # no live Snakemake among its ancestors


def _cmdline(pid: int) -> list[str]:
    try:
        raw = (_PROC / str(pid) / "cmdline").read_bytes()
    except OSError:
        return []
    return [part.decode(errors="replace") for part in raw.split(b"\0") if part]


def _parent(pid: int) -> int:
    """The parent pid from /proc/PID/stat (0 when the process is gone)."""
    try:
        stat = (_PROC / str(pid) / "stat").read_text()
    except OSError:
        return 0
    # "pid (comm) state ppid ...": comm may hold spaces and parentheses, so split after the last ")"
    return int(stat.rsplit(")", 1)[1].split()[1])


def _is_snakemake(pid: int) -> bool:
    return any(Path(arg).name == "snakemake" or arg == "snakemake" for arg in _cmdline(pid)[:3])


def _has_snakemake_ancestor(pid: int) -> bool:
    seen = set()
    pid = _parent(pid)
    while pid > 1 and pid not in seen:
        if _is_snakemake(pid):
            return True
        seen.add(pid)
        pid = _parent(pid)
    return False


def find_job_processes(workdir: str | os.PathLike, *, exclude: int | None = None) -> list[JobProcess]:
    """Processes running a job script of the Snakemake directory ``workdir`` (their command line
    names ``<workdir>/.snakemake/scripts/``), other than ``exclude`` (default: the calling
    process). Empty where /proc is not available."""
    scripts = str(Path(workdir).resolve() / ".snakemake" / "scripts") + os.sep
    me = os.getpid() if exclude is None else exclude
    found = []
    if not _PROC.is_dir():
        return found
    for entry in _PROC.iterdir():
        if not entry.name.isdigit() or int(entry.name) == me:
            continue
        pid = int(entry.name)
        args = _cmdline(pid)
        if any(arg.startswith(scripts) for arg in args):
            found.append(JobProcess(pid, " ".join(args), orphan=not _has_snakemake_ancestor(pid)))
    return sorted(found, key=lambda job: job.pid)


def _descendants(pids: list[int]) -> list[int]:
    """Every live descendant of ``pids`` (a job's own children, e.g. a ccx run it started)."""
    children: dict[int, list[int]] = {}
    for entry in _PROC.iterdir():
        if entry.name.isdigit():
            children.setdefault(_parent(int(entry.name)), []).append(int(entry.name))
    found, stack = [], list(pids)
    while stack:
        for child in children.get(stack.pop(), []):
            found.append(child)
            stack.append(child)
    return found


def _alive(pid: int) -> bool:
    try:
        state = (_PROC / str(pid) / "stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z"  # a zombie has stopped; only its parent's wait is missing


def stop_orphan_jobs(workdir: str | os.PathLike, *, grace: float = 5.0, report=print) -> list[JobProcess]:
    """Stop the orphaned job processes of ``workdir`` (:func:`find_job_processes`): SIGTERM, then
    SIGKILL for those still alive after ``grace`` seconds. ``report`` gets one line per process
    stopped, and one per job of another live Snakemake (not stopped). Returns the orphans."""
    jobs = find_job_processes(workdir)
    orphans = [job for job in jobs if job.orphan]
    for job in jobs:
        if not job.orphan:
            report(f"another Snakemake is running jobs in {workdir} (pid {job.pid}: {job.command}); "
                   "two runs write the same files: stop one of them")
    for job in orphans:
        report(f"stopping a job left running by a killed Snakemake: pid {job.pid}: {job.command}")
    # the jobs' own children first: a job stopped before them leaves them re-parented and running
    pids = _descendants([job.pid for job in orphans])[::-1] + [job.pid for job in orphans]
    for sig in (signal.SIGTERM, signal.SIGKILL):
        for pid in pids:
            try:
                os.kill(pid, sig)
            except ProcessLookupError:
                pass
        deadline = time.monotonic() + grace
        while any(map(_alive, pids)) and time.monotonic() < deadline:
            time.sleep(0.05)
    return orphans
