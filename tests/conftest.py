"""Shared test helpers."""
import json
from pathlib import Path

import pytest

from pendulab.cli import main

#: Test files whose every test takes seconds (a server or a CLI in a subprocess, the
#: browser, Typst, Sphinx, a notebook kernel, ruff and mypy): the slow tier. ``make check``
#: runs the others (``-m "not slow"``) and ruff and mypy directly; ``make test`` runs all.
SLOW_FILES = frozenset({
    "test_boundary_cli.py", "test_docs.py", "test_lint.py", "test_notebook.py", "test_packaging.py",
    "test_report.py", "test_web_e2e.py", "test_web_lab_page.py", "test_web_load.py", "test_web_server.py",
})


def pytest_ignore_collect(collection_path, config):
    """``-m "not slow"`` (``make check``) does not even import the slow files: collecting
    them would import the browser driver, nbformat and pypdf for nothing."""
    if config.getoption("markexpr") == "not slow" and collection_path.name in SLOW_FILES:
        return True
    return None


@pytest.hookimpl(tryfirst=True)  # before -m deselects by marker
def pytest_collection_modifyitems(config, items):
    """Every test of a SLOW_FILES file is slow; a slow test elsewhere says so itself
    (``@pytest.mark.slow`` on the test)."""
    missing = sorted(name for name in SLOW_FILES if not (Path(__file__).parent / name).exists())
    if missing:
        raise pytest.UsageError(f"tests/conftest.py SLOW_FILES names files that do not exist: {missing}")
    for item in items:
        if item.path.name in SLOW_FILES:
            item.add_marker(pytest.mark.slow)


class Run:
    def __init__(self, code, out, err):
        self.code, self.out, self.err = code, out, err

    @property
    def json(self):
        return json.loads(self.out)


@pytest.fixture
def cli(capsys):
    """Run ``pendulab ARGS`` in-process; return exit code, stdout, stderr."""

    def run(*args):
        code = main([str(a) for a in args])
        captured = capsys.readouterr()
        return Run(code, captured.out, captured.err)

    return run


@pytest.fixture(scope="module")
def server():
    """The real command, ``pendulab serve --port N``, in a child until the module's tests are
    done: its base URL."""
    from served import serve_in_child

    with serve_in_child() as base:
        yield base


@pytest.fixture(scope="module")
def browser():
    """One headless Chromium for the module's tests (:func:`_browser.launched`)."""
    from _browser import launched

    with launched() as b:
        yield b


def assert_one_line_error(res, *fragments):
    """Exit status 2, one line on stderr naming what is wrong, no traceback."""
    assert res.code == 2, (res.out, res.err)
    lines = res.err.strip().splitlines()
    assert len(lines) == 1, res.err
    assert "Traceback" not in res.err
    for f in fragments:
        assert f in lines[0], (f, lines[0])
