"""The explorer's streaming loops: one pass over a simulation, keeping only what is drawn.

Both run the library's own step (:func:`pendulab._kernels.step`), so every value they
keep is the value :func:`pendulab.taylor.simulate` computes at that step, bit for bit.

:func:`scan` keeps, for each of ``nb`` columns of steps, the steps where ``theta`` is
smallest and largest and the extremes of the energy drift: a line through these points
in time order has, column by column, the same extent as the whole trajectory (the
min/max reduction of Jugel et al., "M4: A Visualization-Oriented Time Series Data
Aggregation", PVLDB 7(10), 2014). It also keeps the full state at a list of steps (the
phase portrait's and the animation's samples). Memory: O(nb + samples), whatever ``n``.
It runs a chunk of steps at a time, carrying its state, so the caller can stop between
chunks (a request whose client has gone).

The CSV that streams runs the library's trajectory driver (``pendulab._kernels.drive``)
block by block from a carried state.
"""
from __future__ import annotations

import math

from numba import njit

from .._kernels import step


@njit(cache=True, nogil=True)
def scan(method, order, alpha, c, h, n, i0, i1, z, where, samples, s_theta, s_omega,
         i_lo, i_hi, th_lo, th_hi, om_lo, om_hi, e_i_lo, e_i_hi, e_lo, e_hi, omega0=0.0):
    """Steps ``i0 .. i1 - 1`` of a run of ``n`` steps from ``(alpha, 0)``: one chunk of the pass.

    ``z``: the state ``(theta, theta')`` of step ``i0 - 1`` (of step 0 when ``i0 = 0``),
    updated to that of step ``i1 - 1``; ``where``: the pass's position, ``(column, first
    step of the next column, next sample, left, bad)``, updated. The arrays start at
    ``+-inf`` (extremes) and ``-1`` (steps); chunk after chunk they fill as one pass would.

    Column ``b`` (``b < nb = len(i_lo)``) holds the steps ``i`` with ``floor(i nb/(n+1)) = b``.
    ``i_lo[b]``/``i_hi[b]``: the first step of the column's smallest ``theta``, the last of its
    largest (both kept when ``theta`` is constant), with ``theta`` and ``theta'`` there;
    ``-1`` where every value is NaN.
    The energy drift is ``(E - E0)/(m g l) = theta'^2 l/(2g) - cos(theta) + cos(alpha) - omega0^2 l/(2g)``
    (``c = -g/l``). ``samples``: sorted step indices whose state goes to ``s_theta, s_omega``.
    ``left``: the first step with ``|theta| >= pi`` (the pendulum went over the top, which
    the exact motion from rest below pi never does); ``bad``: the first non-finite state;
    ``-1`` when none.
    """
    nb = len(i_lo)
    scale = 1.0 / (-2.0 * c) if c != 0.0 else 0.0
    col, nxt, s, left, bad = where[0], where[1], where[2], where[3], where[4]
    ns = len(samples)
    z1, z2 = z[0], z[1]
    e0 = math.cos(alpha) - omega0 * omega0 * scale
    for i in range(i0, i1):
        if i > 0:
            z1, z2 = step(method, order, z1, z2, h, c)
        while i >= nxt:
            col += 1
            nxt = ((col + 1) * (n + 1) + nb - 1) // nb
        if z1 < th_lo[col]:
            th_lo[col] = z1
            om_lo[col] = z2
            i_lo[col] = i
        if z1 >= th_hi[col]:
            th_hi[col] = z1
            om_hi[col] = z2
            i_hi[col] = i
        e = z2 * z2 * scale - math.cos(z1) + e0
        if e < e_lo[col]:
            e_lo[col] = e
            e_i_lo[col] = i
        if e >= e_hi[col]:
            e_hi[col] = e
            e_i_hi[col] = i
        if left < 0 and not abs(z1) < math.pi:
            left = i
        if bad < 0 and not (math.isfinite(z1) and math.isfinite(z2)):
            bad = i
        while s < ns and samples[s] == i:
            s_theta[s] = z1
            s_omega[s] = z2
            s += 1
    z[0], z[1] = z1, z2
    where[0], where[1], where[2], where[3], where[4] = col, nxt, s, left, bad
