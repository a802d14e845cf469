"""The explorer against hostile clients: each finding reproduced, on 127.0.0.1 only, in bounded loops.

- a request naming another host (DNS rebinding) is refused; redirects never name a host;
- HEAD is answered where GET is;
- every bind other computers can reach prints the exposure notice;
- connections that never finish their headers are closed, and cannot lock others out;
- under a 128-descriptor limit a flood of such connections leaves a quiet log and a
  server that answers;
- the work of a client that has gone is stopped (the pieces the server ran show it).
"""
from __future__ import annotations

import contextlib
import math
import socket
import threading
import time
from urllib.parse import urlencode

import httpx
import numpy as np
import pytest
from fastapi.testclient import TestClient
from hypothesis import given, settings
from hypothesis import strategies as st

from pendulab.cli import main
from pendulab.core import interrupt
from pendulab.core.interrupt import Stopped, stop_when
from pendulab.core.methods import cost_per_step
from pendulab.numerics.crossing import estimate_period
from pendulab.web import create_app, limits, parameters, sampling, server
from pendulab.web.guard import host_name
from served import free_port, serve_in_child


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app(), base_url="http://localhost")


# ------------------------------------------------------------------ Host allow-list, redirects, HEAD

@pytest.mark.parametrize("host", ["localhost", "localhost:8000", "127.0.0.1:8000", "[::1]:8000", "LOCALHOST.", "[::1]"])
def test_this_computers_names_are_answered(client, host):
    assert client.get("/api/config", headers={"host": host}).status_code == 200


@pytest.mark.parametrize("host", ["evil.example", "evil.example:8000", "127.0.0.1.evil.example", "localhost.evil.example",
                                  "[::1", "[::1]x", "localhost:80:80", "", "10.0.0.5", "127.0.0.2"])
def test_other_hosts_are_refused(client, host):
    r = client.get("/api/config", headers={"host": host})
    assert r.status_code == 400 and "Host header" in r.json()["error"]["message"]
    assert client.get("/", headers={"host": host}).status_code == 400


def test_host_name_parsing():
    assert host_name("[::1]:8000") == "::1" and host_name("LocalHost.:80") == "localhost"
    assert host_name("a:b") is None and host_name("[::1]:x:y") is None


def test_allowed_hosts_are_the_bound_addresses(monkeypatch):
    from pendulab.cli import serve as serve_cmd

    monkeypatch.setattr(serve_cmd, "lan_addresses", lambda: ["192.168.1.20"])
    every = serve_cmd.allowed_hosts("0.0.0.0")
    assert "192.168.1.20" in every and "localhost" in every and "evil.example" not in every
    one = serve_cmd.allowed_hosts("127.0.0.1", ("mybox.local",))
    assert "192.168.1.20" not in one and "mybox.local" in one
    app = create_app(every)
    c = TestClient(app, base_url="http://192.168.1.20:8000")
    assert c.get("/api/config").status_code == 200
    assert c.get("/api/config", headers={"host": "192.168.1.21:8000"}).status_code == 400


def test_redirects_are_relative(client):
    r = client.get("/api/config/?x=1", follow_redirects=False)
    assert 300 <= r.status_code < 400 and r.headers["location"] == "/api/config?x=1"
    # The redirect of a refused host is never built: 400 first.
    r = client.get("/api/config/", headers={"host": "evil.example"}, follow_redirects=False)
    assert r.status_code == 400 and "location" not in r.headers


@pytest.mark.parametrize("path", ["/", "/static/app.js", "/api/config", "/api/period?length=1&amplitude=1",
                                  "/api/simulate?length=1&amplitude=1&step=0.01&t_max=2", "/api/openapi.json"])
def test_head_where_get_is(client, path):
    get = client.get(path)
    head = client.head(path)
    assert head.status_code == 200 == get.status_code
    assert head.content == b"" and head.headers["content-type"] == get.headers["content-type"]
    if "content-length" in get.headers:
        assert head.headers["content-length"] == get.headers["content-length"]


