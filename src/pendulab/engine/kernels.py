"""The engine's loops: each integrator's step, one dispatch, one trajectory driver, one period search.

Numba kernels on plain floats and arrays. Each step is its formula written once, short
and literal: :func:`taylor2_step` is the coursework's (3) in the order of operations of
its program (``pendulab/programs/taylor.py``, which the report prints), the same points bit
for bit. :func:`step` dispatches on a method's kernel code: one branch per integrator of
:mod:`pendulab.core.methods`. :func:`drive` runs a trajectory of any code,
:func:`first_return` the period search (in pieces of :func:`search_return`); no method has a loop of its own.
:func:`agm_means` runs the AGM of (7) over arrays.
Compiled kernels are cached on disk (``cache=True``): a second run does not compile.
"""
import math

import numpy as np
from numba import njit, prange

from ..core.interrupt import CHUNK_COST, pieces, run_pieces
from ..core.methods import MAX_TAYLOR_ORDER, Kernel, Status, cost_per_step
from .agm import agm
from .fold import BUFFER, Record, energy
from .fold import fold as fold_states

#: The C library's sine and cosine (numba's ``math.sin``, ``math.cos``): the functions the
#: coursework's program calls, so the same points bit for bit (tests/test_libm.py).
sin, cos = math.sin, math.cos

#: Method codes understood by :func:`step` (the registry's, as plain ints for numba).
TAYLOR2, RK4, VERLET, TAYLOR = (int(k) for k in (Kernel.TAYLOR2, Kernel.RK4, Kernel.VERLET, Kernel.TAYLOR))


@njit(cache=True, nogil=True, inline="always")
def taylor2_step(z1, z2, h, c):
    """One step of the coursework's second-order Taylor algorithm, equations (3)."""
    s = sin(z1)
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


@njit(cache=True, nogil=True, inline="always")
def taylor_sums(x, p, h):
    """``(sum_{k<=p} x_k h^k, sum_{k<=p+1} k x_k h^(k-1))`` by Horner's rule: the state after a
    step of the Taylor method of order ``p`` from the coefficients ``x`` of ``theta``."""
    z1_next = x[p]
    for k in range(p - 1, -1, -1):
        z1_next = z1_next * h + x[k]
    z2_next = (p + 1) * x[p + 1]
    for k in range(p, 0, -1):
        z2_next = z2_next * h + k * x[k]
    return z1_next, z2_next


@njit(cache=True, nogil=True, inline="always")
def sin_cos_coefficient(x, S, C, k):
    """``S_k, C_k`` (:func:`taylor_step`'s recurrence) into ``S[k], C[k]``, from ``x_1 .. x_k``
    and ``S, C`` below ``k``: the Taylor coefficients of ``sin(theta)`` and ``cos(theta)``."""
    sk = 0.0
    ck = 0.0
    for j in range(1, k + 1):
        sk += j * x[j] * C[k - j]
        ck -= j * x[j] * S[k - j]
    S[k] = sk / k
    C[k] = ck / k


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
        sin_cos_coefficient(x, S, C, k)
        x[k + 2] = c * S[k] / ((k + 1) * (k + 2))
    return taylor_sums(x, p, h)


@njit(cache=True, nogil=True, inline="always")
def step(method, order, z1, z2, h, c):
    """One step of the integrator of kernel code ``method`` for ``theta'' = c sin(theta)`` (2).

    ``order`` is used by the Taylor method of any order only.
    """
    if method == TAYLOR2:
        return taylor2_step(z1, z2, h, c)
    if method == RK4:
        return rk4_step(z1, z2, h, c)
    if method == VERLET:
        return verlet_step(z1, z2, h, c)
    return taylor_step(order, z1, z2, h, c)


# ---------- the damped pendulum theta'' = c sin(theta) - gamma theta' - beta theta'|theta'| ----------
# gamma (1/s) a linear damping, beta (1/rad) a quadratic one (air drag); both 0 is (2).


@njit(cache=True, nogil=True, inline="always")
def damped_force(z1, z2, c, gamma, beta):
    """``theta''`` of the damped pendulum: (2) less ``gamma theta' + beta theta'|theta'|``."""
    return c * sin(z1) - gamma * z2 - beta * z2 * abs(z2)


