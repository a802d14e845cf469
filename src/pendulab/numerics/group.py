"""The pendulum length of a group of students, problem 3(b).

Add the student numbers, delete every zero digit of the sum, and take the geometric
mean of the remaining digits, rounded half away from zero to 10 decimals
(the coursework's problem 3(b) and its footnote 4: 262, 407, 634 give m = 133,
l = 2.0800838231). The k-th root of an integer is an integer or irrational, so the rounding
never meets a tie.
"""
from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from decimal import ROUND_HALF_UP, Decimal

from ..core.errors import InputError
from .results import Result

#: Decimal places of the rounded length (problem 3(b)).
DECIMALS = 10


@dataclass(frozen=True, eq=False)
class GroupLength(Result):
    """The length rule's steps: the student numbers, their ``sum``, its non-zero ``digits``
    (``m``), and ``l`` to 10 decimals as written (``length_text``) and as a double (``length``)."""

    numbers: tuple[int, ...]
    sum: int
    digits: str
    length_text: str

    @property
    def length(self) -> float:
        """``l`` in metres (the double nearest to the 10-decimal value)."""
        return float(self.length_text)


def group_length(numbers: Iterable[int]) -> GroupLength:
    """``l`` = geometric mean of the non-zero digits of ``sum(numbers)``, to 10 decimals.

    The geometric mean is computed with mpmath at 50 digits, so the rounding to 10
    decimals (half away from zero) is decided on the true value, not on a double.
    """
    import mpmath

    nums = tuple(numbers)
    if not nums:
        raise InputError("students", "()", "at least one positive integer")
    for n in nums:
        if isinstance(n, bool) or not isinstance(n, int) or n < 0:
            raise InputError("students", n, "non-negative integers (student numbers)")
    total = sum(nums)
    digits = str(total).replace("0", "")
    if not digits:  # the sum is 0
        raise InputError("students", ",".join(map(str, nums)), "numbers whose sum has a non-zero digit")
    with mpmath.workdps(50):
        prod = 1
        for d in digits:
            prod *= int(d)
        mean = mpmath.root(prod, len(digits))
        text = mpmath.nstr(mean, 40, strip_zeros=False)
    rounded = Decimal(text).quantize(Decimal(1).scaleb(-DECIMALS), rounding=ROUND_HALF_UP)
    return GroupLength(nums, total, digits, str(rounded))
