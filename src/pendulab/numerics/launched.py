"""The exact motion of a pendulum released at ``alpha`` with an angular velocity ``omega0``.

Energy per ``2 m g l``: ``k^2 = sin^2(alpha/2) + omega0^2/(4 w^2)``, ``w = sqrt(g/l)``.

- ``k < 1``, libration: ``sin(theta/2) = k sn(u | k^2)``, ``theta' = 2 k w cn(u | k^2)``,
  ``u = w t + u0`` (DLMF 22.19.2 shifted in time); ``u0 = F(phi0 | k^2)`` with
  ``sin(phi0) = sin(alpha/2)/k``, ``cos(phi0) = omega0/(2 k w)``. The turning angle is
  ``2 asin(k)`` and the period ``4 K(k^2)/w``.
- ``k > 1``, circulation: the reciprocal-modulus case (DLMF 22.19.3 with 22.17.2),
  ``theta/2 = am(u | 1/k^2)``, ``theta' = 2 s k w dn(u | 1/k^2)``, ``u = s k w t + F(alpha/2 | 1/k^2)``,
  ``s`` the sign of ``omega0``: the pendulum goes over the top and on, once round in
  ``2 K(1/k^2)/(k w)``.

``omega0 = 0`` is :func:`pendulab.numerics.motion.exact_motion`'s case, which is more accurate near
``alpha = pi`` and at long times; this module serves a launch, drawn in the explorer.
Jacobi functions and ``F`` from scipy (``ellipj``, ``ellipkinc``, ``ellipk``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core import validate as v
from ..core.cases import G
from .results import Result


@dataclass(frozen=True, eq=False)
class Launch(Result):
    """The kind of motion a launch gives: ``k``, libration or circulation, its period."""

    k: float
    circulates: bool
    period: float
    turning_angle: float | None  # 2 asin(k) when it librates, rad


def launch(length: float, amplitude: float, omega0: float, g: float = G) -> Launch:
    """``k``, whether the pendulum goes round, its period (s) and turning angle (rad)."""
    from scipy.special import ellipk

    w = math.sqrt(v.positive("g", g) / v.positive("length", length))
    k = math.hypot(math.sin(0.5 * amplitude), 0.5 * v.finite("omega0", omega0) / w)
    if k < 1:
        return Launch(k, False, 4 * float(ellipk(k * k)) / w, 2 * math.asin(k))
    if k == 1:  # the separatrix: it creeps up to the top forever
        return Launch(k, False, math.inf, math.pi)
    return Launch(k, True, 2 * float(ellipk(1 / (k * k))) / (k * w), None)


def launched_motion(length: float, amplitude: float, omega0: float, t: Any,
                    g: float = G) -> tuple[np.ndarray, np.ndarray]:
    """``(theta, theta')`` at the times ``t`` of the pendulum released at ``alpha`` with ``omega0``.

    ``alpha`` any finite angle (rad); ``theta`` is continuous: a pendulum that goes round
    has ``theta`` growing by ``2 pi`` a turn.
    """
    from scipy.special import ellipj, ellipkinc

    t = np.asarray(t, dtype=float)
    w = math.sqrt(v.positive("g", g) / v.positive("length", length))
    amplitude = v.finite("amplitude", amplitude)
    info = launch(length, amplitude, omega0, g)
    k = info.k
    if not info.circulates:
        if k == 0:
            return np.zeros_like(t), np.zeros_like(t)
        # Released beyond pi: the same motion shifted by whole turns.
        turns = 2 * math.pi * math.floor((amplitude + math.pi) / (2 * math.pi))
        a = amplitude - turns
        m = min(k * k, 1.0)
        phi0 = math.atan2(math.sin(0.5 * a) / k, 0.5 * omega0 / (k * w))
        u = w * t + float(ellipkinc(phi0, m))
        sn, cn, dn, _ = ellipj(u, m)
        return turns + 2 * np.arctan2(k * sn, dn), 2 * k * w * cn
    s = 1.0 if omega0 > 0 else -1.0
    m = 1 / (k * k)
    # F(alpha/2 | m) for any alpha: scipy's ellipkinc takes any real angle.
    u = s * k * w * t + float(ellipkinc(0.5 * amplitude, m))
    _, _, dn, ph = ellipj(u, m)
    return 2 * ph, 2 * s * k * w * dn
