"""A small load check: 200 concurrent API requests on loopback, all answered correctly.

The server is the real command (``pendulab serve``) in a subprocess; the requests go
out at once over 200 connections. Bounded: every request and the whole run time out.
Reference periods: mpmath's complete elliptic integral at 30 digits.
"""
from __future__ import annotations

import asyncio
import contextlib
import math
import time

import httpx
import pytest

from reference import ellipk_period

N_REQUESTS = 200



def requests() -> list[tuple[dict, float | None]]:
    """Every 10th request is bad (amplitude 200 deg); the others vary length and amplitude."""
    out = []
    for i in range(N_REQUESTS):
        if i % 10 == 9:
            out.append(({"length": "1", "amplitude": "200deg", "step": "1e-3", "t_max": "5"}, None))
            continue
        length, deg = 0.5 + 0.05 * i, 1 + (i * 7) % 178
        q = {"length": f"{length:g}", "amplitude": f"{deg}deg", "step": "1e-3", "t_max": "5", "points": "500"}
        out.append((q, ellipk_period(length, math.radians(deg))))
    return out


#: Connections from one address: a class's requests come from many (the server holds at most
#: ``web.server.MAX_PER_CLIENT`` of one), so the tests spread theirs over loopback addresses.
PER_ADDRESS = 16


def clients(base: str, n: int, timeout: float, first: int = 2) -> list[httpx.AsyncClient]:
    """Enough clients for ``n`` connections at once, each from its own address 127.0.0.``first``, ..."""
    count = -(-n // PER_ADDRESS)
    limits = httpx.Limits(max_connections=PER_ADDRESS, max_keepalive_connections=PER_ADDRESS)
    return [httpx.AsyncClient(base_url=base, limits=limits, timeout=httpx.Timeout(timeout),
                              transport=httpx.AsyncHTTPTransport(local_address=f"127.0.0.{first + k}", limits=limits))
            for k in range(count)]


async def fire(base: str, cases) -> list[httpx.Response]:
    pool = clients(base, N_REQUESTS, 60.0)
    async with contextlib.AsyncExitStack() as stack:
        for c in pool:
            await stack.enter_async_context(c)
        tasks = [pool[i % len(pool)].get("/api/simulate", params=q) for i, (q, _) in enumerate(cases)]
        return await asyncio.wait_for(asyncio.gather(*tasks), timeout=120)


def test_200_concurrent_requests_all_answered_correctly(server):
    cases = requests()
    answers = asyncio.run(fire(server, cases))
    assert len(answers) == N_REQUESTS
    for (q, expected), r in zip(cases, answers):
        if expected is None:
            assert r.status_code == 422 and r.json()["error"]["field"] == "amplitude"
            continue
        assert r.status_code == 200, r.text[:200]
        body = r.json()
        assert body["input"]["length"] == float(q["length"])
        assert body["period"]["period"] == pytest.approx(expected, rel=1e-13)
        assert body["n_steps"] == 5000 and body["points"] <= 500
        assert body["theta"][0] == pytest.approx(math.radians(int(q["amplitude"][:-3])), rel=1e-15)
    # The server is still there afterwards.
    assert httpx.get(server + "/api/config", timeout=10).status_code == 200


HEAVY = {"length": "1", "amplitude": "30deg", "step": "1e-5", "t_max": "50"}  # 5 000 000 steps


def heavy_count(base: str, busy_seconds: float = 4.0) -> int:
    """How many heavy simulations keep both simulation slots busy for ``busy_seconds``.

    Calibrated on the machine that runs the test: a fixed count could be done before the
    page is asked for on a fast machine, and the test's premise (heavy work in flight) false.
    """
    httpx.get(base + "/api/simulate", params=HEAVY, timeout=300)  # compiled and warm
    t0 = time.perf_counter()
    httpx.get(base + "/api/simulate", params=HEAVY, timeout=300)
    one = time.perf_counter() - t0
    return min(200, max(8, math.ceil(2 * busy_seconds / one)))


async def page_while_busy(base: str, n_heavy: int) -> tuple[list[httpx.Response], dict[str, tuple[int, float]], int]:
    """Fire ``n_heavy`` simulations, then ask for the page, config and a period.

    Returns the heavy answers, each light answer's status and seconds, and how many heavy
    requests had finished when the last light one answered.
    """
    done = 0
    pool = clients(base, n_heavy, 300.0)  # the class, each student from an address of its own
    async with contextlib.AsyncExitStack() as stack, httpx.AsyncClient(base_url=base, timeout=300.0) as client:
        for c in pool:
            await stack.enter_async_context(c)

        async def heavy(i: int) -> httpx.Response:
            nonlocal done
            r = await pool[i % len(pool)].get("/api/simulate", params=HEAVY)
            done += 1
            return r

        tasks = [asyncio.create_task(heavy(i)) for i in range(n_heavy)]
        await asyncio.sleep(0.3)  # all sent, the first ones computing
        light = {}
        for path in ("/", "/api/config", "/api/period?length=1&amplitude=30deg"):
            t0 = asyncio.get_running_loop().time()
            r = await client.get(path)
            light[path] = (r.status_code, asyncio.get_running_loop().time() - t0)
        done_then = done
        answers = await asyncio.wait_for(asyncio.gather(*tasks), timeout=600)
    return answers, light, done_then


def test_the_page_answers_while_heavy_simulations_are_in_flight(server):
    # Enough 5 000 000-step simulations to keep the simulation slots busy for about 4 s wait
    # for them; the page, the config and an exact period are answered meanwhile (times:
    # benchmarks/bench_web_load.py).
    n_heavy = heavy_count(server)
    answers, light, done_then = asyncio.run(page_while_busy(server, n_heavy))
    for path, (status, _seconds) in light.items():
        assert status == 200, path
    # answered while the heavy ones were still in flight (a stalled server answers after them)
    assert done_then < n_heavy
    assert all(r.status_code == 200 and r.json()["n_steps"] == 5_000_000 for r in answers)
