# roughcontact — one entry point for a fresh machine with Python 3.11 and pip.
#
#   make reproduce   create .venv (if missing), install, run the whole Snakemake workflow
#   make test        create .venv (if missing), install, run the test suite (fast tier, < 3 min)
#
# Other targets: profile (CPU and wall time of a reproduction by job, the critical path), test-slow (the slow tier: mpmath references, workflow runs; CI: test-slow-ci), test-all, test-slurm,
# bench (speed against error, full mode), bench-fe (FE: block-on-base deck vs CalculiX, linear solvers, large contact interfaces), verify (verification report and verdict gate only),
# docs (API reference, Sphinx, warnings are errors), dry-run, ci (.ci/run), clean (generated results),
# distclean (+ .venv).

SHELL := /bin/bash
.DEFAULT_GOAL := help

VENV   ?= .venv
BIN    := $(VENV)/bin
PY     := $(BIN)/python
# The first of python3.11, python3.12, python3.13, python3 that is >= 3.11 (3.11: development
# and CI; 3.12, 3.13: tests/test_optional_tools.py where installed). PYTHON=... overrides.
PYTHON ?= $(shell for p in python3.11 python3.12 python3.13 python3; do \
	command -v $$p >/dev/null 2>&1 && $$p -c 'import sys; sys.exit(sys.version_info < (3, 11))' 2>/dev/null \
	&& { command -v $$p; break; }; done)
CORES  ?= all
# pytest workers (pytest-xdist): the tests are independent; "auto" = one per core; --dist worksteal:
# an idle worker takes tests queued for a busy one (a few tests run ~1 min: the static split left
# one worker idle at the end)
WORKERS ?= auto
PYTEST := $(PY) -m pytest -n $(WORKERS) --dist worksteal
# --scheduler greedy: the default ILP scheduler builds a pulp model and runs the cbc solver on
# every pass of Snakemake's scheduling loop; on 2 cores the greedy choice is as good and its
# CPU is negligible (the Snakemake process's own CPU: `make profile`)
SNAKEMAKE := $(BIN)/snakemake --workflow-profile workflow/profiles/default --cores $(CORES) --scheduler greedy
# Re-install only when the package metadata changes (the install is editable: source edits
# need no re-install).
STAMP  := $(VENV)/.installed
# when this make started, and whether .venv/ existed then: the set-up time (creating .venv/ and
# installing) is recorded in .venv/.setup.json and reported with the workflow's wall time
MAKE_START := $(shell date +%s)
VENV_EXISTED := $(wildcard $(PY))
LOAD_START := $(shell cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)

.PHONY: help venv reproduce profile bench bench-fe test test-slow test-slow-ci test-all test-slurm verify docs dry-run ccx-build ci clean distclean

help:
	@sed -n '3,9p' Makefile

$(PY):
	@test -n "$(PYTHON)" || { echo "error: no Python >= 3.11 found (tried python3.11, python3.12, python3.13, python3): install Python 3.11, or set PYTHON=/path/to/python3.11" >&2; exit 1; }
	@$(PYTHON) -c 'import sys; sys.exit(0 if sys.version_info >= (3, 11) else "error: Python >= 3.11 needed, found " + sys.version.split()[0])'
	$(PYTHON) -m venv $(VENV) || { rm -rf $(VENV); echo "error: '$(PYTHON) -m venv' failed (Debian/Ubuntu: apt-get install python3-venv, or python3.11-venv)" >&2; exit 1; }

# uv (a wheel, installed into the venv by pip) with pip's registry configuration, else pip
# (tools/install_env.py; INSTALLER=pip forces pip)
$(STAMP): pyproject.toml tools/install_env.py | $(PY)
	$(PY) tools/install_env.py --python $(PY) --spec '.[workflow,test,docs,cluster,measure,bem]' || { echo "error: could not install roughcontact into $(VENV) with Python $$($(PY) -c 'import platform; print(platform.python_version())') (tested: 3.11, 3.12, 3.13); the installer's message is above" >&2; exit 1; }
	@$(PY) workflow/scripts/record_wall_time.py setup --make-start $(MAKE_START) \
	    --created $(if $(VENV_EXISTED),no,yes) --load-start "$(LOAD_START)" --out $(VENV)/.setup.json
	@touch $@

venv: $(STAMP)

# The package's bytecode is written first: where PYTHONDONTWRITEBYTECODE is set (containers)
# no import writes it, and every process compiled src/ again (~0.5 s each; the installer
# compiles the dependencies, tools/install_env.py); up to date, this takes 0.2 s
BYTECODE := $(PY) -m compileall -q -j 0 src