def test_head_of_a_stream_stops_after_the_headers(client):
    q = {"length": "1", "amplitude": "1", "step": "1e-6", "t_max": "10"}  # 10^7 rows if read
    r = client.head("/api/trajectory.csv", params=q)
    assert r.status_code == 200 and r.content == b"" and r.headers["content-type"].startswith("text/csv")
    assert client.head("/api/nothing").status_code == 404


def test_openapi_lists_get_only(client):
    schema = client.get("/api/openapi.json").json()
    assert all(set(ops) == {"get"} for ops in schema["paths"].values())


# ------------------------------------------------------------------ the exposure notice

@pytest.mark.parametrize("host, notice", [("127.0.0.1", False), ("localhost", False), ("0", True), ("0.0.0.0", True)])
def test_exposure_notice_for_every_bind_others_reach(capsys, monkeypatch, host, notice):
    from pendulab.cli import serve as serve_cmd

    ran = {}
    monkeypatch.setattr(server, "run", lambda app, h, p, **kw: ran.update(host=h))
    monkeypatch.setattr(serve_cmd, "lan_addresses", lambda: ["192.168.1.20"])
    # Not the bind's check: a port free on 127.0.0.1 may be the source port of a client that
    # another test binds to 127.0.0.90 (test_web_load's class), which a bind of 0.0.0.0 meets.
    monkeypatch.setattr(serve_cmd, "_bind", lambda h, p: None)
    assert main(["serve", "--host", host, "--port", str(free_port())]) == 0
    err = capsys.readouterr().err
    assert ran["host"] == host
    assert ("other computers on the network can open this explorer" in err) is notice
    assert serve_cmd.exposed(host) is notice


def test_a_lan_address_is_exposed():
    from pendulab.cli import serve as serve_cmd

    assert serve_cmd.exposed("::") and not serve_cmd.exposed("::1")
    for address in serve_cmd.lan_addresses():
        assert serve_cmd.exposed(address)


# ------------------------------------------------------------------ incomplete headers, connection cap

@contextlib.contextmanager
def uvicorn_in_thread(keep_alive: int = server.KEEP_ALIVE, **limits_):
    """The real app on uvicorn with the guarded protocol (these limits), in a thread, on 127.0.0.1;
    a kept-alive connection idle for ``keep_alive`` s is closed (the server's by default)."""
    import uvicorn

    port = free_port()
    config = uvicorn.Config(create_app(), host="127.0.0.1", port=port, http=server.protocol(**limits_),
                            loop="asyncio", log_level="warning", timeout_keep_alive=keep_alive)
    srv = uvicorn.Server(config)
    t = threading.Thread(target=srv.run, daemon=True)
    t.start()
    deadline = time.monotonic() + 30
    while not srv.started:
        assert time.monotonic() < deadline and t.is_alive()
        time.sleep(0.05)
    try:
        yield port
    finally:
        srv.should_exit = True
        t.join(10)


def half_request(port: int, text: bytes = b"GET / HTTP/1.1\r\nHost: loc") -> socket.socket:
    s = socket.create_connection(("127.0.0.1", port), timeout=5)
    if text:
        s.sendall(text)
    return s


def closed_by_server(s: socket.socket, within: float) -> bool:
    s.settimeout(within)
    try:
        return s.recv(1024) == b""
    except ConnectionResetError:
        return True
    except TimeoutError:
        return False


def test_incomplete_headers_time_out():
    # A 1.5 s header timeout: the trickled request's 0.2 s pause leaves it 1.3 s for a loaded
    # machine's hiccups; the 10 s waits are hang guards, well past it.
    with uvicorn_in_thread(header_timeout=1.5) as port:
        stalled = [half_request(port), half_request(port, b""), half_request(port, b"GET /api/con")]
        # A request that trickles its headers in but finishes them in time is answered.
        ok = half_request(port, b"GET /api/config HTTP/1.1\r\n")
        time.sleep(0.2)
        ok.sendall(b"Host: localhost\r\n\r\n")
        ok.settimeout(10)
        assert ok.recv(12).startswith(b"HTTP/1.1 200")
        assert all(closed_by_server(s, 10.0) for s in stalled)  # by the 1.5 s header timeout, not our 10 s wait
        # A kept-alive connection that begins a second request and stalls is closed too.
        while b"\r\n\r\n" not in ok.recv(65536):
            pass
        ok.sendall(b"GET / HTT")
        assert closed_by_server(ok, 10.0)
        for s in stalled + [ok]:
            s.close()


