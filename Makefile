# equimesh: the README's two commands are `make reproduce` and `make test`.
#
# Both create .venv with `$(PYTHON) -m venv` on first use (Python >= 3.11) and
# install the project into it with `pip install -e '.[test,bench]'` and then, one
# by one and only where they install, the optional extras; later runs reuse it and
# reinstall only when pyproject.toml is newer than the stamp file.
# Nothing outside .venv is installed, so a machine with Python 3.11+ and make
# is enough.

SHELL := /bin/bash

PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.equimesh-installed
EXTRAS_STAMP := $(VENV)/.equimesh-extras-installed

# Optional extras `make reproduce` and `make test` install when they can
# (pyproject.toml [project.optional-dependencies]): peers = gmsh and pymeshlab
# for experiments/compare_peers.py, rhino = rhino3dm for .3dm input and output,
# compas and dxf (ezdxf) for COMPAS and DXF output, report = plotly for the
# HTML report, dask for sweeps on a cluster, fast = cvxopt (CHOLMOD) and
# mkl = pypardiso (MKL PARDISO) for the optimisation's factorisations.  An
# extra that cannot be installed (no wheel for this platform, no network) is
# reported and skipped: the experiments then compare what they can and the
# tests that need it are skipped with the reason, so CI tests every extra that
# is installable.
OPTIONAL_EXTRAS ?= peers rhino compas dxf report dask fast mkl

# Every experiment script, in the order `make reproduce` runs them.  Each one
# has `main(argv)`, prints its progress and writes results/ (and, for figure
# scripts, paper_figs/).  Add a new experiment by appending it here; arguments
# follow the script after a colon (`script.py:--option`).
EXPERIMENTS := \
	experiments/ratio_sweep.py \
	experiments/problem2.py \
	experiments/sharp_corners.py \
	experiments/sharp_sweep.py \
	experiments/table1.py \
	experiments/figures.py \
	experiments/compare_peers.py \
	experiments/scaling.py \
	experiments/scaling.py:--pipeline \
	experiments/bounded.py \
	experiments/bounded_sweep.py \
	experiments/optimisation_work.py \
	experiments/pardiso_threads.py \
	experiments/optimisation_levers.py \
	experiments/feature_angle.py \
	experiments/inputs.py \
	experiments/fabrication.py \
	experiments/classes_sweep.py

# The hypothesis profile comes from EQUIMESH_HYPOTHESIS_PROFILE (tests/conftest.py;
# quick "ci" when unset); `make test-thorough` selects the thorough one.

# Single-threaded BLAS: the solvers work on many small vectors, where BLAS
# threads cost far more than they give on 2 cores.  Figures are drawn headless.
export OPENBLAS_NUM_THREADS ?= 1
export OMP_NUM_THREADS ?= 1
export MPLBACKEND ?= Agg

PYTEST_ARGS ?= -n 2 -q
# Extra arguments for `asv run`, e.g. `make bench ASV_ARGS=--quick`.
ASV_ARGS ?=
# `make bench-history`: the commits to measure (a git range).
RANGE ?= HEAD~20..HEAD
# `make bench-compare`: the commit to compare HEAD with (default: the merge
# base with main, or HEAD~1 on main) and the factor that counts as a change.
BASE ?=
FACTOR ?= 1.2
# `make mutation`: modules to mutate (default: every module of tools/mutation/modules.py).
MODULES ?=
# and options of `python -m tools.mutation` (e.g. --survivors, --max-children 1, --check, --report).
MUTATION_ARGS ?=
MUTATION_STAMP := $(VENV)/.equimesh-mutation-installed

.PHONY: test test-thorough reproduce bench bench-history bench-compare bench-publish mutation venv clean-venv browser

# Lint and format check first (ruff, configured in pyproject.toml), then the tests.
LINTED := src tests experiments benchmarks tools

test: $(STAMP) $(EXTRAS_STAMP) browser
	$(VENV)/bin/ruff check $(wildcard $(LINTED))
	$(VENV)/bin/ruff format --check $(wildcard $(LINTED))
	$(PY) -m pytest $(PYTEST_ARGS)

test-thorough: $(STAMP) $(EXTRAS_STAMP) browser
	EQUIMESH_HYPOTHESIS_PROFILE=thorough $(PY) -m pytest $(PYTEST_ARGS)

