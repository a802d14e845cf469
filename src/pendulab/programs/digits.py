"""Print only the digits that are right: with an error of at most e, keep the places
down to the first 10^q with e <= 0.5 10^q (the number printed is then within one unit
of its last digit of the true value); a bound is rounded up, so that it stays a bound.
Errors and small numbers in scientific notation (2.96e-5), order-1 values plain (0.880).
"""
from decimal import ROUND_CEILING, Context, Decimal

EXACT = Context(prec=800)  # every digit of a double's exact decimal value

def right(x, error, most=17):
    """x to the place 10^q its error allows, at most `most` digits (half to even on the
    exact value): plain in [1e-3, 1e6) if q <= 0, else m.mme-k; if |x| <= 0.5 10^q (the
    error swamps it), <= |x| + error rounded up: at least the true |x|."""
    e = abs(Decimal(error))
    q = e.adjusted() + 2  # e < 10^(q-1), so e <= 0.5 10^q
    while Decimal(5).scaleb(q - 2) >= e:  # and one place further still holds
        q -= 1
    if x != 0:
        q = max(q, Decimal(x).adjusted() - most + 1)
    d = Decimal(x).quantize(Decimal(1).scaleb(q), context=EXACT)
    if d == 0:
        return "<= " + sci_up(EXACT.add(abs(Decimal(x)), e), 1)
    if Decimal("1e-3") <= abs(d) < Decimal("1e6") and q <= 0:
        return f"{d:f}"
    k = d.adjusted()
    mant = d.scaleb(-k, EXACT).quantize(Decimal(1).scaleb(min(q - k, 0)), context=EXACT)
    return f"{mant:f}e{k}"

def eq(text):  # "= 1.2e-8", or a bound as right prints it: "<= 2e-15"
    return text if text[0] == "<" else "= " + text

def sci(x, n, plain=(0.1, 1000)):
    """x to n significant digits: plain for |x| in [0.1, 1000), else m.mme-k."""
    if x == 0:
        return "0"
    mant, k = f"{x:.{n - 1}e}".split("e")
    k = int(k)  # the power of ten of x rounded (9.996 -> 1.00e1)
    if plain[0] <= abs(float(f"{x:.{n - 1}e}")) < plain[1] and n - 1 - k >= 0:
        return f"{x:.{n - 1 - k}f}"
    return f"{mant}e{k}"

def up(x, n, plain=(1e-3, 1e6)):
    """|x| rounded up to n significant digits (plain for |x| in [10^-3, 10^6))."""
    a = abs(Decimal(x))
    d = a.quantize(Decimal(1).scaleb(a.adjusted() - n + 1), ROUND_CEILING)
    if d.adjusted() > a.adjusted():  # 9.991 -> 10.00: still n digits
        d = a.quantize(Decimal(1).scaleb(d.adjusted() - n + 1), ROUND_CEILING)
    return sci(float(d), n, plain)

def sci_up(x, n):
    """A bound in the form of sci: |x| rounded up to n significant digits."""
    return up(x, n, (0.1, 1000))

def beside(x, limit, n):
    """sci(x, n), with more digits while it would read as limit or on its other side."""
    while n < 17 and ((float(sci(x, n)) < limit) != (x < limit)
                      or (float(sci(x, n)) == limit) != (x == limit)):
        n += 1
    return sci(x, n)
