"""Benchmark: the explorer's answers to a class while heavy, stalled and abandoned requests are in flight.

``pendulab serve`` runs in a child process. Three loads, each while ``GET /``,
``/api/config`` and ``/api/period`` are asked for again and again, one at a time, side by
side with the same requests on the idle server (ratios), with the server's resident memory:

1. **busy**: 200 requests to ``/api/simulate`` with h = 1e-5 s (l = 1 m, 30 deg, t_max =
   20 s: 2 000 000 steps each, plus the period search) at once over 200 connections; then
   a 1 000 001-row CSV streamed to a client that reads slowly;
2. **stalled readers**: 20 clients ask for the largest ``/api/simulate`` answer (20 000
   points) and 5 for a 10^6-row CSV, and never read a byte; memory while they stall and
   after the server's write-stall timeout;
3. **abandoned**: 6 requests of the most work one request may run, with ``taylor:30``,
   whose clients leave after 0.1 s; then the default view's simulation (a 20 000-step
   request) is timed against the idle server's.

The aim: each light answer within 250 ms under every load, memory bounded. Run:
``.venv/bin/python benchmarks/bench_web_load.py`` (about two minutes on 2 cores).
"""
from __future__ import annotations

import asyncio
import contextlib
import multiprocessing
import os
import socket
import statistics
import sys
import threading
import time
from pathlib import Path

import httpx

from pendulab.web import limits, server

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
from served import serve_in_child

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


BIG = {"length": "0.0123456789012345", "amplitude": "2.9876543210987654", "step": "1.234567890123e-3",
       "t_max": "1234.56789", "points": str(limits.MAX_POINTS)}
CSV = {"length": "1", "amplitude": "1", "step": "1e-5", "t_max": "10"}
N_STALLED, N_STALLED_CSV = 20, 5
#: The most work one request may run, with the dearest method.
ABANDONED = {"length": "1", "amplitude": "30deg", "method": "taylor:30", "step": "1e-4", "t_max": "24.9"}
N_ABANDONED = 6
#: Seconds after which the abandoning clients leave.
LEAVE = 0.1
NORMAL = {"length": "3.5", "amplitude": "144", "unit": "deg", "step": "1e-3", "t_max": "20"}


def stalled_reader(port: int, path: str, params: dict) -> socket.socket:
    """A connection that asks for ``path`` and never reads the answer."""
    s = socket.create_connection(("127.0.0.1", port), timeout=10)
    query = str(httpx.QueryParams(params))
    s.sendall(f"GET {path}?{query} HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n".encode())
    return s


def light_while(client: httpx.Client, seconds: float) -> dict[str, list[float]]:
    end = time.monotonic() + seconds
    return light_times(client, 100_000, keep_going=lambda: time.monotonic() < end)


def table(title: str, idle: dict[str, list[float]], busy: dict[str, list[float]]) -> tuple[float, int]:
    """Print one load's light-request times beside the idle ones; return (worst ms, answers at or over the aim)."""
    print(title)
    print(f"{'request':42} {'idle median':>11} {'idle p99':>9} {'idle max':>9} {'busy median':>11} {'busy p99':>9} {'busy max':>9} {'ratio':>6}  (ms)")
    worst, over = 0.0, 0
    for path in LIGHT:
        a, b = statistics.median(idle[path]) * 1e3, statistics.median(busy[path]) * 1e3
        ti, ts = sorted(idle[path]), sorted(busy[path])
        ip99, im = ti[int(0.99 * (len(ti) - 1))] * 1e3, ti[-1] * 1e3
        p99, m = ts[int(0.99 * (len(ts) - 1))] * 1e3, ts[-1] * 1e3
        worst = max(worst, m)
        over += sum(x * 1e3 >= AIM_MS for x in ts)
        print(f"GET {path:38} {a:11.2f} {ip99:9.1f} {im:9.1f} {b:11.2f} {p99:9.1f} {m:9.1f} {b / a:6.2f}")
    return worst, over


def closed(s: socket.socket) -> bool:
    """Whether the server has closed ``s``: reading what the kernel still holds for it ends."""
    s.settimeout(2.0)
    try:
        while s.recv(1 << 20):
            pass
    except TimeoutError:
        return False
    except ConnectionResetError:
        pass
    return True