@njit(cache=True, nogil=True, inline="always")
def taylor2_damped_step(z1, z2, h, c, gamma, beta):
    """The second-order Taylor step of (3) for the damped pendulum: ``z + h z' + h^2/2 z''``.

    ``z2'' = f' = c cos(z1) z2 - (gamma + 2 beta |z2|) f`` (the derivative of :func:`damped_force`
    along the motion); ``gamma = beta = 0`` gives (3).
    """
    f = damped_force(z1, z2, c, gamma, beta)
    ft = c * cos(z1) * z2 - (gamma + 2.0 * beta * abs(z2)) * f
    return z1 + h * z2 + 0.5 * h * h * f, z2 + h * f + 0.5 * h * h * ft


@njit(cache=True, nogil=True, inline="always")
def rk4_damped_step(z1, z2, h, c, gamma, beta):
    """Classical Runge-Kutta (Hairer, Norsett, Wanner, *Solving ODEs I*, II.1, table 1.2) for the damped pendulum."""
    k1 = z2
    l1 = damped_force(z1, z2, c, gamma, beta)
    k2 = z2 + 0.5 * h * l1
    l2 = damped_force(z1 + 0.5 * h * k1, k2, c, gamma, beta)
    k3 = z2 + 0.5 * h * l2
    l3 = damped_force(z1 + 0.5 * h * k2, k3, c, gamma, beta)
    k4 = z2 + h * l3
    l4 = damped_force(z1 + h * k3, k4, c, gamma, beta)
    return z1 + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4), z2 + h / 6 * (l1 + 2 * l2 + 2 * l3 + l4)


@njit(cache=True, nogil=True, inline="always")
def damping_flow(v, t, gamma, beta):
    """``theta'`` after a time ``t`` of ``theta'' = -gamma theta' - beta theta'|theta'|`` alone, exactly.

    For ``u = 1/theta'``, ``u' = gamma u + beta`` (a Bernoulli equation):
    ``v(t) = v e^(-gamma t) / (1 + beta |v| (1 - e^(-gamma t))/gamma)``, ``t`` for the last factor at ``gamma = 0``.
    """
    q = t if gamma == 0.0 else -math.expm1(-gamma * t) / gamma
    return v * math.exp(-gamma * t) / (1.0 + beta * abs(v) * q)


@njit(cache=True, nogil=True, inline="always")
def verlet_damped_step(z1, z2, h, c, gamma, beta):
    """Stormer-Verlet between two half steps of the exact damping (Strang splitting, order 2):
    the conformal symplectic splitting of McLachlan & Perlmutter, "Conformal Hamiltonian
    systems", J. Geom. Phys. 39 (2001) 276-300."""
    a, b = verlet_step(z1, damping_flow(z2, 0.5 * h, gamma, beta), h, c)
    return a, damping_flow(b, 0.5 * h, gamma, beta)


@njit(cache=True, nogil=True)  # not inlined, as taylor_step
def taylor_damped_step(p, z1, z2, h, c, gamma, beta):
    """The Taylor method of order ``p`` (:func:`taylor_step`) for the damped pendulum.

    With ``v_j = (j+1) x_{j+1}`` the coefficients of ``theta'`` and ``s`` the sign of
    ``theta'`` over the step (of ``theta''`` where ``theta' = 0``),
    ``(k+1)(k+2) x_{k+2} = c S_k - gamma v_k - beta s sum_{j<=k} v_j v_{k-j}``
    (the Cauchy product of ``theta' |theta'| = s theta'^2``; over a step where ``theta'``
    changes sign the quadratic term is of order 2 in ``h`` only).
    """
    x = np.empty(MAX_TAYLOR_ORDER + 2)
    S = np.empty(MAX_TAYLOR_ORDER)
    C = np.empty(MAX_TAYLOR_ORDER)
    x[0] = z1
    x[1] = z2
    S[0] = sin(z1)
    C[0] = cos(z1)
    sign = 1.0 if z2 > 0.0 else -1.0 if z2 < 0.0 else (1.0 if c * S[0] > 0.0 else -1.0)
    for k in range(0, p):
        if k > 0:
            sin_cos_coefficient(x, S, C, k)
        q = 0.0
        for j in range(0, k + 1):
            q += (j + 1) * x[j + 1] * (k - j + 1) * x[k - j + 1]
        x[k + 2] = (c * S[k] - gamma * (k + 1) * x[k + 1] - beta * sign * q) / ((k + 1) * (k + 2))
    return taylor_sums(x, p, h)


