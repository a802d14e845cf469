"""The exact motion of a pendulum released at ``alpha`` with an angular velocity ``omega0``.

Energy per ``2 m g l``: ``k^2 = sin^2(alpha/2) + omega0^2/(4 w^2)``, ``w = sqrt(g/l)``, and its
complement, the distance to the separatrix, ``m' = 1 - k^2 = (E_sep - E)/(2 w^2) =
cos^2(alpha/2) - omega0^2/(4 w^2)``.

- ``m' > 0``, libration: ``sin(theta/2) = k sn(u | k^2)``, ``theta' = 2 k w cn(u | k^2)``,
  ``u = w t + u0`` (DLMF 22.19.2 shifted in time); ``u0 = F(phi0 | k^2)`` with
  ``sin(phi0) = sin(alpha/2)/k``, ``cos(phi0) = omega0/(2 k w)``. The turning angle is
  ``2 asin(k)`` and the period ``4 K/w``.
- ``m' < 0``, circulation: the reciprocal-modulus case (DLMF 22.19.3 with 22.17.2),
  ``theta/2 = am(u | 1/k^2)``, ``theta' = 2 s k w dn(u | 1/k^2)``, ``u = s k w t + F(alpha/2 | 1/k^2)``,
  ``s`` the sign of ``omega0``: the pendulum goes over the top and on, once round in
  ``2 K(1/k^2)/(k w)``; ``am(u + 2K) = am(u) + pi``.
- ``m' = 0``, the separatrix: the limits ``sn = tanh``, ``cn = dn = sech`` (DLMF 22.5.4),
  ``theta/2 = gd(s w t + u0)``, ``u0 = gd^-1(alpha/2)``, ``theta' = 2 s w sech(s w t + u0)``:
  it creeps up to the top forever.

Accuracy. Near the separatrix ``k^2`` rounds to 1 in doubles and ``1 - k^2`` loses every
digit; so ``m'`` is formed from the energy difference in mpmath, from the exact input
doubles, at a precision that grows with the cancellation (up to :data:`SEPARATRIX_BITS`;
below that, the motion is the separatrix's). ``K``, ``u0`` and the rate ``1/T`` follow in
mpmath; the motion is then :func:`pendulab.numerics.motion.jacobi_agm` at the phase
``v = u/K``, carried as a double-double from ``t`` by TwoProduct as in
:func:`pendulab.numerics.motion.exact_motion`, with ``k`` and ``k' = sqrt(m')`` given. Neither the
rounding of ``K`` nor that of ``w t`` reaches ``theta``: the error is a few ulps of
``theta`` at any time (:func:`launched_motion_error_bound`, measured by
``benchmarks/adversarial.py``, ``launched_search``; ``docs/accuracy.md``).
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core import validate as v
from ..core.cases import G
from .motion import jacobi_agm, two_prod, two_sum
from .results import Result

#: Below ``2^-SEPARATRIX_BITS`` of the energy's scale, ``m'`` counts as 0: the separatrix.
SEPARATRIX_BITS = 2000
#: Bits kept beyond those lost to the cancellation in ``m'``.
_GUARD_BITS = 192
_EPS = 2.0**-52


@dataclass(frozen=True, eq=False)
class Launch(Result):
    """The kind of motion a launch gives: ``k``, libration or circulation, its period."""

    k: float
    circulates: bool
    period: float
    turning_angle: float | None  # 2 asin(k) when it librates, rad


@dataclass(frozen=True)
class _Orbit:
    """The launch's constants, each rounded once from mpmath."""

    kind: int  # 1 libration, -1 circulation, 0 the separatrix
    k: float  # the modulus (libration) or its reciprocal's inverse k (circulation)
    modulus: float  # of the Jacobi functions: k, or 1/k when it goes round
    complement: float  # sqrt(1 - modulus^2), from m'
    period: float
    turning_angle: float | None
    rate: tuple[float, float]  # d(cycles)/dt, double-double
    offset: tuple[float, float]  # cycles at t = 0, fraction in [0, 1), double-double
    whole: float  # whole cycles at t = 0 (circulation), or 2 pi times the turns (libration)
    exact_rate: Any  # mpmath rate and offset for times too far out for TwoProduct
    exact_offset: Any
    prec: int
    w: float
    sign: float
    u0: float  # the separatrix's gd^-1(alpha/2)


def _split(x: Any) -> tuple[float, float]:
    hi = float(x)
    return hi, float(x - hi)


