"""The hot loops: numba kernels on plain floats and arrays.

These are the programs the report prints, so they stay short and literal. Every
integrator is one branch of :func:`step`; the drivers below run any of them.
Compiled kernels are cached on disk (``cache=True``): a second run does not compile.
"""
import math

import numpy as np
from numba import njit, prange

from ._libm import cos, sin
from .methods import MAX_TAYLOR_ORDER, Kernel, Status

#: Method codes understood by :func:`step` (the registry's, as plain ints for numba).
TAYLOR2, RK4, VERLET, TAYLOR = (int(k) for k in (Kernel.TAYLOR2, Kernel.RK4, Kernel.VERLET, Kernel.TAYLOR))


@njit(cache=True, nogil=True, inline="always")
def taylor2_step(z1, z2, h, c):
    """One step of the coursework's second-order Taylor algorithm, equations (3)."""
    s = sin(z1)  # the C library's sin, then its cos: no slower than one sincos (_libm.py)
    z1_next = z1 + h * z2 + 0.5 * h * h * c * s
    z2_next = z2 + h * c * s + 0.5 * h * h * c * z2 * cos(z1)
    return z1_next, z2_next


@njit(cache=True, nogil=True, inline="always")
def rk4_step(z1, z2, h, c):
    """One step of the classical Runge-Kutta method (order 4) for ``z1' = z2, z2' = c sin z1``.

    Hairer, Norsett, Wanner, *Solving ODEs I*, section II.1, table 1.2 ("la" methode de Runge-Kutta).
    """
    k1 = z2
    l1 = c * sin(z1)
    k2 = z2 + 0.5 * h * l1
    l2 = c * sin(z1 + 0.5 * h * k1)
    k3 = z2 + 0.5 * h * l2
    l3 = c * sin(z1 + 0.5 * h * k2)
    k4 = z2 + h * l3
    l4 = c * sin(z1 + h * k3)
    return z1 + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4), z2 + h / 6 * (l1 + 2 * l2 + 2 * l3 + l4)


@njit(cache=True, nogil=True, inline="always")
def verlet_step(z1, z2, h, c):
    """One step of Stormer-Verlet (velocity form): symplectic, order 2.

    Hairer, Lubich, Wanner, "Geometric numerical integration illustrated by the
    Stormer-Verlet method", Acta Numerica 12 (2003), equation (1.5) (kick, drift, kick).
    """
    z2_half = z2 + 0.5 * h * c * sin(z1)
    z1_next = z1 + h * z2_half
    return z1_next, z2_half + 0.5 * h * c * sin(z1_next)


@njit(cache=True, nogil=True)  # not inlined: its scratch arrays stay out of the other methods' loops
def taylor_step(p, z1, z2, h, c):
    """One step of the Taylor method of order ``p``: the generalisation of (3).

    With ``theta(t + s) = sum_k x_k s^k`` and ``sin(theta) = sum_k S_k s^k``,
    ``cos(theta) = sum_k C_k s^k``, the Taylor coefficients obey (differentiate
    ``sin(theta)' = cos(theta) theta'`` and ``cos(theta)' = -sin(theta) theta'``)::

        S_k =  1/k sum_{j=1..k} j x_j C_{k-j},   C_k = -1/k sum_{j=1..k} j x_j S_{k-j}

    and (2) gives ``(k+1)(k+2) x_{k+2} = c S_k``. Then ``z1 <- sum_{k<=p} x_k h^k`` and
    ``z2 <- sum_{k<=p+1} k x_k h^(k-1)``; ``p = 2`` is (3), ``p = 1`` is Euler's method.
    (Moore, *Interval Analysis*, 1966, ch. 11; Jorba, Zou, Experiment. Math. 14 (2005) 99-117.)
    """
    x = np.empty(MAX_TAYLOR_ORDER + 2)
    S = np.empty(MAX_TAYLOR_ORDER)
    C = np.empty(MAX_TAYLOR_ORDER)
    x[0] = z1
    x[1] = z2
    S[0] = sin(z1)
    C[0] = cos(z1)
    x[2] = c * S[0] / 2
    for k in range(1, p):
        sk = 0.0
        ck = 0.0
        for j in range(1, k + 1):
            sk += j * x[j] * C[k - j]
            ck -= j * x[j] * S[k - j]
        S[k] = sk / k
        C[k] = ck / k
        x[k + 2] = c * S[k] / ((k + 1) * (k + 2))
    z1_next = x[p]  # Horner's rule
    for k in range(p - 1, -1, -1):
        z1_next = z1_next * h + x[k]
    z2_next = (p + 1) * x[p + 1]
    for k in range(p, 0, -1):
        z2_next = z2_next * h + k * x[k]
    return z1_next, z2_next


@njit(cache=True, nogil=True, inline="always")
def step(method, order, z1, z2, h, c):
    """One step of the integrator ``method`` for ``theta'' = c sin(theta)`` (2).

    ``order`` is used by the Taylor method of any order only.
    """
    if method == TAYLOR2:
        return taylor2_step(z1, z2, h, c)
    if method == RK4:
        return rk4_step(z1, z2, h, c)
    if method == VERLET:
        return verlet_step(z1, z2, h, c)
    return taylor_step(order, z1, z2, h, c)


