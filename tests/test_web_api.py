"""The web explorer's JSON API, in process (FastAPI's TestClient): every endpoint, every kind of bad input.

Reference values: the table of Figure 3 of the coursework and the period from
mpmath's complete elliptic integral at 30 digits, ``T = 4 sqrt(l/g) K(sin^2(alpha/2))``
(independent of the AGM loop of ``period.py``).
"""
from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import mpmath
import numpy as np
import pytest
from fastapi.testclient import TestClient

import plain_pendulum
import reference
from pendulab.cli import main
from pendulab.core import digits, methods
from pendulab.numerics import simulation
from pendulab.numerics.crossing import estimate_period
from pendulab.numerics.motion import energy, exact_motion
from pendulab.web import create_app, limits, parameters, sampling, views
from reference import G, ellipk_period


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app(), base_url="http://localhost")


# Figure 3 of the coursework by time: t -> (z1, z2).
FIGURE3 = {t: (z1, z2) for t, z1, z2 in reference.FIGURE3.values()}
FIG3_QUERY = {"length": "1", "amplitude": "pi/4", "step": "0.1", "t_max": "2.1"}
P5_QUERY = {"length": "3.5", "amplitude": "4pi/5", "step": "1e-3", "t_max": "10"}


# ---------------------------------------------------------------- good requests

def test_config_lists_the_family_taylor_p(client):
    family = client.get("/api/config").json()["family"]
    assert [m["name"] for m in family] == [f"taylor:{p}" for p in range(1, methods.MAX_TAYLOR_ORDER + 1)]
    assert [m["order"] for m in family] == list(range(1, 31)) and "Euler" in family[0]["description"]
    for m in family[::7]:  # each one simulates as itself
        r = client.get("/api/simulate", params=FIG3_QUERY | {"method": m["name"]})
        assert r.status_code == 200 and r.json()["input"]["method"] == m["name"]


def test_config_lists_the_methods_registered_now(client, monkeypatch):
    body = client.get("/api/config").json()
    assert [m["name"] for m in body["methods"]] == [m.name for m in methods.menu()]
    assert body["limits"] == {"max_steps": 10**7, "max_points": 20_000, "plot_points": 2000}
    assert body["g_presets"]["earth"] == G
    # A method registered after the app was built shows up, and can be simulated.
    monkeypatch.setitem(methods.METHODS, "taylor2-copy", replace(methods.METHODS["taylor2"], name="taylor2-copy"))
    assert "taylor2-copy" in [m["name"] for m in client.get("/api/config").json()["methods"]]
    r = client.get("/api/simulate", params=FIG3_QUERY | {"method": "taylor2-copy"})
    assert r.status_code == 200 and r.json()["input"]["method"] == "taylor2-copy"


@pytest.mark.parametrize("amplitude, alpha", [("pi/4", math.pi / 4), ("45deg", math.pi / 4), ("4pi/5", 0.8 * math.pi),
                                              ("144deg", 0.8 * math.pi), ("2.5", 2.5), ("0", 0.0)])
def test_period_endpoint_against_elliptic_k(client, amplitude, alpha):
    r = client.get("/api/period", params={"length": "3.5", "amplitude": amplitude})
    assert r.status_code == 200
    body = r.json()
    assert body["amplitude"] == pytest.approx(alpha, rel=1e-15, abs=0)
    assert body["period"] == pytest.approx(ellipk_period(3.5, alpha), rel=1e-14)
    assert body["small_angle_period"] == pytest.approx(2 * math.pi * math.sqrt(3.5 / G), rel=1e-15)


def test_period_endpoint_takes_g(client):
    body = client.get("/api/period", params={"length": "2", "amplitude": "1", "g": "1.62"}).json()
    assert body["g"] == 1.62
    assert body["period"] == pytest.approx(ellipk_period(2, 1, 1.62), rel=1e-14)


def test_simulate_reproduces_figure3(client):
    r = client.get("/api/simulate", params=FIG3_QUERY)
    assert r.status_code == 200
    body = r.json()
    assert body["n_steps"] == 21 and body["thinning"] == "none" and body["points"] == 22
    t = np.array(body["t"])
    for t_ref, (z1, z2) in FIGURE3.items():
        i = int(round(t_ref / 0.1))
        assert t[i] == pytest.approx(t_ref, abs=1e-12)
        assert body["theta"][i] == pytest.approx(z1, rel=5e-12, abs=1e-12)
        assert body["omega"][i] == pytest.approx(z2, rel=5e-12, abs=1e-12)
    assert body["units"] == {"t": "s", "theta": "rad", "omega": "rad/s", "period": "s", "energy": "m g l"}
    # Figure 2: the period lies in (2.0, 2.1) s.
    est = body["period"]["estimate"]
    assert est["bracket"] == pytest.approx([2.0, 2.1])
    assert body["period"]["period"] == pytest.approx(ellipk_period(1, math.pi / 4), rel=1e-14)


@pytest.mark.parametrize(("method", "step"), [("taylor2", 0.1), ("taylor2", 1e-3), ("rk4", 0.05), ("verlet", 0.05),
                                            ("taylor:8", 0.02), ("rk4", 1e-4)])  # rk4 at 1e-4: errors near T's ulp
