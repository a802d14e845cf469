"""The hot loops: numba kernels on plain floats and arrays.

These are the programs the report prints, so they stay short and literal. Every
integrator is one branch of :func:`step`; the drivers below run any of them.
Compiled kernels are cached on disk (``cache=True``): a second run does not compile.
"""
import math

import numpy as np
from numba import njit

#: Method codes understood by :func:`step`.
TAYLOR2 = 0


@njit(cache=True, inline="always")
def taylor2_step(z1, z2, h, c):
    """One step of the coursework's second-order Taylor algorithm, equations (3)."""
    s = math.sin(z1)
    z1_next = z1 + h * z2 + 0.5 * h * h * c * s
    z2_next = z2 + h * c * s + 0.5 * h * h * c * z2 * math.cos(z1)
    return z1_next, z2_next


@njit(cache=True, inline="always")
def step(method, order, z1, z2, h, c):
    """One step of the integrator ``method`` for ``theta'' = c sin(theta)`` (2)."""
    return taylor2_step(z1, z2, h, c)


@njit(cache=True)
def trajectory(method, order, alpha, c, h, n):
    """The points ``Z_j = (z1_j, z2_j)``, ``j = 0..n``, from ``Z_0 = (alpha, 0)``."""
    z1 = np.empty(n + 1)
    z2 = np.empty(n + 1)
    z1[0] = alpha
    z2[0] = 0.0
    for i in range(n):
        z1[i + 1], z2[i + 1] = step(method, order, z1[i], z2[i], h, c)
    return z1, z2


#: Status codes of :func:`first_return`.
FOUND, NO_RETURN, LEFT_OSCILLATION, TOO_EARLY = 0, 1, 2, 3


@njit(cache=True)
def first_return(method, order, alpha, c, h, n):
    """Stream (3) until the first return to ``P = (alpha, 0)``, keeping 5 points only.

    Looks for the first ``j`` with ``z2_j > 0 >= z2_{j+1}`` and ``z1_{j+1} > 0``: the
    sign change of ``theta'`` from + to - at the top of the swing. Returns
    ``(status, j, z1w, z2w)`` where the window holds ``Z_{j-2} .. Z_{j+2}``.
    """
    z1w = np.zeros(5)
    z2w = np.zeros(5)
    z1w[4] = alpha  # the window's last slot holds the newest point
    z1, z2 = alpha, 0.0
    for i in range(n):
        z1n, z2n = step(method, order, z1, z2, h, c)
        if not abs(z1n) < math.pi:  # also catches NaN
            return LEFT_OSCILLATION, i, z1w, z2w
        for k in range(4):
            z1w[k] = z1w[k + 1]
            z2w[k] = z2w[k + 1]
        z1w[4] = z1n
        z2w[4] = z2n
        if z2 > 0.0 and z2n <= 0.0 and z1n > 0.0:  # j = i
            if i < 2:
                return TOO_EARLY, i, z1w, z2w
            if i + 2 > n:  # Z_{j+2} lies beyond t_max
                return NO_RETURN, n, z1w, z2w
            # One more point: the window becomes Z_{j-2} .. Z_{j+2}.
            z1n, z2n = step(method, order, z1n, z2n, h, c)
            for k in range(4):
                z1w[k] = z1w[k + 1]
                z2w[k] = z2w[k + 1]
            z1w[4] = z1n
            z2w[4] = z2n
            return FOUND, i, z1w, z2w
        z1, z2 = z1n, z2n
    return NO_RETURN, n, z1w, z2w
