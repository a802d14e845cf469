"""What a simulation's numbers do (pendulab.numerics.diagnosis), and the explorer's words for it.

References: each method's steps written out here in numpy, the textbook formulas (Euler,
the coursework's Taylor algorithm (3), classical Runge-Kutta, Stormer-Verlet in velocity
form), independent of the library's kernels; the energy ``E/(m g l) = l theta'^2/(2g) +
1 - cos(theta)``; synthetic energy records for the classification's rule.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from pendulab.core.methods import menu
from pendulab.numerics import diagnosis
from pendulab.numerics.diagnosis import diagnose, energy_kind
from pendulab.web import views
from reference import G

# ---------------------------------------------------------------- the rule, on records built for it

@settings(max_examples=200, deadline=None)
@given(a=st.floats(1e-6, 5.0), period=st.floats(0.1, 10.0), periods=st.floats(2.5, 200.0),
       phase=st.floats(0.0, 1.0))
@example(a=2.0, period=1.0, periods=153.87, phase=0.0)  # 26 samples a swing would miss every return
def test_an_error_that_comes_back_at_every_turn_is_bounded(a, period, periods, phase):
    # A symplectic method's error: zero at each turning point, the same size every swing.
    t_end = periods * period
    # 200 samples a swing, as a record of the run has them: coarser samples can miss every
    # return to zero (26 a swing stay 1.4 % of a above it) and the record would not show one.
    t = np.linspace(0.0, t_end, max(4001, int(200 * periods) + 1))
    r = a * np.sin(2 * math.pi * t / period) ** 2 * (1 if phase < 0.5 else -1)
    assert energy_kind(t, r, period, t_end) == "bounded"


@settings(max_examples=200, deadline=None)
@given(loss=st.floats(0.02, 1.0), tau=st.floats(0.01, 0.3), wobble=st.floats(0.0, 0.009), sign=st.sampled_from([-1, 1]))
def test_an_energy_that_never_comes_back_is_decay_or_growth(loss, tau, wobble, sign):
    # Lost (or gained) within the first part of the run and never back: however little it moves after.
    period, t_end = 1.0, 20.0
    t = np.linspace(0.0, t_end, 4001)
    r = sign * loss * (1 - np.exp(-t / (tau * t_end))) + wobble * np.sin(2 * math.pi * t / period) ** 2
    r[0] = 0.0
    late = r[t >= t_end - 0.25 * t_end]
    if sign < 0 and late.max() < -diagnosis.RETURN:
        assert energy_kind(t, r, period, t_end) == "decay"
    if sign > 0 and late.min() > diagnosis.RETURN:
        assert energy_kind(t, r, period, t_end) == "growth"


@settings(max_examples=200, deadline=None)
@given(a=st.floats(1e-6, 1.0), ratio=st.floats(2.2, 50.0), sign=st.sampled_from([-1, 1]))
def test_an_oscillation_that_widens_is_growth_or_decay_by_its_sign(a, ratio, sign):
    # Back at E0 at every turn, but each swing's error larger: the last window's over 1.5 times the first's.
    period, t_end = 1.0, 40.0
    t = np.linspace(0.0, t_end, 8001)
    r = sign * a * (1 + (ratio - 1) * t / t_end) * np.sin(2 * math.pi * t / period) ** 2
    assert energy_kind(t, r, period, t_end) == ("growth" if sign > 0 else "decay")


@pytest.mark.parametrize("t_end", [0.5, 1.0, 1.99])
def test_a_run_shorter_than_two_windows_has_no_kind(t_end):
    t = np.linspace(0.0, t_end, 100)
    assert energy_kind(t, -0.5 * t, 1.0, t_end) is None
    d = diagnose(0.1, t, -0.05 * t / t_end, 1.0, t_end)
    assert [f.kind for f in d.notes] == ["energy-drift"] and not d.trustworthy


def test_over_the_top_or_blown_up_says_nothing_of_the_energy():
    t = np.linspace(0.0, 20.0, 100)
    d = diagnose(0.1, t, -t, 1.0, 20.0, left_t=3.0, error_t=t, error=t)
    assert [(f.kind, f.t) for f in d.notes] == [("over-the-top", 3.0)] and d.energy_drift_kind is None
    d = diagnose(0.1, t, np.where(t > 5, np.nan, -t), 1.0, 20.0, nonfinite_t=5.1)
    assert [f.kind for f in d.notes] == ["blow-up"] and d.max_energy_drift == pytest.approx(t[t <= 5][-1])


@settings(max_examples=100, deadline=None)
@given(size=st.floats(0.0, 2 * diagnosis.BOUNDED_LARGE))
def test_a_bounded_error_is_a_note_only_while_small(size):
    t = np.linspace(0.0, 20.0, 4001)
    d = diagnose(0.5, t, 0.5 * size * np.sin(2 * math.pi * t) ** 2, 1.0, 20.0)
    rel = d.energy_drift_relative
    kinds = [(f.kind, f.severity) for f in d.notes]
    if rel <= diagnosis.ENERGY_WARN:
        assert kinds == []
    elif rel <= diagnosis.BOUNDED_LARGE:
        assert kinds == [("energy-oscillation", "note")] and d.trustworthy
    else:
        assert kinds == [("energy-oscillation-large", "wrong")] and not d.trustworthy


def test_the_diagnosis_is_a_frozen_result_of_codes():
    t = np.linspace(0.0, 20.0, 101)
    d = diagnose(0.1, t, np.zeros_like(t), 1.0, 20.0, error_t=t, error=0.2 * (t > 4))
    out = d.to_dict()
    assert out["notes"] == [{"kind": "phase", "severity": "warn", "t": pytest.approx(t[t > 4][0]), "value": 0.2}]
    assert out["energy_drift_kind"] == "bounded" and out["trustworthy"] is False
    with pytest.raises(AttributeError):
        d.energy_drift_kind = "growth"  # type: ignore[misc]


# ---------------------------------------------------------------- every method and step, run through the page's answer

def _steps(method, alpha, h, n, length):
    """The method's states ``0 .. n`` from ``(alpha, 0)`` for ``theta'' = -(g/l) sin(theta)`` (2)."""
    c = -G / length
    z1, z2 = np.empty(n + 1), np.empty(n + 1)
    a, b = alpha, 0.0
    z1[0], z2[0] = a, b
    for i in range(1, n + 1):
        if method == "taylor:1":  # Euler
            a, b = a + h * b, b + h * c * math.sin(a)
        elif method == "taylor2":  # (3): z + h f + h^2/2 f' (f' = (z2, c cos(z1) z2))
            a, b = a + h * b + 0.5 * h * h * c * math.sin(a), b + h * c * math.sin(a) + 0.5 * h * h * c * math.cos(a) * b
        elif method == "rk4":
            def f(x, y):
                return y, c * math.sin(x)
            k1 = f(a, b)
            k2 = f(a + 0.5 * h * k1[0], b + 0.5 * h * k1[1])
            k3 = f(a + 0.5 * h * k2[0], b + 0.5 * h * k2[1])
            k4 = f(a + h * k3[0], b + h * k3[1])
            a, b = (a + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]),
                    b + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]))
        elif method == "verlet":  # Stormer-Verlet, velocity form
            half = b + 0.5 * h * c * math.sin(a)
            a = a + h * half
            b = half + 0.5 * h * c * math.sin(a)
        else:  # a method of the menu without a reference here: add its step above
            raise AssertionError(f"no reference step for {method}")
        z1[i], z2[i] = a, b
    return z1, z2


