"""numpy's conventions in every public function that takes an array (``pendulab.numerics.arrays``).

Hypothesis feeds each one arrays with NaN (a missing value), pandas Series, masked arrays,
0-d arrays and numpy scalars, and arrays with one bad element: NaN gives NaN in that element
and the others as computed one by one; a Series gives a Series with its index; a masked
array a masked array with its mask; a scalar of any kind a Python float; a bad element an
``InputError`` naming its index and value. The element values are checked against scipy's
``ellipk`` formula (an independent computation) as well as against the scalar call.
"""
import inspect
import math

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.special import ellipk

import pendulab
from pendulab import InputError, agm_period, approximation_errors, exact_motion, small_angle_period
from reference import G

#: Each public array function as ``f(x)`` of its array argument: (name, call, valid elements, a bad one).
AMPLITUDES = st.floats(0.0, 3.0)
LENGTHS = st.floats(1e-3, 1e3)
TIMES = st.floats(-50.0, 50.0)
FUNCTIONS = {
    "agm_period(amplitude)": (lambda x: agm_period(1.5, x), AMPLITUDES, "amplitude", 4.0),
    "agm_period(length)": (lambda x: agm_period(x, 0.5), LENGTHS, "length", -1.0),
    "agm_period(iterations=7)": (lambda x: agm_period(1.5, x, iterations=7), AMPLITUDES, "amplitude", math.pi),
    "small_angle_period": (lambda x: small_angle_period(x), LENGTHS, "length", 0.0),
    "exact_motion": (lambda x: exact_motion(1.0, 2.0, x).theta, TIMES, "t", math.inf),
    "approximation_errors": (lambda x: approximation_errors(x, names=["small-angle"]).errors["small-angle"],
                             AMPLITUDES, "amplitudes", -0.5),
}
NAMES = sorted(FUNCTIONS)


def one_by_one(name, values):
    """The function on each element alone (a Python float), as an array."""
    f = FUNCTIONS[name][0]
    return np.array([f(float(v)) for v in values], dtype=float).reshape(len(values))


def with_missing(elements):
    """Lists of valid elements with some NaN among them, and at least one of each."""
    return st.lists(st.one_of(elements, st.just(math.nan)), min_size=1, max_size=6).filter(
        lambda xs: any(math.isnan(x) for x in xs) and not all(math.isnan(x) for x in xs))


def test_the_table_holds_every_public_array_function():
    """A public function with an array parameter (annotated ArrayLike) is in the table."""
    functions = [n for n in pendulab.__all__ if inspect.isfunction(getattr(pendulab, n))]
    takes_arrays = {n for n in functions if "ArrayLike" in str(inspect.signature(getattr(pendulab, n)))}
    assert takes_arrays == {"agm_period", "small_angle_period", "exact_motion", "approximation_errors"}


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
@settings(max_examples=25, deadline=None)
@given(data=st.data())
def test_nan_in_nan_out_element_wise(name, data):
    xs = data.draw(with_missing(FUNCTIONS[name][1]))
    out = FUNCTIONS[name][0](np.array(xs))
    nan = np.isnan(xs)
    assert isinstance(out, np.ndarray) and np.array_equal(np.isnan(out), nan)
    assert np.array_equal(out[~nan], one_by_one(name, np.array(xs)[~nan]))


@pytest.mark.parametrize("name", NAMES)
@settings(max_examples=20, deadline=None)
@given(data=st.data())
def test_a_series_gives_a_series_with_its_index(name, data):
    xs = data.draw(with_missing(FUNCTIONS[name][1]))
    index = pd.Index([f"p{i}" for i in range(len(xs))][::-1])
    series = pd.Series(xs, index=index, name="x")
    series[series.isna()] = None  # pandas' missing value
    out = FUNCTIONS[name][0](series)
    if name == "exact_motion" or name == "approximation_errors":  # a result's field: its values, in order
        assert np.array_equal(out, FUNCTIONS[name][0](np.array(xs)), equal_nan=True)
        return
    assert isinstance(out, pd.Series) and out.index.equals(index) and out.name == "x"
    assert np.array_equal(out.to_numpy(), FUNCTIONS[name][0](np.array(xs)), equal_nan=True)


