"""The explorer's streaming loops: one pass over a simulation, keeping only what is drawn.

Both run the library's own step (:func:`pendulab._kernels.step`), so every value they
keep is the value :func:`pendulab.taylor.simulate` computes at that step, bit for bit.

:func:`scan` keeps, for each of ``nb`` columns of steps, the steps where ``theta`` is
smallest and largest and the extremes of the energy drift: a line through these points
in time order has, column by column, the same extent as the whole trajectory (the
min/max reduction of Jugel et al., "M4: A Visualization-Oriented Time Series Data
Aggregation", PVLDB 7(10), 2014). It also keeps the full state at a list of steps (the
phase portrait's and the animation's samples). Memory: O(nb + samples), whatever ``n``.

:func:`advance` runs a block of steps from a given state, for the CSV that streams.
"""
from __future__ import annotations

import math

from numba import njit

from .._kernels import step


@njit(cache=True, nogil=True)
def scan(method, order, alpha, c, h, n, samples, s_theta, s_omega,
         i_lo, i_hi, th_lo, th_hi, om_lo, om_hi, e_i_lo, e_i_hi, e_lo, e_hi):
    """Run ``n`` steps from ``(alpha, 0)``; fill the per-column extremes and the samples.

    Column ``b`` (``b < nb = len(i_lo)``) holds the steps ``i`` with ``floor(i nb/(n+1)) = b``.
    ``i_lo[b]``/``i_hi[b]``: the first step of the column's smallest ``theta``, the last of its
    largest (both kept when ``theta`` is constant), with ``theta`` and ``theta'`` there;
    ``-1`` where every value is NaN.
    The energy drift is ``(E - E0)/(m g l) = theta'^2 l/(2g) - cos(theta) + cos(alpha)``
    (``c = -g/l``). ``samples``: sorted step indices whose state goes to ``s_theta, s_omega``.
    Returns ``(left, bad)``: the first step with ``|theta| >= pi`` (the pendulum went over
    the top, which the exact motion from rest below pi never does) and the first
    non-finite state; ``-1`` when none.
    """
    nb = len(i_lo)
    for b in range(nb):
        i_lo[b] = -1
        i_hi[b] = -1
        e_i_lo[b] = -1
        e_i_hi[b] = -1
        th_lo[b] = math.inf
        th_hi[b] = -math.inf
        e_lo[b] = math.inf
        e_hi[b] = -math.inf
    scale = 1.0 / (-2.0 * c) if c != 0.0 else 0.0
    e0 = math.cos(alpha)
    left = -1
    bad = -1
    col = 0
    nxt = (n + 1 + nb - 1) // nb  # first step of column 1: ceil((n+1)/nb)
    s = 0
    ns = len(samples)
    z1, z2 = alpha, 0.0
    for i in range(n + 1):
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
    return left, bad


@njit(cache=True, nogil=True)
def advance(method, order, z1, z2, c, h, i0, i1, stride, n, out1, out2, out_i):
    """Steps ``i0+1 .. i1`` from the state ``(z1, z2)`` of step ``i0``.

    Keeps the state of each step ``i`` with ``i % stride == 0`` or ``i == n`` in
    ``out1, out2, out_i``. Returns ``(z1, z2, kept)`` (the state at ``i1``).
    """
    k = 0
    for i in range(i0 + 1, i1 + 1):
        z1, z2 = step(method, order, z1, z2, h, c)
        if i % stride == 0 or i == n:
            out1[k] = z1
            out2[k] = z2
            out_i[k] = i
            k += 1
    return z1, z2, k
