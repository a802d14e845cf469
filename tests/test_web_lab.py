"""The explorer's lab through the API: damping, drag and mass as query parameters.

References: scipy's DOP853 at rtol 1e-12 on the damped equation; the undamped answer of
the same query (the mass changes no number of the motion).
"""
from __future__ import annotations

import io
import math

import numpy as np
import pytest
from fastapi.testclient import TestClient
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from pendulab.web import create_app
from reference import G

Q = {"length": "1", "amplitude": "30deg", "step": "0.01", "t_max": "10", "points": "2000"}


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app(), base_url="http://localhost")


ALPHA = math.radians(30)


def _damped(gamma, beta, t, length=1.0, alpha=ALPHA):
    def f(_t, z):
        return [z[1], -G / length * math.sin(z[0]) - gamma * z[1] - beta * z[1] * abs(z[1])]

    return solve_ivp(f, (0.0, t[-1]), [alpha, 0.0], method="DOP853", rtol=1e-12, atol=1e-14, t_eval=t).y


def test_a_damped_run_follows_the_damped_equation(client):
    body = client.get("/api/simulate", params=Q | {"damping": "0.3", "drag": "0.2", "method": "rk4"}).json()
    f = body["frames"]
    ref = _damped(0.3, 0.2, np.array(f["t"]))
    assert np.max(np.abs(np.array(f["theta"]) - ref[0])) < 1e-7
    assert body["input"]["damping"] == 0.3 and body["input"]["drag"] == 0.2
    # Its energy goes into heat: the drift ends well below 0, and the flags say why they judge nothing.
    assert body["energy"]["drift"][-1] < -0.5 * (1 - math.cos(math.radians(30)))
    kinds = [n["kind"] for n in body["flags"]["notes"]]
    assert kinds == ["damped"] and body["flags"]["trustworthy"]
    assert "heat" in body["flags"]["notes"][0]["text"] and body["flags"]["energy_drift_kind"] is None
    # The coursework's estimates time the undamped pendulum: not made, and the page is told why.
    assert body["period"]["estimate"] is None and body["period"]["status"] == "not_run"
    assert "undamped" in body["period"]["reason"]


def test_the_damped_flag_in_portuguese(client):
    body = client.get("/api/simulate", params=Q | {"damping": "0.3", "lang": "pt"}).json()
    assert "calor" in body["flags"]["notes"][0]["text"] and "amortecimento" in body["period"]["reason"]


def test_no_damping_is_the_undamped_answer(client):
    plain = client.get("/api/simulate", params=Q).json()
    zero = client.get("/api/simulate", params=Q | {"damping": "0", "drag": "0"}).json()
    assert zero["frames"] == plain["frames"] and zero["flags"] == plain["flags"] and zero["period"] == plain["period"]


@pytest.mark.parametrize("mass", ["0.05", "1", "250"])
def test_the_mass_changes_no_number_of_the_motion(client, mass):
    plain = client.get("/api/simulate", params=Q).json()
    body = client.get("/api/simulate", params=Q | {"mass": mass}).json()
    assert body["input"]["mass"] == float(mass)
    for key in ("frames", "theta", "period", "energy", "flags"):
        assert body[key] == plain[key], key


def test_the_csv_is_the_damped_run(client):
    r = client.get("/api/trajectory.csv", params=Q | {"damping": "0.5", "points": "1001", "method": "rk4"})
    rows = np.loadtxt(io.StringIO(r.text), delimiter=",", skiprows=1)
    ref = _damped(0.5, 0.0, rows[:, 0])
    assert np.max(np.abs(rows[:, 1] - ref[0])) < 1e-7


@settings(max_examples=30, deadline=None)
@given(name=st.sampled_from(["damping", "drag", "mass"]),
       value=st.sampled_from(["-1", "-1e-300", "nan", "inf", "1e400", "x", "2,5"]))
def test_a_bad_damping_or_mass_is_a_422_naming_it_and_its_range(client, name, value):
    r = client.get("/api/simulate", params=Q | {name: value})
    assert r.status_code == 422
    err = r.json()["error"]
    assert err["field"] == name and err["message"].startswith(f"{name} = ")
    assert ("> 0 (kg)" if name == "mass" else ">= 0 (1/") in err["allowed"]


def test_a_zero_mass_is_refused(client):
    r = client.get("/api/simulate", params=Q | {"mass": "0"})
    assert r.status_code == 422 and r.json()["error"]["field"] == "mass"