def test_stalled_connections_cannot_lock_others_out():
    with uvicorn_in_thread(header_timeout=60, max_connections=8) as port:
        stalled = [half_request(port) for _ in range(30)]
        # Past the cap each new connection closes the oldest one still waiting for headers.
        for _ in range(3):
            r = httpx.get(f"http://127.0.0.1:{port}/api/config", timeout=10)
            assert r.status_code == 200
        closed = sum(closed_by_server(s, 0.5) for s in stalled)
        assert closed >= 30 - 8
        for s in stalled:
            s.close()


def test_one_address_gets_half_the_connections_by_default():
    # 256 of 512 (a class of 30 browsers holds 180); half of fewer under a low ulimit -n.
    assert server.per_address_cap(512) == 256 == server.MAX_PER_CLIENT
    assert server.per_address_cap(57) == 28 and server.per_address_cap(4) == 2 and server.per_address_cap(1) == 1
    assert server.protocol(max_connections=100).max_per_client == 50
    assert server.protocol(max_connections=512).max_per_client == 256
    assert server.protocol(max_connections=100, max_per_client=512).max_per_client == 512  # --per-address N as given


def test_descriptor_limit_keeps_the_log_quiet_and_the_server_answering():
    # 200 connections with half a request line against a server limited to 128 descriptors.
    with serve_in_child(descriptors=128) as base:
        before = base.output()
        stalled = []
        for _ in range(200):
            with contextlib.suppress(OSError):
                stalled.append(half_request(base.port))
        time.sleep(2.0)
        r = httpx.get(base + "/api/config", timeout=10)
        assert r.status_code == 200
        log = base.output()[len(before):]
        assert log.count("\n") <= 2 and "Traceback" not in log, log[:2000]
        for s in stalled:
            s.close()


# ------------------------------------------------------------------ abandoned work

HEAVY = {"length": "1", "amplitude": "30deg", "step": "2e-6", "t_max": "20"}  # 10^7 steps of (3): the limit


def until(condition, within: float = 120.0, every: float = 0.05) -> None:
    """Wait until ``condition()`` (bounded: a server that never gets there fails the test)."""
    end = time.monotonic() + within
    while not condition():
        assert time.monotonic() < end, "the server never got there"
        time.sleep(every)


def settled(within: float = 120.0, quiet: float = 1.0) -> int:
    """The pieces run in this process once no piece has run for ``quiet`` seconds."""
    end = time.monotonic() + within
    last = interrupt.pieces_run.value
    while True:
        time.sleep(quiet)
        now = interrupt.pieces_run.value
        if now == last:
            return now
        assert time.monotonic() < end, "the server kept working"
        last = now


def test_abandoned_work_is_stopped(monkeypatch):
    """Clients that leave once their work has begun: the running requests stop at their next
    piece and the queued ones never start. Shown by the pieces run (a count of what the
    server did), in pieces of 10^5 steps: a whole request runs 100."""
    monkeypatch.setattr(sampling, "CHUNK_COST", 100_000)
    with uvicorn_in_thread() as port:
        base = f"http://127.0.0.1:{port}"
        assert httpx.get(base + "/api/simulate", params=HEAVY, timeout=300).status_code == 200  # warm
        before = settled()
        assert httpx.get(base + "/api/simulate", params=HEAVY, timeout=300).status_code == 200
        whole = settled() - before
        assert whole >= 100
        n = 3 * limits.SIMULATION_SLOTS
        start = interrupt.pieces_run.value
        request = (f"GET /api/simulate?{urlencode(HEAVY)} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n").encode()
        clients = [half_request(port, request) for _ in range(n)]
        until(lambda: interrupt.pieces_run.value > start)  # the work has begun
        for c in clients:
            c.close()
        spent = settled() - start
        # Run to the end they would cost n * whole; stopped, the running ones (one per slot)
        # cost the pieces before the server saw them leave, the queued ones nothing.
        assert spent < n * whole / 3, (spent, whole, n)
        assert httpx.get(base + "/api/config", timeout=10).status_code == 200