def test_the_estimates_shown_carry_only_right_digits(client, method, step):
    """The page prints ``shown``: each of its digits right against mpmath's period (within one
    unit of the last place), and one digit fewer than the double where the error is visible."""
    alpha = 2.0
    body = client.get("/api/simulate", params={"length": 1, "amplitude": alpha, "step": step, "method": method,
                                               "t_max": 1}).json()
    e = body["period"]["estimate"]
    mpmath.mp.dps = 40
    truth = 2 * mpmath.pi * mpmath.sqrt(1 / mpmath.mpf(G)) / mpmath.agm(1, mpmath.cos(mpmath.mpf(alpha) / 2))
    for k in ("linear", "cubic"):
        text = e["shown"][k]
        mant, exp = digits.split(text)
        place = (exp or 0) - (len(mant.split(".")[1]) if "." in mant else 0)
        assert abs(mpmath.mpf(text) - truth) <= mpmath.mpf(10) ** place, (k, text, e[k])
        assert abs(e[k] - float(truth)) > 0.5 * 10.0 ** (place - 1), (k, text, e[k])  # not one digit more
        assert len(mant.replace(".", "").lstrip("0")) < 16  # not the double's 16-17 digits
        for suffix, scale in (("_error", 1), ("_relative", truth)):  # |x - T|, |x - T|/T against the truth
            shown, want = e["shown"][k + suffix], abs(mpmath.mpf(e[k]) - truth) / scale
            if shown.startswith("<= "):
                assert want <= mpmath.mpf(shown[3:]), (k, suffix, shown)
            else:
                m, x = digits.split(shown)
                unit = mpmath.mpf(10) ** ((x or 0) - (len(m.split(".")[1]) if "." in m else 0))
                assert abs(mpmath.mpf(shown) - want) <= unit, (k, suffix, shown, mpmath.nstr(want, 6))


def test_simulate_estimates_are_the_librarys(client):
    body = client.get("/api/simulate", params=P5_QUERY).json()
    alpha = 0.8 * math.pi
    e = estimate_period(3.5, alpha, 1e-3)
    got = body["period"]["estimate"]
    assert body["period"]["reason"] is None
    assert (got["j"], got["bracket"], got["linear"], got["cubic"]) == (e.j, list(e.bracket), e.linear, e.cubic)
    assert got["cubic_error_estimate"] == e.cubic_error_estimate
    exact = ellipk_period(3.5, alpha)
    assert got["errors"]["linear"] == pytest.approx(abs(e.linear - exact), rel=1e-6)
    assert got["errors"]["cubic"] == pytest.approx(abs(e.cubic - exact), rel=1e-6)
    assert got["errors"]["bracket_mid"] == pytest.approx(abs(sum(e.bracket) / 2 - exact), rel=1e-6)
    assert got["bracket"][0] < exact < got["bracket"][1] + 1e-3  # h = 1e-3: the bracket is off by O(h^2 T)


def test_simulate_keeps_every_columns_min_and_max(client):
    # 100 001 steps in 1000 columns: each column's smallest and largest theta, at their
    # steps, as the library's own full trajectory has them.
    q = {"length": "3.5", "amplitude": "4pi/5", "step": "1e-4", "t_max": "10", "points": "2000"}
    body = client.get("/api/simulate", params=q).json()
    assert body["n_steps"] == 100_000 and body["columns"] == 1000
    assert body["thinning"] == "min/max per column" and body["points"] <= 2000
    full = simulation.simulate(3.5, 0.8 * math.pi, 1e-4, 10.0)
    idx = np.rint(np.array(body["t"]) / 1e-4).astype(int)
    assert np.all(np.diff(idx) > 0) and idx[0] == 0
    assert body["theta"] == full.theta[idx].tolist() and body["omega"] == full.omega[idx].tolist()
    col = np.arange(100_001) * 1000 // 100_001
    lo = np.minimum.reduceat(full.theta, np.searchsorted(col, np.arange(1000)))
    hi = np.maximum.reduceat(full.theta, np.searchsorted(col, np.arange(1000)))
    got_col = idx * 1000 // 100_001
    for c in (0, 1, 250, 999):
        mine = full.theta[idx[got_col == c]]
        assert mine.min() == lo[c] and mine.max() == hi[c]
    assert np.array_equal(np.unique(got_col), np.arange(1000))


@pytest.mark.slow
def test_long_run_plots_keep_the_shape():
    # l = 1, 30 deg, h = 1e-3, t_max = 2000 s: 980 periods. Every column that holds a turn
    # of the simulation reaches its extreme; the phase curve has no chord across the orbit.
    p = {"length": "1", "amplitude": "30deg", "step": "1e-3", "t_max": "2000"}
    body = views.simulate_view(p)
    alpha = body["input"]["amplitude"]  # 30 deg exactly, rounded once: may differ from math.radians(30)
    assert alpha == pytest.approx(math.pi / 6, rel=1e-15)
    full = simulation.simulate(1, alpha, 1e-3, 2000.0)
    theta = np.array(body["theta"])
    t = np.array(body["t"])
    # Columns of the plot (here 400 pixels): wherever the trajectory has a local max or min.
    px = np.floor(t / 2000.0 * 400).astype(int)
    turns = np.flatnonzero((full.omega[:-1] > 0) != (full.omega[1:] > 0))
    for i in turns[::7]:
        c = min(int(full.t[i] / 2000.0 * 400), 399)
        drawn = theta[px == c]
        target = full.theta[i]
        assert (drawn.max() if target > 0 else -drawn.min()) >= 0.99 * abs(target)
        assert abs(target) == pytest.approx(alpha, rel=1e-3)
    ph_th = np.array(body["phase"]["theta"], dtype=float)
    ph_om = np.array(body["phase"]["omega"], dtype=float)
    width = np.nanmax(ph_th) - np.nanmin(ph_th)
    seg = np.hypot(np.diff(ph_th) / width, np.diff(ph_om) / (np.nanmax(ph_om) - np.nanmin(ph_om)))
    assert np.nanmax(seg) < 0.05 and body["phase"]["orbits"] > 2
    # The animation's samples are the simulation's states at their times.
    ft = np.array(body["frames"]["t"])
    fi = np.rint(ft / 1e-3).astype(int)
    assert body["frames"]["theta"] == full.theta[fi].tolist()
    assert body["frames"]["per_period"] >= 8


