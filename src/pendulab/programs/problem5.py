"""Problem 5: the period integral (1) by the 3-point Gauss rule (11), composite.

T = 4 sqrt(l/(2g)) int_0^alpha dtheta / sqrt(cos theta - cos alpha), l = 3.5 m,
alpha = 4 pi/5; errors against T^ of (8). 5(a): the trapezoidal and Simpson rules
need f(alpha), which is infinite; the nodes of (11) are inside the subintervals."""
import math

import numpy as np

from agm import G, t_hat
from digits import right, sci, sci_up

L, ALPHA = 3.5, 4 * math.pi / 5
U = 2.0**-53  # the unit roundoff of double precision
FLOOR = 128  # 5(d): an error below 128 u T^ is rounding, not the rule's

def integrand(theta):
    """1/sqrt(cos theta - cos alpha), with cos x - cos y = 2 sin((y+x)/2) sin((y-x)/2):
    alpha - theta is exact near alpha, where cos theta - cos alpha would lose digits."""
    return 1 / np.sqrt(2 * np.sin((ALPHA + theta) / 2) * np.sin((ALPHA - theta) / 2))

def gauss3(f, a, b, n):
    """S_n: rule (11) on each of n equal subintervals [a_i, b_i] of [a, b], summed:
    Q_i = (b_i - a_i)/18 [5 f(m - sqrt(3/5) mu) + 8 f(m) + 5 f(m + sqrt(3/5) mu)],
    m = (a_i + b_i)/2, mu = (b_i - a_i)/2 (Gauss-Legendre, exact to degree 5)."""
    h = (b - a) / n
    m = a + (np.arange(n) + 0.5) * h  # the midpoints
    d = math.sqrt(3 / 5) * h / 2
    return float(h / 18 * np.sum(5 * f(m - d) + 8 * f(m) + 5 * f(m + d)))

def period(n):
    return 4 * math.sqrt(L / (2 * G)) * gauss3(integrand, 0.0, ALPHA, n)

def rounding_error(n):
    """A bound on how far rounding moves period(n) from its exact-arithmetic value.
    Each node theta is off by at most 4 u alpha (the operations that give it), which
    moves f by |d ln f/d theta| = |cot((alpha - theta)/2) - cot((alpha + theta)/2)|/4
    times that, large near alpha; each f carries 6 u of its own, the sum and the
    factor 4 sqrt(l/(2g)) h/18 (log2(3n) + 8) u of the period's size."""
    h = ALPHA / n
    m = (np.arange(n) + 0.5) * h
    d = math.sqrt(3 / 5) * h / 2
    total = 0.0
    for theta, w in ((m - d, 5), (m, 8), (m + d, 5)):
        half_gap, half_sum = (ALPHA - theta) / 2, (ALPHA + theta) / 2
        slope = abs(1 / np.tan(half_gap) - 1 / np.tan(half_sum)) / 4
        total += float(np.sum(w * integrand(theta) * (4 * U * ALPHA * slope + 6 * U)))
    size = 4 * math.sqrt(L / (2 * G)) * h / 18
    return size * total + (math.log2(3 * n) + 8) * U * period(n)

def table(reference):
    """5(b)-(d): n = 1, 10, ..., 10^5, the period by S_n, its error, and the rate p
    of error ~ n^(-p) from n/10 to n."""
    rows = [(1, period(1), abs(period(1) - reference), None)]
    for k in range(1, 6):
        p = period(10**k)
        e = abs(p - reference)
        rows.append((10**k, p, e, math.log10(rows[-1][2] / e)))
    return rows

def substituted(n):
    """5(d): sin(theta/2) = k sin(phi), k = sin(alpha/2), turns (1) into the analytic
    T = 4 sqrt(l/g) int_0^(pi/2) dphi / sqrt(1 - k^2 sin^2 phi): S_n on it."""
    k = math.sin(ALPHA / 2)
    f = lambda phi: 1 / np.sqrt(1 - (k * np.sin(phi)) ** 2)  # noqa: E731
    return 4 * math.sqrt(L / G) * gauss3(f, 0.0, math.pi / 2, n)

if __name__ == "__main__":
    reference = t_hat(L, ALPHA)
    rows = table(reference)
    print(f"l = {L:g} m, T^ = {reference:.15g} s")
    for part, (n, p, e, _) in zip(["5(b) one application:", "5(c) n = 10:"], rows):
        print(f"{part:21} {right(p, rounding_error(n))} s, error {sci(e, 3)}")
    print("5(d)      n  estimate            error     rate    substituted       error")
    floor = FLOOR * U * reference
    first = None  # the first n whose substituted error is at the floor
    for n, p, e, rate in rows[1:]:
        s = substituted(n)
        d = abs(s - reference)
        first = first or (n if d <= floor else None)
        d = f"<= {sci_up(floor, 1)}" if d <= floor else sci(d, 2)
        print(f"    {n:6d}  {right(p, rounding_error(n)):<18}  {sci(e, 3):<8}",
              f" {rate:.4f}   {s:<17.15g} {d}")
    print(f"     rounding floor 128 u T^ = {sci(floor, 1)} s,",
          f"first reached at n = {first}")
