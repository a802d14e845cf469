"""The explorer against a client that wants it for itself, on 127.0.0.1 only, in bounded loops:
600 bodies trickled a byte at a time, a 10,000-parameter flood, cross-site requests, numeric
overflow; each time a light request is still answered (its latency is measured in
``benchmarks/bench_web_attack.py``, not here)."""
from __future__ import annotations

import contextlib
import math
import select
import socket
import sys
import threading
import time
import warnings

import httpx
import pytest
from fastapi.testclient import TestClient
from hypothesis import given, settings
from hypothesis import strategies as st

from pendulab.core import interrupt
from pendulab.web import create_app, guard, server
from served import serve_in_child
from test_web_server import closed_by_server, half_request, uvicorn_in_thread


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app(), base_url="http://localhost", raise_server_exceptions=False)


def ends(s: socket.socket, within: float = 10.0) -> bytes | None:
    """What the server sent before it closed ``s`` (None: still open after ``within`` s)."""
    s.settimeout(within)
    got = b""
    try:
        while chunk := s.recv(65536):
            got += chunk
    except ConnectionResetError:
        return got
    except TimeoutError:
        return None
    return got


def trickler(port: int, length: int = 100_000) -> socket.socket:
    """Full headers announcing a body of ``length`` bytes, then its first byte."""
    s = half_request(port, (f"GET /api/config HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
                            f"Content-Length: {length}\r\n\r\nx").encode())
    return s


@pytest.mark.slow
def test_600_trickling_bodies_hold_nothing():
    """600 connections that send a body a byte at a time: each is answered 413 and closed at
    once (or closed unanswered past the client's connection cap), and a light request is
    answered throughout."""
    with serve_in_child() as base:
        socks = []
        try:
            for i in range(600):
                with contextlib.suppress(OSError):
                    socks.append(trickler(base.port))
                if i % 100 == 99:
                    assert httpx.get(base + "/api/config", timeout=30).status_code == 200
            for s in socks[:50]:  # a second byte: the server has closed them
                with contextlib.suppress(OSError):
                    s.sendall(b"y")
            answers = [ends(s) for s in socks]
            assert sum(a is not None for a in answers) >= 590  # closed by the server
            # Answered 413, or closed unanswered where the client's connection cap made room.
            assert all(a.startswith(b"HTTP/1.1 413") for a in answers if a)
            assert httpx.get(base + "/api/config", timeout=30).status_code == 200
        finally:
            for s in socks:
                s.close()


class _Reads:
    """An ASGI app that reads the whole request body before it answers (none of the
    explorer's routes does: this exercises the protocol's own body timeout)."""

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return
        while True:
            m = await receive()
            if m["type"] != "http.request" or not m.get("more_body"):
                break
        await send({"type": "http.response.start", "status": 200, "headers": []})
        await send({"type": "http.response.body", "body": b"ok"})


def test_a_body_that_trickles_past_the_body_timeout_is_closed():
    import time

    import uvicorn

    from served import free_port

    port = free_port()
    config = uvicorn.Config(_Reads(), host="127.0.0.1", port=port, loop="asyncio", log_level="warning",
                            http=server.protocol(body_timeout=1.5))  # 1.5 s: room for a loaded machine
    srv = uvicorn.Server(config)
    t = threading.Thread(target=srv.run, daemon=True)
    t.start()
    for _ in range(600):
        if srv.started:
            break
        time.sleep(0.05)
    try:
        slow = trickler(port, 10)
        ok = trickler(port, 2)
        ok.sendall(b"y")  # complete in time: answered
        ok.settimeout(5)
        assert ok.recv(12).startswith(b"HTTP/1.1 200")
        assert closed_by_server(slow, 10.0)
        slow.close()
        ok.close()
    finally:
        srv.should_exit = True
        t.join(10)


def test_connections_per_client_are_capped_and_the_oldest_waiting_one_goes():
    with uvicorn_in_thread(header_timeout=60, max_per_client=4) as port:
        waiting = [half_request(port) for _ in range(10)]
        r = httpx.get(f"http://127.0.0.1:{port}/api/config", timeout=10)
        assert r.status_code == 200
        # the server closes at least the 6 oldest waiting ones (all watched at once; the
        # 10 s bound is a hang guard: they close as the new connections come)
        open_ones, deadline = list(waiting), time.monotonic() + 10.0
        while len(open_ones) > 4 and time.monotonic() < deadline:
            readable, _, _ = select.select(open_ones, [], [], max(0.0, deadline - time.monotonic()))
            open_ones = [s for s in open_ones if s not in readable or not closed_by_server(s, 0.1)]
        assert len(open_ones) <= 4, f"{10 - len(open_ones)} of 10 closed"
        for s in waiting:
            s.close()


def test_a_connection_kept_alive_idle_makes_room_for_a_new_one():
    """A class's browsers keep their connections alive, idle, after the page loads: at the
    per-address cap a new connection closes the oldest idle one (its browser opens another
    when it needs one) instead of being closed itself. The 60 s keep-alive: none times out."""
    import http.client

    with uvicorn_in_thread(keep_alive=60, max_per_client=4) as port:
        idle = []
        for _ in range(4):
            c = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
            c.request("GET", "/api/config")
            r = c.getresponse()
            r.read()
            assert r.status == 200 and not r.will_close
            idle.append(c)
        r = httpx.get(f"http://127.0.0.1:{port}/api/config", timeout=10)
        assert r.status_code == 200
        assert closed_by_server(idle[0].sock, 10.0)  # the oldest; the 10 s a hang guard
        assert not any(closed_by_server(c.sock, 0.2) for c in idle[1:])
        for c in idle:
            c.close()


