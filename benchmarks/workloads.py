"""The workloads people run, each against its peer in the same run, as ratios.

W1  a notebook's scalar calls, warm, in microseconds per call:
    ``agm_period(1.0, 0.5)`` against scipy's ``4 sqrt(l/g) ellipk(sin(a/2)^2)``;
    ``agm_period(1.0, 0.5, iterations=7)`` (T^) against a plain 7-iteration AGM loop in Python;
    ``simulate`` of 21 steps against a plain Python loop of (3);
    ``estimate_period`` at h = 1e-3 against a plain Python loop of (3) to the first return.
W2  the explorer's request at its defaults (``/api/simulate`` as the page asks it, through
    FastAPI's TestClient, warm) against ``simulate`` of the same run (the library's floor);
    its cold first request (a fresh process, numba's cache filled) against
    ``python -c "import numpy, fastapi"``.
W3  the warm ``pendulab report`` against ``python -c "import numpy, matplotlib.pyplot, typst"``.
W4  the answer key of 50 groups (``jobs.key.answer_key``, warm) against the key of one group.
W5  a sweep of 10^4 amplitudes (1..179 degrees, h = 1e-3, taylor2) against the same searches
    in C (``cc -O2``) on one core.
W6  the first ``pendulab estimate`` after a fresh install (``NUMBA_CACHE_DIR`` an empty
    folder, a fresh process) against the same command with the cache filled.

Each pair takes turns and keeps the best of each (``_peers.side_by_side``), so the ratio
holds when the machine's load moves the absolute times. Every time is CPU time (of this
process's threads, or a child's user + sys; the sweep's two threads added up): on a
machine shared with other work, wall time mostly measures the wait for a core. The ratio
is ours over the peer's: lower is better.

Run: ``make bench`` (after ``run.py``) or ``.venv/bin/python benchmarks/workloads.py [--quick] [--write]``
(about two minutes on 2 cores, ``--quick`` about one); ``--write`` puts the table into
``docs/performance.md`` between the markers ``<!-- workloads -->`` and ``<!-- /workloads -->``.
"""
from __future__ import annotations

import math
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

DOC = Path(__file__).resolve().parent.parent / "docs" / "performance.md"
BEGIN, END = "<!-- workloads -->", "<!-- /workloads -->"
G = 9.80665
PY = sys.executable
#: The page's first request at its defaults (``web.parameters.DEFAULTS``, app.js' PLOT_POINTS).
PAGE_QUERY = "length=3.5&amplitude=144&unit=deg&g=9.80665&method=taylor2&step=1e-3&t_max=20&points=3000"
#: Every row is CPU time (this process's threads, or a child's user + sys): on a machine
#: shared with other work, wall time mostly measures the wait for a core.
CLOCK = time.process_time
HEADER = ("workload (CPU time)", "pendulab", "peer", "peer value", "ratio")


#: Each row's workload and peer, in the order printed (the table's first and third columns).
ROWS = (
    ("W1 agm_period(1.0, 0.5) (us)", "scipy 4 sqrt(l/g) ellipk(m)"),
    ("W1 T^: agm_period(..., iterations=7) (us)", "7-iteration loop in Python"),
    ("W1 simulate, 21 steps (us)", "loop of (3) in Python"),
    ("W1 estimate_period, h = 1e-3 (us)", "loop of (3) in Python"),
    ("W2 explorer /api/simulate at its defaults, warm (ms)", "simulate() of the same run"),
    ("W2 the same, first request of a fresh process (s)", 'python -c "import numpy, fastapi"'),
    ("W3 pendulab report, warm (s)", "import numpy, mpl.pyplot, typst"),
    ("W4 answer key, 50 groups (s)", "the key of one group"),
    ("W5 sweep, 10^4 amplitudes, h = 1e-3 (s)", "C loop (cc -O2), one core"),
    ("W6 first pendulab estimate, empty numba cache (s)", "the same, cache filled"),
)


def row(k: int, ours: float, peer: float) -> dict:
    """Row ``k`` of :data:`ROWS` with its two values."""
    what, peer_name = ROWS[k]
    return {"what": what, "ours": ours, "peer_name": peer_name, "peer": peer}


def per_call(fn: Callable[[], object], calls: int) -> Callable[[], object]:
    """``fn`` called ``calls`` times in one timed round (microbenchmarks)."""
    def loop() -> None:
        for _ in range(calls):
            fn()
    return loop


