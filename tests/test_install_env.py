"""tools/install_env.py (make venv): pip's registry configuration becomes uv's options, and
either installer path is taken as asked or on failure (both paths run on every CI run here; the
real uv install runs in `make test` on a clean clone)."""

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
spec = importlib.util.spec_from_file_location("install_env", ROOT / "tools" / "install_env.py")
install_env = importlib.util.module_from_spec(spec)
spec.loader.exec_module(install_env)

#: `pip config list` on this project's CI machines (files, then PIP_* variables)
SAMPLE = """\
:env:.cert='/etc/ssl/certs/ca-certificates.crt'
:env:.default-timeout='180'
:env:.disable-pip-version-check='1'
:env:.find-links='/opt/wheels'
global.cert='/etc/ssl/certs/other.crt'
global.constraint='/etc/xdg/pip/constraints.txt'
global.extra-index-url='file:///opt/pypi/simple file:///opt/pypi-more/simple'
global.find-links='/opt/other-wheels'
"""


def test_pip_config_is_parsed_with_environment_variables_overriding_files():
    cfg = install_env.parse_pip_config(SAMPLE)
    assert cfg["extra-index-url"] == ["file:///opt/pypi/simple", "file:///opt/pypi-more/simple"]
    assert cfg["find-links"] == ["/opt/wheels"] and cfg["cert"] == ["/etc/ssl/certs/ca-certificates.crt"]
    assert cfg["constraint"] == ["/etc/xdg/pip/constraints.txt"] and cfg["default-timeout"] == ["180"]
    assert "disable-pip-version-check" not in cfg


def test_uv_arguments_follow_pip(tmp_path):
    index = tmp_path / "simple"
    index.mkdir()
    wheels = tmp_path / "wheels"
    wheels.mkdir()
    cfg = {"index-url": ["https://pypi.example/simple"],
           "extra-index-url": [f"file://{index}", f"file://{tmp_path / 'missing'}", "https://extra.example/simple"],
           "find-links": [str(wheels), str(tmp_path / "nowhere")], "constraint": ["/c.txt"],
           "cert": ["/ca.pem"], "timeout": ["60"], "trusted-host": ["extra.example"]}
    args, env = install_env.uv_arguments(cfg)
    joined = " ".join(args)
    # pip takes the best version over all indexes; uv would stop at the first one that has it
    assert args[:2] == ["--index-strategy", "unsafe-best-match"]
    assert "--index-url https://pypi.example/simple" in joined
    assert f"--extra-index-url file://{index}" in joined and "missing" not in joined  # pip ignores it too
    assert "--extra-index-url https://extra.example/simple" in joined
    assert f"--find-links {wheels}" in joined and "nowhere" not in joined
    assert "--constraint /c.txt" in joined and "--allow-insecure-host extra.example" in joined
    assert env == {"SSL_CERT_FILE": "/ca.pem", "UV_HTTP_TIMEOUT": "60"}
    assert "--no-index" in install_env.uv_arguments({"no-index": ["true"]})[0]


@pytest.fixture
def recorded(monkeypatch, tmp_path):
    """Commands install_env would run, with uv's outcome chosen by the test."""
    calls = []
    outcome = {"uv": 0}

    def run(cmd, env=None):
        calls.append(cmd)
        uses_uv = "uv" in cmd or cmd[0].endswith("/uv")  # installing uv, or running it
        return outcome["uv"] if uses_uv else 0

    monkeypatch.setattr(install_env, "_run", run)
    monkeypatch.setattr(install_env, "pip_config", lambda python: {})
    python = str(tmp_path / "bin" / "python")
    return calls, outcome, python


def test_uv_path(recorded):
    calls, _, python = recorded
    assert install_env.install(python, ".[test]") == "uv"
    assert calls[0][-2:] == ["--quiet", "uv"] and calls[1][1:3] == ["pip", "install"]
    assert not any(c[1:4] == ["-m", "pip", "install"] and ".[test]" in c for c in calls)


def test_pip_fallback_when_uv_fails_and_when_asked(recorded):
    calls, outcome, python = recorded
    outcome["uv"] = 1
    assert install_env.install(python, ".[test]") == "pip"
    assert calls[-1] == [python, "-m", "pip", "install", "--quiet", "--editable", ".[test]"]
    calls.clear()
    outcome["uv"] = 0
    assert install_env.install(python, ".[test]", installer="pip") == "pip"
    assert len(calls) == 1 and "uv" not in calls[0]
    outcome["uv"] = 1
    with pytest.raises(SystemExit, match="uv was asked for"):
        install_env.install(python, ".[test]", installer="uv")


def test_makefile_installs_through_it():
    makefile = (ROOT / "Makefile").read_text()
    assert "tools/install_env.py --python $(PY)" in makefile
