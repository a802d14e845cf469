"""The exact motion of the pendulum released at rest, and the error of a simulation against it.

For ``theta'' = -(g/l) sin(theta)`` (2) from ``theta(0) = alpha``, ``theta'(0) = 0``,
``0 <= alpha < pi``, with ``k = sin(alpha/2)``, ``omega0 = sqrt(g/l)`` and ``K = K(k)``::

    sin(theta/2) = k sn(K - omega0 t | k^2),        cos(theta/2) = dn(K - omega0 t | k^2)
    theta(t)  = 2 arcsin(k sn(K - omega0 t | k^2)) = 2 atan2(k sn, dn)
    theta'(t) = -2 k omega0 cn(K - omega0 t | k^2)

(differentiate ``sin(theta/2) = k sn(u)``: ``cos(theta/2) theta'/2 = -omega0 k cn(u) dn(u)``
and ``cos(theta/2) = sqrt(1 - k^2 sn^2) = dn``).

Accuracy: ``scipy.special.ellipj(u, m)`` takes the parameter ``m = k^2``, which rounds
towards 1 and loses the complementary modulus ``k' = cos(alpha/2)`` that the motion near
the top depends on: measured against mpmath (``tests/test_motion.py``), ``theta`` is off
by about 1e-13 rad at ``alpha = 3.14`` and 4e-9 rad at ``alpha = pi - 1e-8``; even far
from pi its ``theta`` errs by up to 4 ulps of ``omega0 t + K`` (7.7e-15 rad at
``alpha = 1``). This module therefore runs the same algorithm as scipy (the AGM scheme
of Abramowitz-Stegun 16.4) for every amplitude, started from ``(a0, b0, c0) = (1, k', k)``
computed directly from ``alpha``, and takes ``dn`` from ``dn^2 = k'^2 + k^2 cn^2``, which
keeps its absolute accuracy where ``dn`` is tiny. The arcsine is evaluated as
``atan2(k sn, dn)``, which stays well conditioned at the turning points where
``k sn -> 1``.

The argument is not formed as ``u = K - omega0 t`` in doubles: the roundings of ``K``,
``omega0`` and their product with ``t`` line up (up to 5 eps ``omega0 t`` in ``theta``
at a zero crossing) and grow with ``t``. :func:`exact_motion` takes the phase instead:
``v = 1 - 4 frac(t/T)`` from ``1/T`` in mpmath (160 bits) and ``t`` by error-free
transformations (Dekker's TwoProduct, Knuth's TwoSum), so ``u = K v`` with
``2^N a_N K = 2^(N-1) pi`` exactly; the AGM descent carries ``phi_n`` as a
double-double, since ``d phi_0/d phi_N = dn/(2^N a_N)`` would turn a rounded
``phi_N`` into ``K |v|`` ulps of ``phi_0``. The error is then a few ulps of ``theta``
whatever ``t``: :func:`exact_motion_error_bound`.

References
----------
.. [1] NIST DLMF 22.20(ii) (AGM method), 22.6.1 (``dn^2 = k'^2 + k^2 cn^2``), and
   Abramowitz, Stegun, *Handbook of Mathematical Functions*, 16.4.
.. [2] G. B. Arfken, H. J. Weber, F. E. Harris, *Mathematical Methods for Physicists*,
   7th ed. (2012), section 18.8 (the pendulum and elliptic functions).
.. [3] NIST DLMF 22.19.2: the pendulum's ``sin(theta/2) = k sn(...)``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core import validate as v
from ..core.cases import G
from .arrays import elementwise
from .results import Result

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from .simulation import Trajectory

# AGM stopping rule: c_n <= eps a_n (the next phi correction is below rounding).
_EPS = np.finfo(float).eps
# pi as a double-double (the low part: pi - fl(pi), to 17 digits).
_PI_HI, _PI_LO = math.pi, 1.2246467991473532e-16
_SPLITTER = 2.0**27 + 1


def two_prod(a: Any, b: Any) -> tuple[Any, Any]:
    """``p + e = a b`` exactly, ``p = fl(a b)`` (Dekker's TwoProduct, Veltkamp splitting).

    Dekker, Numer. Math. 18 (1971) 224-242; exact while ``|a|, |b| < 2^995`` and ``a b``
    neither over- nor underflows.
    """
    def split(x: Any) -> tuple[Any, Any]:
        c = _SPLITTER * x
        hi = c - (c - x)
        return hi, x - hi

    p = a * b
    ah, al = split(a)
    bh, bl = split(b)
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


def two_sum(a: Any, b: Any) -> tuple[Any, Any]:
    """``s + e = a + b`` exactly, ``s = fl(a + b)`` (Knuth's TwoSum)."""
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


def _sin_cos(ph: np.ndarray, pl: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``sin, cos`` of ``ph + pl`` (``|pl| <= ulp(ph)``), to first order in ``pl``."""
    s, c = np.sin(ph), np.cos(ph)
    return s + c * pl, c - s * pl


def _frequency(length: float, alpha: float, g: float) -> tuple[float, float, Fraction]:
    """``1/T`` of the input doubles as a double-double ``(hi, lo)`` and as a rational.

    ``1/T = sqrt(g) M(1, cos(alpha/2)) / (2 pi sqrt(l))`` ((7)-(8)) in mpmath at 160 bits,
    from the exact doubles: relative error below 2^-140 (mpmath's ``cos``, ``agm``, ``sqrt``
    err by a few units of the last bit).
    """
    import mpmath

    with mpmath.workprec(160):
        m = mpmath.mpf
        r = mpmath.sqrt(m(g)) * mpmath.agm(1, mpmath.cos(m(alpha) / 2)) / (2 * mpmath.pi * mpmath.sqrt(m(length)))
        man, exp = r.man_exp
        exact = Fraction(int(man)) * Fraction(2) ** int(exp)
    hi = float(exact)
    return hi, float(exact - Fraction(hi)), exact


def _phase(t: np.ndarray, length: float, alpha: float, g: float) -> tuple[np.ndarray, np.ndarray]:
    """``v = 1 - 4 frac(t/T)``, reduced to ``[-2, 2)``, as a double-double ``vh + vl``.

    Then ``u = K - omega0 t = K v`` modulo the period ``4K`` of ``sn, cn, dn`` in ``u``
    (``omega0 T = 4K``). ``q = t/T = t (rh + rl)`` by TwoProduct, its fraction by TwoSum:
    ``v`` is within ``2^-100 + 2^-104 |t|/T`` of the phase of the exact doubles. Times
    too far out for TwoProduct (``|t|/T >= 2^60``) take the fraction in rationals.
    """
    rh, rl, exact = _frequency(length, alpha, g)
    shape, t = np.shape(t), np.ravel(t).astype(float)
    with np.errstate(over="ignore", invalid="ignore"):
        qh, ql = two_prod(t, rh)
        ql = ql + t * rl
        n = np.floor(qh)
        fh, fl = two_sum(qh, -n)  # q - n exactly, then the low parts
        fh, fl = two_sum(fh, fl + ql)  # renormalised: fh has lost the integer's bits
    far = ~(np.abs(qh) < 2.0**60) | ~np.isfinite(fl)
    for i in np.flatnonzero(far):
        q = Fraction(float(t[i])) * exact
        f = q - math.floor(q)
        fh[i] = float(f)
        fl[i] = float(f - Fraction(fh[i]))
    # v = 1 - 4f in [-3, 1]; add 4 where v < -2 (f > 3/4): |u| <= 2K, the shorter argument.
    shift = np.where(fh + fl > 0.75, 5.0, 1.0)
    vh, e = two_sum(shift, -4.0 * fh)
    vh, vl = two_sum(vh, e - 4.0 * fl)
    return vh.reshape(shape), vl.reshape(shape)


def jacobi_agm(u: np.ndarray, k: float, kp: float,
                phase: tuple[np.ndarray, np.ndarray] | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``sn, cn, dn`` of ``u`` for modulus ``k``, complementary modulus ``kp`` given exactly.

    The AGM method (DLMF 22.20(ii); A&S 16.4): ``a0 = 1, b0 = k', c0 = k``,
    ``a_n = (a + b)/2, b_n = sqrt(a b), c_n = c_{n-1}^2 / (4 a_n)`` until ``c_N`` is
    negligible, ``phi_N = 2^N a_N u``, ``phi_{n-1} = (phi_n + arcsin(c_n/a_n sin phi_n))/2``,
    ``sn = sin phi_0``, ``cn = cos phi_0``; ``dn = sqrt(k'^2 + k^2 cn^2)`` (DLMF 22.6.1).

    ``phase``: the argument given as ``u = K v`` by the double-double ``v = vh + vl``
    instead of ``u``; since ``a_N = M(1, k') = pi/(2K)`` (DLMF 19.8.5),
    ``phi_N = 2^(N-1) pi v``, free of the rounding of ``K`` and of ``K v``.
    """
    a, b, c = [1.0], [kp], [k]
    while c[-1] > _EPS * a[-1] and len(a) < 64:
        a_next = 0.5 * (a[-1] + b[-1])
        c.append(c[-1] * c[-1] / (4 * a_next))  # = (a - b)/2 without cancellation
        b.append(math.sqrt(a[-1] * b[-1]))
        a.append(a_next)
    n = len(a) - 1
    # phi_n as a double-double ph + pl: the descent multiplies phi_N's error by
    # d phi_0/d phi_N = dn/(2^N a_N), so a phi_N rounded to a double would cost
    # K |v| ulps of phi_0 (40 eps at alpha = pi - 1e-8); kept exact, phi_0 errs by the few
    # roundings of the arcsines.
    if phase is None:
        ph, pl = two_prod(2.0**n * a[n], np.asarray(u, dtype=float))
    else:
        vh, vl = phase  # pi v: pi as a double-double, TwoProduct
        p, e = two_prod(_PI_HI, vh)
        ph, pl = two_sum(2.0 ** (n - 1) * p, 2.0 ** (n - 1) * (e + (_PI_HI * vl + _PI_LO * vh)))
    for i in range(n, 0, -1):
        # arcsin(x), x = c_i/a_i sin(phi), as atan2(x, sqrt(1 - x^2)) with
        # 1 - |x| = (b_{i-1} + c_i cos^2(phi)/(1 + |sin(phi)|))/a_i (a_i - c_i = b_{i-1}):
        # near alpha = pi, x -> 1 and arcsin(x) would amplify the rounding of x by 1/sqrt(k').
        s, co = _sin_cos(ph, pl)
        x = c[i] / a[i] * s
        one_minus = (b[i - 1] + c[i] * co * co / (1 + np.abs(s))) / a[i]
        hi, lo = two_sum(ph, np.arctan2(x, np.sqrt(one_minus * (1 + np.abs(x)))))
        ph, pl = two_sum(0.5 * hi, 0.5 * (lo + pl))  # halving is exact
    sn, cn = _sin_cos(ph, pl)
    return sn, cn, np.hypot(kp, k * cn)


def jacobi(u: Any, amplitude: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``sn(u|m), cn(u|m), dn(u|m)`` for ``m = sin^2(alpha/2)``, accurate up to ``alpha -> pi``.

    :func:`jacobi_agm` from ``k = sin(alpha/2)`` and ``k' = cos(alpha/2)`` (module docstring).
    """
    alpha = v.amplitude("amplitude", amplitude)
    k, kp = math.sin(0.5 * alpha), math.cos(0.5 * alpha)
    u = np.asarray(u, dtype=float)
    return jacobi_agm(u, k, kp)


def quarter_period(amplitude: float) -> float:
    """``K(k)``, ``k = sin(alpha/2)``, from ``1 - m = cos^2(alpha/2)`` (``scipy.special.ellipkm1``).

    Passing ``1 - m`` rather than ``m`` keeps full relative accuracy as ``alpha -> pi``:
    within 2 eps of ``K`` of the exact double ``alpha`` (measured: an adversarial search over
    amplitudes near pi, tiny and uniform, ``benchmarks/adversarial.py``,
    ``quarter_period_search``; ``docs/accuracy.md``).
    """
    from scipy.special import ellipkm1

    alpha = v.amplitude("amplitude", amplitude)
    return float(ellipkm1(math.cos(0.5 * alpha) ** 2))


@dataclass(frozen=True, eq=False)
class ExactMotion(Result):
    """``theta(t)`` and ``theta'(t)`` of the exact solution at the times ``t``."""

    t: np.ndarray
    theta: np.ndarray
    omega: np.ndarray
    length: float
    amplitude: float
    g: float

    def _columns(self) -> dict[str, np.ndarray]:
        return {"t": self.t, "theta": self.theta, "omega": self.omega}


@elementwise(t=0.0)
def exact_motion(length: float, amplitude: float, t: ArrayLike, g: float = G) -> ExactMotion:
    """The exact solution of (2) from rest at ``alpha``, at the times ``t`` (s).

    Parameters
    ----------
    length : float
        ``l`` > 0, m.
    amplitude : float
        ``alpha`` in ``[0, pi)``, rad.
    t : float or array_like
        Times (s), any finite values; NaN gives NaN in ``theta`` and ``theta'`` (a missing
        time), a scalar gives floats.
    g : float
        m/s^2.

    Returns
    -------
    ExactMotion
        ``theta = 2 atan2(k sn(u), dn(u))``, ``theta' = -2 k omega0 cn(u)``,
        ``u = K - omega0 t`` reduced modulo the period ``4K``: ``u = K v``,
        ``v = 1 - 4 frac(t/T)`` in ``[-2, 2)`` (module docstring).

    Notes
    -----
    Accurate to ``16 eps + 2^-100 omega0 |t|`` rad (:func:`exact_motion_error_bound`):
    a few ulps of ``theta`` at any time, the phase ``t/T`` being exact to 2^-104.
    """
    length, alpha, g = v.pendulum(length, amplitude, g)
    t = np.asarray(t, dtype=float)
    if not np.all(np.isfinite(t)):
        v.finite("t", t[~np.isfinite(t)].flat[0])
    w0 = math.sqrt(g / length)
    k, kp = math.sin(0.5 * alpha), math.cos(0.5 * alpha)
    sn, cn, dn = jacobi_agm(t, k, kp, phase=_phase(t, length, alpha, g))  # u = K - omega0 t
    theta = 2 * np.arctan2(k * sn, dn)
    omega = -2 * k * w0 * cn
    return ExactMotion(t, theta, omega, length, alpha, g)


#: The constant ``C`` of :func:`exact_motion_error_bound` (``C eps`` rad): the evaluation's
#: own error, measured (see there).
ERROR_BOUND_FACTOR = 16.0
#: The phase term of :func:`exact_motion_error_bound` (``2^-100 omega0 |t|``): derived.
PHASE_ERROR = 2.0**-100


def exact_motion_error_bound(length: Any, amplitude: Any, t: Any, g: Any = G) -> tuple[np.ndarray, np.ndarray]:
    """The error bound of :func:`exact_motion` at the times ``t``: ``(theta bound, theta' bound)``.

    ``|theta~(t) - theta(t)| <= C eps + 2^-100 omega0 |t|`` rad and
    ``|theta'~(t) - theta'(t)| <= omega0 (C eps + 2^-100 omega0 |t|)`` rad/s,
    ``eps = 2^-52``, ``C =`` :data:`ERROR_BOUND_FACTOR`; ``theta(t)`` the motion of the
    input doubles ``l, alpha, g, t`` exactly.

    The phase term is derived: ``q = t/T`` from ``1/T`` within 2^-140 (mpmath, 160 bits)
    by TwoProduct has a relative error below 2^-104, so ``v = 1 - 4 frac(q)`` is within
    ``4 (2^-104 |q| + 2^-105)`` of the exact phase; ``u = K v`` moves by ``K`` times that
    and ``|d theta/du| = 2k |cn| <= 2``: ``8K 2^-104 |q| = 2^-103 omega0 |t|``
    (``4K = omega0 T``), plus ``2^-102 K``, which ``C eps`` covers; likewise
    ``|d theta'/du| <= 2 k omega0``. With ``phi_N`` and the descent in double-double, no
    error grows with ``t`` beyond this.

    ``C`` is measured, not proved: it bounds the rounding of the AGM descent (a few
    arcsines, sines and cosines, each within an ulp), of ``k = sin(alpha/2)``,
    ``k' = cos(alpha/2)``, of ``theta = 2 atan2(k sn, dn)`` and, for ``theta'``, of
    ``omega0 = sqrt(g/l)`` and the product ``2 k omega0 cn``. An adversarial search
    (``benchmarks/adversarial.py``, ``motion_search``: zero crossings and turning points
    after up to 10^10 periods, amplitudes near 0 and within 1e-15 of pi, lengths and ``g``
    over decades, then hill climbing on the ratio of error to bound) against
    ``mpmath.ellipfun`` at 60 digits finds at most the share of this bound that
    ``docs/accuracy.md`` prints; ``tests/test_bounds_adversarial.py`` runs it small.
    """
    length, _, g = v.pendulum(length, amplitude, g)  # the bound holds for every amplitude
    w0 = math.sqrt(g / length)
    scale = ERROR_BOUND_FACTOR * _EPS + PHASE_ERROR * w0 * np.abs(np.asarray(t, dtype=float))
    return scale, w0 * scale


def energy(theta: Any, omega: Any, length: Any, g: Any = G) -> np.ndarray:
    """``E = theta'^2/2 - (g/l) cos(theta)``: conserved by (2) (per unit ``m l^2``), from
    :func:`pendulab.engine.fold.energy` (the one statement of the energy, in ``m g l``)."""
    length = v.positive("length", length)
    g = v.positive("g", g)
    return g / length * energy_drift(theta, omega, 0.0, 0.0, length, g) - g / length


def energy_drift(theta: Any, omega: Any, amplitude: float, omega0: float, length: float, g: float = G) -> np.ndarray:
    """``(E - E0)/(m g l)``: the energy of each state ``(theta, omega)`` less that of the release
    ``(amplitude, omega0)``, in ``m g l`` (:func:`pendulab.engine.fold.energy`); at
    ``amplitude = omega0 = 0``, ``E0`` is the energy at rest at the bottom."""
    from ..engine.fold import energies
    from ..engine.fold import energy as energy_mgl

    th, om = np.broadcast_arrays(np.asarray(theta, dtype=float), np.asarray(omega, dtype=float))
    scale = length / (2.0 * g)
    e = energies(np.ascontiguousarray(th).ravel(), np.ascontiguousarray(om).ravel(), scale)
    return e.reshape(th.shape) - energy_mgl(float(amplitude), float(omega0), scale)


@dataclass(frozen=True, eq=False)
class GlobalError(Result):
    """The error of a simulated trajectory against the exact motion, point by point.

    Attributes
    ----------
    t : ndarray
        The trajectory's times ``t_j``.
    theta_error, omega_error : ndarray
        ``z1_j - theta(t_j)`` and ``z2_j - theta'(t_j)``.
    energy_drift : ndarray
        ``E(z1_j, z2_j) - E(alpha, 0)``.
    max_theta_error, max_omega_error, max_energy_drift : float
        The largest absolute values.
    method : str
        The integrator.
    step : float
        ``h``.
    """

    t: np.ndarray
    theta_error: np.ndarray
    omega_error: np.ndarray
    energy_drift: np.ndarray
    max_theta_error: float
    max_omega_error: float
    max_energy_drift: float
    method: str
    step: float

    def _columns(self) -> dict[str, np.ndarray]:
        return {"t": self.t, "theta_error": self.theta_error, "omega_error": self.omega_error,
                "energy_drift": self.energy_drift}


def global_error(trajectory: Trajectory) -> GlobalError:
    """Compare a :class:`pendulab.numerics.simulation.Trajectory` with the exact motion.

    The simulation starts at rest at ``t0``; the exact motion is evaluated at ``t - t0``.
    """
    tr = trajectory
    exact = exact_motion(tr.length, tr.amplitude, tr.t - tr.t0, tr.g)
    d_theta = tr.theta - exact.theta
    d_omega = tr.omega - exact.omega
    drift = tr.g / tr.length * energy_drift(tr.theta, tr.omega, tr.amplitude, 0.0, tr.length, tr.g)
    return GlobalError(
        t=tr.t,
        theta_error=d_theta,
        omega_error=d_omega,
        energy_drift=drift,
        max_theta_error=float(np.max(np.abs(d_theta))),
        max_omega_error=float(np.max(np.abs(d_omega))),
        max_energy_drift=float(np.max(np.abs(drift))),
        method=tr.method,
        step=tr.step,
    )
