"""The hot loops: numba kernels on plain floats and arrays.

The engine's loops, checked bit for bit against the coursework programs (which the
report prints; these it does not). Every integrator is one branch of :func:`step`;
:func:`drive` runs a trajectory of any of them, :func:`first_return` the period search.
Compiled kernels are cached on disk (``cache=True``): a second run does not compile.
"""
import math
from typing import Any

import numpy as np
from llvmlite import ir  # type: ignore[import-untyped]
from numba import njit, prange, types
from numba.extending import intrinsic

from ._agm import COS_HI, N_TABLE, PI_HI, SIN_HI, agm
from ._interrupt import CHUNK_COST, pieces, run_pieces
from ._libm import cos, sin
from .methods import MAX_TAYLOR_ORDER, Kernel, Status, cost_per_step

#: Method codes understood by :func:`step` (the registry's, as plain ints for numba).
TAYLOR2, RK4, VERLET, TAYLOR = (int(k) for k in (Kernel.TAYLOR2, Kernel.RK4, Kernel.VERLET, Kernel.TAYLOR))


@njit(cache=True, nogil=True, inline="always")
def taylor2_step(z1, z2, h, c):
    """One step of the coursework's second-order Taylor algorithm, equations (3)."""
    s = sin(z1)  # the C library's sin, then its cos: no slower than one sincos (_libm.py)
    z1_next = z1 + h * z2 + 0.5 * h * h * c * s
    z2_next = z2 + h * c * s + 0.5 * h * h * c * z2 * cos(z1)
    return z1_next, z2_next


#: Relative margin of the table's ``sin(z1)`` in :func:`taylor2_fast_step`: 32 units of
#: 2^-52. Measured (1.3 * 10^7 angles in (-pi, pi), dense near 0, +-pi/2 and +-pi and at the
#: table's nodes): the table's sine is within 1.0 unit of 2^-52 (relative) of the C library's,
#: and within 1/32 of the whole margin; ``tests/test_fast_step.py`` requires 1/4 (the safety
#: factor), and 1/8 against mpmath's.
SIN_MARGIN = 2.0**-47
#: Absolute part of the sine's margin for ``|z1| > 3``: near pi the table's sine is the
#: difference of nearly equal terms, so part of its error is absolute, not relative (the
#: worst measured there, both parts together, is also 1/32 of the margin).
SIN_MARGIN_ABS = 2.0**-56
#: Margin of the table's ``cos(z1)``: relative as the sine's, plus an absolute part for the
#: angles near +-pi/2, where the table's cosine is a difference of nearly equal terms, good
#: to about 2^-53 (largest measured: 1.1e-16, 1/40 of the margin).
COS_MARGIN, COS_MARGIN_ABS = 2.0**-47, 2.0**-50
#: :func:`taylor2_fast_step` tries the table only while ``|h^2 c / 2| <= FAST_MAX_K``
#: (``h sqrt|c| <= 5e-4``): its certificate fails in about 1 step in 10^3 at
#: ``h sqrt|c| = 5e-7`` and 1 in 10 at 5e-4, where it stops paying (measured, c = -0.01 to -1000).
FAST_MAX_K = 1.25e-7
_ROUND = 1.5 * 2.0**52 / N_TABLE  # y + _ROUND - _ROUND: y rounded to a multiple of 1/N_TABLE
_S3, _S5, _C2, _C4 = -1.0 / 6, 1.0 / 120, -0.5, 1.0 / 24  # the series' coefficients


@intrinsic
def _likely_intrinsic(typingctx, cond):
    """``cond``, with the hint that it is almost always true (``llvm.expect``): LLVM lays the
    other branch out of the loop's way and keeps the loop's values in registers there."""
    if not isinstance(cond, types.Boolean):
        return None

    def codegen(context, builder, signature, args):
        i1 = ir.IntType(1)
        fn = builder.module.declare_intrinsic("llvm.expect", [i1], ir.FunctionType(i1, [i1, i1]))
        return builder.call(fn, [args[0], ir.Constant(i1, 1)])

    return types.boolean(cond), codegen


