"""The sweep's kernels: the streamed period search for many pendulums, on every core.

:func:`first_returns_serial` runs the period search of :func:`pendulab.engine.kernels.first_return`
for each pendulum in turn (any method). For the coursework's algorithm (3) :func:`first_returns_lanes`
advances :data:`LANES` pendulums in lock-step with a polynomial sine and cosine, a loop
LLVM compiles to vector instructions (AVX: four pendulums per instruction): about twice
the serial kernel's rate on one core. :func:`first_returns` runs either on several
threads; both release the GIL.

The lock-step kernel's sine and cosine are fdlibm's (within 1 ulp), not the C library's,
so its points differ from the scalar kernel's in the last bits, and the differences grow
along the trajectory like any rounding error, the more the nearer the separatrix, where
the motion amplifies every rounding error (the scalar kernel's as much). Its period
estimates differ from :func:`pendulab.numerics.crossing.estimate_period`'s (the scalar kernel),
at h = 1e-2 to 1e-4, by at most a relative 1e-9 up to 179.9 degrees and 2e-7 up to
179.99, and by at most 5 % of the scalar estimate's own error up to 179.999 degrees
(that error is itself near rounding at h = 1e-4): measured, by an adversarial search
towards the top (``benchmarks/adversarial.py``, ``sweep_search``; ``docs/accuracy.md``
prints the worst cases found); ``tests/test_sweep.py`` checks fixed amplitudes.
"""
from __future__ import annotations

import collections
import itertools
import math
import threading
from concurrent.futures import FIRST_EXCEPTION, ThreadPoolExecutor, wait

import numpy as np
from numba import get_num_threads, njit

from ..core.interrupt import CHUNK_COST, deferred, run_pieces, stop_when
from .kernels import (
    FOUND,
    NO_RETURN,
    TAYLOR2,
    UNDECIDED,
    piece_steps,
    return_rule,
    search_return,
)


@njit(cache=True, nogil=True)
def first_returns_serial(method, order, alphas, cs, h, n_steps):
    """``first_return`` for each pendulum ``(alphas[i], cs[i])`` with ``n_steps[i]`` steps, in turn:
    :func:`_serial` with every step in one call.

    Releases the GIL. The same results, bit for bit, as
    :func:`pendulab.numerics.crossing.estimate_period` (the same kernel).
    """
    m = len(alphas)
    status = np.zeros(m, np.int64)
    j = np.zeros(m, np.int64)
    z1w = np.zeros((m, 5))
    z2w = np.zeros((m, 5))
    _serial(method, order, alphas, cs, h, n_steps, status, j, z1w, z2w, np.zeros(2, np.int64),
            np.iinfo(np.int64).max)
    return status, j, z1w, z2w


# sin and cos on [-pi/4, pi/4]: the minimax polynomials of fdlibm's k_sin.c and k_cos.c
# (Sun Microsystems, 1993; error below 2^-58), after reduction by pi/2 in two parts
# (Cody and Waite, *Software Manual for the Elementary Functions*, 1980), in three parts of
# 33 bits each (fdlibm's e_rem_pio2.c), so q PIO2_k is exact for the |q| <= 2 of |x| < 4.
S1, S2, S3 = -1.66666666666666324348e-01, 8.33333333332248946124e-03, -1.98412698298579493134e-04
S4, S5, S6 = 2.75573137070700676789e-06, -2.50507602534068634195e-08, 1.58969099521155010221e-10
C1, C2, C3 = 4.16666666666666019037e-02, -1.38888888888741095749e-03, 2.48015872894767294178e-05
C4, C5, C6 = -2.75573143513906633035e-07, 2.08757232129817482790e-09, -1.13596475577881948265e-11
PIO2_1, PIO2_2, PIO2_3 = 1.57079632673412561417e+00, 6.07710050630396597660e-11, 2.02226624871116645580e-21
PIO2_3T = 8.47842766036889956997e-32
TWO_OVER_PI = 6.36619772367581382433e-01