@pytest.mark.parametrize("name", NAMES)
@settings(max_examples=20, deadline=None)
@given(data=st.data())
def test_a_masked_array_keeps_its_mask(name, data):
    xs = data.draw(st.lists(FUNCTIONS[name][1], min_size=1, max_size=6))
    mask = data.draw(st.lists(st.booleans(), min_size=len(xs), max_size=len(xs)))
    # A masked element is missing whatever it holds, a bad value included.
    held = np.where(mask, FUNCTIONS[name][3], xs)
    out = FUNCTIONS[name][0](np.ma.masked_array(held, mask=mask))
    values = np.ma.getdata(out)
    if name in ("exact_motion", "approximation_errors"):  # a result's field: missing is NaN
        assert np.array_equal(np.isnan(values), mask)
    else:
        assert np.ma.isMaskedArray(out) and np.array_equal(np.ma.getmaskarray(out), mask)
    keep = ~np.array(mask)
    assert np.array_equal(values[keep], one_by_one(name, np.array(xs)[keep]))


@pytest.mark.parametrize("name", NAMES)
@settings(max_examples=15, deadline=None)
@given(data=st.data())
def test_every_kind_of_scalar_gives_a_python_float(name, data):
    x = data.draw(FUNCTIONS[name][1])
    f = FUNCTIONS[name][0]
    if name == "approximation_errors":  # takes a list of amplitudes: a 0-d one is one amplitude
        out = approximation_errors(np.array(x), names=["small-angle"]).errors["small-angle"]
        assert out.shape == (1,)
        return
    want = f(x)
    assert type(want) is float
    for same in (np.float64(x), np.array(x), np.float32(x) if float(np.float32(x)) == x else x):
        got = f(same)
        assert type(got) is float and got == want
    assert math.isnan(f(math.nan)) and math.isnan(f(np.array(math.nan)))


@pytest.mark.parametrize("name", NAMES)
@settings(max_examples=15, deadline=None)
@given(data=st.data())
def test_a_bad_element_is_named_by_its_index(name, data):
    xs = data.draw(st.lists(FUNCTIONS[name][1], min_size=1, max_size=6))
    at = data.draw(st.integers(0, len(xs)))
    bad = FUNCTIONS[name][3]
    values = xs[:at] + [bad] + xs[at:] + [bad]  # the first bad one is named
    with pytest.raises(InputError) as err:
        FUNCTIONS[name][0](np.array(values))
    assert err.value.name == FUNCTIONS[name][2] and err.value.index == (at,)
    assert str(err.value).startswith(f"{FUNCTIONS[name][2]}[{at}] = ")


def test_a_bad_element_of_a_2d_array_is_named_by_both_indices():
    with pytest.raises(InputError, match=r"^length\[1, 0\] = -2 is not allowed"):
        small_angle_period(np.array([[1.0, 2.0], [-2.0, 1.0]]))


@settings(max_examples=50, deadline=None)
@given(st.lists(st.one_of(st.floats(0.0, 3.14), st.just(math.nan)), min_size=1, max_size=8))
def test_the_values_are_the_periods(xs):
    """Against 4 sqrt(l/g) K(sin^2(alpha/2)) (scipy), element by element, NaN where missing."""
    a = np.array(xs)
    with np.errstate(invalid="ignore"):
        want = 4 * np.sqrt(1.5 / G) * ellipk(np.sin(a / 2) ** 2)
    got = agm_period(1.5, a)
    assert np.allclose(got, want, rtol=1e-9, equal_nan=True)


def test_a_missing_value_in_a_dataframe_column():
    """A notebook's table with a gap: the period column has a gap in the same row."""
    df = pd.DataFrame({"length": [0.5, None, 2.0], "amplitude": [0.1, 0.2, math.nan]}, index=[10, 20, 30])
    periods = agm_period(df["length"], df["amplitude"])
    assert isinstance(periods, pd.Series) and list(periods.index) == [10, 20, 30]
    assert periods.isna().tolist() == [False, True, True]
    assert periods[10] == agm_period(0.5, 0.1)


def test_exact_motion_at_one_time_is_floats():
    m = exact_motion(1.0, 0.5, 0.5)
    assert type(m.t) is float and type(m.theta) is float and type(m.omega) is float
    assert m.to_dict()["theta"] == m.theta
    at_nan = exact_motion(1.0, 0.5, [0.5, math.nan])
    assert at_nan.theta[0] == m.theta and math.isnan(at_nan.theta[1]) and math.isnan(at_nan.t[1])
    assert not at_nan.theta.flags.writeable  # still a result's sealed array
