"""The web API's input boundary: no query value crashes the server.

Property (Hypothesis, the grammar of ``hostile.py``): for every endpoint of the API and
every query parameter it declares (read from the app's OpenAPI schema, so a parameter
added later is covered), a hostile value gives status 200 or 422, never 500; a 422 names
that parameter (or, for a value that is fine alone, the other one it conflicts with) and
the server still answers afterwards, and no numpy RuntimeWarning is raised on the way.
"""
from __future__ import annotations

import math
import re
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hostile import HOSTILE
from pendulab.web import create_app
from reference import G

# A numpy RuntimeWarning (overflow, invalid value) fails the request (500) instead of
# reaching the server's log: the values where it is expected are handled where they arise.
pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")

#: Light values for the other parameters, so a hostile value that happens to be valid runs fast.
BASE = {"length": "1", "amplitude": "1", "step": "0.01", "t_max": "2", "steps": "1e-2", "points": "50"}


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app(), base_url="http://localhost", raise_server_exceptions=False)


def endpoints() -> dict[str, list[str]]:
    """``{path: [query parameter names]}`` of every GET route under /api, from the OpenAPI schema."""
    schema = create_app().openapi()
    return {path: [p["name"] for p in op["get"].get("parameters", []) if p["in"] == "query"]
            for path, op in schema["paths"].items() if path.startswith("/api/") and "get" in op}


def test_openapi_lists_every_parameter():
    found = endpoints()
    assert set(found["/api/period"]) == {"length", "amplitude", "unit", "g", "lang"}
    assert set(found["/api/simulate"]) == {"length", "amplitude", "unit", "g", "step", "t_max", "method", "points",
                                           "omega0", "damping", "drag", "mass", "lang"}
    assert set(found["/api/trajectory.csv"]) == set(found["/api/simulate"]) | {"columns"}  # lang: its refusals' words
    assert set(found["/api/motion"]) == {"length", "amplitude", "unit", "g", "t_max", "lang"}
    assert set(found["/api/convergence"]) == {"length", "amplitude", "unit", "g", "method", "steps", "lang"}
    assert set(found["/api/config"]) == {"lang"}


CASES = [(path, name) for path, names in endpoints().items() for name in names]


def check(client, path: str, query: dict[str, str], names: set[str]) -> None:
    r = client.get(path, params=query)
    assert r.status_code in (200, 422), (path, query, r.status_code, r.text[:300])
    if r.status_code == 422:
        err = r.json()["error"]
        assert err["field"] in names, (path, query, err)
        assert "\n" not in err["message"] and err["message"].startswith(f"{err['field']} = ")
    elif path != "/api/trajectory.csv":
        body = r.json()  # strict JSON: a NaN or an infinity would have failed to encode
        assert isinstance(body, dict)
    assert client.get("/api/config").status_code == 200  # still answering