@njit(cache=True, nogil=True, inline="always")
def sincos(x):
    """``(sin x, cos x)`` within 1 ulp for ``|x| < 4``, without branches (so it vectorises).

    Measured: an adversarial search next to the multiples of ``pi/4``
    (``benchmarks/adversarial.py``, ``sincos_search``; ``docs/accuracy.md``).
    """
    q = math.floor(x * TWO_OVER_PI + 0.5)
    # x - q pi/2 as r + y, pi/2 in three parts of 33 bits (the products with q are exact)
    # as fdlibm's e_rem_pio2.c: full relative accuracy also near the zeros of sin and cos.
    r = x - q * PIO2_1
    t, w = r, q * PIO2_2
    r = t - w  # the rounding error of r is carried into the next part
    t, w = r, q * PIO2_3 - ((t - r) - w)
    r = t - w
    w = q * PIO2_3T - ((t - r) - w)
    hi = r
    r = hi - w
    y = (hi - r) - w
    z = r * r
    v = z * r
    s = r - ((z * (0.5 * y - v * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6))))) - y) - v * S1)
    hz = 0.5 * z
    w = 1.0 - hz
    c = w + (((1.0 - w) - hz) + (z * z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6))))) - r * y))
    k = np.int64(q) & 3  # quadrant: sin(r + k pi/2), cos(r + k pi/2)
    sn = c if k & 1 else s
    cs = s if k & 1 else c
    return (-sn if k & 2 else sn), (-cs if (k + 1) & 2 else cs)


#: Pendulums advanced together by :func:`first_returns_lanes`.
LANES = 16
_RUNNING, _LAST, _DONE = 0, 1, 2


@njit(cache=True, nogil=True)
def _lanes(cs, h, n, i0, i1, z, state, status, j, w1, w2):
    """Steps ``i0 .. i1 - 1`` of (3) for up to :data:`LANES` pendulums in lock-step, each to
    its first return; returns True when every lane is done.

    The same search as :func:`pendulab.engine.kernels.first_return`, per lane, by the same rule
    (:func:`pendulab.engine.kernels.return_rule`): the step loop over the lanes and the rule's
    test for every lane vectorise (no branch but the rule's choices among constants,
    which LLVM makes selects); the rare events (a sign change, the end of a lane's
    steps) are handled in a second loop only at the steps where one occurs.

    ``z`` holds the rows ``z1, z2`` (``Z_i``), ``Z_{i-1}`` and ``Z_{i-2}`` of every lane and
    ``state`` each lane's progress, at ``i0`` on entry and at ``i1`` on return: the next call
    resumes the search, the same steps bit for bit as one call over every step
    (``i1 = n.max() + 1``). They are copied into arrays of this call for the loop.
    """
    m = cs.size
    z1, z2, a1, b1, a2, b2 = z[0].copy(), z[1].copy(), z[2].copy(), z[3].copy(), z[4].copy(), z[5].copy()
    z1n, z2n = np.empty(m), np.empty(m)
    hh = 0.5 * h * h
    left = 0
    for k in range(m):
        left += state[k] != _DONE
    for i in range(i0, min(i1, n.max() + 1)):
        if left == 0:
            break
        for k in range(m):  # equations (3), as taylor2_step
            s, co = sincos(z1[k])
            z1n[k] = z1[k] + h * z2[k] + hh * cs[k] * s
            z2n[k] = z2[k] + h * cs[k] * s + hh * cs[k] * z2[k] * co
        event = False
        for k in range(m):  # the rule for every lane: vectorised
            decided = return_rule(i, n[k], z1n[k], z2[k], z2n[k])[0]
            event |= (state[k] != _DONE) & ((state[k] == _LAST) | (i >= n[k]) | (decided != UNDECIDED))
        if event:
            for k in range(m):
                if state[k] == _DONE:
                    continue
                if state[k] == _LAST:  # Z_{j+2}
                    w1[k, 4], w2[k, 4] = z1n[k], z2n[k]
                    state[k] = _DONE
                elif i >= n[k]:  # the lane's steps ran out
                    status[k], j[k], state[k] = NO_RETURN, n[k], _DONE
                else:
                    decided, jj = return_rule(i, n[k], z1n[k], z2[k], z2n[k])
                    if decided == FOUND:
                        status[k], j[k], state[k] = FOUND, jj, _LAST
                        w1[k, 0], w1[k, 1], w1[k, 2], w1[k, 3] = a2[k], a1[k], z1[k], z1n[k]
                        w2[k, 0], w2[k, 1], w2[k, 2], w2[k, 3] = b2[k], b1[k], z2[k], z2n[k]
                    elif decided != UNDECIDED:
                        status[k], j[k], state[k] = decided, jj, _DONE
                if state[k] == _DONE:
                    left -= 1
                    z1n[k] = z2n[k] = 0.0  # at rest: no further events
        for k in range(m):
            a2[k], b2[k], a1[k], b1[k] = a1[k], b1[k], z1[k], z2[k]
            z1[k], z2[k] = z1n[k], z2n[k]
    z[0], z[1], z[2], z[3], z[4], z[5] = z1, z2, a1, b1, a2, b2
    return left == 0