# the wall time of the whole workflow is recorded in paper_figures/reproduction_time.md
reproduce: $(STAMP)
	@fresh=$$(test -d results && echo no || echo yes); start=$$(date +%s); \
	$(BYTECODE) && $(SNAKEMAKE) all && \
	$(PY) workflow/scripts/record_wall_time.py --seconds $$(( $$(date +%s) - start )) --cores $(CORES) --fresh $$fresh \
	    --setup $(VENV)/.setup.json --make-start $(MAKE_START) --load-start "$(LOAD_START)"

# the profile of a whole reproduction from scratch (results/, paper_figures/, logs/ and numba's
# cache removed; .venv/ kept): CPU and wall time by job, by rule and by phase, and the critical
# path, in results/benchmarks/workflow_profile.md and .csv (benchmarks/workflow_profile.py)
profile: $(STAMP)
	$(PY) benchmarks/workflow_profile.py

# speed against error, full mode (~5 min on 2 cores; the naive tplquad, 10-60 min per quantity,
# runs only where benchmarks/data/tplquad.json has no record; mpmath references are cached)
bench: $(STAMP)
	$(SNAKEMAKE) speed_vs_error --config benchmark_mode=full

# FE: the block-on-base deck in CalculiX and in the engine, refined 1x, 2x, 3x (3.4k-67k dofs;
# results/benchmarks/fe_block_on_base/; the 3x ccx run takes most of the time), then the linear
# strategies (sparse refactorisation vs condensed bulk) on the beam, coarse to fine meshes, the
# large contact interface (plate on base) and C3D10 against C3D20 in both codes
bench-fe: $(STAMP)
	$(PY) benchmarks/fe_block_on_base.py
	$(PY) benchmarks/fe_linear_solvers.py
	$(PY) benchmarks/fe_large_interface.py
	$(PY) benchmarks/fe_tetra_vs_ccx.py

# pyproject.toml deselects the mpmath- and slow-marked tests by default ("fast by default")
# numba's on-disk cache filled before the workers start (roughcontact.warmup: on a fresh clone
# ~55 s in two processes; each pytest worker would otherwise compile the same kernels, ~70 s
# each; with a warm cache ~3 s)
WARM := $(BYTECODE) && $(PY) -m roughcontact.warmup --jobs 2

test: $(STAMP)
	$(WARM)
	$(PYTEST)

test-slow: $(STAMP)
	$(WARM)
	$(PYTEST) -m "mpmath or slow"

# the slow tier as CI runs it (20-minute budget): without the tests that build whole new
# environments (venv_install: a library-only `pip install .`, Python 3.12/3.13; CI's own `make`
# builds an environment from scratch on every run) and the elasto-plastic twin comparisons at
# rtol 1e-10 (ep_twin: minutes each; CI checks the same kernels in the gate's ep_numerics scene
# and the fast tier's coarse twin test) and three tests of 26-48 s whose subject CI checks in
# another form (ci_elsewhere, named in each docstring); `make test-slow` runs them all
test-slow-ci: $(STAMP)
	$(WARM)
	$(PYTEST) -m "(mpmath or slow) and not venv_install and not ep_twin and not ci_elsewhere"

test-all: $(STAMP)
	$(WARM)
	$(PYTEST) -m ""

# the SLURM tier: a one-node cluster (munged, slurmctld, slurmd as root) started by the test;
# skips with one line where it cannot start (docs/sweeps.rst)
test-slurm: $(STAMP)
	$(PY) -m pytest -n 0 -m slurm tests/test_slurm.py

verify: $(STAMP)
	$(BYTECODE)
	$(SNAKEMAKE) verify

# the API reference from the docstrings (docs/_build/html; -W: a warning fails the build)
docs: $(STAMP)
	$(BIN)/sphinx-build -q -W --keep-going -b html docs docs/_build/html

# CalculiX 2.20 with the interface law as a user element (roughcontact ccx build, docs/ccx.md):
# 3-15 min the first time, then cached outside the clone (~/.cache/roughcontact); where the build
# tools or the source are absent it says in one line what to install, and what needs it skips
ccx-build: $(STAMP)
	$(BIN)/roughcontact ccx build || echo "ccx-build: no CalculiX with the law (the line above says why); tests/ccx and the scene ccx_friction skip"

dry-run: $(STAMP)
	$(BIN)/snakemake -n all

ci:
	bash .ci/run

clean:
	rm -rf results paper_figures logs .snakemake docs/_build

distclean: clean
	rm -rf $(VENV) src/*.egg-info
