"""The layers of the package: every import runs downward, no import circle, no private
name taken from another module.

Each module's imports are read with ``ast`` (module-level and inside functions alike),
so an import hidden in a function to dodge a circle at import time still counts.
:data:`LAYERS` is the table of the design page (``docs/design.md``, checked below).
"""
from __future__ import annotations

import ast
import re
import sys
from functools import cache
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src"
PACKAGE = "pendulab"

#: The layers, bottom first, each the folders of ``src/pendulab`` it is made of: a module's
#: layer is the folder it lies in (``pendulab.engine.kernels`` is in ``engine``).
LAYERS: dict[str, tuple[str, ...]] = {
    "core": ("core",),
    "engine": ("engine",),
    "numerics": ("numerics",),
    "jobs": ("jobs",),
    "presenters": ("cli", "report", "web", "plots", "__main__", ""),  # "": the package's face
}

#: Private names that one module takes from another, each with its reason. Keep it short.
PRIVATE_ALLOWED: dict[tuple[str, str], str] = {}


def module_name(path: Path) -> str:
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


@cache
def modules() -> dict[str, Path]:
    """The package's modules: files in folders with an ``__init__.py`` (``programs/``, the
    coursework's stand-alone files, is package data and imports nothing of the package)."""
    return {module_name(p): p for p in sorted((SRC / PACKAGE).rglob("*.py"))
            if all((d / "__init__.py").is_file() for d in p.parents if d.is_relative_to(SRC / PACKAGE))}


@cache
def tree(module: str) -> ast.Module:
    return ast.parse(modules()[module].read_text(encoding="utf-8"))


def layer_of(module: str) -> int:
    """The index in :data:`LAYERS` of ``module``: the layer of the folder it lies in."""
    top = module.split(".")[1] if "." in module else ""
    for i, names in enumerate(LAYERS.values()):
        if top in names:
            return i
    raise AssertionError(f"{module} lies in no layer's folder: move it into one (docs/design.md)")


def imports(module: str) -> list[tuple[str, str, int]]:
    """``(target module, name taken or "", line)`` for every import of the package in ``module``."""
    path = modules()[module]
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    out = []
    for node in ast.walk(tree(module)):
        if isinstance(node, ast.Import):
            out += [(a.name, "", node.lineno) for a in node.names if a.name.split(".")[0] == PACKAGE]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.split(".")[0] != PACKAGE:
                continue
            for a in node.names:
                sub = f"{target}.{a.name}"
                # ``from . import inputs`` imports the module pendulab.core.inputs, not a name of pendulab
                out.append((sub, "", node.lineno) if sub in modules() else (target, a.name, node.lineno))
    return out


def private_attributes(module: str) -> list[tuple[str, str, int]]:
    """``(module, name, line)`` for each ``alias._x`` where ``alias`` is a module of the package."""
    aliases: dict[str, str] = {}
    package = module if modules()[module].name == "__init__.py" else module.rpartition(".")[0]
    for node in ast.walk(tree(module)):
        if isinstance(node, ast.ImportFrom) and node.level:
            base = ".".join(package.split(".")[: len(package.split(".")) - node.level + 1]
                            + ([node.module] if node.module else []))
            for a in node.names:
                if f"{base}.{a.name}" in modules():
                    aliases[a.asname or a.name] = f"{base}.{a.name}"
    return [(aliases[n.value.id], n.attr, n.lineno) for n in ast.walk(tree(module))
            if isinstance(n, ast.Attribute) and isinstance(n.value, ast.Name) and n.value.id in aliases
            and _private(n.attr) and f"{aliases[n.value.id]}.{n.attr}" not in modules()]


def _private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def test_every_module_has_a_layer():
    for module in modules():
        layer_of(module)


def test_no_import_runs_upward():
    names = list(LAYERS)
    upward = [f"{m}:{line} ({names[layer_of(m)]}) imports {t} ({names[layer_of(t)]})"
              for m in modules() for t, _, line in imports(m)
              if t in modules() and layer_of(t) > layer_of(m)]
    assert not upward, "\n".join(upward)


def test_no_import_circle():
    graph = {m: sorted({t for t, _, _ in imports(m) if t in modules() and t != m}) for m in modules()}
    # A package's __init__ importing its own modules is how a package hands names on; a
    # module of it importing the package's face back would be a circle and is kept.
    circles, state = [], dict.fromkeys(graph, 0)  # 0 new, 1 on the path, 2 done

    def visit(m: str, path: list[str]) -> None:
        state[m] = 1
        for t in graph[m]:
            if state[t] == 1:
                circles.append(" -> ".join(path[path.index(t):] + [m, t]) if t in path else f"{m} -> {t}")
            elif state[t] == 0:
                visit(t, path + [m])
        state[m] = 2

    for m in graph:
        if state[m] == 0:
            visit(m, [])
    assert not circles, "\n".join(circles)