_likely: Any = _likely_intrinsic  # called without the typing context


@intrinsic
def _bits_intrinsic(typingctx, x):
    """The bits of the double ``x`` as an int64 (no conversion: a move between registers)."""
    if not isinstance(x, types.Float):
        return None

    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.IntType(64))

    return types.int64(types.float64), codegen


_bits: Any = _bits_intrinsic  # called without the typing context


#: ``sin(k/256), cos(k/256)``, ``k = 0..805`` (``k/256`` up to pi): the nearest doubles, the
#: leading parts of :mod:`pendulab._agm`'s double-double table.
FAST_SIN, FAST_COS = SIN_HI, COS_HI


@njit(cache=True, nogil=True, inline="always")
def _table_sin_cos(z1):
    """``sin(z1), cos(z1)`` for ``|z1| < pi`` from a table and two short series (no call).

    ``|z1| = k/256 + r``, ``|r| <= 2^-9`` with ``r`` exact (Sterbenz), the table's
    ``sin(k/256), cos(k/256)`` (:data:`FAST_SIN`, :data:`FAST_COS`) and ``sin r = r + r u (-1/6 + u/120)``,
    ``cos r = 1 + u (-1/2 + u/24)``, ``u = r^2`` (truncation below 2^-66 and 2^-63 of the
    value); the sums add the table's value last. ``k`` is read from the bits of
    ``|z1| + 1.5 * 2^44`` (whose last bit is worth 1/256), off the angle's path.
    Near pi the sine is the difference of nearly equal terms: its error there is absolute
    (below 2^-61), hence the absolute part of :func:`_certified_step`'s margin above 3.
    """
    x = abs(z1)
    t = x + _ROUND
    k = _bits(t) & 1023
    r = x - (t - _ROUND)
    st = FAST_SIN[k]
    ct = FAST_COS[k]
    u = r * r
    ps = _S3 + u * _S5
    pc = _C2 + u * _C4
    cr = ct * r
    sr = st * r
    sin_x = st + (cr + (cr * u * ps + st * u * pc))
    cos_x = ct - (sr - (ct * u * pc - sr * u * ps))
    return math.copysign(sin_x, z1), cos_x


@njit(cache=True, nogil=True, inline="always")
def _margins(z1, s, co):
    """``(ds, dc)``: how far the C library's ``sin z1``, ``cos z1`` may lie from the table's
    ``s``, ``co`` (:data:`SIN_MARGIN`, :data:`SIN_MARGIN_ABS`, :data:`COS_MARGIN`, :data:`COS_MARGIN_ABS`)."""
    ds = abs(s) * SIN_MARGIN + (SIN_MARGIN_ABS if abs(z1) > 3.0 else 1e-300)
    return ds, abs(co) * COS_MARGIN + COS_MARGIN_ABS


@njit(cache=True, nogil=True)
def _certified_step(z1, z2, h, c, K):
    """``(certified, z1', z2')``: (3) with the table's ``sin`` and ``cos`` (``|z1| < pi``), and
    whether the rounding test of :func:`taylor2_fast_step` shows it equal to :func:`taylor2_step`."""
    s, co = _table_sin_cos(z1)
    a1 = z1 + h * z2
    z1_next = a1 + K * s
    hc = h * c
    kz2 = K * z2
    z2_next = (z2 + hc * s) + kz2 * co
    ds, dc = _margins(z1, s, co)
    a_lo, a_hi = z2 + hc * (s - ds), z2 + hc * (s + ds)
    b_lo, b_hi = kz2 * (co - dc), kz2 * (co + dc)
    if a_hi < a_lo:
        a_lo, a_hi = a_hi, a_lo
    if b_hi < b_lo:
        b_lo, b_hi = b_hi, b_lo
    certified = (a1 + K * (s - ds) == a1 + K * (s + ds) and z1_next != 0.0 and z2_next != 0.0
                 and a_lo + b_lo == a_hi + b_hi)
    return certified, z1_next, z2_next


