"""One name per quantity (docs/glossary.md), held against every name pendulab publishes.

The published names are read from the code, not typed here: the fields and derived values
of every :class:`~pendulab.numerics.results.Result` subclass, the keys of each command's
``--json``, the sweep's columns, the command line's option names, the web API's response
models and query parameters. Each must stand in the glossary's register ("Every published
name"), and the register may hold no name that nothing publishes; no retired name comes
back; "exact" names only the exact motion; degrees are ``_deg``. Words are checked too:
no help text, catalogue sentence, page label or docstring in ``src`` calls a period exact.
"""
from __future__ import annotations

import dataclasses
import importlib
import json
import pkgutil
import re
from pathlib import Path

import click
import pytest

import pendulab
from pendulab.cli import cli, main
from pendulab.numerics.results import Result
from reference import EXAMPLE_GROUP

ROOT = Path(__file__).resolve().parents[1]
GLOSSARY = (ROOT / "docs" / "glossary.md").read_text()
SRC = ROOT / "src" / "pendulab"
NAME = re.compile(r"`([A-Za-z_][A-Za-z0-9_]*)`")


def _section(title: str) -> str:
    match = re.search(rf"^## {re.escape(title)}\n(.*?)(?=^## |\Z)", GLOSSARY, re.MULTILINE | re.DOTALL)
    assert match, f"docs/glossary.md has no section '## {title}'"
    return match.group(1)


def _entry(head: str) -> str:
    """The text of the glossary entry whose head line is ``head``."""
    match = re.search(rf"^{re.escape(head)}\n((?::.*\n|  .*\n)+)", GLOSSARY, re.MULTILINE)
    assert match, head
    return match.group(1)


REGISTER = set(NAME.findall(_section("Every published name")))
RETIRED = set(NAME.findall(_section("Retired names")))
EXACT_MOTION = set(NAME.findall(_entry("The exact motion")))


# ------------------------------------------------------------------ what is published

def _modules():
    for info in pkgutil.walk_packages(pendulab.__path__, "pendulab."):
        if ".programs" not in info.name and not info.name.endswith("__main__"):
            importlib.import_module(info.name)


def _subclasses(cls):
    for sub in cls.__subclasses__():
        yield sub
        yield from _subclasses(sub)


def result_names() -> dict[str, set[str]]:
    """Field and derived-value names of every Result subclass, with the classes that use them."""
    _modules()
    names: dict[str, set[str]] = {}
    for cls in set(_subclasses(Result)):
        properties = [n for klass in cls.__mro__ for n, v in vars(klass).items()
                      if isinstance(v, property) and not n.startswith("_")]
        for name in [f.name for f in dataclasses.fields(cls)] + properties:
            names.setdefault(name, set()).add(cls.__name__)
    return names


def json_keys(doc):
    """Every key of a JSON document, at any depth (test_front_door.py uses it too)."""
    if isinstance(doc, dict):
        for k, v in doc.items():
            yield k
            yield from json_keys(v)
    elif isinstance(doc, list):
        for v in doc:
            yield from json_keys(v)


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


#: One run of every command that takes --json, at inputs that answer in a moment.
JSON_RUNS = [
    ["period"], ["period", "--iterations", "7"], ["simulate"], ["estimate", "--step", "1e-2,1e-3"],
    ["length", *map(str, EXAMPLE_GROUP)], ["gravity"], ["newton"], ["fit"], ["quadrature", "--n", "10,100"],
    ["approximations"], ["sweep", "-a", "10deg:30deg:3", "--step", "1e-2", "--method", "taylor2"],
]


@pytest.fixture(scope="module")
def json_names(tmp_path_factory) -> dict[str, set[str]]:
    """The keys of each command's --json (a key that is a number, a threshold, is data)."""
    tmp = tmp_path_factory.mktemp("glossary")
    groups = tmp / "groups.txt"
    groups.write_text(" ".join(map(str, EXAMPLE_GROUP)) + "\n")
    runs = [*JSON_RUNS, ["key", "--groups", str(groups)], ["programs", "--output", str(tmp / "programs")]]
    names: dict[str, set[str]] = {}
    for args in runs:
        out = _run_json(args)
        for key in json_keys(out):
            if not _is_number(key):
                names.setdefault(key, set()).add(args[0])
    return names


def _run_json(args):
    import contextlib
    import io

    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer):
        code = main([*args, "--json"])
    assert code == 0, args
    return json.loads(buffer.getvalue())


def _commands():
    ctx = click.Context(cli)
    return {name: cli.get_command(ctx, name) for name in cli.list_commands(ctx)}


def option_names() -> dict[str, set[str]]:
    """Each command's options as typed (``--t-max`` is ``t_max``) and its arguments."""
    names: dict[str, set[str]] = {}
    for name, cmd in _commands().items():
        for p in cmd.params:
            typed = max(p.opts, key=len).lstrip("-").replace("-", "_") if isinstance(p, click.Option) else p.name
            if typed != "help":
                names.setdefault(typed, set()).add(f"{name} option")
    return names