@functools.lru_cache(maxsize=256)
def _orbit(length: float, amplitude: float, omega0: float, g: float) -> _Orbit:
    import mpmath

    prec = 128
    while True:
        with mpmath.workprec(prec):
            mpf = mpmath.mpf
            w = mpmath.sqrt(mpf(g) / mpf(length))
            r = mpf(omega0) / (2 * w)
            c = mpmath.cos(mpf(amplitude) / 2)
            scale = c * c + r * r
            mp = (c - r) * (c + r)  # m' = cos^2(alpha/2) - omega0^2/(4 w^2): no 1 - k^2
            lost = prec if mp == 0 else max(0, int(mpmath.log(scale / abs(mp), 2)) + 1)
        if lost + _GUARD_BITS <= prec or prec >= SEPARATRIX_BITS + _GUARD_BITS:
            break
        prec = min(2 * prec + lost, SEPARATRIX_BITS + _GUARD_BITS)
    separatrix = mp == 0 or lost >= SEPARATRIX_BITS
    sign = 1.0 if omega0 > 0 else -1.0
    with mpmath.workprec(prec):
        mpf = mpmath.mpf
        w = mpmath.sqrt(mpf(g) / mpf(length))
        alpha, r = mpf(amplitude), mpf(omega0) / (2 * w)
        if separatrix or mp > 0:
            # Libration (and the separatrix): the same motion shifted by whole turns.
            turns = mpmath.floor((alpha + mpmath.pi) / (2 * mpmath.pi))
            a = alpha - 2 * mpmath.pi * turns
            whole = float(2 * mpmath.pi * turns)
        if separatrix:
            u0 = mpmath.asinh(mpmath.tan(a / 2))
            return _Orbit(0, 1.0, 1.0, 0.0, math.inf, math.pi, (0.0, 0.0), (0.0, 0.0), whole, None, None,
                          prec, float(w), sign, float(u0))
        if mp > 0:
            k2 = mpmath.sin(a / 2) ** 2 + r * r
            k, kp = mpmath.sqrt(k2), mpmath.sqrt(mp)
            big_k = mpmath.pi / (2 * mpmath.agm(1, kp))  # DLMF 19.8.5, from k' with no cancellation
            u0 = mpmath.ellipf(mpmath.atan2(mpmath.sin(a / 2), r), k2)
            rate = w / (4 * big_k)
            q0 = u0 / (4 * big_k)
            q0 -= mpmath.floor(q0)
            return _Orbit(1, float(k), float(k), float(kp), float(4 * big_k / w), float(2 * mpmath.atan2(k, kp)),
                          _split(rate), _split(q0), whole, rate, q0, prec, float(w), sign, 0.0)
        # Circulation: modulus 1/k, complement sqrt(k^2 - 1)/k = sqrt(-m')/k.
        k = mpmath.sqrt(mpmath.sin(alpha / 2) ** 2 + r * r)
        mu, mup = 1 / k, mpmath.sqrt(-mp) / k
        big_k = mpmath.pi / (2 * mpmath.agm(1, mup))
        u0 = mpmath.ellipf(alpha / 2, mu * mu)  # any real angle: F(phi + j pi) = F(phi) + 2 j K
        rate = k * w / (2 * big_k)
        q0 = u0 / (2 * big_k)
        whole_cycles = mpmath.floor(q0)
        return _Orbit(-1, float(k), float(mu), float(mup), float(2 * big_k / (k * w)), None,
                      _split(rate), _split(q0 - whole_cycles), float(whole_cycles), rate, q0, prec, float(w), sign,
                      0.0)


def _checked(length: float, amplitude: float, omega0: float, g: float) -> _Orbit:
    return _orbit(float(v.positive("length", length)), float(v.finite("amplitude", amplitude)),
                  float(v.finite("omega0", omega0)), float(v.positive("g", g)))


def launch(length: float, amplitude: float, omega0: float, g: float = G) -> Launch:
    """``k``, whether the pendulum goes round, its period (s) and turning angle (rad).

    ``k`` is rounded from the exact energy; whether it goes round is decided by the sign
    of ``m' = cos^2(alpha/2) - omega0^2/(4 w^2)``, exactly (module docstring).
    """
    o = _checked(length, amplitude, omega0, g)
    return Launch(o.k, o.kind < 0, o.period, o.turning_angle)


