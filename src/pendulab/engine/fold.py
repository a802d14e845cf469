"""The explorer's streamed pass: the library's trajectory driver, folded into what is drawn.

:func:`pendulab.engine.kernels.drive` runs the steps into a small buffer, :data:`BUFFER` states
at a time, and folds each full buffer into the pass's record by :func:`fold` (its keep-mode
``fold``; no step inside the fold), so
every value kept is the value :func:`pendulab.numerics.simulation.simulate` computes at that step, bit
for bit, and the memory is O(columns + samples + :data:`BUFFER`) whatever the run's length.

The record keeps, for each of ``nb`` columns of steps, the steps where ``theta`` is
smallest and largest and the extremes of the energy drift: a line through these points
in time order has, column by column, the same extent as the whole trajectory (the
min/max reduction of Jugel et al., "M4: A Visualization-Oriented Time Series Data
Aggregation", PVLDB 7(10), 2014). It also keeps the full state at a list of steps (the
phase portrait's and the animation's samples), the first step over the top and the first
non-finite state. :func:`pendulab.engine.kernels.folded` carries the record from piece to
piece of the run, so the caller stops between two pieces (a request whose client has gone,
Ctrl+C).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

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

    def fold_args(self, n: int, scale: float, e0: float) -> tuple:
        """The record as :func:`fold`'s last argument (``drive``'s ``fold``): a run of ``n`` steps,
        the energy drift's ``scale`` and ``e0``."""
        return (n, scale, e0, self.value, self.step, self.where, self.samples, self.s_theta, self.s_omega)


@njit(cache=True, nogil=True, inline="always")
def energy(theta, omega, scale):
    """The energy of (2), ``E/(m g l) - 1 = theta'^2 l/(2g) - cos(theta)`` with ``scale = l/(2g)``:
    the kinetic ``m l^2 theta'^2/2`` and the potential ``m g l (1 - cos theta)`` over ``m g l``,
    less 1. The one statement of the energy (the page's fold, :func:`energies`)."""
    return omega * omega * scale - math.cos(theta)


@njit(cache=True, nogil=True)
def energies(theta, omega, scale):
    """:func:`energy` of each state ``(theta[i], omega[i])`` (1-D arrays of one size), a new array."""
    out = np.empty(theta.size)
    for i in range(theta.size):
        out[i] = energy(theta[i], omega[i], scale)
    return out


@njit(cache=True, nogil=True)
def fold(z1, z2, count, i0, rec):
    """Fold the states ``z1[k], z2[k]`` of steps ``i0 + k``, ``k < count``, into the record
    ``rec`` (:meth:`Record.fold_args`).

    The energy drift is ``(E - E0)/(m g l) = energy(theta, theta', scale) + e0`` with
    ``scale = l/(2g)`` and ``e0 = -energy(alpha, omega0, scale)`` (:func:`energy`). A column's part of the
    buffer is folded with its extremes held in locals; the samples are copied from the
    buffer afterwards.
    """
    n, scale, e0, value, step, where, samples, s_theta, s_omega = rec
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
            e = energy(a, b, scale) + e0
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
