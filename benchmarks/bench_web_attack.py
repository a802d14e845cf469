"""Benchmark: the explorer's light request while one client attacks it.

``pendulab serve`` runs in a child process. Three attacks, each while ``/api/period`` is
asked for again and again, one at a time, against the same request on the idle server
(the ratio of medians):

1. **trickling bodies**: 600 connections send full headers with ``Content-Length: 100000``
   and then a byte of body every 2 s (each is answered 413 and closed);
2. **parameter flood**: 20 clients at once send queries of 10,000 parameters (20 KB each);
3. **cross-site**: 20 clients at once ask for a heavy simulation with ``Origin:
   http://evil.example`` (each refused 403 before any work).

The aim: the light request within 250 ms (median and worst) under every attack. Run:
``.venv/bin/python benchmarks/bench_web_attack.py`` (about a minute on 2 cores).
"""
from __future__ import annotations

import contextlib
import socket
import statistics
import sys
import threading
import time
from pathlib import Path

import httpx

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
from served import serve_in_child

LIGHT = "/api/period?length=1&amplitude=30deg"
AIM_MS = 250.0
ROUNDS = 60


def light(base: str, rounds: int = ROUNDS) -> list[float]:
    times = []
    with httpx.Client(base_url=base, timeout=30) as c:
        for _ in range(rounds):
            t0 = time.perf_counter()
            r = c.get(LIGHT)
            times.append(time.perf_counter() - t0)
            assert r.status_code == 200, r.status_code
            time.sleep(0.02)
    return times


def trickle(port: int, stop: threading.Event) -> None:
    socks = []
    for _ in range(600):
        with contextlib.suppress(OSError):
            s = socket.create_connection(("127.0.0.1", port), timeout=5)
            s.sendall(f"GET /api/config HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Length: 100000\r\n\r\n".encode())
            socks.append(s)
    while not stop.wait(2.0):
        for s in socks:
            with contextlib.suppress(OSError):
                s.sendall(b"x")
    for s in socks:
        s.close()


def flood(base: str, stop: threading.Event, query: str) -> None:
    with httpx.Client(base_url=base, timeout=30) as c:
        while not stop.is_set():
            with contextlib.suppress(httpx.HTTPError):
                c.get(query)


def cross_site(base: str, stop: threading.Event) -> None:
    q = "/api/simulate?length=1&amplitude=30deg&step=2e-6&t_max=20"
    with httpx.Client(base_url=base, timeout=30, headers={"origin": "http://evil.example"}) as c:
        while not stop.is_set():
            with contextlib.suppress(httpx.HTTPError):
                assert c.get(q).status_code == 403


def under(base: str, start) -> list[float]:
    stop = threading.Event()
    threads = start(stop)
    for t in threads:
        t.start()
    time.sleep(1.0)
    try:
        return light(base)
    finally:
        stop.set()
        for t in threads:
            t.join(30)


def main() -> None:
    with serve_in_child() as base:
        light(base, 10)  # warm
        idle = statistics.median(light(base))
        rows = []
        flood_query = "/api/simulate?" + "&".join(["a"] * 10_000)
        attacks = {
            "600 trickling bodies": lambda stop: [threading.Thread(target=trickle, args=(base.port, stop))],
            "20 parameter floods": lambda stop: [threading.Thread(target=flood, args=(base, stop, flood_query))
                                                 for _ in range(20)],
            "20 cross-site clients": lambda stop: [threading.Thread(target=cross_site, args=(base, stop))
                                                   for _ in range(20)],
        }
        for name, start in attacks.items():
            times = under(base, start)
            med, worst = statistics.median(times), max(times)
            rows.append((name, med * 1e3, worst * 1e3, med / idle))
        print(f"light request {LIGHT}: idle median {idle * 1e3:.1f} ms; aim {AIM_MS:.0f} ms")
        print(f"{'attack':<24} {'median ms':>10} {'worst ms':>10} {'x idle':>8}  aim")
        for name, med, worst, ratio in rows:
            print(f"{name:<24} {med:>10.1f} {worst:>10.1f} {ratio:>8.2f}  {'met' if worst <= AIM_MS else 'missed'}")


if __name__ == "__main__":
    main()