def test_exact_overlay_error_and_energy_are_the_librarys(client):
    from pendulab.numerics.motion import energy, exact_motion

    q = {"length": "1", "amplitude": "pi/4", "step": "1e-2", "t_max": "30", "method": "taylor2"}
    body = client.get("/api/simulate", params=q).json()
    alpha = math.pi / 4
    T = ellipk_period(1, alpha)
    ex_t, ex_th = np.array(body["exact"]["t"]), np.array(body["exact"]["theta"])
    # The exact curve reaches +-alpha at its turns k T/2 (mpmath's T), and is the exact motion elsewhere.
    for k in range(1, int(30 / (T / 2))):
        i = np.argmin(abs(ex_t - k * T / 2))
        assert ex_t[i] == pytest.approx(k * T / 2, rel=1e-12) and ex_th[i] == (-1) ** k * alpha
    assert np.allclose(ex_th, exact_motion(1, alpha, ex_t).theta, rtol=0, atol=1e-12)
    full = simulation.simulate(1, alpha, 1e-2, 30.0)
    et = np.array(body["error"]["t"])
    ei = np.rint(et / 1e-2).astype(int)
    assert np.allclose(body["error"]["theta"], full.theta[ei] - exact_motion(1, alpha, et).theta, rtol=0, atol=1e-14)
    drift = energy(full.theta, full.omega, 1.0) / G + math.cos(alpha)  # in m g l
    gt = np.array(body["energy"]["t"])
    assert np.allclose(body["energy"]["drift"], drift[np.rint(gt / 1e-2).astype(int)], rtol=0, atol=1e-14)
    assert body["flags"]["max_energy_drift"] == pytest.approx(np.max(np.abs(drift)), rel=1e-9)


def test_blown_up_simulation_is_flagged(client):
    # l = 10 um, h = 1e-3 s: 3 steps a period; the discrete pendulum spins over the top.
    body = client.get("/api/simulate", params={"length": "1e-5", "amplitude": "30deg", "step": "1e-3", "t_max": "20"}).json()
    flags = body["flags"]
    assert not flags["trustworthy"] and flags["left_oscillation_t"] > 0
    assert any("over the top" in w for w in flags["warnings"])
    full = simulation.simulate(1e-5, body["input"]["amplitude"], 1e-3, 20.0)
    first = int(np.argmax(np.abs(full.theta) >= math.pi))
    assert flags["left_oscillation_t"] == pytest.approx(first * 1e-3)
    # Energy drift, the other kind: Euler's method gains energy every swing.
    body = client.get("/api/simulate", params={"length": "1", "amplitude": "30deg", "step": "1e-2", "t_max": "20",
                                                "method": "taylor:1"}).json()
    assert not body["flags"]["trustworthy"] and "the energy grows" in body["flags"]["warnings"][0]
    # A good simulation is not flagged.
    body = client.get("/api/simulate", params=P5_QUERY | {"method": "rk4"}).json()
    assert body["flags"]["trustworthy"] and body["flags"]["warnings"] == []


def test_simulate_without_period_says_why(client):
    # At rest nothing moves; a huge step sends the discrete pendulum over the top.
    body = client.get("/api/simulate", params={"length": "1", "amplitude": "0", "step": "0.01", "t_max": "2"}).json()
    assert body["period"]["estimate"] is None and "amplitude" in body["period"]["reason"]
    assert body["theta"] == [0.0] * 201
    body = client.get("/api/simulate", params={"length": "1", "amplitude": "3", "step": "0.5", "t_max": "20"}).json()
    assert body["period"]["estimate"] is None and "over the top" in body["period"]["reason"]


@pytest.mark.parametrize("query, status, words", [
    # rk4 at h = 1 s on a 2 s pendulum: no sign change near P within 1.5 T + 4h.
    ({"length": "1", "amplitude": "0.5", "step": "1", "t_max": "20", "method": "rk4"}, "no_return", "does not return"),
    # h = 0.8 s: theta' changes sign at the first or second step, before two earlier points exist.
    ({"length": "1", "amplitude": "0.1", "step": "0.8", "t_max": "20", "method": "rk4"}, "too_early", "too early"),
    ({"length": "1", "amplitude": "0", "step": "0.01", "t_max": "2"}, "not_run", "at rest"),
    ({"length": "1", "amplitude": "1", "step": "0.01", "t_max": "2", "omega0": "1"}, "not_run", "release at rest"),
    # within 8e-13 of pi: rk4 returns, 30 % off, with an energy error above the distance to the separatrix
    ({"length": "1", "amplitude": "3.141592653589", "step": "0.001", "t_max": "2", "method": "rk4"}, "untrusted",
     "cannot be trusted near the separatrix"),
])
def test_no_estimate_has_a_status_and_a_reason(client, query, status, words):
    from pendulab.numerics.crossing import search_period

    period = client.get("/api/simulate", params=query).json()["period"]
    assert (period["estimate"], period["status"]) == (None, status) and words in period["reason"]
    if status == "no_return":  # the search's own span, 1.5 T + 4h, is what it names
        s = search_period(1.0, 0.5, 1.0, method="rk4")
        assert f"{s.t_max:.4g} s" in period["reason"] and "--t-max" not in period["reason"]
    rows = client.get("/api/convergence", params=query | {"steps": query["step"]}).json()["rows"] if status != "not_run" else []
    assert all((r["estimate"], r["status"]) == (None, status) and words in r["reason"] for r in rows)


