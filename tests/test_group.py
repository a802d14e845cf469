"""The group's pendulum length, problem 3(b) and its footnote 4."""
import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pendulab.core.errors import InputError
from pendulab.numerics.group import group_length
from reference import EXAMPLE_LENGTH, EXAMPLE_LENGTH_TEXT


def test_spec_example():
    # Footnote 4: 262, 407, 634 give m = 133 and l = 2.0800838231.
    res = group_length([262, 407, 634])
    assert res.sum == 1303 and res.digits == "133"
    assert res.length_text == EXAMPLE_LENGTH_TEXT and res.length == EXAMPLE_LENGTH


@pytest.mark.parametrize(
    "numbers, text",
    [
        ([1000], "1.0000000000"),  # digits "1"
        ([9], "9.0000000000"),
        ([20, 4], "2.8284271247"),  # sqrt(8) = 2.828427124746...
        ([12], "1.4142135624"),  # sqrt(2) = 1.41421356237...: rounds up
    ],
)
def test_hand_computed_cases(numbers, text):
    assert group_length(numbers).length_text == text


@pytest.mark.slow
@settings(max_examples=200, deadline=None)
@given(st.lists(st.integers(0, 10**7), min_size=1, max_size=6).filter(lambda ns: str(sum(ns)).strip("0")))
def test_length_is_the_correctly_rounded_geometric_mean(numbers):
    """Checked in integers only: l = L / 10^10 is the rounding of the k-th root of P iff
    (2L - 1)^k < P (2 10^10)^k < (2L + 1)^k. The k-th root of an integer is an integer or
    irrational, so it is never half-way between two 10-decimal numbers: no tie to break,
    and the rule's "half away from zero" never decides."""
    res = group_length(numbers)
    digits = [int(d) for d in str(sum(numbers)) if d != "0"]
    assert res.sum == sum(numbers) and res.digits == "".join(map(str, digits))
    whole, frac = res.length_text.split(".")
    assert len(frac) == 10
    big = int(whole + frac)
    k, prod = len(digits), math.prod(digits)
    assert (2 * big - 1) ** k < prod * (2 * 10**10) ** k < (2 * big + 1) ** k
    assert res.length == float(res.length_text)


@pytest.mark.parametrize("numbers", [[], [0], [0, 0], [-5], [1.5]])
def test_bad_groups(numbers):
    with pytest.raises(InputError) as err:
        group_length(numbers)
    assert err.value.name == "students"