@njit(cache=True, nogil=True)
def fill_trajectory(method, order, alpha, c, h, z1, z2):
    """Fill ``z1, z2`` (length ``n + 1``) with ``Z_j = (z1_j, z2_j)`` from ``Z_0 = (alpha, 0)``."""
    a, b = alpha, 0.0
    z1[0] = a
    z2[0] = b
    for i in range(1, len(z1)):
        a, b = step(method, order, a, b, h, c)
        z1[i] = a
        z2[i] = b


@njit(cache=True, nogil=True)
def fill_thinned(method, order, alpha, c, h, n, stride, z1, z2):
    """Run ``n`` steps from ``Z_0 = (alpha, 0)``; keep ``Z_j`` for ``j = 0, stride, 2 stride, ...`` and ``j = n``."""
    a, b = alpha, 0.0
    z1[0] = a
    z2[0] = b
    k = 1
    for i in range(1, n + 1):
        a, b = step(method, order, a, b, h, c)
        if i % stride == 0 or i == n:
            z1[k] = a
            z2[k] = b
            k += 1


def trajectory(method, order, alpha, c, h, n):
    """The points ``Z_j``, ``j = 0..n``, as two new arrays."""
    z1 = np.empty(n + 1)
    z2 = np.empty(n + 1)
    fill_trajectory(method, order, alpha, c, h, z1, z2)
    return z1, z2


#: Status codes of :func:`first_return` (:class:`pendulab.methods.Status`, as plain ints).
FOUND, NO_RETURN, LEFT_OSCILLATION, TOO_EARLY = (
    int(s) for s in (Status.FOUND, Status.NO_RETURN, Status.LEFT_OSCILLATION, Status.TOO_EARLY)
)


@njit(cache=True, nogil=True)
def first_return(method, order, alpha, c, h, n):
    """Stream (3) until the first return to ``P = (alpha, 0)``, keeping 5 points only.

    Looks for the first ``j`` with ``z2_j > 0 >= z2_{j+1}`` and ``z1_{j+1} > 0``: the
    sign change of ``theta'`` from + to - at the top of the swing. Returns
    ``(status, j, z1w, z2w)`` where the window holds ``Z_{j-2} .. Z_{j+2}`` when found.
    The two points before ``Z_i`` are kept in scalars (registers), not in an array.
    One call of ``step`` and one exit (the loop runs one step past ``j`` for
    ``Z_{j+2}``): ``step`` is inlined once, which shortens the compilation.
    """
    a2 = b2 = a1 = b1 = 0.0  # Z_{i-2}, Z_{i-1}
    z1, z2 = alpha, 0.0  # Z_i
    z1w = np.empty(5)  # np.empty, not np.zeros: the one allocator taylor_step compiles already
    z2w = np.empty(5)
    for k in range(5):
        z1w[k] = 0.0
        z2w[k] = 0.0
    status, j = NO_RETURN, n
    for i in range(n):
        z1n, z2n = step(method, order, z1, z2, h, c)
        if status == FOUND:  # i = j + 1: Z_{j+2}
            z1w[4] = z1n
            z2w[4] = z2n
            break
        if not abs(z1n) < math.pi:  # also catches NaN
            status, j = LEFT_OSCILLATION, i
            break
        if z2 > 0.0 and z2n <= 0.0 and z1n > 0.0:  # j = i
            if i < 2:
                status, j = TOO_EARLY, i
                break
            if i + 2 > n:  # Z_{j+2} lies beyond t_max
                break
            status, j = FOUND, i
            z1w[0], z1w[1], z1w[2], z1w[3] = a2, a1, z1, z1n
            z2w[0], z2w[1], z2w[2], z2w[3] = b2, b1, z2, z2n
        a2, b2 = a1, b1
        a1, b1 = z1, z2
        z1, z2 = z1n, z2n
    return status, j, z1w, z2w


@njit(cache=True, nogil=True, parallel=True)
def agm_means(alpha, iterations, rtol):
    """``v = (a_n + b_n)/2`` of (7)-(8) from ``(1, cos(alpha_i/2))`` for each amplitude.

    ``iterations < 0``: iterate until ``a - b <= rtol a``; otherwise exactly that many
    steps (7 is the coursework's). The same loop as ``period.agm_mean`` on one float.
    """
    out = np.empty(alpha.size)
    for i in prange(alpha.size):
        a, b = 1.0, math.cos(0.5 * alpha[i])
        if iterations < 0:
            for _ in range(64):
                if a - b <= rtol * a:
                    break
                a, b = 0.5 * (a + b), math.sqrt(a * b)
        else:
            for _ in range(iterations):
                a, b = 0.5 * (a + b), math.sqrt(a * b)
        out[i] = 0.5 * (a + b)
    return out
