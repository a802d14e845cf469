"""Problem 3 in plain Python, written from the coursework's formulas for the tests.

Independent of the library: its own group-length rule (decimal arithmetic), AGM (8),
Taylor algorithm (3), sign-change search and inverse interpolation by divided
differences. Used by test_report.py and test_key.py as the reference.
"""
from __future__ import annotations

import math
from decimal import ROUND_HALF_UP, Decimal, localcontext

G = 9.80665
ALPHA = 4 * math.pi / 5


def length_text(numbers) -> str:
    """3(b): geometric mean of the non-zero digits of the sum, half away from zero, 10 decimals."""
    digits = [int(d) for d in str(sum(numbers)) if d != "0"]
    with localcontext() as ctx:
        ctx.prec = 60
        product = Decimal(math.prod(digits))
        mean = (product.ln() / len(digits)).exp() if product != 1 else Decimal(1)
        return str(mean.quantize(Decimal("1e-10"), rounding=ROUND_HALF_UP))


def agm7_period(length: float, alpha: float = ALPHA) -> float:
    """(8): 2 pi sqrt(l/g) / v, v = (a7 + b7)/2 from a0 = 1, b0 = cos(alpha/2)."""
    a, b = 1.0, math.cos(alpha / 2)
    for _ in range(7):
        a, b = (a + b) / 2, math.sqrt(a * b)
    return 2 * math.pi * math.sqrt(length / G) / ((a + b) / 2)


def taylor(length: float, h: float, alpha: float = ALPHA):
    """The points Z_0, Z_1, ... of (3) from Z_0 = (alpha, 0)."""
    z1, z2 = alpha, 0.0
    while True:
        yield z1, z2
        z1, z2 = _step(length, h, z1, z2)


def first_event(length: float, h: float, t_end: float):
    """("returns", j, points j-2 .. j+2) or ("leaves", t) or ("none", None): what comes first."""
    points = []
    for k, (z1, z2) in enumerate(taylor(length, h)):
        points.append((z1, z2))
        if k * h > t_end:
            return "none", None
        if abs(z1) > math.pi:
            return "leaves", k * h
        if k >= 1:
            (_, a2), (b1, b2) = points[-2], points[-1]
            if a2 > 0 >= b2 and b1 > 0:
                j = k - 1
                for _ in range(2):  # two more points after j + 1
                    z1, z2 = _step(length, h, *points[-1])
                    points.append((z1, z2))
                return "returns", j, points[j - 2:j + 3]


def _step(length, h, z1, z2):
    """(3): z1 <- z1 + h z2 - h^2/2 (g/l) sin z1,  z2 <- z2 - h (g/l) sin z1 - h^2/2 (g/l) z2 cos z1."""
    w = G / length
    return (z1 + h * z2 - h * h / 2 * w * math.sin(z1),
            z2 - h * w * math.sin(z1) - h * h / 2 * w * z2 * math.cos(z1))


def divided_differences(x, y):
    """Newton's coefficients f[x0], f[x0,x1], ... (the table computed column by column)."""
    coef = list(y)
    n = len(x)
    for level in range(1, n):
        for i in range(n - 1, level - 1, -1):
            coef[i] = (coef[i] - coef[i - 1]) / (x[i] - x[i - level])
    return coef


def estimate(length: float, h: float, t_end: float):
    """3(c)-(d): j, bracket, linear and cubic estimates, the error estimate from the fifth point."""
    event = first_event(length, h, t_end)
    assert event[0] == "returns", event
    _, j, window = event
    z2 = [p[1] for p in window]
    t = [(j - 2 + i) * h for i in range(5)]
    linear = t[2] + h * z2[2] / (z2[2] - z2[3])
    x, y = z2[1:5], t[1:5]
    coef = divided_differences(x, y)
    value = coef[3]
    for k in (2, 1, 0):
        value = coef[k] + (0.0 - x[k]) * value
    fifth = divided_differences(x + [z2[0]], y + [t[0]])[-1]
    error = fifth * math.prod(0.0 - xi for xi in x)
    # How far rounding each of the five times to a double (half an ulp) moves that estimate:
    # t[x_0..x_4] = sum_k t_k / prod_(i != k) (x_k - x_i).
    nodes = x + [z2[0]]
    rounding = sum(math.ulp(tk) / 2 / abs(math.prod(xk - xi for i, xi in enumerate(nodes) if i != k))
                   for k, (xk, tk) in enumerate(zip(nodes, y + [t[0]]))) * abs(math.prod(x))
    return {"j": j, "bracket": (t[2], t[3]), "linear": linear, "cubic": value, "error_estimate": error,
            "rounding_level": rounding,
            "nodes": x, "times": y, "coefficients": coef}