@njit(cache=True, nogil=True, inline="always")
def taylor2_fast_step(z1, z2, h, c):
    """:func:`taylor2_step`, bit for bit, mostly without calling the C library.

    (3) as numba evaluates it (no fused multiply-add, no reassociation) is, with
    ``s = sin z1``, ``co = cos z1`` and ``K = ((0.5 h) h) c``::

        z1' = fl(fl(z1 + fl(h z2)) + fl(K s))
        z2' = fl(A(s) + B(co)),  A(s) = fl(z2 + fl(fl(h c) s)),  B(co) = fl(fl(K z2) co)

    Rounding to nearest is monotone (``a <= b`` gives ``fl(a) <= fl(b)``), so ``z1'`` and
    ``A`` are monotone functions of ``s``, ``B`` of ``co``, and ``z2'`` is increasing in ``A``
    and ``B``. The step takes ``s, co`` from :func:`_table_sin_cos`, whose distance from the
    C library's values is below :data:`SIN_MARGIN` and :data:`COS_MARGIN` (less the rounding
    of ``s +- ds``: 32 units of 2^-52 against 1.0 measured, :data:`SIN_MARGIN`). If
    ``z1'`` is the same double at ``s - ds`` and ``s + ds``, and ``z2'`` at the smallest and
    the largest ``A + B`` over those ends and ``co +- dc``, then the C library's ``s`` and
    ``co``, which lie between the ends, give those doubles too: the step returns them. This
    is Ziv's rounding test (as in :mod:`pendulab._agm`) on a monotone formula. Otherwise
    (about 1 step in 10^3 at ``h = 1e-6``; a zero or a NaN also goes this way), and where
    ``|z1| >= pi`` or the step is coarse (``|K| > FAST_MAX_K``, where the test would fail
    often), it is :func:`taylor2_step` with the C library's ``sin`` and ``cos``. The
    next angle waits on the table, not on the test: the test's branch is almost always taken.
    :func:`_certified_step` is a call, compiled once for the drivers (inlined into each,
    numba's typing of it made a driver's first compilation about 0.7 s longer).

    :func:`fill_trajectory_fast` and :func:`fill_thinned_fast` run (3) this way, for the
    simulations where it pays (:func:`fast_pays`: fine steps, long runs); the others run
    :func:`step`'s literal :func:`taylor2_step`, and so does :func:`first_return` (the period
    search, the sweep's scalar kernel): the table ran it about 1.2x faster there too
    (0.88-1.24x the C loop against 0.72-0.92x, in noisy runs), but compiling it made the
    first, cold period estimate 0.5-0.9 s slower (README: at most 3 s).
    """
    K = 0.5 * h * h * c
    if _likely(abs(z1) < PI_HI and abs(K) <= FAST_MAX_K):
        certified, z1_next, z2_next = _certified_step(z1, z2, h, c, K)
        if _likely(certified):
            return z1_next, z2_next
    return taylor2_step(z1, z2, h, c)


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
def drive(method, order, a, b, c, h, i0, i1, stride, n, z1, z2):
    """Steps ``i0 + 1 .. i1`` of a run of ``n`` steps, from the state ``(a, b)`` of step ``i0``:
    the one loop of a trajectory, with "what to keep" as its parameters.

    Keeps the state of every step that is a multiple of ``stride``, and of step ``n``, in
    ``z1[k], z2[k]`` for ``k = 0, 1, ...``. Returns ``(a, b, k)``: the state of step ``i1`` and
    how many states were kept. ``i1 <= n``.
    """
    k = 0
    keep = (i0 // stride + 1) * stride  # the next multiple of stride: no division per step (~7 ns of ~30)
    for i in range(i0 + 1, i1 + 1):
        a, b = step(method, order, a, b, h, c)
        if i == keep or i == n:  # noqa: SIM109 (two compares in the compiled loop, no tuple)
            z1[k] = a
            z2[k] = b
            k += 1
            keep += stride
    return a, b, k


@njit(cache=True, nogil=True)
def fill_trajectory(method, order, alpha, c, h, z1, z2):
    """Fill ``z1, z2`` (length ``n + 1``) with ``Z_j = (z1_j, z2_j)`` from ``Z_0 = (alpha, 0)``."""
    n = len(z1) - 1
    z1[0] = alpha
    z2[0] = 0.0
    drive(method, order, alpha, 0.0, c, h, 0, n, 1, n, z1[1:], z2[1:])


@njit(cache=True, nogil=True)
def fill_thinned(method, order, alpha, c, h, n, stride, z1, z2):
    """Run ``n`` steps from ``Z_0 = (alpha, 0)``; keep ``Z_j`` for ``j = 0, stride, 2 stride, ...`` and ``j = n``."""
    z1[0] = alpha
    z2[0] = 0.0
    drive(method, order, alpha, 0.0, c, h, 0, n, stride, n, z1[1:], z2[1:])


#: The fewest steps for which a simulation of (3) runs the fast kernels below: shorter runs
#: take milliseconds either way, and keeping them on the literal ones spares the report
#: (whose simulations are short) and any short simulation on a fresh install the fast
#: kernels' compilation (about 0.5 s each).
FAST_MIN_STEPS = 100_000


def fast_pays(method, c, h, n) -> bool:
    """Whether ``n`` steps of ``method`` run through :func:`taylor2_fast_step`: (3), a step
    fine enough for its rounding test to pass (``|h^2 c/2| <= FAST_MAX_K``) and a long run."""
    return method == TAYLOR2 and abs(0.5 * h * h * c) <= FAST_MAX_K and n >= FAST_MIN_STEPS


@njit(cache=True, nogil=True)
def drive_fast(a, b, c, h, i0, i1, stride, n, z1, z2):
    """:func:`drive` for (3) through :func:`taylor2_fast_step`: the same states, the same contract."""
    k = 0
    keep = (i0 // stride + 1) * stride
    for i in range(i0 + 1, i1 + 1):
        a, b = taylor2_fast_step(a, b, h, c)
        if i == keep or i == n:  # noqa: SIM109 (two compares in the compiled loop, no tuple)
            z1[k] = a
            z2[k] = b
            k += 1
            keep += stride
    return a, b, k


@njit(cache=True, nogil=True)
def fill_trajectory_fast(alpha, c, h, z1, z2):
    """:func:`fill_trajectory` for (3) through :func:`taylor2_fast_step`: the same points."""
    n = len(z1) - 1
    z1[0] = alpha
    z2[0] = 0.0
    drive_fast(alpha, 0.0, c, h, 0, n, 1, n, z1[1:], z2[1:])


@njit(cache=True, nogil=True)
def fill_thinned_fast(alpha, c, h, n, stride, z1, z2):
    """:func:`fill_thinned` for (3) through :func:`taylor2_fast_step`: the same points."""
    z1[0] = alpha
    z2[0] = 0.0
    drive_fast(alpha, 0.0, c, h, 0, n, stride, n, z1[1:], z2[1:])


def _piece(method, order) -> int:
    """Steps per piece of a run cut into pieces (:func:`pendulab._interrupt.run_pieces`): the
    same cost for every method, so that Ctrl+C waits one piece at most (tens of ms)."""
    name = f"taylor:{order}" if method == TAYLOR else Kernel(method).name.lower()
    return max(1, int(CHUNK_COST / cost_per_step(name)))


def thinned(method, order, alpha, c, h, n, stride, size):
    """The points ``Z_j`` for ``j = 0, stride, 2 stride, ...`` and ``j = n`` (``size`` of them),
    as two new arrays.

    :func:`drive` (or :func:`drive_fast`) in pieces, each from the state the one before
    ended in: the same points, bit for bit, and a signal stops the run between two pieces.
    """
    z1 = np.empty(size)
    z2 = np.empty(size)
    z1[0], z2[0] = alpha, 0.0
    fast = fast_pays(method, c, h, n)  # (3), fine and long: the same points, faster (taylor2_fast_step)
    state = [alpha, 0.0, 1]  # the state (a, b) of the last step run, the next point to keep

    def run(lo, hi):
        a, b, k = state
        if fast:
            a, b, kept = drive_fast(a, b, c, h, lo, hi, stride, n, z1[k:], z2[k:])
        else:
            a, b, kept = drive(method, order, a, b, c, h, lo, hi, stride, n, z1[k:], z2[k:])
        state[:] = a, b, k + kept
        return False

    run_pieces(pieces(n, _piece(method, order)), run)
    return z1, z2


def trajectory(method, order, alpha, c, h, n):
    """The points ``Z_j``, ``j = 0..n``, as two new arrays (:func:`thinned`, every step kept)."""
    return thinned(method, order, alpha, c, h, n, 1, n + 1)


#: Status codes of :func:`first_return` (:class:`pendulab.methods.Status`, as plain ints).
FOUND, NO_RETURN, LEFT_OSCILLATION, TOO_EARLY = (
    int(s) for s in (Status.FOUND, Status.NO_RETURN, Status.LEFT_OSCILLATION, Status.TOO_EARLY)
)


@njit(cache=True, nogil=True)
def first_return(method, order, alpha, c, h, n):
    """Stream (3) until the first return to ``P = (alpha, 0)``, keeping 5 points only.

    Looks for the first ``j`` with ``z2_j > 0 >= z2_{j+1}`` and ``z1_{j+1} > 0``: the
    sign change of ``theta'`` from + to - at the top of the swing. Returns
    ``(status, j, z1w, z2w)`` where the window holds ``Z_{j-2} .. Z_{j+2}`` when found
    (zeros otherwise). The search itself is :func:`search_return`, all ``n`` steps at once.
    """
    z1w = np.empty(5)  # np.empty, not np.zeros: the one allocator taylor_step compiles already
    z2w = np.empty(5)
    for k in range(5):
        z1w[k] = 0.0
        z2w[k] = 0.0
    z1w[2] = alpha
    status, j = search_return(method, order, c, h, n, 0, n, z1w, z2w)
    if status != FOUND:
        for k in range(5):
            z1w[k] = 0.0
            z2w[k] = 0.0
    return status, j, z1w, z2w


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
    if status == NO_RETURN:
        z1w[0], z1w[1], z1w[2] = a2, a1, z1
        z2w[0], z2w[1], z2w[2] = b2, b1, z2
    return status, j


def first_return_pieces(method, order, alpha, c, h, n):
    """:func:`first_return`, run in pieces of :func:`search_return` (the same result, bit for
    bit): a signal stops it between two pieces (:func:`pendulab._interrupt.run_pieces`)."""
    z1w = np.zeros(5)
    z2w = np.zeros(5)
    z1w[2] = alpha
    out = [NO_RETURN, n]

    def run(lo, hi):
        out[:] = search_return(method, order, c, h, n, lo, hi, z1w, z2w)
        return out[0] != NO_RETURN  # found, or stopped for good

    run_pieces(pieces(n, _piece(method, order)), run)
    status, j = out
    if status != FOUND:
        z1w[:] = 0.0
        z2w[:] = 0.0
    return status, j, z1w, z2w


@njit(cache=True, nogil=True, parallel=True)
def agm_means(x, of_angle, iterations, rtol):
    """``pendulab._mean.agm(b0, iterations, rtol)[0]`` for each ``b0 = x_i``, or
    ``b0 = cos(x_i/2)`` where ``of_angle``: the one loop of (7), compiled (:data:`agm`)."""
    out = np.empty(x.size)
    for i in prange(x.size):
        b0 = math.cos(0.5 * x[i]) if of_angle else x[i]
        out[i] = agm(b0, iterations, rtol)[0]
    return out