@pytest.mark.slow
@settings(max_examples=300, deadline=30_000, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(case=st.sampled_from(CASES), value=HOSTILE)
def test_hostile_value_in_any_parameter(client, case, value):
    path, name = case
    # step and t_max judge each other, and the pendulum bounds the period search.
    related = {"step": {"t_max"}, "t_max": {"step"}, "length": {"g"}, "g": {"length"}}.get(name, set())
    check(client, path, BASE | {name: value}, {name} | related)


@pytest.mark.slow
@settings(max_examples=100, deadline=30_000, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(path=st.sampled_from(sorted(p for p, names in endpoints().items() if len(names) >= 2)), data=st.data())
def test_several_hostile_values_at_once(client, path, data):
    names = endpoints()[path]
    chosen = data.draw(st.lists(st.sampled_from(names), min_size=2, max_size=4, unique=True), label="parameters")
    query = BASE | {n: data.draw(HOSTILE, label=n) for n in chosen}
    check(client, path, query, set(names) | {"steps"})


# ------------------------------------------------------------------ the reported cases, one by one

@pytest.mark.parametrize("query, field", [
    ({"g": "1e-320"}, "g"),
    ({"length": "1e308", "g": "1e-308"}, "g"),
    ({"length": "1e-308", "g": "1e308"}, "length"),
    ({"step": "1e-320"}, "step"),
    ({"t_max": "1e308"}, "t_max"),
    ({"t_max": "1e6"}, "t_max"),
    ({"step": "100"}, "step"),
])
def test_reported_cases_name_the_right_field(client, query, field):
    r = client.get("/api/simulate", params=BASE | query)
    assert r.status_code == 422 and r.json()["error"]["field"] == field, r.text
    if query == {"step": "100"}:
        assert "t0" not in r.json()["error"]["message"]


def test_convergence_takes_every_method_the_api_takes(client):
    r = client.get("/api/convergence", params={"length": "1", "amplitude": "1", "steps": "1e-2", "method": "taylor:4"})
    assert r.status_code == 200 and r.json()["order"] == 4 and r.json()["method"] == "taylor:4"


@pytest.mark.slow
def test_long_periods_are_answered_without_an_estimate(client):
    # l = 1e300 m: T = 2 pi sqrt(l/g) ~ 2e150 s, computed right; no simulation reaches it.
    r = client.get("/api/simulate", params=BASE | {"length": "1e300"})
    assert r.status_code == 200
    body = r.json()
    t0 = 2 * math.pi * math.sqrt(1e300 / G)
    assert body["period"]["small_angle_period"] == pytest.approx(t0, rel=1e-15)
    assert body["period"]["estimate"] is None and "1e+07" in body["period"]["reason"]


def test_extreme_ratio_period_is_computed_right(client):
    # sqrt(l)/sqrt(g) where l/g underflows: l = 1e-300, g = 1e300 gives T0 = 2 pi 1e-300 s, not 0.
    body = client.get("/api/period", params={"length": "1e-300", "amplitude": "0", "g": "1e300"}).json()
    assert body["small_angle_period"] == pytest.approx(2 * math.pi * 1e-300, rel=1e-15)
    assert body["period"] == body["small_angle_period"]


def test_degrees_are_echoed_as_typed(client):
    r = client.get("/api/period", params={"length": "1", "amplitude": "-10", "unit": "deg"})
    assert r.status_code == 422 and r.json()["error"]["value"] == "-10"
    ok = client.get("/api/period", params={"length": "1", "amplitude": "45", "unit": "deg"}).json()
    assert ok["amplitude"] == math.pi / 4


@settings(max_examples=40, deadline=60_000, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(amplitude=st.one_of(st.sampled_from([5e-324, 1e-300, 1e-10, 3.1415926535897931 - 1e-15]),
                           st.floats(0.0, math.pi, exclude_max=True)),
       length=st.floats(1e-3, 1e3), step=st.floats(1e-3, 1.5), method=st.sampled_from(["taylor2", "rk4", "verlet", "taylor:1"]))
def test_a_run_without_an_estimate_is_an_answer_with_its_status(client, amplitude, length, step, method):
    # Any pendulum at rest below pi and any step the run allows: the estimate, or its absence
    # with the search's status and one line why; never a refusal because no period was found.
    q = {"length": repr(length), "amplitude": repr(amplitude), "step": repr(step), "t_max": "2", "method": method}
    r = client.get("/api/simulate", params=q)
    assert r.status_code == 200, r.text[:300]
    period = r.json()["period"]
    assert (period["estimate"] is None) == (period["status"] != "found") == (period["reason"] is not None)
    if period["reason"] is not None:
        assert "\n" not in period["reason"] and "--" not in period["reason"]


def test_the_docs_name_every_parameter_of_every_route():
    """docs/explorer.md's API tables list each route's query parameters as the OpenAPI schema
    has them, over the rows that name the route (``as above``: the row before's too)."""
    doc = (Path(__file__).resolve().parents[1] / "docs" / "explorer.md").read_text(encoding="utf-8")
    listed: dict[str, set[str]] = {}
    before: set[str] = set()
    for routes, params in re.findall(r"^\| ((?:`/api/[^`]+`(?:, )?)+) \|([^|]*)\|", doc, flags=re.M):
        bare = re.sub(r"\([^)]*\)", "", params)  # not the notes: (default 2000), (`state` or `all`)
        names = {n for chunk in re.findall(r"`([^`]+)`", bare) for n in re.split(r",\s*", chunk)}
        names |= before if params.strip().startswith("as above") else set()
        for route in re.findall(r"`(/api/[^`]+)`", routes):
            listed.setdefault(route, set()).update(names)
        before = names
    assert listed == {route: set(names) for route, names in endpoints().items()}
