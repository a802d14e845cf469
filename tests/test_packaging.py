"""Packaging: the version, the lean core and the one-line message for a missing extra."""
import io
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

import pendulab
from conftest import assert_one_line_error

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())
# Every package an extra brings; the core must work with all of them absent.
OPTIONAL = ("matplotlib", "typst", "rich", "fastapi", "uvicorn", "orjson", "swagger_ui_bundle", "pyarrow", "dask", "distributed", "pandas")


def test_version_is_single_sourced(cli):
    project = PYPROJECT["project"]
    assert "version" in project["dynamic"] and "version" not in project
    assert PYPROJECT["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "pendulab.core.version.__version__"}
    assert re.fullmatch(r"\d+\.\d+\.\d+", pendulab.__version__)
    res = cli("--version")
    assert res.code == 0
    assert res.out.strip() == f"pendulab, version {pendulab.__version__}"


def test_metadata_licence_and_typed_marker():
    assert PYPROJECT["project"]["license"] == "MIT"  # an SPDX expression, not a table
    assert (ROOT / "src" / "pendulab" / "py.typed").is_file()
    assert "py.typed" in PYPROJECT["tool"]["setuptools"]["package-data"]["pendulab"]


def test_core_dependencies_are_lean():
    names = {re.match(r"[A-Za-z0-9_.-]+", d).group(0).lower() for d in PYPROJECT["project"]["dependencies"]}
    # python-flint: `pendulab period` prints digits proved by its Arb balls.
    assert {"numpy", "scipy", "mpmath", "numba", "click", "python-flint"} <= names
    assert not names & set(OPTIONAL)  # no report, web, sweep, dask or pandas stack in the core
    extras = PYPROJECT["project"]["optional-dependencies"]
    for extra in ("report", "web", "sweep", "dask", "test", "docs", "all"):
        assert extra in extras


def test_each_optional_package_belongs_to_a_declared_extra():
    from pendulab.core.extras import EXTRA_OF

    extras = PYPROJECT["project"]["optional-dependencies"]
    for package, extra in EXTRA_OF.items():
        listed = " ".join(extras[extra])
        listed = listed.replace("-", "_")  # distribution names: swagger-ui-bundle is swagger_ui_bundle
        assert package in listed or (package == "distributed" and "dask[distributed]" in listed), (package, extra)


def test_core_runs_without_any_extra():
    """Periods, simulations and the period estimate with every optional package blocked."""
    code = f"""
import sys
for name in {OPTIONAL!r}:
    sys.modules[name] = None
from pendulab.cli import main
assert main(["period", "-l", "1", "-a", "pi/4"]) == 0
assert main(["simulate", "-l", "1", "-a", "pi/4", "--step", "0.1", "--t-max", "0.3"]) == 0
assert main(["estimate", "-l", "1", "-a", "pi/4", "--step", "1e-3"]) == 0
from pendulab.jobs import problems
problems.problem1()
problems.problem3()
print("core ok")
"""
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stderr
    assert "core ok" in res.stdout


@pytest.mark.parametrize(
    ("args", "package", "extra"),
    [
        (["simulate", "-l", "1", "-a", "pi/4", "--plot", "{tmp}/f.png"], "matplotlib", "report"),
        (["fit", "--plot", "{tmp}/f.png"], "matplotlib", "report"),
        (["approximations", "--plot", "{tmp}/f.png"], "matplotlib", "report"),
        (["report", "--output", "{tmp}/r.pdf"], "typst", "report"),
        (["report", "--output", "{tmp}/r.pdf"], "matplotlib", "report"),
        (["serve", "--port", "1"], "fastapi", "web"),
        (["serve", "--port", "1"], "orjson", "web"),
        (["serve", "--port", "1"], "swagger_ui_bundle", "web"),
        (["sweep", "-a", "1deg:2deg:2", "--output", "{tmp}/s.parquet"], "pyarrow", "sweep"),
        (["sweep", "-a", "1deg:2deg:2", "--output", "{tmp}/s.csv"], "pyarrow", "sweep"),
        (["sweep", "-a", "1deg:2deg:2", "--scheduler", "tcp://127.0.0.1:1"], "dask", "dask"),
    ],
)
def test_missing_extra_is_one_line(cli, monkeypatch, tmp_path, args, package, extra):
    # `import package` (and of any module of it an earlier test imported) now fails as if absent
    for name in [m for m in sys.modules if m == package or m.startswith(package + ".")] + [package]:
        monkeypatch.setitem(sys.modules, name, None)
    res = cli(*[a.format(tmp=tmp_path) for a in args])
    assert_one_line_error(res, f"needs {package}, which is not installed", "-m pip install -e '", f"[{extra}]'")
    assert list(tmp_path.iterdir()) == []  # refused before any work or output


def test_require_reraises_a_broken_install(monkeypatch):
    """Only the package itself being absent is 'not installed'; other import errors pass through."""
    from pendulab.core.errors import MissingExtraError
    from pendulab.core.extras import require

    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(MissingExtraError, match=r"-m pip install -e '\S*\[pandas\]'"):  # from a clone
        require("pandas", "to_frame()")
    with pytest.raises(ModuleNotFoundError) as info:
        require("pyarrow.no_such_module", "x")
    assert not isinstance(info.value, MissingExtraError)


# ---------------------------------------------------------------- the browser test's Chromium
def _fake_executable(folder, name):
    path = folder / name
    path.write_text("#!/bin/sh\n")
    path.chmod(0o755)
    return str(path)


def test_chromium_found_on_path_under_each_name(monkeypatch, tmp_path):
    from _browser import NAMES, find_chromium

    monkeypatch.delenv("PENDULAB_CHROMIUM", raising=False)
    monkeypatch.setenv("PATH", str(tmp_path))
    for name in reversed(NAMES):  # each name alone, then the first of the list wins
        path = _fake_executable(tmp_path, name)
        assert find_chromium() == path
    assert find_chromium() == str(tmp_path / "chromium")


def test_chromium_from_playwright_then_a_clear_message(monkeypatch, tmp_path):
    from _browser import HOW_TO_GET_ONE, find_chromium

    monkeypatch.delenv("PENDULAB_CHROMIUM", raising=False)
    monkeypatch.setenv("PATH", str(tmp_path))  # nothing on PATH

    class Playwright:
        class chromium:
            executable_path = str(tmp_path / "ms-playwright" / "chrome")

    with pytest.raises(LookupError) as info:
        find_chromium(Playwright)  # its download is not there either
    assert str(info.value) == HOW_TO_GET_ONE
    assert "apt-get install chromium" in HOW_TO_GET_ONE and "playwright install chromium" in HOW_TO_GET_ONE
    (tmp_path / "ms-playwright").mkdir()
    own = _fake_executable(tmp_path / "ms-playwright", "chrome")
    assert find_chromium(Playwright) == own


def test_chromium_named_by_the_environment(monkeypatch, tmp_path):
    from _browser import find_chromium

    chosen = _fake_executable(tmp_path, "my-chrome")
    monkeypatch.setenv("PENDULAB_CHROMIUM", chosen)
    assert find_chromium() == chosen
    monkeypatch.setenv("PENDULAB_CHROMIUM", str(tmp_path / "missing"))
    with pytest.raises(LookupError, match=r"PENDULAB_CHROMIUM = .*missing is not an executable file"):
        find_chromium()


def test_one_progress_bar_library(monkeypatch):
    """click's progress bar for the report as for the sweep; rich is not used anywhere."""
    sources = [p.read_text() for p in (ROOT / "src" / "pendulab").rglob("*.py")]
    assert not [s for s in sources if re.search(r"^\s*(from|import) rich\b", s, re.M)]
    from pendulab.report.builder import _Bar

    class Terminal(io.StringIO):
        def isatty(self):
            return True

    monkeypatch.setattr(sys, "stderr", Terminal())
    with _Bar() as bar:
        task = bar.add_task("starting", total=2)
        bar.update(task, description="problem 3")
        bar.advance(task)
        bar.update(task, description="typesetting")
        bar.advance(task)
    err = sys.stderr.getvalue()
    assert "report" in err and "typesetting" in err and "100%" in err


def test_docs_extra_brings_every_module_the_reference_imports():
    """The API reference walks the whole package, so `make docs` (pendulab[docs]) needs [all]."""
    extras = PYPROJECT["project"]["optional-dependencies"]
    assert "pendulab[all]" in extras["docs"]
    listed = " ".join(extras["all"])
    for extra in ("report", "web", "sweep", "dask", "pandas"):
        assert extra in listed
