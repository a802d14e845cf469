"""The period from dense output: the zero of ``theta'`` on the flow's own Taylor polynomial.

The inverse cubic of problem 3(d) interpolates four points ``(z2_k, t_k)``, so its error
is ``O(h^4)`` whatever the method: past order 4 it, not the integrator, limits the period
(``taylor:8`` and ``taylor:12`` stop at the same ``h``). But the simulation knows more
than ``z2`` at each step: ``z2' = c sin(z1)`` and every higher derivative follow from
``(z1, z2)`` through (2). From one point ``Z_j`` of the simulation, the Taylor series of
the solution of (2) through it,

    ``theta(t_j + s) = sum_k x_k s^k``,  ``x_0 = z1_j``, ``x_1 = z2_j``,
    ``(k+1)(k+2) x_(k+2) = c S_k``  (``S_k``: the Taylor coefficients of ``sin theta``),

is the dense output of the Taylor method of any order (the same recurrence as
:func:`pendulab.engine.kernels.taylor_step`, to a higher degree), and its derivative's zero
``theta'(t_j + s) = 0`` gives the crossing. Its error is that of the state ``Z_j``,
``O(h^p)`` for a method of order ``p``, plus the series' truncation, ``O(h^(DEGREE+1))``:
the method's own order.

References
----------
.. [1] R. E. Moore, *Interval Analysis*, Prentice-Hall, 1966, chapter 11 (the
   recurrences for the Taylor coefficients of sin and cos of a series).
.. [2] E. Hairer, S. P. Norsett, G. Wanner, *Solving Ordinary Differential Equations I*,
   2nd ed., Springer, 1993, section II.6 (dense output; Hermite interpolation from the
   derivative ``f(y)`` known at every step).
"""
from __future__ import annotations

import math

#: Degree of the series. Its truncation falls like ``(omega0 s / R)^17``, ``|s| <= h/2``,
#: with ``R`` (2 to 3) the distance from the real axis to the motion's complex
#: singularities in ``omega0 t``, not like ``1/17!``. The time returned obeys
#: :func:`crossing_bound`.
DEGREE = 16
#: ``omega0`` times the error of the series' zero ``s`` (truncation and Newton's rounding) for
#: ``omega0 h`` up to each key: measured (``benchmarks/adversarial.py``, ``dense_search``).
SERIES_ERROR = {0.4: 2.0**-52, 1.0: 1e-10}
#: The roundings of ``t_j = j h``, of ``h + s`` and of the returned sum: half an ulp each,
#: ``2^-53 (|t_j| + h + |t|) <= 2^-52 (|t| + h)`` for ``0 <= t_j <= t``.
SUM_ROUNDING = 2.0**-52
_MAX_NEWTON = 60


def crossing_bound(t: float, omega0: float, step: float) -> float:
    """The bound on the error of :func:`dense_crossing`'s time ``t`` (s) against the zero of ``theta'``
    of the flow through the bracket point, that point taken at the real time ``j h``.

    ``SERIES_ERROR/omega0 + 2^-52 (|t| + h)``: the first for the series' zero ``s``
    (measured, for ``omega0 h`` up to :data:`SERIES_ERROR`'s keys; infinite beyond), the
    second for the roundings of ``t_j = j h``, of ``h + s`` and of the sum (derived: half an
    ulp each, :data:`SUM_ROUNDING`), which a double near ``t`` cannot avoid. Searched as
    :func:`pendulab.numerics.crossing.estimate_period` calls it (``benchmarks/adversarial.py``,
    ``dense_search``; ``docs/accuracy.md``).
    """
    limit = next((e for wh, e in sorted(SERIES_ERROR.items()) if omega0 * step <= wh), math.inf)
    return limit / omega0 + SUM_ROUNDING * (abs(t) + step)


def flow_series(z1: float, z2: float, c: float, degree: int = DEGREE) -> list[float]:
    """Taylor coefficients ``x_0 .. x_degree`` of the solution of ``theta'' = c sin(theta)``
    through ``theta = z1``, ``theta' = z2``.

    ``S_k = 1/k sum_(j=1..k) j x_j C_(k-j)``, ``C_k = -1/k sum_(j=1..k) j x_j S_(k-j)``
    (``sin(theta)' = cos(theta) theta'``, ``cos(theta)' = -sin(theta) theta'``; Moore 1966, ch. 11)
    and ``(k+1)(k+2) x_(k+2) = c S_k``.
    """
    x = [0.0] * (degree + 1)
    x[0], x[1] = float(z1), float(z2)
    s = [math.sin(z1)]
    co = [math.cos(z1)]
    for k in range(degree - 1):
        if k > 0:
            s.append(math.fsum(j * x[j] * co[k - j] for j in range(1, k + 1)) / k)
            co.append(-math.fsum(j * x[j] * s[k - j] for j in range(1, k + 1)) / k)
        x[k + 2] = c * s[k] / ((k + 1) * (k + 2))
    return x


def _derivative(x: list[float], s: float) -> tuple[float, float]:
    """``theta'(s)`` and ``theta''(s)`` of the series ``x`` (Horner)."""
    d1 = 0.0
    d2 = 0.0
    for k in range(len(x) - 1, 0, -1):
        d2 = d2 * s + d1
        d1 = d1 * s + k * x[k]
    return d1, d2


def series_zero(x: list[float], s0: float, lo: float, hi: float) -> float:
    """The zero of ``theta'(s)`` of the series ``x`` in ``[lo, hi]``, by Newton from ``s0``.

    ``theta'`` is monotone there (``theta'' = c sin(theta) < 0`` near the top of the
    swing), so Newton converges; a step that leaves ``[lo, hi]`` is replaced by bisection.
    """
    a, b = min(lo, hi), max(lo, hi)
    fa = _derivative(x, a)[0]
    s = min(max(s0, a), b)
    for _ in range(_MAX_NEWTON):
        f, df = _derivative(x, s)
        if f == 0:
            return s
        if (f > 0) == (fa > 0):
            a, fa = s, f
        else:
            b = s
        nxt = s - f / df if df != 0 else 0.5 * (a + b)
        if not a <= nxt <= b:
            nxt = 0.5 * (a + b)
        if abs(nxt - s) <= 2 * math.ulp(max(abs(a), abs(b))):
            return nxt
        s = nxt
    return s


def dense_crossing(z1: tuple[float, float], z2: tuple[float, float], c: float, step: float,
                   t_j: float) -> float:
    """The time in ``[t_j, t_j + h]`` at which ``theta'`` vanishes, from the flow's series.

    The series is expanded about whichever bracket end the linear estimate puts closer
    to the zero, so that ``|s| <= h/2`` and the truncation is smallest.

    Parameters
    ----------
    z1, z2 : (float, float)
        ``(z1_j, z1_(j+1))`` and ``(z2_j, z2_(j+1))``: the points bracketing the sign change.
    c : float
        ``-g/l``.
    step : float
        ``h``.
    t_j : float
        ``t_j`` (relative to ``t0``).

    Returns
    -------
    float
        The crossing time, relative to ``t0``: within :func:`crossing_bound` of the flow's.
    """
    frac = z2[0] / (z2[0] - z2[1])  # linear estimate, in units of h from t_j
    if frac <= 0.5:
        x = flow_series(z1[0], z2[0], c)
        return t_j + series_zero(x, frac * step, 0.0, step)
    x = flow_series(z1[1], z2[1], c)
    # t_j + (h + s), h + s in [0, h]: one rounding of the size of t fewer than (t_j + h) + s
    return t_j + (step + series_zero(x, (frac - 1) * step, -step, 0.0))