#: The lesson's pendulum: l = 1 m, 30 deg, 20 s.
LESSON = {"length": "1", "amplitude": "30deg", "t_max": "20"}
STEPS = (0.6, 0.5, 0.3, 0.25, 0.1, 0.01)


@pytest.mark.slow
@pytest.mark.parametrize("h", STEPS)
@pytest.mark.parametrize("method", ["taylor:1"] + [m.name for m in menu()])  # every method the page offers
def test_each_method_and_step_is_flagged_as_its_energy_behaves(method, h):
    alpha, length, t_end = math.radians(30), 1.0, 20.0
    n = round(t_end / h)
    z1, z2 = _steps(method, alpha, h, n, length)
    t = h * np.arange(n + 1)
    swing = 1 - math.cos(alpha)
    r = (length * z2 ** 2 / (2 * G) + 1 - np.cos(z1) - swing) / swing  # (E - E0)/E0, the reference
    flags = views.simulate_view(LESSON | {"step": repr(h), "method": method})["flags"]
    kinds = [n["kind"] for n in flags["notes"]]
    texts = " ".join(n["text"] for n in flags["notes"])
    over = np.flatnonzero(np.abs(z1) >= math.pi)
    if len(over):  # over the top: said once, with its time, and nothing more of the energy
        assert flags["left_oscillation_t"] == pytest.approx(t[over[0]]) and kinds == ["over-the-top"]
        assert "went over the top" in texts
        return
    assert flags["energy_drift_relative"] == pytest.approx(np.max(np.abs(r)), rel=1e-9)
    late, early = r[t >= 0.75 * t_end], r[t <= 0.25 * t_end]
    kind = flags["energy_drift_kind"]
    if kind == "decay":  # lost for good, or each swing losing more
        assert late.max() < -0.01 or -late.min() > 1.5 * np.abs(early).max()
    elif kind == "growth":
        assert late.min() > 0.01 or late.max() > 1.5 * np.abs(early).max()
    else:  # bounded: back near E0 in the last quarter, and no larger there than in the first
        assert kind == "bounded" and late.max() >= -0.01 and late.min() <= 0.01
        assert np.abs(late).max() <= 1.5 * np.abs(early).max()
    rel = np.max(np.abs(r))
    if rel > diagnosis.ENERGY_WARN:
        word = {"decay": "numerical damping", "growth": "the energy grows", "bounded": "bounded"}[kind]
        assert word in texts
        if kind == "bounded" and rel <= diagnosis.BOUNDED_LARGE:
            assert "neither grows nor decays" in texts and "energy-oscillation" in kinds
        else:  # never a mild note for a large error
            assert any(n["severity"] == "wrong" and n["kind"].startswith("energy") for n in flags["notes"])
    else:
        assert not any(k.startswith("energy") for k in kinds)
    # The methods as theory has them: Verlet's error bounded, Euler's growing, RK4 damping at large steps.
    if method == "verlet":
        assert kind == "bounded"
    if method == "taylor:1":
        assert kind == "growth"
    if method == "rk4" and h >= 0.25:
        assert kind == "decay" and r[-1] < -0.15


def test_rk4_at_half_a_second_is_named_damping():
    # The lesson's case: RK4 at l = 1 m, 30 deg, h = 0.5 s swings down to a standstill.
    flags = views.simulate_view(LESSON | {"step": "0.5", "method": "rk4"})["flags"]
    z1, _ = _steps("rk4", math.radians(30), 0.5, 40, 1.0)
    assert abs(z1[-1]) < 0.05 * math.radians(30)  # the reference: at 20 s nearly at rest (1.5 % of the swing)
    first = flags["notes"][0]
    assert first["kind"] == "energy-decay" and first["severity"] == "wrong"
    assert "numerical damping" in first["text"] and "bounded" not in first["text"]
    assert not flags["trustworthy"]


def test_the_flags_in_portuguese():
    flags = views.simulate_view(LESSON | {"step": "0.5", "method": "rk4", "lang": "pt"})["flags"]
    text = flags["notes"][0]["text"]
    assert "amortecimento numérico" in text and "99,8 %" in text  # a decimal comma
    phase = flags["notes"][1]["text"]
    assert "0,1 rad" in phase and "desfasa" in phase