def test_over_the_top_is_the_time_the_plain_program_finds(client):
    # The coursework's program (3) from 4 pi/5 with h = 0.5 s: the first t_j with |theta| > pi.
    kind, t = plain_pendulum.first_event(1.0, 0.5, 20.0)
    assert kind == "leaves"
    body = client.get("/api/simulate", params={"length": "1", "amplitude": "4pi/5", "step": "0.5", "t_max": "20"}).json()
    period = body["period"]
    assert (period["estimate"], period["status"]) == (None, "left_oscillation")
    assert f"t = {t:.6g} s" in period["reason"] and "step h = 0.5 s is too large" in period["reason"]
    assert body["flags"]["left_oscillation_t"] == t  # the streamed pass and the search see the same step
    ok = client.get("/api/simulate", params=P5_QUERY).json()["period"]
    assert ok["status"] == "found" and ok["reason"] is None and ok["estimate"]["j"] > 0


def test_an_underflowing_search_says_which_amplitude_works():
    # h (g/l) alpha = 1e-6 x 1 x 1e-320 rounds to zero: theta' never moves.
    est = views.estimate_view(1.0, 1e-320, 1e-6, 1.0, "taylor2")
    assert (est["estimate"], est["status"]) == (None, "no_return")
    assert f"amplitude above {5e-324 / 1e-6 / 2:.3g} rad" in est["reason"]


def test_simulate_blow_up_is_valid_json_and_flagged(client):
    # h = 1 with c = -9.8: the Taylor map is unstable, theta overflows to inf then NaN.
    r = client.get("/api/simulate", params={"length": "1", "amplitude": "3", "step": "1", "t_max": "2000", "points": "3000"})
    assert r.status_code == 200
    body = r.json()
    full = simulation.simulate(1, 3, 1, 2000)
    first_bad = int(np.argmax(~np.isfinite(full.theta) | ~np.isfinite(full.omega)))
    assert first_bad > 0 and body["flags"]["nonfinite_t"] == first_bad
    assert body["theta"][0] == 3.0 and "blew up" in body["flags"]["warnings"][0]


@pytest.mark.parametrize("method", [m.name for m in methods.menu()])
def test_every_method_simulates(client, method):
    body = client.get("/api/simulate", params=P5_QUERY | {"method": method}).json()
    assert body["input"]["method"] == method
    assert body["period"]["estimate"]["errors"]["cubic"] < 1e-3


def test_trajectory_csv_is_the_full_trajectory(client):
    r = client.get("/api/trajectory.csv", params=FIG3_QUERY)
    assert r.status_code == 200 and r.headers["content-type"].startswith("text/csv")
    assert "attachment" in r.headers["content-disposition"] and ".csv" in r.headers["content-disposition"]
    lines = r.text.splitlines()
    assert lines[0] == "t,theta,omega"
    rows = np.array([[float(x) for x in line.split(",")] for line in lines[1:]])
    assert rows.shape == (22, 3)
    for t_ref, (z1, z2) in FIGURE3.items():
        row = rows[int(round(t_ref / 0.1))]
        assert row[1:] == pytest.approx([z1, z2], rel=5e-12, abs=1e-12)
    # Full precision: the shortest repr of each double reads back to the same double.
    full = simulation.simulate(1, math.pi / 4, 0.1, 2.1)
    assert rows[:, 1].tolist() == full.theta.tolist()


def test_trajectory_csv_thins_on_request(client):
    r = client.get("/api/trajectory.csv", params=P5_QUERY | {"points": "101"})
    assert len(r.text.splitlines()) == 1 + 101


def test_convergence_errors_fall_like_the_method_order(client):
    body = client.get("/api/convergence", params={"length": "3.5", "amplitude": "4pi/5", "steps": "1e-2,1e-3"}).json()
    assert body["method"] == "taylor2" and body["order"] == 2
    assert body["period"]["period"] == pytest.approx(ellipk_period(3.5, 0.8 * math.pi), rel=1e-14)
    (a, b) = body["rows"]
    assert (a["step"], b["step"]) == (1e-2, 1e-3)
    ratio = a["estimate"]["errors"]["cubic"] / b["estimate"]["errors"]["cubic"]
    assert 10**1.7 < ratio < 10**2.3  # second order: h / 10 gives error / 100


def test_convergence_default_steps(client):
    body = client.get("/api/convergence", params={"length": "1", "amplitude": "pi/4"}).json()
    steps = [r["step"] for r in body["rows"]]
    assert steps[0] == pytest.approx(0.1) and steps[-1] == pytest.approx(1e-4) and len(steps) == 13


