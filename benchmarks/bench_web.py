"""Benchmark of the web explorer: the time to answer ``/api/simulate`` with h = 1e-4.

Problem 5's pendulum (l = 3.5 m, alpha = 4 pi/5), h = 1e-4 s, t_max = 20 s (the page's
default duration): 200 000 Taylor steps stored and thinned to 2000 points, plus the
period search streamed over 1.5 T / h = 93 000 steps. Side by side, as ratios to the
library's own work (the floor the web layer cannot go below):

1. library   ``simulation.simulate`` + ``crossing.estimate_period`` + ``period.agm_period``
2. presenter ``web.views.simulate_view`` + the JSON encoding of the response, in process:
             one streamed pass keeping each column's min/max of theta and of the energy,
             the phase and animation samples, the exact motion and the global error
3. HTTP      a GET to ``pendulab serve`` on loopback (keep-alive), JSON decoded

The aim is under 50 ms for (3). Run: ``.venv/bin/python benchmarks/bench_web.py``
(about 30 s). The load benchmark (200 heavy requests at once) is
``benchmarks/bench_web_load.py``.

First, the streamed pass alone (``--pass``: only this): :func:`pendulab.engine.kernels.folded`
(the library's driver into a buffer, folded by a compiled reduction) against the fused loop
it replaces (``fused_scan`` below: the step and the reduction in one loop), on the example
group's pendulum (l = 2.0800838231 m, alpha = 4 pi/5, t_max = 20 s, 1000 columns and the
page's samples) at h = 1e-4 and 1e-5, taking turns, best CPU time of ``PASS_REPEAT``
(100 at 1e-4); both are first checked to keep the same bits.
"""
from __future__ import annotations

import functools
import math
import statistics
import sys
import time
from pathlib import Path

import httpx
import numpy as np
from _peers import print_table, side_by_side
from numba import njit

from pendulab.core.interrupt import CHUNK_COST, pieces, run_pieces
from pendulab.core.methods import cost_per_step
from pendulab.engine import fold, kernels
from pendulab.engine.kernels import step
from pendulab.numerics.crossing import estimate_period
from pendulab.numerics.period import agm_period
from pendulab.numerics.simulation import method_code, simulate, step_count
from pendulab.web import sampling, views
from pendulab.web.app import _encode

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
from served import serve_in_child

LENGTH, ALPHA, STEP, T_MAX = 3.5, 4 * math.pi / 5, 1e-4, 20.0
QUERY = {"length": "3.5", "amplitude": "4pi/5", "step": "1e-4", "t_max": "20"}
REPEATS = 40


# ------------------------------------------------------------------ the streamed pass
EXAMPLE_LENGTH = 2.0800838231
PASS_REPEAT = 10  # rounds at h = 1e-5; ten times as many at 1e-4 (a tenth of the steps)


