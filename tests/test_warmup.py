"""roughcontact.warmup: its parts run in this process, its command line runs them in two
processes, and it refuses bad arguments."""

import subprocess
import sys

import pytest

from roughcontact import warmup


def test_the_parts_run_in_this_process():
    warmup.warm_up(["rest"])  # a warm cache: loads, does not compile (make test warmed it)


def test_two_processes_run_every_part_and_exit_zero():
    r = subprocess.run([sys.executable, "-m", "roughcontact.warmup", "--jobs", "2"],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr


@pytest.mark.parametrize("argv", [["--jobs", "0"], ["--part", "nonsense"]])
def test_bad_arguments_are_refused(argv):
    with pytest.raises(SystemExit) as exc:
        warmup.main(argv)
    assert exc.value.code == 2
