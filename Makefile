# lagsolve: `make run` derives and simulates a shipped problem; `make test` runs every test.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
# the compiled templates and bytecode (python -m lagsolve.prepare) are made again when a template or module changes:
# a stale entry is never used (Jinja2 and Python check each against its source), only compiled at every command
READY  := $(VENV)/.prepared
SOURCES := $(wildcard templates/*/*.j2 src/lagsolve/*.py src/lagsolve/*/*.py src/lagsolve/*/*/*.py)

.PHONY: run test test-fast golden lint bench docs clean

$(STAMP): pyproject.toml
	test -d $(VENV) || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[dev]'
	touch $(STAMP)

$(READY): $(STAMP) $(SOURCES)
	$(BIN)/python -m lagsolve.prepare
	touch $(READY)

run: $(READY)
	$(BIN)/lagsolve derive problems/bead.yaml -o out/
	$(BIN)/lagsolve simulate problems/bead.yaml --plot -o out/

# PYTHONDONTWRITEBYTECODE emptied for the tests: each pytest worker would otherwise compile, and rewrite the
# assertions of, every test module at every run (about 6 s of each worker's start); the caches go in __pycache__
test: $(READY)
	$(BIN)/ruff check src tests bench
	$(BIN)/mypy
	PYTHONDONTWRITEBYTECODE= $(BIN)/python -m pytest -q -n auto

test-fast: $(READY)
	$(BIN)/ruff check src tests bench
	$(BIN)/mypy
	PYTHONDONTWRITEBYTECODE= $(BIN)/python -m pytest -q -n auto -m "not slow"

golden: $(READY)
	$(BIN)/lagsolve derive problems/*.yaml --golden tests/golden --update-golden
	for name in bead rotating_tube; do for to in python c; do \
		$(BIN)/lagsolve export problems/$$name.yaml --to $$to -o tests/golden/export || exit 1; done; done

lint: $(READY)
	$(BIN)/ruff check src tests bench
	$(BIN)/mypy

bench: $(READY)
	$(BIN)/python bench/derive.py
	$(BIN)/python bench/classics.py
	$(BIN)/python bench/simulate.py
	$(BIN)/python bench/scale.py
	$(BIN)/python bench/startup.py --phases
	$(BIN)/python bench/sweep.py
	$(BIN)/python bench/export.py
	$(BIN)/python bench/sweep_fast.py --numpy

docs: $(READY)
	$(BIN)/mkdocs build --strict

clean:
	rm -rf $(VENV) out build dist site .pytest_cache