# ---------------------------------------------------------------- static files, offline

def test_page_and_its_files_are_local(client):
    page = client.get("/")
    assert page.status_code == 200 and "text/html" in page.headers["content-type"]
    for needle in ("http://", "https://", "//cdn"):
        assert needle not in page.text.replace('href="/api/docs"', "")
    assert client.get("/static/app.js").status_code == 200
    assert client.get("/static/style.css").headers["content-type"].startswith("text/css")


def test_plotly_is_the_shipped_basic_bundle_with_its_licence(client):
    from pendulab.web.app import STATIC

    r = client.get("/vendor/plotly.min.js")
    assert r.status_code == 200 and r.headers["content-type"].startswith("text/javascript")
    assert r.content == (STATIC / "plotly-basic.min.js").read_bytes()
    assert r.content.startswith(b"/**\n* plotly.js (basic - minified)")
    assert "MIT License" in (STATIC / "plotly-basic.LICENSE.txt").read_text()


@pytest.mark.parametrize("path", ["/", "/static/app.js", "/vendor/plotly.min.js", "/api/config",
                                  "/api/simulate?length=1&amplitude=30deg&step=1e-3&t_max=20"])
def test_answers_are_gzipped_when_the_client_accepts_it(client, path):
    plain = client.get(path, headers={"Accept-Encoding": "identity"})
    packed = client.get(path, headers={"Accept-Encoding": "gzip"})
    assert "content-encoding" not in plain.headers
    assert packed.headers["content-encoding"] == "gzip"
    # httpx decodes it: the same bytes, sent in fewer (the raw stream is the gzip member).
    assert packed.content == plain.content
    assert int(packed.headers["content-length"]) < 0.5 * len(plain.content)


@pytest.mark.parametrize("path", ["/static/nothing.js", "/static/..%2fapp.py", "/static/%2e%2e/api.py", "/api/nothing", "/nothing"])
def test_unknown_paths_are_json_404(client, path):
    r = client.get(path)
    assert r.status_code == 404 and "error" in r.json()


def test_an_internal_error_is_500_and_the_server_keeps_serving(monkeypatch):
    c = TestClient(create_app(), base_url="http://localhost", raise_server_exceptions=False)

    def boom(params):
        raise RuntimeError("a bug")

    monkeypatch.setattr(views, "simulate_view", boom)
    r = c.get("/api/simulate", params=FIG3_QUERY)
    assert r.status_code == 500 and r.json()["error"]["message"] == "internal error: RuntimeError"
    assert c.get("/api/period", params={"length": "1", "amplitude": "1"}).status_code == 200


# ---------------------------------------------------------------- bad input: 422 naming the field

def assert_422(r, field: str, allowed_part: str = ""):
    assert r.status_code == 422, r.text[:300]
    err = r.json()["error"]
    assert err["field"] == field
    assert allowed_part in err["allowed"]
    assert err["message"].startswith(f"{field} = ") and err["allowed"] in err["message"]
    return err


SIM_ENDPOINTS = ["/api/simulate", "/api/trajectory.csv"]
PENDULUM_ENDPOINTS = SIM_ENDPOINTS + ["/api/period", "/api/convergence"]

BAD_NUMBERS = ["abc", "-1", "0", "nan", "inf", "-inf", "1e400", "1/0", "", "1e99999999", "9" * 70, "1,5", "0x10"]


@pytest.mark.parametrize("endpoint", PENDULUM_ENDPOINTS)
@pytest.mark.parametrize("field", ["length", "g"])
@pytest.mark.parametrize("bad", BAD_NUMBERS)
def test_bad_length_or_g(client, endpoint, field, bad):
    r = client.get(endpoint, params=P5_QUERY | {field: bad})
    if field == "g" and bad == "":  # empty counts as missing, and g defaults to the coursework's
        assert r.status_code == 200
        return
    err = assert_422(r, field, "> 0")
    if bad == "":
        assert err["value"] == "(missing)"


@pytest.mark.parametrize("endpoint", SIM_ENDPOINTS)
@pytest.mark.parametrize("field", ["step", "t_max"])
@pytest.mark.parametrize("bad", BAD_NUMBERS)
def test_bad_step_or_t_max(client, endpoint, field, bad):
    assert_422(client.get(endpoint, params=P5_QUERY | {field: bad}), field, "> 0")


@pytest.mark.parametrize("endpoint", PENDULUM_ENDPOINTS)
@pytest.mark.parametrize("bad", ["pi", "180deg", "4pi/4", "3.2", "-0.1", "-pi/4", "1e400", "abc", "45 degrees east", "1e99999999pi", "nan"])
def test_bad_amplitude(client, endpoint, bad):
    assert_422(client.get(endpoint, params=P5_QUERY | {"amplitude": bad}), "amplitude", "[0, pi)")


@pytest.mark.parametrize("endpoint", PENDULUM_ENDPOINTS)
@pytest.mark.parametrize("field", ["length", "amplitude"])
def test_missing_pendulum_field(client, endpoint, field):
    q = {k: val for k, val in P5_QUERY.items() if k != field}
    assert assert_422(client.get(endpoint, params=q), field)["value"] == "(missing)"


