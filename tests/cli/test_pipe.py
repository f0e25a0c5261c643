"""`roughcontact … | head -1`: a reader that goes away ends the command quietly (issue 22: it
ended with a BrokenPipeError traceback, and a second one from the interpreter's final flush).

Run through a real shell pipe. The output (~100 kB) is larger than a pipe's buffer (64 kB on
Linux), so the writer is still writing when ``head`` exits and the broken pipe is certain."""

import shlex
import subprocess
import sys

import pytest

from roughcontact.cli import EXIT_BROKEN_PIPE

RATIOS = " ".join(str(1 + i / 10) for i in range(3000))


@pytest.mark.parametrize("fmt", ["--json", ""])
def test_closed_pipe_exits_quietly(fmt):
    cmd = f"{shlex.quote(sys.executable)} -m roughcontact mindlin --b2-over-a2 {RATIOS} --nu 0.25 {fmt}"
    r = subprocess.run(["bash", "-o", "pipefail", "-c", f"{cmd} | head -1"], capture_output=True, text=True,
                       timeout=120)
    assert r.stderr == ""  # no traceback, no "Exception ignored" from the final flush
    assert r.returncode == EXIT_BROKEN_PIPE == 141  # 128 + SIGPIPE, as `seq 1 100000 | head -1` gives
    lines = r.stdout.splitlines()
    assert len(lines) == 1 and (lines[0] == "{" if fmt else lines[0].strip())
    # (exit 141 proves the pipe broke: an output that fitted the pipe's buffer would end with 0)
