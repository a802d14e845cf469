"""The explorer's streamed pass: the library's trajectory driver, folded into what is drawn.

:func:`pendulab.engine.kernels.drive` runs the steps into a small buffer, :data:`BUFFER` states
at a time, and :func:`fold` (no step inside) folds each buffer into the pass's record, so
every value kept is the value :func:`pendulab.numerics.simulation.simulate` computes at that step, bit
for bit, and the memory is O(columns + samples + :data:`BUFFER`) whatever the run's length.

The record keeps, for each of ``nb`` columns of steps, the steps where ``theta`` is
smallest and largest and the extremes of the energy drift: a line through these points
in time order has, column by column, the same extent as the whole trajectory (the
min/max reduction of Jugel et al., "M4: A Visualization-Oriented Time Series Data
Aggregation", PVLDB 7(10), 2014). It also keeps the full state at a list of steps (the
phase portrait's and the animation's samples), the first step over the top and the first
non-finite state. :func:`run` carries the record from piece to piece of the run, so the
caller stops between two pieces (a request whose client has gone, Ctrl+C).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..core.interrupt import pieces, run_pieces
from .kernels import drive

#: States per buffer of the driver (16 bytes each): small enough to stay in the cache
#: between the driver writing it and the fold reading it.
BUFFER = 4096

# Rows of Record.value and Record.step (plain ints for numba).
TH_LO, TH_HI, OM_LO, OM_HI, E_LO, E_HI = range(6)
I_LO, I_HI, E_I_LO, E_I_HI = range(4)
# Fields of Record.where: the column, the first step of the next column, the next sample,
# the first step over the top, the first non-finite step.
COL, NEXT, SAMPLE, LEFT, BAD = range(5)


@dataclass(frozen=True)
class Record:
    """What the pass keeps, filled as the steps stream (numpy arrays, updated in place).

    ``value[TH_LO, b]``, ``step[I_LO, b]``: the smallest ``theta`` of column ``b`` (``b < nb``,
    the steps ``i`` with ``floor(i nb/(n+1)) = b``) and its first step; ``TH_HI``/``I_HI`` the
    largest and its last step (both kept when ``theta`` is constant); ``OM_LO``/``OM_HI``
    ``theta'`` at those steps; ``E_LO``/``E_HI`` with ``E_I_LO``/``E_I_HI`` the energy drift's
    extremes, the same way. A step of ``-1`` where every value is NaN. ``samples``: sorted
    steps whose state goes to ``s_theta, s_omega``. ``where``: see the row names above;
    ``LEFT`` is the first step with ``|theta| >= pi`` (over the top, which the exact motion
    from rest below pi never does), ``BAD`` the first non-finite state, ``-1`` when none.
    """

    value: np.ndarray
    step: np.ndarray
    samples: np.ndarray
    s_theta: np.ndarray
    s_omega: np.ndarray
    where: np.ndarray

    @classmethod
    def empty(cls, n: int, nb: int, samples: np.ndarray) -> Record:
        value = np.empty((6, nb))
        value[[TH_LO, E_LO]] = np.inf
        value[[TH_HI, E_HI]] = -np.inf
        where = np.array([0, (n + 1 + nb - 1) // nb, 0, -1, -1], dtype=np.int64)  # NEXT: ceil((n+1)/nb)
        return cls(value, np.full((4, nb), -1, dtype=np.int64), samples,
                   np.empty(len(samples)), np.empty(len(samples)), where)


@njit(cache=True, nogil=True)
def fold(z1, z2, count, i0, n, scale, e0, value, step, where, samples, s_theta, s_omega):
    """Fold the states ``z1[k], z2[k]`` of steps ``i0 + k``, ``k < count``, into the record.

    The energy drift is ``(E - E0)/(m g l) = theta'^2 l/(2g) - cos(theta) + e0`` with
    ``scale = l/(2g)`` and ``e0 = cos(alpha) - omega0^2 l/(2g)``. A column's part of the
    buffer is folded with its extremes held in locals; the samples are copied from the
    buffer afterwards.
    """
    nb = value.shape[1]
    col, nxt, left, bad = where[COL], where[NEXT], where[LEFT], where[BAD]
    k = 0
    while k < count:
        while i0 + k >= nxt:
            col += 1
            nxt = ((col + 1) * (n + 1) + nb - 1) // nb
        end = min(count, nxt - i0)  # the buffer's states k .. end - 1 lie in column col
        t_lo, t_hi, w_lo, w_hi = value[TH_LO, col], value[TH_HI, col], value[OM_LO, col], value[OM_HI, col]
        en_lo, en_hi = value[E_LO, col], value[E_HI, col]
        j_lo, j_hi, je_lo, je_hi = step[I_LO, col], step[I_HI, col], step[E_I_LO, col], step[E_I_HI, col]
        for m in range(k, end):
            a = z1[m]
            b = z2[m]
            if a < t_lo:
                t_lo = a
                w_lo = b
                j_lo = i0 + m
            if a >= t_hi:
                t_hi = a
                w_hi = b
                j_hi = i0 + m
            e = b * b * scale - math.cos(a) + e0
            if e < en_lo:
                en_lo = e
                je_lo = i0 + m
            if e >= en_hi:
                en_hi = e
                je_hi = i0 + m
            if left < 0 and not abs(a) < math.pi:
                left = i0 + m
            if bad < 0 and not (math.isfinite(a) and math.isfinite(b)):
                bad = i0 + m
        value[TH_LO, col], value[TH_HI, col], value[OM_LO, col], value[OM_HI, col] = t_lo, t_hi, w_lo, w_hi
        value[E_LO, col], value[E_HI, col] = en_lo, en_hi
        step[I_LO, col], step[I_HI, col], step[E_I_LO, col], step[E_I_HI, col] = j_lo, j_hi, je_lo, je_hi
        k = end
    s = where[SAMPLE]
    while s < len(samples) and samples[s] < i0 + count:
        s_theta[s] = z1[samples[s] - i0]
        s_omega[s] = z2[samples[s] - i0]
        s += 1
    where[COL], where[NEXT], where[SAMPLE], where[LEFT], where[BAD] = col, nxt, s, left, bad


@njit(cache=True, nogil=True)
def piece(method, order, c, h, n, i0, i1, z, buf1, buf2, scale, e0, value, step, where, samples,
          s_theta, s_omega, gamma, beta):
    """Steps ``i0 + 1 .. i1`` from the state ``z`` of step ``i0`` (updated to that of ``i1``):
    :func:`pendulab.engine.kernels.drive` a buffer at a time, each folded by :func:`fold`. The
    first piece (``i0 = 0``) folds the start state too; ``gamma, beta`` the damping (``drive``)."""
    a, b = z[0], z[1]
    if i0 == 0:
        buf1[0], buf2[0] = a, b
        fold(buf1, buf2, 1, 0, n, scale, e0, value, step, where, samples, s_theta, s_omega)
    size = len(buf1)
    i = i0
    while i < i1:
        j = min(i1, i + size)
        a, b, k = drive(method, order, a, b, c, h, i, j, 1, n, buf1, buf2, gamma, beta)
        fold(buf1, buf2, k, i + 1, n, scale, e0, value, step, where, samples, s_theta, s_omega)
        i = j
    z[0], z[1] = a, b


def run(method: int, order: int, alpha: float, omega0: float, c: float, h: float, n: int, nb: int,
        samples: np.ndarray, size: int, gamma: float = 0.0, beta: float = 0.0) -> Record:
    """Steps ``0 .. n`` (``n >= 1``) of a run from ``(alpha, omega0)`` (``c = -g/l``) of the method
    of code ``method`` (the steps of :func:`pendulab.numerics.simulation.simulate`), in pieces of ``size`` steps
    (:func:`pendulab.core.interrupt.run_pieces`: a set event or a signal stops it between two),
    damped by ``gamma, beta`` (:func:`pendulab.engine.kernels.drive`)."""
    rec = Record.empty(n, nb, samples)
    scale = 1.0 / (-2.0 * c) if c != 0.0 else 0.0
    e0 = math.cos(alpha) - omega0 * omega0 * scale
    z = np.array([alpha, omega0])
    buf1, buf2 = np.empty(min(BUFFER, max(1, n))), np.empty(min(BUFFER, max(1, n)))

    def one(i0: int, i1: int) -> bool:
        piece(method, order, c, h, n, i0, i1, z, buf1, buf2, scale, e0, rec.value, rec.step, rec.where,
              samples, rec.s_theta, rec.s_omega, float(gamma), float(beta))
        return False

    run_pieces(pieces(n, size), one)
    return rec
