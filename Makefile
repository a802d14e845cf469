# `make test` and `make report` create .venv/ on first use and install pendulab into it:
# `make report` only what the report needs (pendulab[report]), `make test` everything
# (pendulab[test]). Each set has its own stamp, so one after the other installs what is missing.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin

.PHONY: check test lint docs report bench clean browser
.PRECIOUS: $(VENV)/.installed-%

$(BIN)/python:
	@echo "pendulab: creating $(VENV)/ with $(PYTHON) (once)"
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

$(VENV)/.installed-%: pyproject.toml | $(BIN)/python
	@echo "pendulab: installing pendulab[$*] and its dependencies into $(VENV)/ (once)"
	$(BIN)/python -m pip install --quiet -e '.[$*]'
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
# (a test tool's own browser download fails here). Other systems: see the README.
browser:
	@command -v chromium >/dev/null 2>&1 || command -v chromium-browser >/dev/null 2>&1 || \
		command -v google-chrome >/dev/null 2>&1 || { apt-get update -qq && \
		DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null; }

report: $(VENV)/.installed-report
	@echo "pendulab: writing report.pdf for the example group 262, 407, 634"
	$(BIN)/pendulab report --output report.pdf

bench: $(VENV)/.installed-test
	$(BIN)/python benchmarks/run.py

clean:
	rm -rf $(VENV) build src/*.egg-info docs/_build
