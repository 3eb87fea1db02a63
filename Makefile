# lagsolve: `make run` derives and simulates a shipped problem; `make test` runs every test.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: run test test-fast golden lint bench docs clean

$(STAMP): pyproject.toml
	test -d $(VENV) || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[dev]'
	$(BIN)/python -m lagsolve.prepare
	touch $(STAMP)

run: $(STAMP)
	$(BIN)/lagsolve derive problems/bead.yaml -o out/
	$(BIN)/lagsolve simulate problems/bead.yaml --plot -o out/

# PYTHONDONTWRITEBYTECODE emptied for the tests: each pytest worker would otherwise compile, and rewrite the
# assertions of, every test module at every run (about 6 s of each worker's start); the caches go in __pycache__
test: $(STAMP)
	$(BIN)/ruff check src tests bench
	$(BIN)/mypy
	PYTHONDONTWRITEBYTECODE= $(BIN)/python -m pytest -q -n auto

test-fast: $(STAMP)
	$(BIN)/ruff check src tests bench
	$(BIN)/mypy
	PYTHONDONTWRITEBYTECODE= $(BIN)/python -m pytest -q -n auto -m "not slow"

golden: $(STAMP)
	$(BIN)/lagsolve derive problems/*.yaml --golden tests/golden --update-golden
	for name in bead rotating_tube; do for to in python c; do \
		$(BIN)/lagsolve export problems/$$name.yaml --to $$to -o tests/golden/export || exit 1; done; done

lint: $(STAMP)
	$(BIN)/ruff check src tests bench
	$(BIN)/mypy

bench: $(STAMP)
	$(BIN)/python bench/derive.py
	$(BIN)/python bench/classics.py
	$(BIN)/python bench/simulate.py
	$(BIN)/python bench/scale.py
	$(BIN)/python bench/startup.py --phases
	$(BIN)/python bench/sweep.py
	$(BIN)/python bench/export.py
	$(BIN)/python bench/sweep_fast.py --numpy

docs: $(STAMP)
	$(BIN)/mkdocs build --strict

clean:
	rm -rf $(VENV) out build dist site .pytest_cache