def test_a_flood_of_parameters_is_refused_before_parsing(client):
    flood = "&".join(["a"] * 10_000)  # 10,000 parameters in 20 KB
    r = client.get("/api/simulate?" + flood)
    assert r.status_code == 414 and "at most 2048 bytes" in r.json()["error"]["message"]
    many = "&".join(f"a={i}" for i in range(guard.MAX_PARAMETERS + 1))
    r = client.get("/api/period?" + many)
    assert r.status_code == 422 and f"at most {guard.MAX_PARAMETERS} query parameters" in r.json()["error"]["message"]
    few = "&".join(["length=1", "amplitude=1"] + [f"x{i}=1" for i in range(guard.MAX_PARAMETERS - 2)])
    r = client.get("/api/period?" + few)  # at the cap: the route judges it
    assert "query parameters" not in r.text and r.status_code in (200, 422)


@pytest.mark.slow
def test_twenty_floods_at_once_leave_the_light_request_answered():
    with serve_in_child() as base:
        flood = "&".join(["a"] * 10_000)  # 10,000 parameters in 20 KB
        codes: list[int] = []

        def attack() -> None:
            for _ in range(5):
                with contextlib.suppress(httpx.HTTPError):
                    codes.append(httpx.get(base + "/api/simulate?" + flood, timeout=30).status_code)

        threads = [threading.Thread(target=attack) for _ in range(20)]
        for t in threads:
            t.start()
        light = [httpx.get(base + "/api/period", params={"length": "1", "amplitude": "1"}, timeout=30).status_code
                 for _ in range(10)]
        for t in threads:
            t.join()
        assert light == [200] * 10
        assert set(codes) <= {414, 431, 400} and codes


@pytest.mark.parametrize("headers", [{"origin": "http://evil.example"}, {"origin": "null"},
                                     {"sec-fetch-site": "cross-site"},
                                     {"origin": "http://localhost.evil.example:8000"},
                                     {"origin": "http://evil.example", "sec-fetch-site": "same-origin"}])
def test_cross_site_requests_are_refused_before_any_work(client, headers):
    before = interrupt.pieces_run.value
    r = client.get("/api/simulate", params={"length": "1", "amplitude": "1", "step": "1e-5", "t_max": "20"},
                   headers=headers)
    assert r.status_code == 403 and "another site" in r.json()["error"]["message"]
    assert interrupt.pieces_run.value == before  # nothing ran
    assert client.get("/", headers=headers).status_code == 403


@pytest.mark.parametrize("headers", [{}, {"origin": "http://localhost"}, {"origin": "http://127.0.0.1:8000"},
                                     {"sec-fetch-site": "same-origin"}, {"sec-fetch-site": "none"}])
def test_the_own_page_is_answered(client, headers):
    assert client.get("/api/config", headers=headers).status_code == 200


def test_a_request_body_is_refused(client):
    r = client.request("GET", "/api/config", content=b"x" * 10)
    assert r.status_code == 413 and r.headers["connection"] == "close"


EXTREMES = ["1e308", "-1e308", "1.7976931348623157e308", "1e-308", "5e-324", "1e309", "-0", "1e-320"]
FIELDS = {"/api/period": ["length", "amplitude", "g"], "/api/motion": ["length", "amplitude", "g", "t_max"]}
BASE = {"length": "1", "amplitude": "1"}


@pytest.mark.slow
@settings(max_examples=150, deadline=None)
@given(st.sampled_from(sorted(FIELDS)), st.data())
def test_no_numeric_overflow_is_a_500(client, route, data):
    names = data.draw(st.lists(st.sampled_from(FIELDS[route]), min_size=1, max_size=3, unique=True))
    q = dict(BASE) | {n: data.draw(st.sampled_from(EXTREMES) | st.floats(allow_nan=False).map(repr)) for n in names}
    r = client.get(route, params=q)
    assert r.status_code in (200, 422), (route, q, r.text[:300])
    if r.status_code == 422:
        assert r.json()["error"]["field"] in (*FIELDS[route], "query", "unit")


def test_a_sample_count_beyond_the_doubles_is_still_an_answer(client):
    """Hypothesis found it: g = t_max = 2.7e-215, a period of 1.2e108 s sampled every 2.7e-215 s,
    1e322 samples a period (beyond the doubles; JSON has no infinity): the largest double."""
    q = {"length": "1", "amplitude": "0.0", "g": "2.735055730101642e-215", "t_max": "2.735055730101642e-215"}
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # and no overflow warning on the way
        r = client.get("/api/motion", params=q)
    assert r.status_code == 200, r.text[:300]
    assert r.json()["frames"]["per_period"] == sys.float_info.max


def test_the_motion_to_t_max_1e308_is_a_422_naming_t_max(client):
    r = client.get("/api/motion", params={"length": "1", "amplitude": "1", "t_max": "1e308"})
    assert r.status_code == 422 and r.json()["error"]["field"] == "t_max"
    assert math.isfinite(float(r.json()["error"]["allowed"].split()[2]))
