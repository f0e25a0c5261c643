"""benchmarks/workflow_profile.py: Snakemake's log read into jobs, Python processes attributed to
them, the critical path — on a hand-written log and records whose answers are worked out here."""

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("workflow_profile", ROOT / "benchmarks" / "workflow_profile.py")
wp = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(wp)

LOG = """\
[Sat Nov 28 18:53:53 2026]
localrule code_fingerprint:
    output: results/code/a.py.0123456789abcdef.sha256
    log: logs/code/a.log
    jobid: 3
    reason: Missing output files
    resources: tmpdir=/tmp
[Sat Nov 28 18:53:54 2026]
Finished jobid: 3 (Rule: code_fingerprint)
[Sat Nov 28 18:53:54 2026]
rule production:
    input: results/code/a.py.0123456789abcdef.sha256
    output: results/production/table1/gw.nc
    log: logs/production/table1/gw.log
    jobid: 2
    wildcards: scene=table1, model=gw
[Sat Nov 28 18:53:54 2026]
rule fe_punch_case:
    input: results/code/a.py.0123456789abcdef.sha256
    output: results/fe/punch/quadratic-main
    log: logs/fe/punch/quadratic-main.log
    jobid: 4
[Sat Nov 28 18:54:04 2026]
Finished jobid: 2 (Rule: production)
[Sat Nov 28 18:54:24 2026]
Finished jobid: 4 (Rule: fe_punch_case)
[Sat Nov 28 18:54:24 2026]
localrule table:
    input: results/production/table1/gw.nc, results/fe/punch/quadratic-main/a.nc
    output: paper_figures/table1.md, paper_figures/table1.csv
    log: logs/table/table1.log
    jobid: 1
[Sat Nov 28 18:54:27 2026]
Finished jobid: 1 (Rule: table)
"""


def _jobs(tmp_path):
    path = tmp_path / "snakemake.log"
    path.write_text(LOG)
    return wp.parse_snakemake_log(path)


def test_log_parsed_into_jobs_with_inputs_outputs_and_times(tmp_path):
    jobs = _jobs(tmp_path)
    assert sorted(jobs) == [1, 2, 3, 4]
    assert jobs[1]["rule"] == "table" and jobs[1]["output"] == ["paper_figures/table1.md", "paper_figures/table1.csv"]
    assert jobs[1]["input"] == ["results/production/table1/gw.nc", "results/fe/punch/quadratic-main/a.nc"]
    assert jobs[2]["end"] - jobs[2]["start"] == 10.0  # 18:53:54 -> 18:54:04
    assert jobs[4]["end"] - jobs[4]["start"] == 30.0


def test_processes_attributed_and_nested_children_not_counted_twice(tmp_path):
    jobs = _jobs(tmp_path)
    t = jobs[2]["start"]
    records = [
        # the Snakemake process itself
        {"pid": 1, "ppid": 0, "start": t - 5, "end": t + 40, "cpu_self": 7.0, "cpu_children": 50.0,
         "argv": ["/venv/bin/snakemake", "all"]},
        # a script: job, known by its outputs
        {"pid": 2, "ppid": 1, "start": t + 0.2, "end": t + 9.5, "cpu_self": 8.0, "cpu_children": 0.0,
         "argv": ["python", "x.production.py"], "rule": "production", "output": ["results/production/table1/gw.nc"]},
        # a shell: job's python, known by its parent's command line (the log path)
        {"pid": 3, "ppid": 9, "start": t + 0.5, "end": t + 29.0, "cpu_self": 20.0, "cpu_children": 6.0,
         "argv": ["python", "-m", "x"], "parent": "bash -c python -m x > logs/fe/punch/quadratic-main.log"},
        # its worker process: already in pid 3's children time
        {"pid": 4, "ppid": 3, "start": t + 1.0, "end": t + 20.0, "cpu_self": 6.0, "cpu_children": 0.0,
         "argv": ["python", "worker"], "parent": "python -m x"},
    ]
    main, unattributed = wp.attribute(jobs, records)
    assert main["pid"] == 1 and unattributed == []
    assert jobs[2]["cpu"] == 8.0 and jobs[2]["procs"] == 1
    assert jobs[4]["cpu"] == 26.0 and jobs[4]["procs"] == 1
    assert wp.wall(jobs[2]) == pytest.approx(9.5 - 0.2)  # the process's own clock, finer than the log's seconds
    assert wp.wall(jobs[1]) == 3.0  # no Python process: the log's timestamps


def test_critical_path_is_the_longest_chain(tmp_path):
    jobs = _jobs(tmp_path)
    wp.attribute(jobs, [])
    length, chain = wp.critical_path(jobs)
    # fingerprint (1 s) -> punch (30 s, through the file inside its directory output) -> table (3 s);
    # the production branch (10 s) is shorter
    assert chain == [3, 4, 1]
    assert length == pytest.approx(1.0 + 30.0 + 3.0)
