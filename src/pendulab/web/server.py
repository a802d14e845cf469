"""The explorer's HTTP server: uvicorn (h11) with bounds on what a client may hold.

uvicorn waits for a request's headers for ever and accepts every connection; a client that
opens connections and sends half a request line (or nothing) would hold the server's file
descriptors until none is left. :class:`GuardedH11` bounds that:

- **header timeout**: a connection whose request headers are not complete within
  :data:`HEADER_TIMEOUT` seconds of its first byte (or of connecting) is closed;
- **write stall**: a client that reads nothing of an answer for :data:`STALL_TIMEOUT`
  seconds is dropped, with the answer's bytes still buffered for it;
- **body timeout**: a request body (which :mod:`pendulab.web.guard` refuses at once, a
  client may still send one) not complete within :data:`BODY_TIMEOUT` seconds closes the
  connection;
- **idle timeout**: a kept-alive connection with no new request for :data:`KEEP_ALIVE`
  seconds is closed (uvicorn's ``timeout_keep_alive``);
- **connection cap**: at most :func:`connection_cap` connections, below the process's
  descriptor limit less a batch of accepts (:func:`accept_batch`), and at most
  :func:`per_address_cap` from one address (a classroom behind one NAT address shares
  them); a new one past either cap closes the oldest connection (of that address, for its
  cap) still waiting for its headers or body, or kept alive idle after its answer (a
  browser opens another when it needs one), or is itself closed when every such
  connection is busy. A client that opens hundreds of connections and trickles bytes into
  them holds its own places only.

An accept that still fails for want of descriptors is logged once a minute in one line
(:func:`quiet_accept_errors`); asyncio alone logs a traceback per attempt, thousands a
second.
"""
from __future__ import annotations

import asyncio
import logging
import os
import time
from collections.abc import Callable
from typing import Any, ClassVar

import h11
from uvicorn.protocols.http.h11_impl import H11Protocol

#: Seconds a connection may take to send its request headers.
HEADER_TIMEOUT = 10.0
#: Seconds a request's body may take once its headers are in.
BODY_TIMEOUT = 10.0
#: Seconds a kept-alive connection may wait idle for its next request.
KEEP_ALIVE = 5
#: At most this many connections from one address by default (``pendulab serve --per-address``):
#: half of :data:`MAX_CONNECTIONS`. A browser opens up to 6 per server and keeps them alive
#: (:data:`KEEP_ALIVE` here) after a page load, so a class of 30 behind one NAT address holds 180 at once:
#: 256 fits 42 such browsers, and leaves the other half of the places to every other address.
MAX_PER_CLIENT = 256
#: Seconds a client may read nothing of an answer before it is dropped.
STALL_TIMEOUT = 30.0
#: At most this many connections, whatever the descriptor limit.
MAX_CONNECTIONS = 512
#: Descriptors kept for everything but connections (the listening socket, files, numba's cache).
_RESERVE = 32

_log = logging.getLogger("pendulab.web")


def _descriptors_free() -> int | None:
    """Descriptors this process may still open (``ulimit -n`` less those open), or None when unlimited."""
    try:
        import resource

        soft = resource.getrlimit(resource.RLIMIT_NOFILE)[0]
    except (ImportError, OSError, ValueError):
        return None
    if soft == resource.RLIM_INFINITY:
        return None
    try:
        used = len(os.listdir("/proc/self/fd"))
    except OSError:
        used = 16
    return soft - used - _RESERVE


