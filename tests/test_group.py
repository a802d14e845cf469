"""The group's pendulum length, problem 3(b) and its footnote 4."""
import pytest

from pendulab.errors import InputError
from pendulab.group import group_length


def test_spec_example():
    # Footnote 4: 262, 407, 634 give m = 133 and l = 2.0800838231.
    res = group_length([262, 407, 634])
    assert res.total == 1303 and res.digits == "133"
    assert res.text == "2.0800838231" and res.length == 2.0800838231


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
    assert group_length(numbers).text == text


def test_half_away_from_zero():
    # digits "2" -> 2 exactly; sum 11 -> sqrt(1) = 1; the rounding direction is visible
    # on sqrt(2*5) = 3.16227766016838...: 10 decimals -> 3.1622776602 (up).
    assert group_length([25]).text == "3.1622776602"


@pytest.mark.parametrize("numbers", [[], [0], [0, 0], [-5], [1.5]])
def test_bad_groups(numbers):
    with pytest.raises(InputError) as err:
        group_length(numbers)
    assert err.value.name == "students"