def test_the_streamed_pass_stops_between_pieces(monkeypatch):
    p = parameters.simulation(HEAVY)
    stop = threading.Event()
    stop.set()
    with pytest.raises(Stopped), stop_when(stop):
        sampling.simulate_arrays(p, 2000)
    with pytest.raises(Stopped), stop_when(stop):  # the library's period search too
        estimate_period(1.0, 0.5, 1e-5)
    # In pieces, the pass keeps exactly what one pass keeps (pieces of 1000 steps here).
    q = parameters.simulation({"length": "1", "amplitude": "1", "step": "1e-2", "t_max": "50"})
    whole = sampling.simulate_arrays(q, 500)
    monkeypatch.setattr(sampling, "CHUNK_COST", 1000)
    parts = sampling.simulate_arrays(q, 500)
    for key, value in whole.items():
        assert np.array_equal(value, parts[key]) if isinstance(value, np.ndarray) else value == parts[key] or (
            isinstance(value, float) and math.isnan(value) and math.isnan(parts[key])), key


# ------------------------------------------------------------------ numpy warnings

@pytest.mark.filterwarnings("error::RuntimeWarning")
@pytest.mark.parametrize("query", [
    {"length": "1", "amplitude": "3", "step": "1", "t_max": "2000"},  # blows up: inf, then NaN
    {"length": "1e-300", "amplitude": "1", "step": "1e-3", "t_max": "20", "g": "1e300"},  # sqrt(g/l) t overflows
    {"length": "1", "amplitude": "3", "step": "1.9", "t_max": "2000", "method": "taylor:30"},
    {"length": "1e300", "amplitude": "1", "step": "1e-3", "t_max": "20"},
    {"length": "1", "amplitude": "3.14159265358979", "step": "0.1", "t_max": "20"},
    {"length": "1", "amplitude": "1", "step": "1e-3", "t_max": "20", "omega0": "1e300"},  # k^2 overflows
    {"length": "1e-300", "amplitude": "1", "step": "1e-3", "t_max": "20", "g": "1e300", "omega0": "-3"},
    {"length": "1", "amplitude": "0", "step": "1e-3", "t_max": "20", "omega0": "6.2632"},  # near the separatrix
])
def test_no_runtime_warning_reaches_the_log(client, query):
    # A warning is an error here: the request would answer 500.
    r = client.get("/api/simulate", params=query)
    assert r.status_code == 200
    assert client.get("/api/motion", params=query).status_code == 200
    assert client.get("/api/trajectory.csv", params=query | {"columns": "all", "points": "50"}).status_code == 200
    assert client.get("/api/convergence", params=query | {"steps": "1,0.5,0.1"}).status_code in (200, 422)


# ------------------------------------------------------------------ answers bounded in bytes

def list_bounds(points: int) -> dict[str, int]:
    """The longest each list of an /api/simulate answer can be (from how each is drawn)."""
    nb = points // 2
    phase = sampling.PHASE_POINTS + 1 + sampling.PHASE_POINTS // 2  # samples, and a null between whole orbits
    return {"t": 2 * nb, "theta": 2 * nb, "omega": 2 * nb, "energy.t": 2 * nb, "energy.drift": 2 * nb,
            "exact.t": 3 * nb + 1, "exact.theta": 3 * nb + 1, "error.t": 2 * nb, "error.theta": 2 * nb,
            "phase.theta": phase, "phase.omega": phase,
            "frames.t": sampling.FRAME_POINTS + 1, "frames.theta": sampling.FRAME_POINTS + 1,
            "frames.omega": sampling.FRAME_POINTS + 1}


def test_the_stated_byte_bound_follows_from_the_list_bounds():
    # 24 characters: the longest shortest-repr of a double (-2.2250738585072014e-308), and a comma;
    # 16 kB for the keys, the scalars and the warnings.
    assert sum(list_bounds(limits.MAX_POINTS).values()) * 25 + 16_000 <= limits.MAX_ANSWER_BYTES


