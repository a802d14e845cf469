"""A small load check: 200 concurrent API requests on loopback, all answered correctly.

The server is the real command (``pendulab serve``) in a subprocess; the requests go
out at once over 200 connections. Bounded: every request and the whole run time out.
Reference periods: mpmath's complete elliptic integral at 30 digits.
"""
from __future__ import annotations

import asyncio
import math

import httpx
import pytest

from pendulab.web.child import serve_in_child
from conftest import ellipk_period

N_REQUESTS = 200


@pytest.fixture(scope="module")
def server():
    with serve_in_child() as base:
        yield base


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


async def fire(base: str, cases) -> list[httpx.Response]:
    limits = httpx.Limits(max_connections=N_REQUESTS, max_keepalive_connections=N_REQUESTS)
    async with httpx.AsyncClient(base_url=base, limits=limits, timeout=httpx.Timeout(60.0)) as client:
        tasks = [client.get("/api/simulate", params=q) for q, _ in cases]
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
        assert body["period"]["exact"] == pytest.approx(expected, rel=1e-13)
        assert body["n_steps"] == 5000 and body["points"] <= 500
        assert body["theta"][0] == pytest.approx(math.radians(int(q["amplitude"][:-3])), rel=1e-15)
    # The server is still there afterwards.
    assert httpx.get(server + "/api/config", timeout=10).status_code == 200