@njit(cache=True, nogil=True)
def first_returns_lanes(alphas, cs, h, n_steps):
    """:func:`first_returns_serial` for (3), :data:`LANES` pendulums at a time in lock-step.

    Pendulums of similar step counts should be neighbours (:func:`first_returns` sorts
    them): a group of lanes runs until its slowest lane is done. Each pendulum's result
    does not depend on its neighbours.
    """
    m = len(alphas)
    status = np.zeros(m, np.int64)
    j = np.zeros(m, np.int64)
    z1w = np.zeros((m, 5))
    z2w = np.zeros((m, 5))
    z = np.zeros((6, m))
    z[0] = alphas
    _lanes_run(cs, h, n_steps, z, np.zeros(m, np.int64), status, j, z1w, z2w, np.zeros(2, np.int64),
               np.iinfo(np.int64).max)
    return status, j, z1w, z2w


@njit(cache=True, nogil=True)
def _lanes_run(cs, h, n_steps, z, state, status, j, w1, w2, at, budget):
    """:func:`_lanes` over groups of :data:`LANES` pendulums in turn, from group ``at[0]``, its
    step ``at[1]``, for about ``budget`` pendulum-steps; ``at`` is moved on, and the result
    is True when every group is done. ``z`` (rows as in :func:`_lanes`, one column per
    pendulum, row 0 the amplitudes before a group begins) and ``state`` carry the search
    between calls: the same steps, bit for bit, as one call. The loop over the groups is
    compiled: a piece of many short searches costs one call from Python, not one a group."""
    m = cs.size
    g, i = at[0], at[1]
    while g * LANES < m and budget > 0:
        lo = g * LANES
        hi = min(lo + LANES, m)
        steps = max(1, budget // (hi - lo))
        done = _lanes(cs[lo:hi], h, n_steps[lo:hi], i, i + steps, z[:, lo:hi], state[lo:hi], status[lo:hi],
                      j[lo:hi], w1[lo:hi], w2[lo:hi])
        budget -= min(steps, n_steps[lo:hi].max() + 1 - i) * (hi - lo)  # a group done early used less
        if done:
            g, i = g + 1, 0
        else:
            i += steps
    at[0], at[1] = g, i
    return g * LANES >= m


@njit(cache=True, nogil=True)
def _serial(method, order, alphas, cs, h, n_steps, status, j, z1w, z2w, at, budget):
    """:func:`first_returns_serial`'s searches from pendulum ``at[0]``, its step ``at[1]``, for
    about ``budget`` steps (each pendulum counts one at least); ``at`` is moved on, and the
    result is True when every pendulum is done. The window ``z1w[i], z2w[i]`` carries a
    search between calls (:func:`pendulab.engine.kernels.search_return`): the same steps, bit for
    bit, as :func:`pendulab.engine.kernels.first_return` in one call."""
    m = len(alphas)
    i, lo = at[0], at[1]
    while i < m and budget > 0:
        n = n_steps[i]
        if lo == 0:
            z1w[i, :] = 0.0
            z2w[i, :] = 0.0
            z1w[i, 2] = alphas[i]
        hi = min(n, lo + budget)
        s, ji = search_return(method, order, cs[i], h, n, lo, hi, z1w[i], z2w[i])
        budget -= max(hi - lo, 1)
        if s != NO_RETURN or hi >= n:  # this pendulum's search is over
            status[i], j[i] = s, ji
            if s != FOUND:
                z1w[i, :] = 0.0
                z2w[i, :] = 0.0
            i, lo = i + 1, 0
        else:
            lo = hi
    at[0], at[1] = i, lo
    return i >= m


#: Pendulums per task of :func:`first_returns`, at least: small enough that the threads
#: finish together (the periods differ by 5x between 1 and 179 degrees). A task takes
#: further groups of as many until it holds :data:`TASK_STEPS` steps, so that a task of
#: short searches outlasts its scheduling and its Python calls.
BLOCK = 16
#: Steps (pendulum-steps) a task of :func:`first_returns` gathers at least: a few ms.
TASK_STEPS = 1 << 18


def tasks(n_steps, block: int = BLOCK, work: int = TASK_STEPS) -> list[tuple[int, int]]:
    """``[0, m)`` cut into ``(lo, hi)``, in order: each the fewest whole groups of ``block``
    pendulums (the last group may be short) that hold ``work`` steps of ``n_steps``, at
    least one group."""
    m = len(n_steps)
    if m == 0:
        return []
    held = np.concatenate(([0], np.cumsum(np.add.reduceat(np.asarray(n_steps, np.int64), np.arange(0, m, block)))))
    groups = len(held) - 1
    out, g = [], 0
    while g < groups:
        k = min(max(int(np.searchsorted(held, held[g] + work)), g + 1), groups)
        out.append((g * block, min(k * block, m)))
        g = k
    return out


_POOL: list[ThreadPoolExecutor] = []


def _block(method, order, alphas, cs, h, n_steps, lanes, out):
    """One block's searches as pieces: a function that runs the next piece, of about
    ``CHUNK_COST`` steps of (3), writing into ``out`` (status, j and the windows of these
    pendulums), and returns True when the block is done. Run by
    :func:`pendulab.core.interrupt.run_pieces`, Ctrl+C in the main thread, or a set
    :func:`~pendulab.core.interrupt.stop_when` event in a worker, stops it within one piece."""
    status, j, z1w, z2w = out
    if lanes:
        m = len(alphas)
        z = np.zeros((6, m))
        z[0] = alphas
        state = np.zeros(m, np.int64)
        at = np.zeros(2, np.int64)

        def piece() -> bool:
            return bool(_lanes_run(cs, h, n_steps, z, state, status, j, z1w, z2w, at, CHUNK_COST))
    else:
        where = np.zeros(2, np.int64)
        budget = piece_steps(method, order)

        def piece() -> bool:
            return bool(_serial(method, order, alphas, cs, h, n_steps, status, j, z1w, z2w, where, budget))
    return piece


def first_returns(method, order, alphas, cs, h, n_steps, threads: int | None = None):
    """The period search for each pendulum on ``threads`` threads (default: numba's thread count).

    (3) (``method`` taylor2) runs the lock-step kernel of :func:`first_returns_lanes` on the
    pendulums sorted by step count, the other methods the searches of
    :func:`first_returns_serial`. Tasks of whole groups of :data:`BLOCK` pendulums, about
    :data:`TASK_STEPS` steps each (:func:`tasks`), go to the threads as they
    become free; the kernels release the GIL, so the threads run on separate cores. Each
    pendulum gives the same result, bit for bit, on any number of threads (a
    ``parallel=True`` build of the serial loop is slower per thread than the serial kernel:
    ``benchmarks/bench_sweep.py``). Each block runs in pieces: Ctrl+C or SIGTERM stops every thread within
    one piece (tens of ms), and is raised once they all stopped.
    """
    threads = get_num_threads() if threads is None else threads
    lanes = method == TAYLOR2
    order_ = np.argsort(n_steps, kind="stable") if lanes else None
    if lanes:
        alphas, cs, n_steps = alphas[order_], cs[order_], n_steps[order_]
    m = len(alphas)
    out: tuple = np.zeros(m, np.int64), np.zeros(m, np.int64), np.zeros((m, 5)), np.zeros((m, 5))
    blocks = [_block(method, order, alphas[lo:hi], cs[lo:hi], h, n_steps[lo:hi], lanes,
                     tuple(x[lo:hi] for x in out)) for lo, hi in tasks(n_steps)]
    if threads <= 1 or len(blocks) <= 1:  # in this thread, every piece of every block in one run_pieces
        left = collections.deque(blocks)

        def run(lo: int, hi: int) -> bool:
            if left and left[0]():
                left.popleft()
            return not left

        run_pieces(itertools.repeat((0, 0)), run)
    else:
        _on_threads(blocks, threads)
    if lanes:
        back = np.empty_like(order_)
        back[order_] = np.arange(m)
        out = tuple(x[back] for x in out)
    return out


def _on_threads(blocks, threads: int) -> None:
    """Run every block (:func:`_block`) to its end on a pool of ``threads`` threads. The main
    thread waits under :func:`~pendulab.core.interrupt.deferred`: on a signal every block stops at
    its next piece (:func:`~pendulab.core.interrupt.stop_when`), those not begun never begin,
    and the signal is raised once no thread works any more (none runs on into the exit)."""
    if not _POOL or _POOL[0]._max_workers != threads:
        _POOL[:] = [ThreadPoolExecutor(threads, thread_name_prefix="pendulab-sweep")]
    stop = threading.Event()

    def task(piece) -> None:
        with stop_when(stop):
            run_pieces(itertools.repeat((0, 0)), lambda lo, hi: piece())

    with deferred() as got:
        tasks = [_POOL[0].submit(task, piece) for piece in blocks]
        try:
            pending = set(tasks)
            while pending and not got:
                done, pending = wait(pending, timeout=0.05, return_when=FIRST_EXCEPTION)
                for f in done:
                    f.result()  # a block's error, raised here
        finally:
            stop.set()
            for f in tasks:
                f.cancel()
            wait(tasks)