# The worst cases: most points; many periods per column (every column has turns); a run
# blown up early (nulls), long floats (g, length with 17 digits), every method's drift.
WORST = [
    {"length": "0.0123456789012345", "amplitude": "2.9876543210987654", "step": "1.234567890123e-3", "t_max": "1234.56789"},
    {"length": "1.00000000000001", "amplitude": "pi/3", "step": "2e-4", "t_max": "2000", "g": "9.87654321098765"},
    {"length": "1e-3", "amplitude": "3.1", "step": "1e-3", "t_max": "2900", "method": "taylor:1"},
    {"length": "1", "amplitude": "3", "step": "1", "t_max": "2000000"},
    {"length": "2e-2", "amplitude": "1", "step": "3.3e-4", "t_max": "1400", "method": "rk4"},
]


@pytest.mark.parametrize("query", WORST)
def test_simulate_answers_stay_within_the_byte_bound(client, query):
    r = client.get("/api/simulate", params=query | {"points": str(limits.MAX_POINTS)})
    assert r.status_code == 200, r.text[:300]
    assert len(r.content) <= limits.MAX_ANSWER_BYTES
    body = r.json()
    for key, most in list_bounds(limits.MAX_POINTS).items():
        node = body
        for part in key.split("."):
            node = node[part]
        assert len(node) <= most, key
    # A query past the points limit is refused, so no answer grows beyond the bound.
    r = client.get("/api/simulate", params=query | {"points": str(limits.MAX_POINTS + 1)})
    assert r.status_code == 422 and r.json()["error"]["field"] == "points"


def test_a_client_that_stops_reading_is_dropped():
    # A 10^6-row CSV (about 40 MB) asked for and never read: after the write-stall timeout the
    # server drops the connection, and what it had buffered for it.
    q = "length=1&amplitude=1&step=1e-5&t_max=10"
    with uvicorn_in_thread(stall_timeout=1.0) as port:
        s = socket.create_connection(("127.0.0.1", port), timeout=10)
        s.sendall(f"GET /api/trajectory.csv?{q} HTTP/1.1\r\nHost: localhost\r\n\r\n".encode())
        time.sleep(4.0)
        got = 0
        with contextlib.suppress(ConnectionResetError):
            while chunk := s.recv(1 << 16):
                got += len(chunk)
        s.close()
        assert 0 < got < 10_000_000
        # The server is still there.
        assert httpx.get(f"http://127.0.0.1:{port}/api/config", timeout=10).status_code == 200


# ------------------------------------------------------------------ work limits by cost

METHOD_NAMES = ["taylor2", "rk4", "verlet"] + [f"taylor:{p}" for p in range(1, 31)]


@settings(max_examples=200, deadline=None)
@given(method=st.sampled_from(METHOD_NAMES), log_step=st.floats(-7, -1), log_t=st.floats(0, 5))
def test_every_accepted_run_is_within_the_work_limit(method, log_step, log_t):
    from pendulab.core.errors import InputError
    from pendulab.core.methods import resolve

    q = {"length": "1", "amplitude": "1", "method": method, "step": f"{10 ** log_step:.6g}", "t_max": f"{10 ** log_t:.6g}"}
    try:
        p = parameters.simulation(q)
    except InputError as exc:
        assert exc.name in ("step", "t_max") and method in exc.allowed
        assert round(float(q["t_max"]) / float(q["step"])) > limits.max_steps(resolve(method))
        return
    # N = Round(t_max / h) steps, (6), each costing weight steps of (3).
    assert round(p["t_max"] / p["step"]) * cost_per_step(method) <= limits.MAX_WORK


@pytest.mark.parametrize("method", ["taylor2", "rk4", "taylor:30"])
def test_the_work_limit_is_exact(method):
    from pendulab.core.errors import InputError
    from pendulab.core.methods import resolve

    most = limits.max_steps(resolve(method))
    q = {"length": "1", "amplitude": "1", "method": method, "step": "1e-4"}
    assert parameters.simulation(q | {"t_max": repr(most * 1e-4)})["t_max"] == pytest.approx(most * 1e-4)
    with pytest.raises(InputError):
        parameters.simulation(q | {"t_max": repr((most + 2) * 1e-4)})
    # A dearer method gets fewer steps, in proportion to its cost.
    assert most == int(limits.MAX_WORK / cost_per_step(method))