def sweep_columns() -> set[str]:
    import numpy as np

    from pendulab.jobs.sweep import sweep

    return set(sweep(np.radians([30.0]), [1e-2], ["taylor2"]).columns)


@pytest.fixture(scope="module")
def schema():
    from fastapi.testclient import TestClient

    from pendulab.web import create_app

    return TestClient(create_app(), base_url="http://localhost").get("/api/openapi.json").json()


def web_names(schema) -> dict[str, set[str]]:
    """Response model fields and query parameters of the web API."""
    names: dict[str, set[str]] = {}
    for model, body in schema["components"]["schemas"].items():
        if model in ("HTTPValidationError", "ValidationError"):
            continue
        for prop in body.get("properties", {}):
            names.setdefault(prop, set()).add(model)
    for path, ops in schema["paths"].items():
        for op in ops.values():
            for param in op.get("parameters", []):
                names.setdefault(param["name"], set()).add(path)
    return names


@pytest.fixture(scope="module")
def published(json_names, schema) -> dict[str, set[str]]:
    names: dict[str, set[str]] = {}
    for source in (result_names(), json_names, option_names(), web_names(schema),
                   {c: {"SweepResult column"} for c in sweep_columns()}):
        for name, where in source.items():
            names.setdefault(name, set()).update(where)
    return names


# ------------------------------------------------------------------ the names

def test_every_published_name_is_in_the_glossary(published):
    missing = {name: sorted(where) for name, where in sorted(published.items()) if name not in REGISTER}
    assert not missing, f"add these to docs/glossary.md, 'Every published name' (or use a name it has): {missing}"


def test_the_glossary_lists_no_name_that_nothing_publishes(published):
    assert not REGISTER - set(published), sorted(REGISTER - set(published))


def test_no_retired_name_is_published(published):
    assert RETIRED and not RETIRED & set(published), sorted(RETIRED & set(published))
    assert not RETIRED & REGISTER


def test_exact_names_only_the_exact_motion(published):
    assert {"exact", "exact_frames", "exact_phase", "curve_exact", "exact_deviation"} <= EXACT_MOTION
    with_exact = {name for name in published if "exact" in name.lower()}
    assert with_exact <= EXACT_MOTION, sorted(with_exact - EXACT_MOTION)


def test_degrees_are_deg_everywhere(published):
    assert not [name for name in published if re.search(r"_degrees?$", name)]
    assert {"amplitude_deg", "alpha_deg"} <= set(published)


def test_each_error_name_has_one_meaning(published):
    # |linear - period| (PeriodEstimate); the sweep's signed error and the key's error
    # against T^ are other quantities with names of their own.
    # EstimateShown: the same quantity as the explorer prints it (its right digits, a text).
    assert published["linear_error"] == {"PeriodEstimate", "estimate", "EstimateShown"}
    assert published["cubic_error"] == {"PeriodEstimate", "estimate", "EstimateShown"}
    assert {"linear_signed_error", "cubic_signed_error"} <= sweep_columns()
    assert {"linear_t_hat_error", "cubic_t_hat_error"} <= published.keys()


# ------------------------------------------------------------------ the words

#: "exact" beside a period: the AGM period is "the period", T^ is "T^" (glossary).
EXACT_PERIOD = re.compile(
    r"\bexact[oa]?s?\b[\s(]*(AGM\)?\s*)?(period|período|T\b|\$?hat\(T\)|one\b|ratio\b|\(AGM)"
    r"|\bper[ií]odos?\b[^.\n]{0,12}\bexact[oa]?\b(?!\s+(motion|orbit|state|solution))|\bExact \((AGM|eq)",
    re.IGNORECASE)


@pytest.mark.parametrize("text, calls_a_period_exact", [
    ("The exact period by the AGM", True), ("against the exact (AGM) period", True), ("exact T = 2.1", True),
    ("Exact (AGM, eq. 8)", True), ("o período exacto é", True), ("the exact one", True),
    ("the exact motion theta(t)", False), ("exactly one root", False), ("the period of the exact motion", False),
    ("the double's exact value", False), ("one period of the exact orbit", False), ("an exact rational", False),
])
def test_the_exact_period_pattern(text, calls_a_period_exact):
    assert bool(EXACT_PERIOD.search(text)) == calls_a_period_exact


def _help_texts():
    for name, cmd in _commands().items():
        yield f"{name} --help", cmd.get_help(click.Context(cmd, info_name=name))


def test_no_help_text_calls_a_period_exact():
    found = [(where, m.group(0)) for where, text in _help_texts() for m in EXACT_PERIOD.finditer(text)]
    assert not found, found


def _source_texts():
    for path in sorted(SRC.rglob("*")):
        if path.suffix in (".py", ".js", ".html", ".json", ".typ", ".css") and ".min." not in path.name:
            yield path.relative_to(ROOT), path.read_text()


def test_nothing_in_src_calls_a_period_exact():
    """``grep -rn exact src`` finds no period: code, docstrings, catalogues, the page."""
    found = [f"{path}:{text.count(chr(10), 0, m.start()) + 1}: {m.group(0)}"
             for path, text in _source_texts() for m in EXACT_PERIOD.finditer(text)]
    assert not found, found