@njit(cache=True, nogil=True)
def fused_scan(method, order, alpha, c, h, n, i0, i1, z, where, samples, s_theta, s_omega,
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


def fused_pass(code, order, alpha, c, h, n, nb, samples, size):
    """The explorer's pass as the fused loop ran it: the arrays, the record, the pieces."""
    s_th, s_om = np.empty(len(samples)), np.empty(len(samples))
    i_lo, i_hi, e_i_lo, e_i_hi = (np.full(nb, -1, dtype=np.int64) for _ in range(4))
    th_lo, e_lo = np.full(nb, np.inf), np.full(nb, np.inf)
    th_hi, e_hi = np.full(nb, -np.inf), np.full(nb, -np.inf)
    om_lo, om_hi = np.empty(nb), np.empty(nb)
    z = np.array([alpha, 0.0])
    where = np.array([0, (n + 1 + nb - 1) // nb, 0, -1, -1], dtype=np.int64)

    def run(i0, i1):
        fused_scan(code, order, alpha, c, h, n, i0, i1, z, where, samples, s_th, s_om,
                   i_lo, i_hi, th_lo, th_hi, om_lo, om_hi, e_i_lo, e_i_hi, e_lo, e_hi)
        return False

    run_pieces(pieces(n + 1, size), run)
    return (np.array([th_lo, th_hi, om_lo, om_hi, e_lo, e_hi]), np.array([i_lo, i_hi, e_i_lo, e_i_hi]),
            s_th, s_om, where[3:])


def pass_rows() -> list[dict]:
    out = []
    code, order = method_code("taylor2")
    alpha, c, t_max, nb = 4 * math.pi / 5, -9.80665 / EXAMPLE_LENGTH, 20.0, 1000
    size = max(1, int(CHUNK_COST / cost_per_step("taylor2")))
    for h in (1e-4, 1e-5):
        n = step_count(0.0, t_max, h)
        per = float(agm_period(EXAMPLE_LENGTH, alpha)) / h
        samples = np.union1d(np.union1d(sampling.phase_samples(n, per)[0], sampling.frame_samples(n, per)),
                             sampling.frame_samples(n, per, 64, sampling.ERROR_POINTS))
        new = functools.partial(kernels.folded, code, order, alpha, 0.0, c, h, n, nb, samples, size)
        old = functools.partial(fused_pass, code, order, alpha, c, h, n, nb, samples, size)
        r, (value, steps, s_th, s_om, flags) = new(), old()
        same = (np.array_equal(r.value.view(np.int64), value.view(np.int64)) and np.array_equal(r.step, steps)
                and np.array_equal(r.s_theta, s_th) and np.array_equal(r.s_omega, s_om)
                and np.array_equal(r.where[fold.LEFT:], flags))
        assert same, "the two passes keep different values"
        # The thread's CPU time: the kernels run on one thread, and other work on a shared
        # machine takes the core away from either at random (wall times vary twofold).
        t = side_by_side({"new": new, "old": old}, int(PASS_REPEAT * 1e-5 / h), time.thread_time)
        out.append({"what": f"streamed pass, {n} steps of (3), h = {h:g} (CPU s)", "ours": t["new"],
                    "peer_name": "the fused scan", "peer": t["old"], "target": "<= 1.0x"})
    return out


def timed(fn, repeats: int = REPEATS) -> list[float]:
    fn()  # warm: numba's on-disk cache loaded, imports done
    out = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return out


def library() -> None:
    # The explorer keeps every 100th of the 200 000 steps (2000 points), as here.
    simulate(LENGTH, ALPHA, STEP, T_MAX, stride=100)
    estimate_period(LENGTH, ALPHA, STEP)
    agm_period(LENGTH, ALPHA)


def presenter() -> None:
    _encode(views.simulate_view(QUERY))  # the app's own encoder


def main() -> None:
    print_table(pass_rows())
    if "--pass" in sys.argv:
        return
    rows = [("library (simulate + estimate + AGM)", timed(library)), ("presenter in process (+ JSON)", timed(presenter))]
    with serve_in_child() as base, httpx.Client(base_url=base, timeout=30) as client:
        def http() -> None:
            r = client.get("/api/simulate", params=QUERY)
            assert r.status_code == 200
            r.json()

        rows.append(("HTTP GET /api/simulate on loopback", timed(http)))
        size = len(client.get("/api/simulate", params=QUERY).content)
    floor = statistics.median(rows[0][1])
    print(f"problem 5's pendulum, h = {STEP:g} s, t_max = {T_MAX:g} s; median and 90th percentile of {REPEATS} runs; response {size / 1e3:.0f} kB")
    print(f"{'stage':40} {'median ms':>10} {'p90 ms':>8} {'ratio':>6}")
    for name, ts in rows:
        med = statistics.median(ts)
        p90 = sorted(ts)[int(0.9 * len(ts)) - 1]
        print(f"{name:40} {med * 1e3:10.2f} {p90 * 1e3:8.2f} {med / floor:6.2f}")
    http_ms = statistics.median(rows[-1][1]) * 1e3
    print(f"aim: under 50 ms for the HTTP answer: {'met' if http_ms < 50 else 'NOT met'} ({http_ms:.1f} ms)")


if __name__ == "__main__":
    main()
