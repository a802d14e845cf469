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
keeps its absolute accuracy where ``dn`` is tiny: about 1 ulp of ``omega0 t + K``
(:func:`exact_motion_error_bound`), at the same speed. The arcsine is evaluated as
``atan2(k sn, dn)``, which stays well conditioned at the turning points where
``k sn -> 1``.

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
from typing import Any

import numpy as np

from . import _validate as v
from .cases import G
from .results import Result

# AGM stopping rule: c_n <= eps a_n (the next phi correction is below rounding).
_EPS = np.finfo(float).eps


def jacobi_agm(u: np.ndarray, k: float, kp: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``sn, cn, dn`` of ``u`` for modulus ``k``, complementary modulus ``kp`` given exactly.

    The AGM method (DLMF 22.20(ii); A&S 16.4): ``a0 = 1, b0 = k', c0 = k``,
    ``a_n = (a + b)/2, b_n = sqrt(a b), c_n = c_{n-1}^2 / (4 a_n)`` until ``c_N`` is
    negligible, ``phi_N = 2^N a_N u``, ``phi_{n-1} = (phi_n + arcsin(c_n/a_n sin phi_n))/2``,
    ``sn = sin phi_0``, ``cn = cos phi_0``; ``dn = sqrt(k'^2 + k^2 cn^2)`` (DLMF 22.6.1).
    """
    a, b, c = [1.0], [kp], [k]
    while c[-1] > _EPS * a[-1] and len(a) < 64:
        a_next = 0.5 * (a[-1] + b[-1])
        c.append(c[-1] * c[-1] / (4 * a_next))  # = (a - b)/2 without cancellation
        b.append(math.sqrt(a[-1] * b[-1]))
        a.append(a_next)
    n = len(a) - 1
    phi = (2.0**n * a[n]) * np.asarray(u, dtype=float)
    for i in range(n, 0, -1):
        # arcsin(x), x = c_i/a_i sin(phi), as atan2(x, sqrt(1 - x^2)) with
        # 1 - |x| = (b_{i-1} + c_i cos^2(phi)/(1 + |sin(phi)|))/a_i (a_i - c_i = b_{i-1}):
        # near alpha = pi, x -> 1 and arcsin(x) would amplify the rounding of x by 1/sqrt(k').
        s, co = np.sin(phi), np.cos(phi)
        x = c[i] / a[i] * s
        one_minus = (b[i - 1] + c[i] * co * co / (1 + np.abs(s))) / a[i]
        phi = 0.5 * (phi + np.arctan2(x, np.sqrt(one_minus * (1 + np.abs(x)))))
    cn = np.cos(phi)
    return np.sin(phi), cn, np.hypot(kp, k * cn)


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

    Passing ``1 - m`` rather than ``m`` keeps full relative accuracy as ``alpha -> pi``.
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


def exact_motion(length: Any, amplitude: Any, t: Any, g: Any = G) -> ExactMotion:
    """The exact solution of (2) from rest at ``alpha``, at the times ``t`` (s).

    Parameters
    ----------
    length : float
        ``l`` > 0, m.
    amplitude : float
        ``alpha`` in ``[0, pi)``, rad.
    t : float or array_like
        Times (s), any finite values.
    g : float
        m/s^2.

    Returns
    -------
    ExactMotion
        ``theta = 2 atan2(k sn(u), dn(u))``, ``theta' = -2 k omega0 cn(u)``,
        ``u = K - omega0 t`` with ``omega0 t`` reduced modulo the period ``4K``.

    Notes
    -----
    Accurate to ``4 eps (omega0 |t| + K)`` rad (:func:`exact_motion_error_bound`): the
    rounding of ``omega0 t`` sets the error, which grows linearly with ``t`` (4e-11 rad
    at 1000 periods of a pendulum released at ``pi - 1e-12``).
    """
    length = v.positive("length", length)
    alpha = v.amplitude("amplitude", amplitude)
    g = v.positive("g", g)
    t = np.asarray(t, dtype=float)
    if not np.all(np.isfinite(t)):
        v.finite("t", t[~np.isfinite(t)].flat[0])
    w0 = math.sqrt(g / length)
    k = math.sin(0.5 * alpha)
    big_k = quarter_period(alpha)
    u = big_k - np.mod(w0 * t, 4 * big_k)  # sn, cn, dn have period 4K in u
    sn, cn, dn = jacobi(u, alpha)
    theta = 2 * np.arctan2(k * sn, dn)
    omega = -2 * k * w0 * cn
    return ExactMotion(t, theta, omega, length, alpha, g)


#: The constant of :func:`exact_motion_error_bound`: measured errors reach 2.6 (theta) and
#: 1.4 (theta'), over 2.5 periods and at 1000 periods, ``alpha`` up to ``pi - 1e-12``.
ERROR_BOUND_FACTOR = 4.0


def exact_motion_error_bound(length: Any, amplitude: Any, t: Any, g: Any = G) -> tuple[np.ndarray, np.ndarray]:
    """The error bound of :func:`exact_motion` at the times ``t``: ``(theta bound, theta' bound)``.

    ``|theta~(t) - theta(t)| <= 4 eps (omega0 |t| + K(k))`` rad and
    ``|theta'~(t) - theta'(t)| <= 4 eps omega0 (omega0 |t| + K(k))`` rad/s, ``eps = 2^-52``.

    Why this form: the argument ``u = K - omega0 t`` carries the rounding of ``omega0 t``
    (``omega0 = sqrt(g/l)`` and the product, about ``eps omega0 |t|``) and of ``K`` and of
    the reduction modulo ``4K`` (about ``eps K`` per period, the same order), and
    ``|d theta/du| = 2k |cn| <= 2``, ``|d theta'/du| <= 2 k omega0``: so the error grows
    linearly with ``t``, and the Jacobi functions add a few ulps. The factor 4 is
    measured, not proved: against ``mpmath.ellipfun`` at 60 digits the largest ratio of
    error to ``eps (omega0 |t| + K)`` is 2.6 for theta and 1.4 for theta', densely over 2.5
    periods and around ``t = 1000 T``, for amplitudes from 1e-3 to ``pi - 1e-12``
    (``tests/test_motion.py``, ``benchmarks/accuracy_claims.py``).
    """
    length = v.positive("length", length)
    alpha = v.amplitude("amplitude", amplitude)
    g = v.positive("g", g)
    w0 = math.sqrt(g / length)
    scale = ERROR_BOUND_FACTOR * _EPS * (w0 * np.abs(np.asarray(t, dtype=float)) + quarter_period(alpha))
    return scale, w0 * scale


def energy(theta: Any, omega: Any, length: Any, g: Any = G) -> np.ndarray:
    """``E = theta'^2/2 - (g/l) cos(theta)``: conserved by (2) (per unit ``m l^2``)."""
    length = v.positive("length", length)
    g = v.positive("g", g)
    return 0.5 * np.asarray(omega) ** 2 - g / length * np.cos(theta)


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


def global_error(trajectory) -> GlobalError:
    """Compare a :class:`pendulab.taylor.Trajectory` with the exact motion.

    The simulation starts at rest at ``t0``; the exact motion is evaluated at ``t - t0``.
    """
    tr = trajectory
    exact = exact_motion(tr.length, tr.amplitude, tr.t - tr.t0, tr.g)
    d_theta = tr.theta - exact.theta
    d_omega = tr.omega - exact.omega
    e0 = -tr.g / tr.length * math.cos(tr.amplitude)
    drift = energy(tr.theta, tr.omega, tr.length, tr.g) - e0
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