def test_no_private_name_crosses_modules():
    found = {(m, f"{t}.{name}"): line for m in modules() for t, name, line in imports(m) if _private(name)}
    found |= {(m, f"{t}.{name}"): line for m in modules() for t, name, line in private_attributes(m)}
    bad = [f"{m}:{line} uses {name}" for (m, name), line in found.items() if (m, name) not in PRIVATE_ALLOWED]
    assert not bad, "\n".join(bad)
    stale = [k for k in PRIVATE_ALLOWED if k not in found]
    assert not stale, f"allowed but no longer used (remove from PRIVATE_ALLOWED): {stale}"


def test_results_carry_no_words_and_jobs_no_typesetting():
    """Results and jobs hold decisions; the catalogues and the typesetter belong to the presenters."""
    for m in modules():
        if layer_of(m) < list(LAYERS).index("presenters"):
            for t, _, line in imports(m):
                assert layer_of(t) < list(LAYERS).index("presenters"), f"{m}:{line} imports {t}"


# --------------------------------------------------------------------------- the checker itself
def test_the_checker_sees_function_level_relative_imports(tmp_path, monkeypatch):
    """A function-level ``from ..numerics.period import _x`` in a core module is an upward, private import."""
    pkg = tmp_path / PACKAGE
    for folder in ("core", "numerics"):
        (pkg / folder).mkdir(parents=True)
        (pkg / folder / "__init__.py").write_text("")
    (pkg / "__init__.py").write_text("")
    (pkg / "numerics" / "period.py").write_text("from ..core.inputs import parse\n\ndef _x():\n    return 1\n")
    (pkg / "core" / "inputs.py").write_text("def parse():\n    from ..numerics.period import _x\n    return _x()\n")
    monkeypatch.setattr(sys.modules[__name__], "SRC", tmp_path)
    modules.cache_clear()
    tree.cache_clear()
    try:
        assert ("pendulab.numerics.period", "_x", 2) in imports("pendulab.core.inputs")
        with pytest.raises(AssertionError, match="inputs:2"):
            test_no_import_runs_upward()
        with pytest.raises(AssertionError, match=r"pendulab\.core\.inputs -> pendulab\.numerics\.period|"
                                                 r"pendulab\.numerics\.period -> pendulab\.core\.inputs"):
            test_no_import_circle()
        with pytest.raises(AssertionError, match=r"uses pendulab\.numerics\.period\._x"):
            test_no_private_name_crosses_modules()
    finally:
        modules.cache_clear()
        tree.cache_clear()


def test_design_page_lists_the_same_layers():
    """docs/design.md's layer table names every folder of :data:`LAYERS`, each on its layer's line."""
    text = (ROOT / "docs" / "design.md").read_text(encoding="utf-8")
    table = text.split("<!-- layers -->")[1]
    for layer, names in LAYERS.items():
        line = next((ln for ln in table.splitlines() if re.match(rf"\|\s*{layer}\s*\|", ln)), None)
        assert line is not None, layer
        for name in names:
            if name and not name.startswith("__"):
                assert f"`{name}/`" in line, (layer, name)


def test_the_top_level_holds_only_the_entry_points():
    """``ls src/pendulab`` shows the architecture: every module lies in a layer's folder but the
    package's face (``__init__``) and ``python -m pendulab`` (``__main__``)."""
    top = sorted(p.name for p in (SRC / PACKAGE).glob("*.py"))
    assert top == ["__init__.py", "__main__.py"], top
    folders = {p.name for p in (SRC / PACKAGE).iterdir() if p.is_dir() and (p / "__init__.py").is_file()}
    assert folders == {name for names in LAYERS.values() for name in names if name and not name.startswith("__")}


# --------------------------------------------------------------------------- numba's cache
def test_kernel_sources_are_what_compiled_code_is_made_of():
    """``numba_cache.KERNEL_SOURCES`` lists the modules with kernels and every package module
    they import, transitively: a cached kernel is kept only while all of them are unchanged."""
    from pendulab.engine.numba_cache import KERNEL_SOURCES

    def compiles(m: str) -> bool:
        text = modules()[m].read_text(encoding="utf-8")
        return any(k in text for k in ("@njit", "njit(", "@intrinsic", "register_jitable"))

    seen: set[str] = set()
    todo = [m for m in modules() if compiles(m)]
    while todo:
        m = todo.pop()
        if m not in seen:
            seen.add(m)
            todo += [t for t, _, _ in imports(m) if t in modules() and t != PACKAGE]
    files = {str(modules()[m].relative_to(SRC / PACKAGE).as_posix()) for m in seen}
    assert files == set(KERNEL_SOURCES)
