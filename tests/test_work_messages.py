"""The refusals of too much work and the choice of the input to blame: one helper each.

Every "too much work" refusal names the argument, its value, the range it must be in and
the numbers that decide it (at most so many steps; these need so many). Where two inputs
share a limit, the one furthest in decades from an ordinary case is blamed.
"""
import math
import re

import mpmath
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from pendulab.core import validate as v
from pendulab.core.errors import InputError
from pendulab.core.methods import resolve
from pendulab.jobs.sweep import sweep
from pendulab.numerics.crossing import estimate_period
from pendulab.numerics.simulation import MAX_STEPS, simulate
from pendulab.numerics.uncertainty import gravity_estimate
from pendulab.web import limits


def _parts(exc: InputError) -> tuple[str, str]:
    """``(value as shown, allowed)`` from the one line ``NAME = VALUE is not allowed: must be ALLOWED``."""
    m = re.fullmatch(rf"{re.escape(exc.name)} = (.+?) is not allowed: must be (.+)", str(exc))
    assert m, str(exc)
    return m.group(1), m.group(2)


def _assert_work_message(exc: InputError, name: str, most: float, need: float, what: str = "steps"):
    shown, allowed = _parts(exc)
    assert exc.name == name and shown
    assert f"(at most {most:.3g} {what}" in allowed, allowed
    assert f"these need {need:.3g}" in allowed, allowed


def test_simulate_names_step_its_bound_the_limit_and_the_need():
    with pytest.raises(InputError) as info:
        simulate(1.0, 0.5, 1e-9, 1e3)
    _assert_work_message(info.value, "step", MAX_STEPS, 1e12)
    assert "step = 1e-09 is not allowed: must be >= t_max/2e+09 = 5e-07 s" in str(info.value)
    alt = info.value.alternative
    assert alt is not None and alt.name == "t_max"
    _assert_work_message(alt, "t_max", MAX_STEPS, 1e12)
    assert "<= 2 s with step = 1e-09 s" in str(alt)


def test_a_dearer_method_names_itself():
    m = resolve("taylor:30")
    most = v.steps_for(m, MAX_STEPS)
    with pytest.raises(InputError) as info:
        estimate_period(1.0, 0.5, 1e-9, t_max=10.0, method="taylor:30")
    _assert_work_message(info.value, "step", most, 1e10, "steps of taylor:30")


def test_work_within_states_the_method_and_its_cost():
    with pytest.raises(InputError) as info:
        v.work_within("steps", "1e-6,2e-6", 5e9, "rk4", MAX_STEPS)
    most = v.steps_for("rk4", MAX_STEPS)
    _assert_work_message(info.value, "steps", most, 5e9, "steps of rk4 in all")
    assert "must be larger or fewer steps" in str(info.value) and "a step of rk4 costs" in str(info.value)


def test_sweep_refuses_naming_the_step():
    with pytest.raises(InputError) as info:
        sweep([0.5], steps=[1e-10])
    exc = info.value
    assert exc.name == "step" and "step = 1e-10 is not allowed: must be >= " in str(exc)
    assert "(at most 2e+09 steps" in str(exc) and "the longest period" in str(exc)


def test_web_limits_blame_step_or_t_max_with_the_numbers():
    m = resolve("taylor2")
    most = limits.max_steps(m)
    with pytest.raises(InputError) as info:
        limits.check_run(20.0, 1e-7, m, "1e-7", "20")
    _assert_work_message(info.value, "step", most, 20.0 / 1e-7, "steps of taylor2")
    assert str(info.value).startswith("step = 1e-7 is not allowed: must be >= 2e-06 s for 20 s")
    with pytest.raises(InputError) as info:
        limits.check_run(1e6, 1e-3, m, "1e-3", "1e6")  # t_max 4.7 decades from 20 s, step none from 1e-3 s
    _assert_work_message(info.value, "t_max", most, 1e9, "steps of taylor2")
    assert "t_max = 1e6 is not allowed: must be <= 1e+04 s with h = 0.001 s" in str(info.value)
    with pytest.raises(InputError) as info:
        limits.check_sweep([10.0, 10.0], [1e-6, 2e-6], m)
    _assert_work_message(info.value, "steps", most, 1.5e7, "steps of taylor2 in all")


@settings(max_examples=60, deadline=None)
@given(step=st.floats(1e-12, 1e-3), t_max=st.floats(1.0, 1e6))
def test_the_stated_bound_is_the_true_one(step, t_max):
    """A step at the bound the message states passes the same check; the one refused does not."""
    limit = 10**6
    try:
        v.steps_within("step", 0.0, t_max, step, limit)
    except InputError as exc:
        bound = float(re.search(r">= t_max/1e\+06 = (\S+) s", str(exc)).group(1))
        assert step < bound
        v.steps_within("step", 0.0, t_max, bound, limit)  # the bound as shown is allowed
    else:
        assert t_max / step <= limit + 0.5


def _mp_decades(value, ordinary):
    with mpmath.workdps(40):
        return abs(mpmath.log10(mpmath.mpf(value) / mpmath.mpf(ordinary)))


positive = st.floats(min_value=5e-324, max_value=1.7e308, allow_nan=False, allow_infinity=False)


@settings(max_examples=200, deadline=None)
@given(a=positive, b=positive)
@example(a=1.0, b=9.80665)  # a tie: the first is blamed
@example(a=5e-324, b=1.0)  # a quotient that underflows
@example(a=1e308, b=1e-300)
def test_furthest_blames_the_input_furthest_in_decades(a, b):
    d_a, d_b = _mp_decades(a, 1.0), _mp_decades(b, 9.80665)
    got = v.furthest(("length", a, 1.0), ("g", b, 9.80665))
    if abs(d_a - d_b) > 1e-9 * max(1, d_a, d_b):  # mpmath decides; float logs may tie closer than that
        assert got == ("length" if d_a > d_b else "g")
    elif d_a == d_b:
        assert got == "length"


def test_gravity_blames_the_input_less_like_a_laboratory_pendulum():
    # T = 1e-200: T^2 underflows to 0; the period is 200 decades from 2 s, the length none from 1 m.
    with pytest.raises(InputError) as info:
        gravity_estimate(1.0, 0.0, 1e-200, 0.0)
    assert info.value.name == "period" and "such that g = 4 pi^2 l/T^2 and its error bounds are finite" in str(info.value)
    with pytest.raises(InputError) as info:
        gravity_estimate(1e-300, 0.0, 1e150, 0.0)  # l/T^2 underflows: the length is further (300 > 149.7)
    assert info.value.name == "length"


def test_period_scale_blames_length_or_g():
    with pytest.raises(InputError) as info:
        v.period_scale(1e308, 1e-292)  # the length 308 decades from 1 m, g 293 from 9.8 m/s^2
    assert info.value.name == "length" and "for g = 1e-292" in str(info.value)
    with pytest.raises(InputError) as info:
        v.period_scale(1e300, 1e-300)  # g is 301 decades from 9.8 m/s^2, the length 300 from 1 m
    assert info.value.name == "g" and math.isfinite(float(str(info.value).split(">= ")[1].split()[0]))