reproduce: $(STAMP) $(EXTRAS_STAMP)
	@set -e; for entry in $(EXPERIMENTS); do \
		script=$${entry%%:*}; args=$${entry#"$$script"}; args=$${args//:/ }; \
		if [ ! -f "$$script" ]; then echo "make reproduce: $$script is missing" >&2; exit 1; fi; \
		echo "==> $(PY) $$script$$args"; \
		$(PY) "$$script" $$args; \
	done; \
	echo "==> make reproduce: all experiments done"

# asv runs in this project's own .venv (environment "existing") and writes
# only under the gitignored .asv/ (see benchmarks/asv.conf.json).  Results
# are recorded against HEAD; uncommitted changes are measured as they are.
bench: $(STAMP)
	@commit=$$(git rev-parse HEAD) || { echo "make bench: needs a git checkout (asv records results per commit)" >&2; exit 1; }; \
	set -ex; cd benchmarks; \
	../$(VENV)/bin/asv machine --yes >/dev/null; \
	../$(VENV)/bin/asv run --environment existing:../$(PY) --set-commit-hash $$commit --show-stderr $(ASV_ARGS)

# Performance history: every commit of RANGE, each in a virtualenv that asv
# builds from the repository (benchmarks/asv.conf.json); commits measured
# before on this machine are skipped.  Results: .asv/results/<machine>/.
bench-history: $(STAMP)
	cd benchmarks && ../$(VENV)/bin/asv machine --yes >/dev/null && \
		../$(VENV)/bin/asv run --skip-existing-commits --show-stderr $(ASV_ARGS) "$(RANGE)"

# HEAD against BASE: prints the benchmarks that changed by more than FACTOR
# and fails (non-zero exit) when one got slower.  BASE is checked before the
# .venv is made, so a wrong one fails at once.
bench-compare:
	@base="$(BASE)"; \
	if [ -z "$$base" ]; then \
		main=$$(git rev-parse --verify -q main || git rev-parse --verify -q origin/main) || { \
			echo "make bench-compare: no branch main to compare with; give BASE=<commit>" >&2; exit 2; }; \
		base=$$(git merge-base "$$main" HEAD); \
		if [ "$$base" = "$$(git rev-parse HEAD)" ]; then base=$$(git rev-parse HEAD~1); fi; \
	fi; \
	git rev-parse --verify -q "$$base^{commit}" >/dev/null || { \
		echo "make bench-compare: unknown base commit '$$base'" >&2; exit 2; }; \
	$(MAKE) --no-print-directory venv || exit $$?; \
	echo "==> HEAD against $$base, factor $(FACTOR)"; \
	cd benchmarks && ../$(VENV)/bin/asv machine --yes >/dev/null && \
		../$(VENV)/bin/asv continuous --factor $(FACTOR) --split --show-stderr $(ASV_ARGS) "$$base" HEAD

bench-publish: $(STAMP)
	cd benchmarks && ../$(VENV)/bin/asv publish
	@echo "==> open .asv/html/index.html (or: cd benchmarks && ../$(VENV)/bin/asv preview)"

# Mutation testing of the algorithm modules (not part of `make test`; see
# docs/development.md): writes results/mutation.md and .json.
mutation: $(MUTATION_STAMP)
	$(PY) -m tools.mutation $(MUTATION_ARGS) $(MODULES)

$(MUTATION_STAMP): $(STAMP)
	$(PY) -m pip install -e '.[test,bench,mutation]'
	touch $(MUTATION_STAMP)

venv: $(STAMP)

# Headless Chromium for the report's browser tests (tests/io/test_report_browser.py): installed with
# apt-get only when it is missing and apt-get is usable (as root); otherwise nothing, and those tests
# are skipped with the reason.
browser:
	@if ! command -v chromium >/dev/null 2>&1 && [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
		echo "==> installing chromium (apt-get) for the report's browser tests"; \
		{ apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium; } \
			|| echo "make: chromium not installed; the browser tests will be skipped" >&2; \
	fi

# Install (again) only when pyproject.toml changed since the last install.
$(STAMP): pyproject.toml | $(PY)
	$(PY) -m pip install -e '.[test,bench]'
	touch $(STAMP)

# Each optional extra on its own, so that one failing leaves the others installed.
$(EXTRAS_STAMP): pyproject.toml | $(STAMP)
	@for extra in $(OPTIONAL_EXTRAS); do \
		echo "==> optional extra [$$extra]"; \
		$(PY) -m pip install -q -e ".[$$extra]" || echo "make: optional extra [$$extra] not installed; continuing without it" >&2; \
	done
	touch $(EXTRAS_STAMP)

$(PY):
	@$(PYTHON) -c 'import sys; sys.exit(sys.version_info < (3, 11))' 2>/dev/null || { \
		echo "equimesh needs Python >= 3.11, but '$(PYTHON)' is" \
			"$$($(PYTHON) --version 2>/dev/null || echo 'not found')." >&2; \
		echo "Run again with e.g. 'make PYTHON=python3.11 ...'." >&2; \
		exit 1; }
	@echo "==> creating $(VENV) with $$($(PYTHON) --version)"
	@{ $(PYTHON) -m venv $(VENV) && $(PY) -m pip --version >/dev/null 2>&1; } || { \
		rm -rf $(VENV); \
		echo "'$(PYTHON) -m venv' could not make a virtual environment with pip" \
			"(on Debian/Ubuntu: apt install python3-venv)." >&2; \
		exit 1; }

clean-venv:
	rm -rf $(VENV)