def t_hat_loop(length: float, alpha: float, g: float = G) -> float:
    """(7)-(8) with 7 iterations, as a student writes it."""
    a, b = 1.0, math.cos(alpha / 2)
    for _ in range(7):
        a, b = (a + b) / 2, math.sqrt(a * b)
    return 2 * math.pi * math.sqrt(length / g) / ((a + b) / 2)


def taylor_loop(alpha: float, c: float, h: float, n: int) -> tuple[list[float], list[float]]:
    """(3) for ``n`` steps in plain Python, every point kept."""
    z1, z2 = [alpha], [0.0]
    x, v = alpha, 0.0
    for _ in range(n):
        s = math.sin(x)
        x, v = x + h * v + 0.5 * h * h * c * s, v + h * c * s + 0.5 * h * h * c * v * math.cos(x)
        z1.append(x)
        z2.append(v)
    return z1, z2


def return_loop(alpha: float, c: float, h: float) -> float:
    """(3) in plain Python to the first sign change of z2 from + to - (theta > 0), the time by
    linear interpolation: the period as a notebook would estimate it."""
    x, v = alpha, 0.0
    i = 0
    while True:
        s = math.sin(x)
        xn, vn = x + h * v + 0.5 * h * h * c * s, v + h * c * s + 0.5 * h * h * c * v * math.cos(x)
        if v > 0.0 and vn <= 0.0 and xn > 0.0:
            return h * (i + v / (v - vn))
        x, v, i = xn, vn, i + 1


