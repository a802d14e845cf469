"""Print only the digits that are right: with an error of at most e, keep the places
down to the first 10^q with e <= 0.5 10^q (the number printed is then within one unit
of its last digit of the true value); a bound is rounded up, so that it stays a bound.
"""
from decimal import ROUND_CEILING, Decimal

def right(x, error):
    """x rounded to the place 10^q its error allows (scientific below 10^-3)."""
    e = abs(Decimal(error))
    q = e.adjusted() + 2  # e < 10^(q-1), so e <= 0.5 10^q
    while Decimal(5).scaleb(q - 2) >= e:  # and one place further still holds
        q -= 1
    if x == 0 or abs(x) >= 1e-3:
        return f"{x:.{max(0, -q)}f}"
    n = Decimal(x).adjusted() - q + 1  # the significant digits down to 10^q
    return f"{x:.{n - 1}e}" if n >= 1 else "0"

def up(x, n):
    """|x| rounded up to n significant digits."""
    d = abs(Decimal(x))
    return f"{d.quantize(Decimal(1).scaleb(d.adjusted() - n + 1), ROUND_CEILING):f}"