def stalled(base: str, pid: int, client: httpx.Client, idle: dict[str, list[float]]) -> None:
    port = int(base.rsplit(":", 1)[1])
    size = len(client.get("/api/simulate", params=BIG).content)
    rss_before = rss(pid)
    with PeakRSS(pid) as mem:
        socks = [stalled_reader(port, "/api/simulate", BIG) for _ in range(N_STALLED)]
        socks += [stalled_reader(port, "/api/trajectory.csv", CSV) for _ in range(N_STALLED_CSV)]
        busy = light_while(client, server.STALL_TIMEOUT + 5.0)
    rss_after = rss(pid)
    dropped = sum(closed(s) for s in socks)
    for s in socks:
        s.close()
    n = len(busy[LIGHT[0]])
    worst, over = table(f"\n{N_STALLED} clients never reading a {size / 2**20:.1f} MiB /api/simulate answer and {N_STALLED_CSV} a "
                        f"10^6-row CSV, for {server.STALL_TIMEOUT + 5:.0f} s (write-stall timeout {server.STALL_TIMEOUT:.0f} s); "
                        f"{n} rounds of the light requests meanwhile", idle, busy)
    print(f"aim: every light answer within {AIM_MS:.0f} ms: {'met' if worst < AIM_MS else 'NOT met'} (worst {worst:.1f} ms; "
          f"{over} of {3 * n} at or over)")
    print(f"server memory (RSS): before {rss_before / 2**20:.0f} MiB, peak with the stalled readers {mem.peak / 2**20:.0f} MiB, "
          f"after the stall timeout {rss_after / 2**20:.0f} MiB; {dropped} of {len(socks)} stalled connections closed by the server")


def abandoned(base: str, pid: int, client: httpx.Client, idle: dict[str, list[float]]) -> None:
    normal_idle = []
    for _ in range(5):
        t0 = time.perf_counter()
        assert client.get("/api/simulate", params=NORMAL).status_code == 200
        normal_idle.append(time.perf_counter() - t0)
    t0 = time.perf_counter()
    assert client.get("/api/simulate", params=ABANDONED).status_code == 200
    whole = time.perf_counter() - t0

    def leave() -> None:
        with contextlib.suppress(httpx.TimeoutException):
            httpx.get(base + "/api/simulate", params=ABANDONED, timeout=LEAVE)

    with PeakRSS(pid) as mem:
        threads = [threading.Thread(target=leave) for _ in range(N_ABANDONED)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        t0 = time.perf_counter()
        assert client.get("/api/simulate", params=NORMAL).status_code == 200
        normal_after = time.perf_counter() - t0
        busy = light_while(client, 3.0)
    n = len(busy[LIGHT[0]])
    worst, _ = table(f"\n{N_ABANDONED} x /api/simulate taylor:30, 2.5e5 steps (the work limit; {whole:.2f} s alone), "
                        f"clients gone after {LEAVE} s; {n} rounds of the light requests after", idle, busy)
    print(f"aim: every light answer within {AIM_MS:.0f} ms: {'met' if worst < AIM_MS else 'NOT met'} (worst {worst:.1f} ms)")
    mid = statistics.median(normal_idle)
    print(f"the default view's /api/simulate right after they left: {normal_after * 1e3:.0f} ms, idle median {mid * 1e3:.0f} ms "
          f"(ratio {normal_after / mid:.2f}); run to the end they would have held the slots "
          f"{N_ABANDONED * whole / limits.SIMULATION_SLOTS:.1f} s; server memory peak {mem.peak / 2**20:.0f} MiB")


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
    worst, over = table("", idle, busy)
    print(f"aim: every light answer within {AIM_MS:.0f} ms while busy: {'met' if worst < AIM_MS else 'NOT met'} "
          f"(worst {worst:.1f} ms; {over} of {3 * n} at or over)")
    print(f"server memory (RSS): idle {rss_idle / 2**20:.0f} MiB, peak with {N_HEAVY} in flight {mem.peak / 2**20:.0f} MiB, "
          f"peak streaming a {size / 2**20:.0f} MiB CSV {csv_mem.peak / 2**20:.0f} MiB")
    with httpx.Client(base_url=base, timeout=httpx.Timeout(900.0)) as client:
        stalled(base, pid, client, idle)
        abandoned(base, pid, client, idle)


def main() -> None:
    with serve_in_child() as base:
        run(base, base.pid)


if __name__ == "__main__":
    main()
