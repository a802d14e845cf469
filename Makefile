# `make test`, `make report` and `make notebook` create .venv/ on first use and install
# pendulab into it: `make report` only what the report needs (pendulab[report]), `make
# notebook` what the tutorial needs (pendulab[notebook]), `make test` everything
# (pendulab[test]). Each set has its own stamp, so one after the other installs what is
# missing. `make` alone lists the targets.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin

.DEFAULT_GOAL := help
.PHONY: help check test lint docs report notebook tutorial bench clean browser
.PRECIOUS: $(VENV)/.installed-%

help:
	@echo "pendulab: make TARGET (the first one creates .venv/ and installs into it, a few minutes)"
	@echo "  make report     report.pdf for the example group 262, 407, 634"
	@echo "  make notebook   open the tutorial (examples/tutorial.ipynb) in JupyterLab"
	@echo "  make tutorial   run the tutorial from top to bottom, headless, in a fresh kernel"
	@echo "  make check      for every change: ruff, mypy and the tests not marked slow"
	@echo "  make test       every test (CI runs it)"
	@echo "  make docs       the API reference and the guides, into docs/_build/html"
	@echo "  make bench      the benchmarks, as ratios against their peers"
	@echo "  make clean      remove .venv/ and the built docs"
	@echo "then: .venv/bin/pendulab --help"

$(BIN)/python:
	@echo "pendulab: creating $(VENV)/ with $(PYTHON) (once)"
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

# pip's own progress (each download, then the install), not --quiet: the first install takes
# minutes (numba, scipy, and with [test] a browser driver and JupyterLab).
$(VENV)/.installed-%: pyproject.toml | $(BIN)/python
	@echo "pendulab: installing pendulab[$*] and its dependencies into $(VENV)/ (once; pip shows its progress)"
	$(BIN)/python -m pip install --progress-bar on -e '.[$*]'
	@echo "pendulab: installed; the command is $(BIN)/pendulab (or: source $(BIN)/activate)"
	touch $@

# The fast tier, for every change: lint, types, and the tests not marked slow (tests/conftest.py
# lists the slow ones). `make test` runs every test, the slow ones too (CI runs it).
check: $(VENV)/.installed-test
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/mypy
	$(BIN)/python -m pytest -n 2 -q -m "not slow"

test: $(VENV)/.installed-test browser
	$(BIN)/python -m pytest -n 2

# ruff and mypy, configured in pyproject.toml (the tests run them too: tests/test_lint.py).
lint: $(VENV)/.installed-test
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/mypy

# The API reference and the narrative pages, into docs/_build/html (warnings are errors).
docs: $(VENV)/.installed-docs
	$(BIN)/sphinx-build -W --keep-going -q -b html docs docs/_build/html

# The browser test drives a Chromium; on a machine without one, install Debian's
# (a test tool's own browser download fails here). The PDF tests read text boxes with
# poppler's pdftotext. Other systems: see the README.
browser:
	@command -v chromium >/dev/null 2>&1 || command -v chromium-browser >/dev/null 2>&1 || \
		command -v google-chrome >/dev/null 2>&1 || { apt-get update -qq && \
		DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null; }
	@command -v pdftotext >/dev/null 2>&1 || { apt-get update -qq && \
		DEBIAN_FRONTEND=noninteractive apt-get install -y -qq poppler-utils >/dev/null; }

report: $(VENV)/.installed-report
	@echo "pendulab: writing report.pdf for the example group 262, 407, 634"
	$(BIN)/pendulab report --output report.pdf

# The tutorial in JupyterLab (the browser opens it; Ctrl+C in this terminal stops the server).
notebook: $(VENV)/.installed-notebook
	$(BIN)/jupyter lab examples/tutorial.ipynb

# The tutorial from top to bottom in a fresh kernel, without a browser (nbclient): an error
# in any cell stops it with the cell and the traceback.
tutorial: $(VENV)/.installed-notebook
	$(BIN)/jupyter execute --kernel_name=python3 examples/tutorial.ipynb
	@echo "pendulab: the tutorial ran without an error"

bench: $(VENV)/.installed-test
	$(BIN)/python benchmarks/run.py
	$(BIN)/python benchmarks/workloads.py

clean:
	rm -rf $(VENV) build src/*.egg-info docs/_build
