"""Benchmark: the explorer's answers to a class while 200 heavy simulations are in flight.

``pendulab serve`` runs in a child process. 200 requests to ``/api/simulate`` with
h = 1e-5 s (l = 1 m, 30 deg, t_max = 20 s: 2 000 000 steps each, plus the period search)
go out at once over 200 connections; while they are in flight, ``GET /``,
``/api/config`` and ``/api/period`` are asked for again and again, one at a time. Side by
side with the same requests on the idle server (ratios), and the server's resident memory
(peak while busy, and while a 1 000 001-row CSV streams to a client that reads slowly).

The aim: each light answer within 250 ms while busy. Run:
``.venv/bin/python benchmarks/bench_web_load.py`` (about a minute on 2 cores).
"""
from __future__ import annotations

import asyncio
import multiprocessing
import os
import statistics
import threading
import time

import httpx

from pendulab.web.child import serve_in_child

N_HEAVY = 200
HEAVY = {"length": "1", "amplitude": "30deg", "step": "1e-5", "t_max": "20"}
LIGHT = ["/", "/api/config", "/api/period?length=1&amplitude=30deg"]
AIM_MS = 250.0
#: Rounds of light requests on the idle server: its tail shows what the machine alone adds.
IDLE_ROUNDS = 200


def light_times(client: httpx.Client, rounds: int, keep_going=lambda: True) -> dict[str, list[float]]:
    out: dict[str, list[float]] = {p: [] for p in LIGHT}
    for _ in range(rounds):
        if not keep_going():
            break
        for path in LIGHT:
            t0 = time.perf_counter()
            r = client.get(path)
            out[path].append(time.perf_counter() - t0)
            assert r.status_code == 200, (path, r.status_code)
        time.sleep(0.05)
    return out


def fire_heavy(base: str, n: int, params: dict, seconds) -> None:
    """In a process of its own at nice +10: the class's browsers are other machines, so their
    200 answers must not delay the measuring client's here."""
    os.nice(10)
    async def go() -> None:
        limits = httpx.Limits(max_connections=n, max_keepalive_connections=n)
        async with httpx.AsyncClient(base_url=base, limits=limits, timeout=httpx.Timeout(900.0)) as client:
            t0 = time.perf_counter()
            rs = await asyncio.gather(*[client.get("/api/simulate", params=params) for _ in range(n)])
            seconds.value = time.perf_counter() - t0
            assert all(r.status_code == 200 for r in rs)

    asyncio.run(go())


async def stream_csv(base: str) -> int:
    """A 1 000 001-row CSV, read slowly (64 kB every 10 ms)."""
    size = 0
    async with (httpx.AsyncClient(base_url=base, timeout=httpx.Timeout(900.0)) as client,
                client.stream("GET", "/api/trajectory.csv", params=HEAVY | {"step": "2e-5"}) as r):
        async for chunk in r.aiter_bytes(65536):
            size += len(chunk)
            await asyncio.sleep(0.01)
    return size


def rss(pid: int) -> int:
    """Resident memory of a process, bytes (Linux: /proc/PID/status)."""
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) * 1024
    raise RuntimeError("no VmRSS")


class PeakRSS:
    """The peak resident memory of a process, sampled every 20 ms in a thread."""

    def __init__(self, pid: int):
        self.pid = pid
        self.peak = rss(pid)
        self._stop = threading.Event()
        self._t = threading.Thread(target=self._run, daemon=True)

    def _run(self) -> None:
        while not self._stop.is_set():
            self.peak = max(self.peak, rss(self.pid))
            time.sleep(0.02)

    def __enter__(self) -> PeakRSS:
        self._t.start()
        return self

    def __exit__(self, *exc) -> None:
        self._stop.set()
        self._t.join()


def run(base: str, pid: int) -> None:
    with httpx.Client(base_url=base, timeout=httpx.Timeout(900.0)) as client:
        client.get("/api/simulate", params=HEAVY)  # kernels loaded
        idle = light_times(client, IDLE_ROUNDS)
        rss_idle = rss(pid)
        seconds = multiprocessing.Value("d", 0.0)
        heavy = multiprocessing.Process(target=fire_heavy, args=(base, N_HEAVY, HEAVY, seconds))
        with PeakRSS(pid) as mem:
            heavy.start()
            time.sleep(1.0)
            busy = light_times(client, 100_000, keep_going=heavy.is_alive)
            heavy.join()
        assert heavy.exitcode == 0
    with PeakRSS(pid) as csv_mem:
        size = asyncio.run(stream_csv(base))
    n = len(busy[LIGHT[0]])
    print(f"machine load average at the end: {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    print(f"{N_HEAVY} x /api/simulate h = 1e-5 s, t_max = 20 s in flight: all answered in {seconds.value:.1f} s; "
          f"meanwhile {n} rounds of the light requests, one at a time")
    print(f"{'request':42} {'idle median':>11} {'idle p99':>9} {'idle max':>9} {'busy median':>11} {'busy p99':>9} {'busy max':>9} {'ratio':>6}  (ms)")
    worst = 0.0
    over = 0
    for path in LIGHT:
        a, b = statistics.median(idle[path]) * 1e3, statistics.median(busy[path]) * 1e3
        ti, ts = sorted(idle[path]), sorted(busy[path])
        ip99, im = ti[int(0.99 * (len(ti) - 1))] * 1e3, ti[-1] * 1e3
        p99, m = ts[int(0.99 * (len(ts) - 1))] * 1e3, ts[-1] * 1e3
        worst = max(worst, m)
        over += sum(x * 1e3 >= AIM_MS for x in ts)
        print(f"GET {path:38} {a:11.2f} {ip99:9.1f} {im:9.1f} {b:11.2f} {p99:9.1f} {m:9.1f} {b / a:6.2f}")
    print(f"aim: every light answer within {AIM_MS:.0f} ms while busy: {'met' if worst < AIM_MS else 'NOT met'} "
          f"(worst {worst:.1f} ms; {over} of {3 * n} at or over)")
    print(f"server memory (RSS): idle {rss_idle / 2**20:.0f} MiB, peak with {N_HEAVY} in flight {mem.peak / 2**20:.0f} MiB, "
          f"peak streaming a {size / 2**20:.0f} MiB CSV {csv_mem.peak / 2**20:.0f} MiB")


def main() -> None:
    with serve_in_child() as base:
        run(base, base.pid)


if __name__ == "__main__":
    main()