def accept_batch() -> int:
    """Connections accepted at once (the listen backlog): asyncio accepts this many before
    the protocol sees any, so the cap must leave room for a whole batch."""
    free = _descriptors_free()
    return 2048 if free is None else max(4, min(2048, free // 4))


def connection_cap(most: int = MAX_CONNECTIONS) -> int:
    """Connections allowed: ``most``, fewer where the descriptor limit (``ulimit -n``) is low."""
    free = _descriptors_free()
    return most if free is None else max(4, min(most, free - accept_batch()))


def per_address_cap(connections: int) -> int:
    """Connections one address may hold by default, of ``connections`` in all: half of them,
    at most :data:`MAX_PER_CLIENT` (256 of 512; fewer where a low ``ulimit -n`` allows fewer)."""
    return max(1, min(MAX_PER_CLIENT, connections // 2))


class GuardedH11(H11Protocol):
    """uvicorn's h11 protocol with a header timeout, a write-stall timeout and a connection cap.

    The limits are class attributes; :func:`protocol` makes a subclass with others.
    """

    header_timeout: float = HEADER_TIMEOUT
    body_timeout: float = BODY_TIMEOUT
    stall_timeout: float = STALL_TIMEOUT
    max_connections: int = MAX_CONNECTIONS
    max_per_client: int = MAX_PER_CLIENT
    #: Connections still waiting for their request's headers or body, or idle between two
    #: requests, oldest first (one list per class: :func:`protocol` gives each server its own).
    waiting: ClassVar[dict[GuardedH11, float]] = {}
    #: The open connections of each client address.
    by_client: ClassVar[dict[str, set[GuardedH11]]] = {}

    def __init__(self, *args: Any, **kwargs: Any):
        super().__init__(*args, **kwargs)
        self._header_timer: asyncio.TimerHandle | None = None
        self._body_timer: asyncio.TimerHandle | None = None
        self._stall_timer: asyncio.TimerHandle | None = None
        self._peer = ""

    def connection_made(self, transport: asyncio.Transport) -> None:  # type: ignore[override]
        super().connection_made(transport)
        peer = transport.get_extra_info("peername")
        self._peer = str(peer[0]) if isinstance(peer, tuple) and peer else ""
        mine = self.by_client.setdefault(self._peer, set())
        mine.add(self)
        if len(mine) > self.max_per_client and not self._make_room(mine):
            return
        if len(self.connections) > self.max_connections and not self._make_room(None):
            return
        self._wait_for_headers()

    def _make_room(self, among: set[GuardedH11] | None) -> bool:
        """Close the oldest waiting connection (of ``among``, else of all); where none waits,
        close this one and return False."""
        oldest = next((c for c in self.waiting if among is None or c in among), None)
        if oldest is None:  # every such connection is at work: this one waits for a free place
            self._forget_client()
            self.transport.abort()
            return False
        oldest._drop()
        return True

    def _forget_client(self) -> None:
        mine = self.by_client.get(self._peer)
        if mine is not None:
            mine.discard(self)
            if not mine:
                del self.by_client[self._peer]

    def connection_lost(self, exc: Exception | None) -> None:
        self._forget_client()
        self._headers_done()
        self._body_done()
        if self._stall_timer is not None:
            self._stall_timer.cancel()
            self._stall_timer = None
        super().connection_lost(exc)

    def data_received(self, data: bytes) -> None:
        super().data_received(data)
        if self.transport.is_closing():
            self._headers_done()
            self._body_done()
        elif self.conn.their_state is h11.IDLE:  # a request begun, its headers not all here
            self._wait_for_headers()
        else:
            self._headers_done()
            if self.conn.their_state is h11.SEND_BODY:  # headers in, a body on its way
                self._wait_for_body()
            else:
                self._body_done()

    def on_response_complete(self) -> None:
        super().on_response_complete()
        if not self.transport.is_closing() and self.conn.their_state is h11.IDLE:
            # Kept alive, idle until its next request: a place the caps may take back.
            self.waiting[self] = time.monotonic()

    def pause_writing(self) -> None:
        super().pause_writing()
        if self._stall_timer is None:
            self._stall_timer = self.loop.call_later(self.stall_timeout, self._drop)

    def resume_writing(self) -> None:
        super().resume_writing()
        if self._stall_timer is not None:
            self._stall_timer.cancel()
            self._stall_timer = None

    def _wait_for_headers(self) -> None:
        if self._header_timer is None:
            self._header_timer = self.loop.call_later(self.header_timeout, self._drop)
            self.waiting[self] = time.monotonic()

    def _headers_done(self) -> None:
        if self._header_timer is not None:
            self._header_timer.cancel()
            self._header_timer = None
        self.waiting.pop(self, None)

    def _wait_for_body(self) -> None:
        if self._body_timer is None:
            self._body_timer = self.loop.call_later(self.body_timeout, self._drop)
            self.waiting[self] = time.monotonic()

    def _body_done(self) -> None:
        if self._body_timer is not None:
            self._body_timer.cancel()
            self._body_timer = None
            if self._header_timer is None:
                self.waiting.pop(self, None)

    def _drop(self) -> None:
        """Close the connection at once (its unsent bytes are discarded)."""
        self._headers_done()
        self._body_done()
        if not self.transport.is_closing():
            self.transport.abort()


def protocol(header_timeout: float = HEADER_TIMEOUT, stall_timeout: float = STALL_TIMEOUT,
             max_connections: int | None = None, body_timeout: float = BODY_TIMEOUT,
             max_per_client: int | None = None) -> type[GuardedH11]:
    """A :class:`GuardedH11` with these limits and its own lists of waiting connections and clients.

    ``max_connections``: :func:`connection_cap` when None; ``max_per_client`` (connections
    from one address): :func:`per_address_cap` of those when None.
    """
    most = connection_cap() if max_connections is None else max_connections
    return type("GuardedH11", (GuardedH11,), {
        "header_timeout": header_timeout, "stall_timeout": stall_timeout, "body_timeout": body_timeout,
        "max_connections": most, "max_per_client": per_address_cap(most) if max_per_client is None else max_per_client,
        "waiting": {}, "by_client": {},
    })


def quiet_accept_errors(loop: asyncio.AbstractEventLoop, every: float = 60.0) -> None:
    """Log a failed accept (no descriptor left) in one line, at most once per ``every`` seconds.

    Other errors go to the loop's default handler as before.
    """
    last = [-float("inf")]

    def handler(loop: asyncio.AbstractEventLoop, context: dict[str, Any]) -> None:
        exc = context.get("exception")
        if context.get("message", "").startswith("socket.accept() out of system resource"):
            now = time.monotonic()
            if now - last[0] >= every:
                last[0] = now
                _log.warning("cannot accept connections: %s (waiting for descriptors to free; "
                             "at most one such line a minute)", getattr(exc, "strerror", None) or exc)
            return
        loop.default_exception_handler(context)

    loop.set_exception_handler(handler)


def run(app: Any, host: str, port: int, before: Callable[[], None] | None = None, **limits: Any) -> None:
    """Serve ``app`` on ``host:port`` until Ctrl+C, with the bounds of :func:`protocol` (``limits``).

    ``before``: called after uvicorn's import, just before the server takes Ctrl+C over
    (the CLI's check for a signal that some callback swallowed on the way).
    """
    import uvicorn

    config = uvicorn.Config(app, host=host, port=port, http=protocol(**limits), loop="asyncio",
                            log_level="warning", timeout_keep_alive=KEEP_ALIVE, backlog=accept_batch())
    server = uvicorn.Server(config)

    async def main() -> None:
        quiet_accept_errors(asyncio.get_running_loop())
        await server.serve()

    if before is not None:
        before()

    asyncio.run(main())  # Ctrl+C: uvicorn shuts down, then raises KeyboardInterrupt as uvicorn.run does