def _cycles(o: _Orbit, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``n + (fh + fl) = s rate t + offset``, ``n`` whole, ``fh + fl`` about in ``[0, 1)``.

    ``rate t`` by TwoProduct from the double-double rate (relative error below 2^-104,
    as :func:`pendulab.numerics.motion.exact_motion`'s phase); times too far out for it
    (``|rate t| >= 2^60``) in mpmath.
    """
    import mpmath

    rh, rl = o.rate
    ts = o.sign * t if o.kind < 0 else t
    with np.errstate(over="ignore", invalid="ignore"):
        qh, ql = two_prod(ts, rh)
        ql = ql + ts * rl
        n = np.floor(qh)
        fh, fl = two_sum(qh, -n)
        s, e = two_sum(fh, o.offset[0])  # s in [0, 2): s - floor(s) is exact
        c = np.floor(s)
        n, s = n + c, s - c
        fh, fl = two_sum(s, e + fl + ql + o.offset[1])
    far = ~(np.abs(qh) < 2.0**60) | ~np.isfinite(fl)
    for i in np.flatnonzero(far & np.isfinite(ts)):
        with mpmath.workprec(o.prec + 64 + max(0, math.frexp(float(ts[i]))[1])):
            q = mpmath.mpf(float(ts[i])) * o.exact_rate + o.exact_offset
            whole = mpmath.floor(q)
            n[i] = float(whole)
            fh[i], fl[i] = _split(q - whole)
    if o.kind < 0:
        n = n + o.whole
    return n, fh, fl


def launched_motion(length: float, amplitude: float, omega0: float, t: Any,
                    g: float = G) -> tuple[np.ndarray, np.ndarray]:
    """``(theta, theta')`` at the times ``t`` of the pendulum released at ``alpha`` with ``omega0``.

    ``alpha`` any finite angle (rad); ``theta`` is continuous: a pendulum that goes round
    has ``theta`` growing by ``2 pi`` a turn. Within :func:`launched_motion_error_bound`
    of the motion of the exact input doubles; a time that is not finite gives NaN.
    """
    t = np.asarray(t, dtype=float)
    o = _checked(length, amplitude, omega0, g)
    shape, t = t.shape, t.ravel()
    if o.kind == 0:
        with np.errstate(over="ignore", invalid="ignore"):
            u = o.sign * o.w * t + o.u0
            theta = o.whole + 2 * np.arctan(np.sinh(u))
            omega = 2 * o.sign * o.w / np.cosh(u)
        return theta.reshape(shape), omega.reshape(shape)
    if o.k == 0:
        return np.zeros(shape), np.zeros(shape)
    n, fh, fl = _cycles(o, t)
    with np.errstate(invalid="ignore"):
        if o.kind > 0:
            # u = K v, v = 4 f in [-2, 2): sn, cn, dn have the period 4K.
            back = np.where(fh + fl > 0.5, 4.0, 0.0)
            vh, e = two_sum(4.0 * fh, -back)
            vh, vl = two_sum(vh, e + 4.0 * fl)
            sn, cn, dn = jacobi_agm(t, o.k, o.complement, phase=(vh, vl))
            theta = o.whole + 2 * np.arctan2(o.k * sn, dn)
            omega = 2 * o.k * o.w * cn
        else:
            # u = K v, v = 2 f in [-1, 1): am(K v + 2 K n) = am(K v) + n pi.
            up = fh + fl > 0.5
            vh, e = two_sum(2.0 * fh, np.where(up, -2.0, 0.0))
            vh, vl = two_sum(vh, e + 2.0 * fl)
            sn, cn, dn = jacobi_agm(t, o.modulus, o.complement, phase=(vh, vl))
            theta = 2 * math.pi * (n + up) + 2 * np.arctan2(sn, cn)
            omega = 2 * o.sign * o.k * o.w * dn
    bad = ~np.isfinite(t)
    theta[bad] = omega[bad] = math.nan
    return theta.reshape(shape), omega.reshape(shape)


#: The constant ``C`` of :func:`launched_motion_error_bound`: measured (see there).
ERROR_BOUND_FACTOR = 16.0
#: The phase term of :func:`launched_motion_error_bound`: derived.
PHASE_ERROR = 2.0**-100


def launched_motion_error_bound(length: float, amplitude: float, omega0: float, t: Any,
                                g: float = G) -> tuple[np.ndarray, np.ndarray]:
    """The error bound of :func:`launched_motion` at the times ``t``: ``(theta bound, theta' bound)``.

    ``|theta~ - theta| <= C eps max(1, |theta|) + 2^-100 max(1, k) w |t|`` rad and
    ``|theta'~ - theta'| <= 2 max(1, k) w (C eps + 2^-100 max(1, k) w |t|)`` rad/s, ``eps = 2^-52``,
    ``C =`` :data:`ERROR_BOUND_FACTOR`, ``theta`` the motion of the exact input doubles.

    The phase term is derived as :func:`pendulab.numerics.motion.exact_motion_error_bound`'s:
    the cycles ``q`` err by 2^-104 ``|q|``; ``v`` is ``4q`` (libration, ``|d theta/dv| <= 2K``)
    or ``2q`` (circulation, ``|d theta/dv| <= 2K``), which gives ``2^-102 w |t|`` and
    ``2^-103 k w |t|``. ``C`` is measured: the roundings of ``k``, ``k'``, the descent and
    ``2 atan2``; the ``|theta|`` term is the rounding of ``2 pi n`` once round ``n`` times.

    The bound is against the motion of the input doubles; the problem's own conditioning
    near the separatrix is far larger (``docs/accuracy.md`` prints what a 1-ulp change of
    ``omega0`` does at the worst case found).
    """
    o = _checked(length, amplitude, omega0, g)
    t = np.asarray(t, dtype=float)
    theta, _ = launched_motion(length, amplitude, omega0, t, g)
    big = max(1.0, o.k)
    scale = PHASE_ERROR * big * o.w * np.abs(t)
    return ERROR_BOUND_FACTOR * _EPS * np.maximum(1.0, np.abs(theta)) + scale, \
        2 * big * o.w * (ERROR_BOUND_FACTOR * _EPS + scale)
