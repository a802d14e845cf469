"""The web API's contract: every endpoint the page fetches publishes its answer's schema in
``/api/openapi.json``, and real answers (ordinary, blown up, without an estimate, refused)
validate against that published schema (jsonschema, not the server's own models)."""
from __future__ import annotations

import re
import sys

import pytest
from fastapi.testclient import TestClient

from pendulab.web import create_app
from pendulab.web.app import STATIC

# jsonschema's optional "iri" format checker imports rfc3987_syntax, which builds a grammar for
# seconds (each test worker, at collection); these validators check no formats: kept out.
_IRI = sys.modules.get("rfc3987_syntax")
sys.modules["rfc3987_syntax"] = None  # its import is then an ImportError, which jsonschema expects
try:
    from jsonschema import Draft202012Validator
finally:
    if _IRI is None:
        del sys.modules["rfc3987_syntax"]
    else:
        sys.modules["rfc3987_syntax"] = _IRI


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app(), base_url="http://localhost")


@pytest.fixture(scope="module")
def schema(client):
    return client.get("/api/openapi.json").json()


def fetched_by_the_page() -> set[str]:
    """Every ``/api/...`` path that ``static/app.js`` names (fetches, links)."""
    return set(re.findall(r'"(/api/[A-Za-z0-9_.]+)', (STATIC / "app.js").read_text()))


def validator(schema: dict, path: str, status: str = "200") -> Draft202012Validator:
    content = schema["paths"][path]["get"]["responses"][status]["content"]
    body = content.get("application/json", content.get("text/csv"))["schema"]
    return Draft202012Validator(body | {"components": schema["components"]})


def test_the_page_reads_only_endpoints_with_a_published_answer(schema):
    paths = fetched_by_the_page()
    assert {"/api/config", "/api/simulate", "/api/convergence", "/api/trajectory.csv"} <= paths
    for path in paths:
        responses = schema["paths"][path]["get"]["responses"]
        content = responses["200"]["content"]
        if path.endswith(".csv"):
            assert content["text/csv"]["schema"] == {"type": "string"}
            continue
        ref = content["application/json"]["schema"]["$ref"]
        assert schema["components"]["schemas"][ref.split("/")[-1]]["properties"], path
        if path not in ("/api/config", "/api/period_curve"):  # the two without parameters
            assert "422" in responses, path


def test_published_keys_use_the_glossarys_names(schema):
    """One name per quantity (docs/glossary.md): the period answer's keys are the library's
    (:class:`pendulab.numerics.period.Periods`) and "exact" names only the exact motion, never a period."""
    from dataclasses import fields

    from pendulab.numerics.period import Periods

    props = {name: set(m.get("properties", {})) for name, m in schema["components"]["schemas"].items()}
    assert props["PeriodAnswer"] - {"amplitude_deg"} <= {f.name for f in fields(Periods)}
    assert {k for keys in props.values() for k in keys if "exact" in k} == {"exact", "exact_frames", "exact_phase"}


def test_the_published_schemas_forbid_unlisted_keys(schema):
    for name, model in schema["components"]["schemas"].items():
        if "properties" in model and name not in ("HTTPValidationError", "ValidationError"):
            assert model.get("additionalProperties") is False, name


ANSWERS = [
    ("/api/config", {}),
    ("/api/period", {"length": "3.5", "amplitude": "4pi/5"}),
    ("/api/simulate", {"length": "3.5", "amplitude": "144", "unit": "deg", "step": "1e-3", "t_max": "20", "points": "3000"}),
    ("/api/simulate", {"length": "1", "amplitude": "3", "step": "1", "t_max": "2000"}),  # blows up: nulls
    ("/api/simulate", {"length": "1", "amplitude": "0", "step": "0.01", "t_max": "2"}),  # no estimate
    ("/api/simulate", {"length": "1", "amplitude": "0.5", "step": "1", "t_max": "20", "method": "rk4"}),  # no return
    ("/api/simulate", {"length": "1", "amplitude": "0.1", "step": "0.8", "t_max": "20", "method": "rk4"}),  # too early
    ("/api/simulate", {"length": "1e300", "amplitude": "1", "step": "1e-3", "t_max": "20"}),  # shorter than a period
    ("/api/convergence", {"length": "1", "amplitude": "pi/4", "method": "rk4"}),
    ("/api/convergence", {"length": "1", "amplitude": "3", "steps": "0.5,0.1"}),  # a row without an estimate
    ("/api/simulate", {"length": "3.5", "amplitude": "144", "unit": "deg", "step": "0.2", "t_max": "20",
                       "method": "verlet"}),  # a note: bounded energy error
    ("/api/motion", {"length": "20", "amplitude": "120deg", "t_max": "20"}),
    ("/api/motion", {"length": "1", "amplitude": "0", "t_max": "1e300"}),
    ("/api/period_curve", {}),
    ("/api/simulate", {"length": "1", "amplitude": "17deg", "step": "1e-3", "t_max": "20", "omega0": "7"}),  # goes round
    ("/api/simulate", {"length": "1", "amplitude": "17deg", "step": "1e-3", "t_max": "20", "omega0": "-2"}),  # swings
]


@pytest.mark.parametrize("path, query", ANSWERS)
def test_real_answers_validate_against_the_published_schema(client, schema, path, query):
    r = client.get(path, params=query)
    assert r.status_code == 200, r.text[:300]
    errors = sorted(validator(schema, path).iter_errors(r.json()), key=str)
    assert not errors, [f"{list(e.absolute_path)}: {e.message}" for e in errors[:5]]


@pytest.mark.parametrize("path", ["/api/period", "/api/simulate", "/api/convergence", "/api/motion"])
def test_refusals_validate_against_the_published_error(client, schema, path):
    r = client.get(path, params={"length": "-1", "amplitude": "1", "step": "1e-3", "t_max": "1"})
    assert r.status_code == 422
    assert not list(validator(schema, path, "422").iter_errors(r.json()))
    # The contract can fail: an answer with a key the schema does not list is refused.
    assert list(validator(schema, path, "422").iter_errors(r.json() | {"extra": 1}))
