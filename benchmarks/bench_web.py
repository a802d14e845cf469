"""Benchmark of the web explorer: the time to answer ``/api/simulate`` with h = 1e-4.

Problem 5's pendulum (l = 3.5 m, alpha = 4 pi/5), h = 1e-4 s, t_max = 20 s (the page's
default duration): 200 000 Taylor steps stored and thinned to 2000 points, plus the
period search streamed over 1.5 T / h = 93 000 steps. Side by side, as ratios to the
library's own work (the floor the web layer cannot go below):

1. library   ``taylor.simulate`` + ``crossing.estimate_period`` + ``period.agm_period``
2. presenter ``web.views.simulate_view`` + the JSON encoding of the response, in process:
             one streamed pass keeping each column's min/max of theta and of the energy,
             the phase and animation samples, the exact motion and the global error
3. HTTP      a GET to ``pendulab serve`` on loopback (keep-alive), JSON decoded

The aim (issue 5) is under 50 ms for (3). Run: ``.venv/bin/python benchmarks/bench_web.py``
(about 15 s). The load benchmark (200 heavy requests at once) is
``benchmarks/bench_web_load.py``.
"""
from __future__ import annotations

import math
import statistics
import time

import httpx

from pendulab.crossing import estimate_period
from pendulab.period import agm_period
from pendulab.taylor import simulate
from pendulab.web import views
from pendulab.web.app import _encode
from pendulab.web.child import serve_in_child

LENGTH, ALPHA, STEP, T_MAX = 3.5, 4 * math.pi / 5, 1e-4, 20.0
QUERY = {"length": "3.5", "amplitude": "4pi/5", "step": "1e-4", "t_max": "20"}
REPEATS = 40


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