def w1(repeat: int) -> list[dict]:
    from _peers import side_by_side
    from scipy.special import ellipk

    from pendulab import agm_period, estimate_period, simulate

    length, alpha, c = 1.0, 0.5, -G
    calls = 2000

    def scipy_period() -> float:
        return 4 * math.sqrt(length / G) * ellipk(math.sin(alpha / 2) ** 2)

    h21 = 1e-3
    assert abs(t_hat_loop(length, alpha) - agm_period(length, alpha, iterations=7)) <= 4e-16 * t_hat_loop(length, alpha)
    assert taylor_loop(alpha, c, h21, 21)[0][-1] == simulate(length, alpha, h21, 21 * h21).theta[-1]
    t = side_by_side({
        "period": per_call(lambda: agm_period(length, alpha), calls),
        "scipy": per_call(scipy_period, calls),
        "t_hat": per_call(lambda: agm_period(length, alpha, iterations=7), calls),
        "t_hat_loop": per_call(lambda: t_hat_loop(length, alpha), calls),
        "simulate": per_call(lambda: simulate(length, alpha, h21, 21 * h21), calls // 10),
        "taylor_loop": per_call(lambda: taylor_loop(alpha, c, h21, 21), calls // 10),
    }, repeat, clock=CLOCK)
    est = side_by_side({"estimate": lambda: estimate_period(length, alpha, 1e-3),
                        "return_loop": lambda: return_loop(alpha, c, 1e-3)}, repeat, clock=CLOCK)
    us = 1e6 / calls
    return [
        row(0, t["period"] * us, t["scipy"] * us),
        row(1, t["t_hat"] * us, t["t_hat_loop"] * us),
        row(2, t["simulate"] * us * 10, t["taylor_loop"] * us * 10),
        row(3, est["estimate"] * 1e6, est["return_loop"] * 1e6),
    ]


def w2(repeat: int) -> list[dict]:
    from _peers import run, side_by_side
    from fastapi.testclient import TestClient

    from pendulab import simulate
    from pendulab.web.app import create_app

    client = TestClient(create_app(), base_url="http://localhost")

    def request() -> None:
        r = client.get("/api/simulate?" + PAGE_QUERY)
        assert r.status_code == 200, r.text
        r.json()

    t = side_by_side({"request": request,
                      "simulate": lambda: simulate(3.5, math.radians(144), 1e-3, 20.0)}, repeat, clock=CLOCK)
    cold_cmd = [PY, "-c", "from fastapi.testclient import TestClient; from pendulab.web.app import create_app; "
                f"r = TestClient(create_app(), base_url='http://localhost').get('/api/simulate?{PAGE_QUERY}'); "
                "assert r.status_code == 200"]
    floor_cmd = [PY, "-c", "import numpy, fastapi"]
    run(cold_cmd)  # fills the numba cache and the OS's file cache
    best = {"cold": math.inf, "floor": math.inf}
    for _ in range(max(2, repeat // 2)):
        for k, cmd in (("cold", cold_cmd), ("floor", floor_cmd)):
            best[k] = min(best[k], run(cmd)[1])
    return [
        row(4, t["request"] * 1e3, t["simulate"] * 1e3),
        row(5, best["cold"], best["floor"]),
    ]


def w3(repeat: int) -> list[dict]:
    from bench_report import report_rows

    report = report_rows(repeat)[1]  # CPU time
    return [row(6, report["ours"], report["peer"])]


def w4(repeat: int) -> list[dict]:
    from _peers import side_by_side

    from pendulab.jobs import key

    groups = [(100_000 + 7919 * i, 200_000 + 104_729 * i % 99_991, 300_000 + i) for i in range(50)]
    t = side_by_side({"50": lambda: key.answer_key(groups), "1": lambda: key.answer_key(groups[:1])},
                     max(2, repeat // 2), clock=CLOCK)
    return [row(7, t["50"], t["1"])]


def w5(repeat: int) -> list[dict]:
    import ctypes

    import numpy as np
    from _peers import build_c, ptr, side_by_side

    from pendulab.jobs.sweep import sweep
    from pendulab.numerics.crossing import default_t_max
    from pendulab.numerics.period import agm_period
    from pendulab.numerics.simulation import step_count

    h = 1e-3
    alphas = np.radians(np.linspace(1, 179, 10_000))
    cs = np.full_like(alphas, -G)
    n = np.array([step_count(0.0, default_t_max(T, h), h) for T in agm_period(1.0, alphas)], dtype=np.int64)
    j = np.empty(alphas.size, dtype=np.int64)
    dll = build_c()
    t = side_by_side({
        "sweep": lambda: sweep(alphas, h),
        "C": lambda: dll.sweep(ptr(alphas), ptr(cs), h, ptr(n, ctypes.c_long), alphas.size, ptr(j, ctypes.c_long)),
    }, max(2, repeat // 2), clock=CLOCK)
    return [row(8, t["sweep"], t["C"])]


def w6(repeat: int) -> list[dict]:
    from _peers import run

    cold, warm = math.inf, math.inf
    for _ in range(max(1, repeat // 2)):
        with tempfile.TemporaryDirectory(prefix="pendulab-numba-") as cache:
            env = dict(os.environ, NUMBA_CACHE_DIR=cache)
            cmd = [PY, "-m", "pendulab", "estimate"]
            cold = min(cold, run(cmd, env)[1])
            warm = min(warm, run(cmd, env)[1])
    return [row(9, cold, warm)]


def table(rows: list[dict]) -> str:
    """The rows as a Markdown table (the shape ``--write`` puts into docs/performance.md)."""
    lines = ["| " + " | ".join(HEADER) + " |", "|" + "|".join(["---"] + ["---:"] * (len(HEADER) - 1)) + "|"]
    for r in rows:
        lines.append(f"| {r['what']} | {r['ours']:.3g} | {r['peer_name']} | {r['peer']:.3g} | "
                     f"{r['ours'] / r['peer']:.2f}x |")
    return "\n".join(lines)


def write(text: str, path: Path = DOC) -> None:
    """``text`` between the markers of ``path``."""
    from _peers import write_between

    write_between(path, BEGIN, END, text)


WORKLOADS = (w1, w2, w3, w4, w5, w6)


def main() -> None:
    quick = "--quick" in sys.argv
    repeat = 3 if quick else 7
    started = time.perf_counter()
    load = os.getloadavg()[0]
    rows = [r for w in WORKLOADS for r in w(repeat)]
    assert [(r["what"], r["peer_name"]) for r in rows] == list(ROWS)
    text = table(rows)
    head = subprocess.run(["git", "-C", str(DOC.parent), "rev-parse", "--short", "HEAD"],
                          capture_output=True, text=True).stdout.strip() or "?"
    note = (f"One run of `benchmarks/workloads.py{' --quick' if quick else ''}` at {head}: "
            f"{os.cpu_count()} CPUs, {time.perf_counter() - started:.0f} s, load average "
            f"{load:.1f} at the start, {os.getloadavg()[0]:.1f} at the end.")
    print(text)
    print()
    print(note)
    if "--write" in sys.argv:
        write(text + "\n\n" + note)


if __name__ == "__main__":
    main()
