"""Install the project into a virtual environment with uv (falling back to pip).

    python tools/install_env.py --python .venv/bin/python --spec '.[workflow,test,docs,cluster]'
        [--installer auto|uv|pip]

Run by ``make venv`` (and so by ``make test`` / ``make reproduce``) after ``python -m venv``.
``uv`` (a Rust installer, itself one wheel on PyPI) resolves and installs the ~90 packages in
parallel; it is installed into the venv with pip first. uv does not read pip's configuration,
so the registry settings pip would use are translated: ``pip config list`` (files and PIP_*
variables) gives index-url, extra-index-url, find-links, constraint, cert, timeout,
trusted-host, no-index, and they become uv's options; pip considers every index and takes the
best version, uv by default stops at the first index that has a package, hence
``--index-strategy unsafe-best-match``. A ``file://`` index or find-links directory that does
not exist is dropped (pip ignores it with a warning; uv would fail). If uv cannot be installed
or its install fails, pip installs the same specification (``--installer pip`` forces it).
The lower bounds are pyproject.toml's, for either installer. Standard library only.
"""

from __future__ import annotations

import argparse
import os
import shlex
import subprocess
import sys
import time
from pathlib import Path
from urllib.parse import urlparse

#: pip configuration keys that change where packages come from, and how
KEYS = ("index-url", "extra-index-url", "find-links", "constraint", "cert", "timeout", "default-timeout",
        "trusted-host", "no-index")


def pip_config(python: str) -> dict[str, list[str]]:
    """{key: values} of ``pip config list`` for the KEYS (later scopes override earlier ones,
    as pip applies them: global < user < site < environment variables)."""
    res = subprocess.run([python, "-m", "pip", "config", "list"], capture_output=True, text=True)
    return parse_pip_config(res.stdout)


def parse_pip_config(text: str) -> dict[str, list[str]]:
    """The KEYS of ``pip config list`` output (``section.key='value'`` lines; ``:env:.key`` for
    PIP_* variables, which override the files)."""
    files: dict[str, list[str]] = {}
    env: dict[str, list[str]] = {}
    for line in text.splitlines():
        name, sep, value = line.partition("=")
        if not sep:
            continue
        section, _, key = name.strip().rpartition(".")
        if key in KEYS:
            (env if section == ":env:" else files)[key] = shlex.split(value.strip().strip("'\""))
    return {**files, **env}


def _local_path_missing(location: str) -> bool:
    """A file:// URL or a plain path that does not exist on this machine."""
    if "://" in location:
        parsed = urlparse(location)
        return parsed.scheme == "file" and not Path(parsed.path).exists()
    return not Path(location).exists()


def uv_arguments(config: dict[str, list[str]]) -> tuple[list[str], dict[str, str]]:
    """uv pip install options and environment variables equivalent to pip's ``config``."""
    args = ["--index-strategy", "unsafe-best-match"]
    env: dict[str, str] = {}
    for url in config.get("index-url", [])[:1]:
        args += ["--index-url", url]
    for url in config.get("extra-index-url", []):
        if not (url.startswith("file:") and _local_path_missing(url)):
            args += ["--extra-index-url", url]
    for loc in config.get("find-links", []):
        if not _local_path_missing(loc):
            args += ["--find-links", loc]
    for path in config.get("constraint", []):
        args += ["--constraint", path]
    for host in config.get("trusted-host", []):
        args += ["--allow-insecure-host", host]
    if config.get("no-index", ["false"])[0].lower() in ("1", "true", "yes", "on"):
        args.append("--no-index")
    if config.get("cert"):
        env["SSL_CERT_FILE"] = config["cert"][0]
    timeout = (config.get("timeout") or config.get("default-timeout") or [None])[0]
    if timeout:
        env["UV_HTTP_TIMEOUT"] = str(int(float(timeout)))
    return args, env


def _run(cmd: list[str], env: dict[str, str] | None = None) -> int:
    print("+", " ".join(shlex.quote(c) for c in cmd), flush=True)
    return subprocess.run(cmd, env={**os.environ, **(env or {})}).returncode


def install(python: str, spec: str, installer: str = "auto") -> str:
    """Install ``spec`` (editable) into the environment of ``python``; returns the installer used.
    Raises SystemExit if pip fails too."""
    bin_dir = Path(python).parent
    if installer in ("auto", "uv"):
        uv = bin_dir / "uv"
        if uv.exists() or _run([python, "-m", "pip", "install", "--quiet", "uv"]) == 0:
            args, env = uv_arguments(pip_config(python))
            # --compile-bytecode: pip writes the packages' .pyc at install, uv does not; where
            # PYTHONDONTWRITEBYTECODE is set (containers) no .pyc was ever written and every
            # process compiled scipy, xarray, numba ... from source again (~4.5 s each)
            if _run([str(uv), "pip", "install", "--python", python, *args, "--compile-bytecode", "--editable", spec],
                    env) == 0:
                return "uv"
            print("uv could not install the environment: falling back to pip", file=sys.stderr)
        else:
            print("uv could not be installed: falling back to pip", file=sys.stderr)
        if installer == "uv":
            raise SystemExit("uv was asked for and failed")
    if _run([python, "-m", "pip", "install", "--quiet", "--editable", spec]) != 0:
        raise SystemExit("pip could not install the environment")
    return "pip"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--python", required=True, help="the virtual environment's interpreter")
    ap.add_argument("--spec", required=True, help="what to install (editable), e.g. '.[workflow,test]'")
    ap.add_argument("--installer", choices=("auto", "uv", "pip"), default=os.environ.get("INSTALLER", "auto"))
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    used = install(args.python, args.spec, args.installer)
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"installed {args.spec} with {used} in {time.perf_counter() - t0:.0f} s (load average {load:.1f})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