@pytest.mark.parametrize("endpoint", SIM_ENDPOINTS)
@pytest.mark.parametrize("field", ["step", "t_max"])
def test_missing_simulation_field(client, endpoint, field):
    q = {k: val for k, val in P5_QUERY.items() if k != field}
    assert assert_422(client.get(endpoint, params=q), field)["value"] == "(missing)"


@pytest.mark.parametrize("endpoint", SIM_ENDPOINTS)
def test_step_not_below_t_max(client, endpoint):
    assert_422(client.get(endpoint, params=P5_QUERY | {"step": "10"}), "step", "< t_max")


@pytest.mark.parametrize("endpoint", SIM_ENDPOINTS + ["/api/convergence"])
@pytest.mark.parametrize("bad", ["rk5", "TAYLOR2", "taylor2; drop", "x" * 100])
def test_unknown_method(client, endpoint, bad):
    err = assert_422(client.get(endpoint, params=P5_QUERY | {"method": bad}), "method")
    assert all(m.name in err["allowed"] for m in methods.menu()) or len(bad) > 64
    if len(bad) <= 40:  # as typed, as every other field echoes it (was a repr, 'rk5')
        assert err["value"] == bad and err["message"].startswith(f"method = {bad} is not allowed")


@pytest.mark.parametrize("endpoint", SIM_ENDPOINTS)
def test_more_than_1e7_steps_is_refused(client, endpoint):
    # t_max / h = 1e7 + 1 steps: refused before anything runs.
    err = assert_422(client.get(endpoint, params=P5_QUERY | {"step": "1e-6", "t_max": "10.000001"}), "step", "1e+07")
    assert err["value"] == "1e-6"  # as typed
    # A short trajectory, but the period search of /api/simulate would stream over 1.5 T / h
    # = 3e7 steps (T ~ 2.1e3 s for l = 1000 km): the trajectory is answered, the estimate
    # is not, and says why; the CSV runs no search.
    q = {"length": "1e6", "amplitude": "1", "step": "1e-4", "t_max": "1"}
    r = client.get(endpoint, params=q)
    assert r.status_code == 200
    if endpoint == "/api/simulate":
        est = r.json()["period"]
        assert est["estimate"] is None and "1e+07" in est["reason"] and "step" in est["reason"]
        assert est["status"] == "not_run"
        assert r.json()["n_steps"] == 10_000
    else:
        assert len(r.text.splitlines()) == 1 + 10_001


@pytest.mark.parametrize("endpoint, most", [("/api/simulate", "20000"), ("/api/trajectory.csv", "1000000")])
@pytest.mark.parametrize("bad", ["1", "0", "-5", "1000001", "1e7", "2.5", "many", "１０"])
def test_bad_points(client, endpoint, most, bad):
    assert_422(client.get(endpoint, params=P5_QUERY | {"points": bad}), "points", f"[2, {most}]")


@pytest.mark.parametrize("bad, allowed", [("1e-2,-1", "steps > 0"), ("1e-2,,abc", "steps > 0"), (",".join(["0.01"] * 41), "1 to 40"),
                                          ("1e-7", "1e+07"), ("0.01,1e99999", "steps > 0")])
def test_bad_convergence_steps(client, bad, allowed):
    q = {"length": "3.5", "amplitude": "4pi/5", "steps": bad}
    assert_422(client.get("/api/convergence", params=q), "steps", allowed)


def test_bad_input_answers_fast_even_when_huge(client):
    # The exact parser would build a 10^99999999 integer: the web layer refuses it first.
    for text in ("1e99999999", "1e-99999999", "1e99999999/3"):
        assert_422(client.get("/api/period", params={"length": text, "amplitude": "1"}), "length")


def test_unknown_parameters_are_ignored(client):
    assert client.get("/api/period", params={"length": "1", "amplitude": "1", "colour": "red"}).status_code == 200


# ---------------------------------------------------------------- the CLI command

def test_serve_help(capsys):
    assert main(["serve", "--help"]) == 0
    out = capsys.readouterr().out
    assert "--port" in out and "--host" in out and "127.0.0.1" in out


@pytest.fixture
def busy_port():
    """A port of 127.0.0.1 that a listening socket holds until the test ends."""
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen()
        yield s.getsockname()[1]


