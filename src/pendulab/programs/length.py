"""The pendulum length of a group, problem 3(b): add the student numbers, delete
the zeros of the sum; l is the geometric mean of the digits left, rounded half away
from zero to 10 decimals (262, 407, 634 give m = 133 and l = 2.0800838231)."""
import math
import sys
from decimal import ROUND_HALF_UP, Decimal

import mpmath

def group_length(students):
    """The sum, its non-zero digits, and l as text with 10 decimals."""
    total = sum(students)
    digits = [int(d) for d in str(total) if d != "0"]
    # The mean to 50 digits: the rounding to 10 decimals is decided on the true value
    # (a k-th root of an integer is an integer or irrational, so never a tie).
    with mpmath.workdps(50):
        mean = mpmath.root(math.prod(digits), len(digits))
        text = mpmath.nstr(mean, 40, strip_zeros=False)
    l_text = Decimal(text).quantize(Decimal("1e-10"), rounding=ROUND_HALF_UP)
    return total, digits, str(l_text)

if __name__ == "__main__":
    students = [int(s) for s in sys.argv[1:]] or [262, 407, 634]
    total, digits, l_text = group_length(students)
    print(f"sum = {total}, m = {''.join(map(str, digits))}",
          f"(digits {', '.join(map(str, digits))}: {len(digits)}), l = {l_text} m")