@njit(cache=True, nogil=True, inline="always")
def damped_step(method, order, z1, z2, h, c, gamma, beta):
    """:func:`step` for the damped pendulum (one branch per integrator, as there)."""
    if method == TAYLOR2:
        return taylor2_damped_step(z1, z2, h, c, gamma, beta)
    if method == RK4:
        return rk4_damped_step(z1, z2, h, c, gamma, beta)
    if method == VERLET:
        return verlet_damped_step(z1, z2, h, c, gamma, beta)
    return taylor_damped_step(order, z1, z2, h, c, gamma, beta)


@njit(cache=True, nogil=True)
def drive(method, order, a, b, c, h, i0, i1, stride, n, z1, z2, gamma=0.0, beta=0.0, fold=None):
    """Steps ``i0 + 1 .. i1`` of a run of ``n`` steps, from the state ``(a, b)`` of step ``i0``:
    the one loop of a trajectory, with "what to keep" as its parameters.

    Keeps the state of every step that is a multiple of ``stride``, and of step ``n``, in
    ``z1[k], z2[k]`` for ``k = 0, 1, ...``. With ``fold`` (the page's record,
    :meth:`pendulab.engine.fold.Record.fold_args`; ``stride`` 1), ``z1, z2`` are a buffer:
    each time it is full, and at the end, its states go to :func:`pendulab.engine.fold.fold`
    and it is emptied (diffrax's ``SaveAt(fn=...)``: a function of the states kept, not the
    states). Returns ``(a, b, k)``: the state of step ``i1`` and how many states are in
    ``z1, z2`` (0 with ``fold``). ``i1 <= n``. ``gamma, beta``: the damping
    (:func:`damped_step`); without it the step is :func:`step`'s, the same points bit for bit.
    """
    k = 0
    first = i0 + 1  # the step of z1[0], z2[0] (with fold: consecutive steps from there)
    size = len(z1)
    keep = (i0 // stride + 1) * stride  # the next multiple of stride: no division per step
    damped = gamma != 0.0 or beta != 0.0
    for i in range(i0 + 1, i1 + 1):
        if damped:
            a, b = damped_step(method, order, a, b, h, c, gamma, beta)
        else:
            a, b = step(method, order, a, b, h, c)
        if i == keep or i == n:  # noqa: SIM109 (two compares in the compiled loop, no tuple)
            z1[k] = a
            z2[k] = b
            k += 1
            keep += stride
            if fold is not None and k == size:
                fold_states(z1, z2, k, first, fold)
                k, first = 0, i + 1
    if fold is not None and k > 0:
        fold_states(z1, z2, k, first, fold)
        k = 0
    return a, b, k


def piece_steps(method, order) -> int:
    """Steps per piece of a run cut into pieces (:func:`pendulab.core.interrupt.run_pieces`): the
    same cost for every method, so that Ctrl+C waits one piece at most (tens of ms)."""
    name = f"taylor:{order}" if method == TAYLOR else Kernel(method).name.lower()
    return max(1, int(CHUNK_COST / cost_per_step(name)))


def thinned(method, order, alpha, c, h, n, stride, size, gamma=0.0, beta=0.0):
    """The points ``Z_j`` for ``j = 0, stride, 2 stride, ...`` and ``j = n`` (``size`` of them),
    as two new arrays, for the method of code ``method`` (a :class:`~pendulab.core.methods.Kernel`),
    damped by ``gamma, beta`` (:func:`drive`).

    :func:`drive` in pieces, each from the state the one before ended in: the same points,
    bit for bit, and a signal stops the run between two pieces.
    """
    z1 = np.empty(size)
    z2 = np.empty(size)
    gamma, beta = float(gamma), float(beta)  # one compiled signature of drive
    z1[0], z2[0] = alpha, 0.0
    state = [alpha, 0.0, 1]  # the state (a, b) of the last step run, the next point to keep

    def run(lo, hi):
        a, b, k = state
        a, b, kept = drive(method, order, a, b, c, h, lo, hi, stride, n, z1[k:], z2[k:], gamma, beta)
        state[:] = a, b, k + kept
        return False

    run_pieces(pieces(n, piece_steps(method, order)), run)
    return z1, z2


def trajectory(method, order, alpha, c, h, n, gamma=0.0, beta=0.0):
    """The points ``Z_j``, ``j = 0..n``, as two new arrays (:func:`thinned`, every step kept)."""
    return thinned(method, order, alpha, c, h, n, 1, n + 1, gamma, beta)


def folded(method: int, order: int, alpha: float, omega0: float, c: float, h: float, n: int, nb: int,
           samples: np.ndarray, size: int, gamma: float = 0.0, beta: float = 0.0) -> Record:
    """The page's record (:class:`pendulab.engine.fold.Record`) of steps ``0 .. n`` (``n >= 1``)
    of a run from ``(alpha, omega0)`` (``c = -g/l``) of the method of code ``method`` (the
    steps of :func:`pendulab.numerics.simulation.simulate`), damped by ``gamma, beta``
    (:func:`drive`), in pieces of ``size`` steps (:func:`pendulab.core.interrupt.run_pieces`:
    a set event or a signal stops it between two)."""
    rec = Record.empty(n, nb, samples)
    scale = 1.0 / (-2.0 * c) if c != 0.0 else 0.0
    e0 = -energy(float(alpha), float(omega0), scale)
    args = rec.fold_args(n, scale, e0)
    z = [float(alpha), float(omega0)]
    gamma, beta = float(gamma), float(beta)
    fold_states(np.array([alpha]), np.array([omega0]), 1, 0, args)  # step 0
    buf1, buf2 = np.empty(min(BUFFER, max(1, n))), np.empty(min(BUFFER, max(1, n)))

    def one(i0: int, i1: int) -> bool:
        z[:] = drive(method, order, z[0], z[1], c, h, i0, i1, 1, n, buf1, buf2, gamma, beta, args)[:2]
        return False

    run_pieces(pieces(n, size), one)
    return rec


#: Status codes of :func:`first_return` (:class:`pendulab.core.methods.Status`, as plain ints).
FOUND, NO_RETURN, LEFT_OSCILLATION, TOO_EARLY = (
    int(s) for s in (Status.FOUND, Status.NO_RETURN, Status.LEFT_OSCILLATION, Status.TOO_EARLY)
)
#: :func:`return_rule`'s code of a step that decides nothing.
UNDECIDED = -1


@njit(cache=True, nogil=True, inline="always")
def return_rule(i, n, z1n, z2, z2n):
    """``(status, j)``: what step ``i`` (``Z_i -> Z_{i+1}``) of a search of ``n`` steps decides.

    The first return to ``P = (alpha, 0)`` (problem 3) is the first ``j`` with
    ``z2_j > 0 >= z2_{j+1}`` and ``z1_{j+1} > 0``, the sign change of ``theta'`` from + to -
    at the top of the swing: ``FOUND`` at ``j = i``, ``TOO_EARLY`` where ``j < 2`` (no
    ``Z_{j-2}``), ``NO_RETURN`` with ``j = n`` where ``Z_{j+2}`` lies beyond the ``n`` steps.
    ``|z1_{i+1}| >= pi`` (or NaN) comes first: ``LEFT_OSCILLATION`` at ``j = i``. Otherwise
    ``UNDECIDED``. The one statement of the rule, for :func:`search_return` and the sweep's
    lock-step lanes (each loop ends its own steps). Its branches only choose constants:
    LLVM turns them into selects, so the lanes' loop that tests every lane still
    vectorises, and the scalar loop still skips the rest after the first failed test.
    """
    if not abs(z1n) < math.pi:
        return LEFT_OSCILLATION, i
    if z2 > 0.0 and z2n <= 0.0 and z1n > 0.0:
        if i < 2:
            return TOO_EARLY, i
        if i + 2 > n:
            return NO_RETURN, n
        return FOUND, i
    return UNDECIDED, i


@njit(cache=True, nogil=True)
def search_return(method, order, c, h, n, lo, hi, z1w, z2w):
    """Steps ``lo .. hi - 1`` (of ``n``) of :func:`first_return`'s search; returns ``(status, j)``.

    On entry ``z1w[0:3], z2w[0:3]`` hold ``Z_{lo-2}, Z_{lo-1}, Z_lo`` (zeros before ``Z_0 =
    (alpha, 0)``). Where the search goes on (``NO_RETURN`` with ``hi < n``) they hold
    ``Z_{hi-2} .. Z_hi`` on return, so that the next piece resumes it: the same steps, bit
    for bit, as one call with ``lo = 0, hi = n``. Where found, the window holds
    ``Z_{j-2} .. Z_{j+2}`` (the step after ``hi`` is taken for ``Z_{j+2}``).
    The two points before ``Z_i`` are kept in scalars (registers), not in an array.
    One call of ``step`` and one exit (the loop runs one step past ``j`` for
    ``Z_{j+2}``): ``step`` is inlined once, which shortens the compilation.
    """
    a2, a1, z1 = z1w[0], z1w[1], z1w[2]  # Z_{i-2}, Z_{i-1}, Z_i
    b2, b1, z2 = z2w[0], z2w[1], z2w[2]
    status, j = NO_RETURN, n
    for i in range(lo, n):
        if i == hi and status == NO_RETURN:  # the end of this piece
            break
        z1n, z2n = step(method, order, z1, z2, h, c)
        if status == FOUND:  # i = j + 1: Z_{j+2}
            z1w[4] = z1n
            z2w[4] = z2n
            break
        decided, jj = return_rule(i, n, z1n, z2, z2n)
        if decided != UNDECIDED:
            status, j = decided, jj
            if decided != FOUND:  # over the top, too early, or Z_{j+2} beyond t_max
                break
            z1w[0], z1w[1], z1w[2], z1w[3] = a2, a1, z1, z1n
            z2w[0], z2w[1], z2w[2], z2w[3] = b2, b1, z2, z2n
        a2, b2 = a1, b1
        a1, b1 = z1, z2
        z1, z2 = z1n, z2n
    if status == NO_RETURN:
        z1w[0], z1w[1], z1w[2] = a2, a1, z1
        z2w[0], z2w[1], z2w[2] = b2, b1, z2
    return status, j


def first_return(method, order, alpha, c, h, n):
    """The period search: stream the integrator of kernel code ``method`` (a
    :class:`~pendulab.core.methods.Kernel`) until the first return to ``P = (alpha, 0)``,
    keeping 5 points only.

    Looks for the first ``j`` with ``z2_j > 0 >= z2_{j+1}`` and ``z1_{j+1} > 0``: the
    sign change of ``theta'`` from + to - at the top of the swing (:func:`return_rule`).
    Returns ``(status, j, z1w, z2w)`` where the window holds ``Z_{j-2} .. Z_{j+2}`` when found
    (zeros otherwise). The steps run in pieces of :func:`search_return` (the same result, bit
    for bit, as one call over all ``n`` steps): a signal stops it between two pieces
    (:func:`pendulab.core.interrupt.run_pieces`).
    """
    z1w = np.zeros(5)
    z2w = np.zeros(5)
    z1w[2] = alpha
    out = [NO_RETURN, n]

    def run(lo, hi):
        out[:] = search_return(method, order, c, h, n, lo, hi, z1w, z2w)
        return out[0] != NO_RETURN  # found, or stopped for good

    run_pieces(pieces(n, piece_steps(method, order)), run)
    status, j = out
    if status != FOUND:
        z1w[:] = 0.0
        z2w[:] = 0.0
    return status, j, z1w, z2w


@njit(cache=True, nogil=True, parallel=True)
def agm_means(x, of_angle, iterations, rtol):
    """``pendulab.engine.mean.agm(b0, iterations, rtol)[0]`` for each ``b0 = x_i``, or
    ``b0 = cos(x_i/2)`` where ``of_angle``: the one loop of (7), compiled (:data:`agm`)."""
    out = np.empty(x.size)
    for i in prange(x.size):
        b0 = math.cos(0.5 * x[i]) if of_angle else x[i]
        out[i] = agm(b0, iterations, rtol)[0]
    return out