def test_serve_on_a_busy_port_is_one_line_exit_2(capsys, busy_port):
    assert main(["serve", "--port", str(busy_port)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"127.0.0.1:{busy_port}" in err and "Traceback" not in err


@pytest.mark.parametrize("bad", ["0", "70000", "http"])
def test_serve_bad_port(capsys, bad):
    assert main(["serve", "--port", bad]) == 2
    assert "--port" in capsys.readouterr().err


def test_api_docs_are_served_locally(client):
    import swagger_ui_bundle

    page = client.get("/api/docs")
    assert page.status_code == 200
    assert "http://" not in page.text and "https://" not in page.text
    js = client.get("/vendor/swagger/swagger-ui-bundle.js")
    assert js.content == (Path(swagger_ui_bundle.swagger_ui_path) / "swagger-ui-bundle.js").read_bytes()
    assert client.get("/vendor/swagger/index.html").status_code == 404
    # The Swagger UI shipped reads OpenAPI 3.0 documents only.
    schema = client.get("/api/openapi.json").json()
    assert schema["openapi"].startswith("3.0.") and "/api/simulate" in schema["paths"]


@pytest.mark.slow
def test_csv_streams_in_blocks():
    # 10^6 rows are never held at once: the text comes in blocks of CSV_BLOCK rows, each
    # computed when asked for, and they join into the library's trajectory.
    p = parameters.simulation({"length": "1", "amplitude": "1", "step": "1e-3", "t_max": "50"})
    blocks = views.csv_blocks(p, limits.MAX_CSV_ROWS)
    first = next(blocks)
    assert first.count("\n") == 2  # the header and t = 0
    rest = list(blocks)
    assert len(rest) == math.ceil(50_000 / views.CSV_BLOCK)
    assert max(b.count("\n") for b in rest) == views.CSV_BLOCK
    rows = np.array([[float(x) for x in line.split(",")] for line in (first + "".join(rest)).splitlines()[1:]])
    full = simulation.simulate(1, 1, 1e-3, 50.0)
    assert rows[:, 1].tolist() == full.theta.tolist() and rows[:, 2].tolist() == full.omega.tolist()
    assert np.array_equal(rows[:, 0], full.t)


def test_serve_suggests_a_free_port_and_lists_lan_addresses(capsys, monkeypatch, busy_port):
    import socket

    from pendulab.cli import serve as serve_cmd

    assert main(["serve", "--port", str(busy_port)]) == 2
    err = capsys.readouterr().err
    free = int(err.split("port ")[-1].split()[0])
    assert free > busy_port and f"pendulab serve --port {free}" in err
    with socket.socket() as s:
        s.bind(("127.0.0.1", free))  # the port named is free
    assert all(not a.startswith("127.") for a in serve_cmd.lan_addresses())
    monkeypatch.setattr(serve_cmd, "lan_addresses", lambda: ["192.168.1.20", "10.0.0.5"])
    assert serve_cmd.urls("0.0.0.0", 8000) == ["http://192.168.1.20:8000/", "http://10.0.0.5:8000/", "http://127.0.0.1:8000/"]
    assert serve_cmd.urls("127.0.0.1", 8000) == ["http://127.0.0.1:8000/"]


def test_a_run_shorter_than_a_period_is_drawn(client):
    # l = 1e6 m: T ~ 2000 s, t_max = 20 s holds a hundredth of a swing; T = 1e150 s as well.
    for length in ("1e6", "1e300"):
        body = client.get("/api/simulate", params={"length": length, "amplitude": "1", "step": "1e-3", "t_max": "20"}).json()
        assert body["n_steps"] == 20_000 and 2 <= len(body["frames"]["t"]) <= sampling.FRAME_POINTS
        assert 2 <= len(body["phase"]["theta"]) <= sampling.PHASE_POINTS and None not in body["phase"]["theta"]
        assert body["frames"]["t"][-1] == pytest.approx(20.0)


# ---------------------------------------------------------------- the classroom lab's answers

def test_flags_tell_a_bounded_oscillation_from_a_drift_and_a_phase_error(client):
    # Verlet at h = 0.2 s: the energy oscillates by about 2 % and does not grow (symplectic).
    q = {"length": "3.5", "amplitude": "144deg", "step": "0.2", "t_max": "20", "method": "verlet"}
    flags = client.get("/api/simulate", params=q).json()["flags"]
    full = simulation.simulate(3.5, 0.8 * math.pi, 0.2, 20.0, method="verlet")
    drift = np.abs(energy(full.theta, full.omega, 3.5) / G + math.cos(0.8 * math.pi)) / (1 - math.cos(0.8 * math.pi))
    quarter = len(drift) // 4
    assert drift.max() > 0.01 and drift[-quarter:].max() < 1.5 * drift[:quarter].max()  # bounded, by the reference
    assert flags["energy_drift_kind"] == "bounded" and flags["trustworthy"] and flags["warnings"] == []
    assert [n["severity"] for n in flags["notes"]] == ["note"]
    # Euler's method gains energy every swing: growth, not the pendulum's motion.
    q = {"length": "1", "amplitude": "30deg", "step": "1e-2", "t_max": "20", "method": "taylor:1"}
    flags = client.get("/api/simulate", params=q).json()["flags"]
    assert flags["energy_drift_kind"] == "growth" and flags["notes"][0]["severity"] == "wrong"
    # taylor2 at h = 0.01 over 2000 s: the energy barely moves, the phase is radians off.
    q = {"length": "3.5", "amplitude": "144deg", "step": "1e-2", "t_max": "2000"}
    body = client.get("/api/simulate", params=q).json()
    full = simulation.simulate(3.5, 0.8 * math.pi, 1e-2, 2000.0)
    ref = np.max(np.abs(full.theta - exact_motion(3.5, 0.8 * math.pi, full.t).theta))
    assert ref > 1 and body["flags"]["max_theta_error"] <= ref and body["flags"]["max_theta_error"] > 0.9 * ref
    assert [n["kind"] for n in body["flags"]["notes"]] == ["phase"] and not body["flags"]["trustworthy"]


def test_motion_is_the_exact_motion(client):
    from scipy.integrate import solve_ivp

    body = client.get("/api/motion", params={"length": "20", "amplitude": "120deg", "t_max": "30"}).json()
    assert body["period"] == pytest.approx(ellipk_period(20, math.radians(120)), rel=1e-14)
    f = body["frames"]
    assert f["t"][0] == 0 and f["t"][-1] == 30 and f["per_period"] == pytest.approx(16, rel=0.1)
    sol = solve_ivp(lambda t, z: [z[1], -G / 20 * math.sin(z[0])], (0, 30), [math.radians(120), 0.0],
                    method="DOP853", rtol=1e-12, atol=1e-14, t_eval=f["t"])
    assert np.allclose(f["theta"], sol.y[0], rtol=0, atol=1e-9) and np.allclose(f["omega"], sol.y[1], rtol=0, atol=1e-9)
    assert client.get("/api/motion", params={"length": "0", "amplitude": "1"}).json()["error"]["field"] == "length"


def test_period_curve_is_the_period_ratio_and_the_formulas(client):
    import mpmath

    body = client.get("/api/period_curve").json()
    assert body["amplitude_deg"] == list(range(180))
    for deg in (1, 60, 179):
        with mpmath.workdps(30):
            ref = 2 * mpmath.ellipk(mpmath.sin(mpmath.radians(deg) / 2) ** 2) / mpmath.pi
        assert body["period_ratio"][deg] == pytest.approx(float(ref), rel=1e-13)
    kf = next(a for a in body["approximations"] if a["name"] == "kidd-fogg")
    assert kf["ratio"][100] == pytest.approx(1 / math.sqrt(math.cos(math.radians(50))), rel=1e-15)


def test_csv_with_every_column(client):
    q = {"length": "1", "amplitude": "pi/4", "step": "0.1", "t_max": "2.1", "columns": "all"}
    lines = client.get("/api/trajectory.csv", params=q).text.splitlines()
    assert lines[0].split(",") == ["t", "theta", "omega", "theta_exact", "omega_exact", "theta_error",
                                   "energy_error"]
    full = simulation.simulate(1, math.pi / 4, 0.1, 2.1)
    rows = np.array([[float(x) for x in line.split(",")] for line in lines[1:]])
    assert np.array_equal(rows[:, 1], full.theta) and np.array_equal(rows[:, 2], full.omega)
    assert np.array_equal(rows[:, 5], rows[:, 1] - rows[:, 3])
    r = client.get("/api/trajectory.csv", params=q | {"columns": "some"})
    assert r.status_code == 422 and r.json()["error"]["field"] == "columns"


def test_a_launch_is_simulated_and_flagged_against_its_own_exact_motion(client):
    from scipy.integrate import solve_ivp

    q = {"length": "1", "amplitude": "17deg", "step": "1e-3", "t_max": "20", "omega0": "7"}
    body = client.get("/api/simulate", params=q).json()
    launch = body["launch"]
    assert launch["circulates"] and launch["turning_angle"] is None
    assert body["flags"]["left_oscillation_t"] is None and body["flags"]["trustworthy"]  # over the top is right here
    assert body["period"]["estimate"] is None and "release at rest" in body["period"]["reason"]
    # The simulation from (alpha, omega0), bit for bit the library's step from that state.
    full = simulation.simulate(1, math.radians(17), 1e-3, 20.0)  # from rest: a different motion
    assert body["theta"][-1] > 2 * math.pi * 15 and abs(full.theta).max() < math.pi
    lines = client.get("/api/trajectory.csv", params=q | {"columns": "all", "points": "201"}).text.splitlines()
    rows = np.array([[float(x) for x in line.split(",")] for line in lines[1:]])
    assert rows[0, 2] == 7.0 and rows[0, 1] == math.radians(17)
    sol = solve_ivp(lambda _, z: [z[1], -G * math.sin(z[0])], (0, 20), [math.radians(17), 7.0],
                    method="DOP853", rtol=1e-12, atol=1e-12, t_eval=rows[:, 0])
    assert np.max(np.abs(rows[:, 3] - sol.y[0])) < 1e-7 and np.max(np.abs(rows[:, 4] - sol.y[1])) < 1e-7
    assert np.max(np.abs(rows[:, 5])) < 1e-2 and np.max(np.abs(rows[:, 6])) < 1e-4  # taylor2 at h = 1e-3 follows it
    # Too little energy to reach the top, and a step too large: the simulation's trip over the top is flagged.
    body = client.get("/api/simulate", params={"length": "1e-5", "amplitude": "30deg", "step": "1e-3", "t_max": "20",
                                                "omega0": "2"}).json()
    assert not body["launch"]["circulates"] and body["flags"]["left_oscillation_t"] is not None
    assert "too little energy" in body["flags"]["warnings"][0]
    r = client.get("/api/simulate", params=q | {"omega0": "inf"})
    assert r.status_code == 422 and r.json()["error"]["field"] == "omega0"


def test_one_period_per_request(monkeypatch):
    # The AGM period and the period as written are computed once per simulation and passed down.
    from pendulab.numerics import crossing, period

    calls = {"agm": 0, "double": 0}
    agm, double = period.agm_period, period.period_double

    def counted_agm(*a, **k):
        calls["agm"] += 1
        return agm(*a, **k)

    def counted_double(*a, **k):
        calls["double"] += 1
        return double(*a, **k)

    monkeypatch.setattr(period, "agm_period", counted_agm)
    monkeypatch.setattr(crossing, "agm_period", counted_agm)
    monkeypatch.setattr(period, "period_double", counted_double)
    body = views.simulate_view(P5_QUERY)
    # periods(): the period of the doubles and the period as written, each once, both by Arb.
    assert calls == {"agm": 0, "double": 2}
    assert body["period"]["period"] == pytest.approx(ellipk_period(3.5, 0.8 * math.pi), rel=1e-14)
    assert body["period"]["estimate"]["period"] == body["period"]["period"]
