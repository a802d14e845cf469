"""The explorer's front door, as ASGI middleware: who may ask, and how answers leave.

- **Host allow-list**: a request whose ``Host`` header names anything but this computer
  (``localhost``, ``127.0.0.1``, ``[::1]``) or an address ``pendulab serve`` was told to
  answer on gets status 400. A web page from elsewhere can point its own host name at
  127.0.0.1 (DNS rebinding) and read a local server's answers; its requests still carry
  its own name, so they are refused here.
- **Relative redirects**: the ``Location`` of a redirect (``/api/config/`` to
  ``/api/config``) is a path, never a URL built from the request's ``Host``.
- **HEAD where GET is**: a ``HEAD`` request is answered as the ``GET`` would be, without
  the body; a streamed body stops after its first block.
- **No cross-site request**: a request a page of another site makes (``Sec-Fetch-Site:
  cross-site``, or an ``Origin`` that is not one of the allowed hosts, or ``null``) gets 403
  before any work: another site's page cannot start simulations on this machine.
- **Bounded requests, before parsing**: a query of more than :data:`MAX_QUERY_BYTES` bytes
  gets 414, one of more than :data:`MAX_PARAMETERS` parameters 422, and any request body
  (the API has only GET) 413 with the connection closed, so a body sent a byte at a time
  holds nothing (:mod:`pendulab.web.server` bounds the time of what is left).
"""
from __future__ import annotations

import asyncio
from collections.abc import Iterable
from typing import Any
from urllib.parse import urlsplit

import orjson

#: The names of this computer that every server answers to.
LOCAL_HOSTS = ("localhost", "127.0.0.1", "::1")
#: The longest query string answered (the page's longest is under 300 bytes).
MAX_QUERY_BYTES = 2048
#: The most query parameters answered (a route takes at most 10).
MAX_PARAMETERS = 32

Scope = dict[str, Any]
Message = dict[str, Any]


def host_name(header: str) -> str | None:
    """The host of a ``Host`` header, lower case, without its port (``[::1]:8000`` -> ``::1``)."""
    h = header.strip().lower()
    if h.startswith("["):  # an IPv6 literal in brackets, maybe a port after it
        end = h.find("]")
        rest = h[end + 1:]
        if end < 0 or (rest and not (rest[0] == ":" and rest[1:].isdigit())):
            return None
        return h[1:end]
    name, _, port = h.partition(":")
    if ":" in port or (port and not port.isdigit()):
        return None
    return name.rstrip(".") or None


class Guard:
    """ASGI middleware: the Host allow-list, relative redirects and HEAD (see the module)."""

    def __init__(self, app: Any, allowed_hosts: Iterable[str] = LOCAL_HOSTS):
        self.app = app
        self.allowed = {h.strip().lower().strip("[]").rstrip(".") for h in allowed_hosts}

    async def __call__(self, scope: Scope, receive: Any, send: Any) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        header = next((v.decode("latin-1") for k, v in scope["headers"] if k == b"host"), "")
        if host_name(header) not in self.allowed:
            await _refuse(send, header)
            return
        refused = self.refusal(scope)
        if refused is not None:
            await _answer(send, *refused)
            return
        head = scope["method"] == "HEAD"
        if head:
            scope = dict(scope, method="GET")
        done = False  # the HEAD answer is complete
        finished = asyncio.Event()

        async def guarded_send(message: Message) -> None:
            nonlocal done
            if done:
                return
            if message["type"] == "http.response.start" and 300 <= message["status"] < 400:
                message = dict(message, headers=[_relative(k, v) for k, v in message.get("headers", [])])
            elif message["type"] == "http.response.body" and head:
                message = {"type": "http.response.body", "body": b"", "more_body": False}
                done = True
                finished.set()
            await send(message)

        async def head_receive() -> Message:
            # Once the HEAD answer is complete, a stream stops as if the client had left.
            got = asyncio.ensure_future(receive())
            end = asyncio.ensure_future(finished.wait())
            try:
                await asyncio.wait((got, end), return_when=asyncio.FIRST_COMPLETED)
            finally:
                end.cancel()
            if got.done():
                return got.result()
            got.cancel()
            return {"type": "http.disconnect"}

        await self.app(scope, head_receive if head else receive, guarded_send)


    def refusal(self, scope: Scope) -> tuple[int, str] | None:
        """(status, message) for a request refused before any parsing or work, else None."""
        headers = scope["headers"]
        site = next((v for k, v in headers if k == b"sec-fetch-site"), None)
        origin = next((v.decode("latin-1") for k, v in headers if k == b"origin"), None)
        if site == b"cross-site" or (origin is not None and not self.same_host(origin)):
            return 403, "this server answers its own page only, not a page of another site (Origin, Sec-Fetch-Site)"
        query = scope.get("query_string", b"")
        if len(query) > MAX_QUERY_BYTES:
            return 414, f"the query string must be at most {MAX_QUERY_BYTES} bytes ({len(query)} sent)"
        count = query.count(b"&") + query.count(b";") + 1 if query else 0
        if count > MAX_PARAMETERS:
            return 422, f"at most {MAX_PARAMETERS} query parameters ({count} sent)"
        for k, v in headers:
            if (k == b"content-length" and v.strip() not in (b"0", b"")) or k == b"transfer-encoding":
                return 413, "the API takes no request body (every route is GET)"
        return None

    def same_host(self, origin: str) -> bool:
        """Whether an ``Origin`` header names an allowed host (``null``, a sandboxed or file page, does not)."""
        parts = urlsplit(origin.strip())
        return parts.scheme in ("http", "https") and host_name(parts.netloc) in self.allowed


def _relative(key: bytes, value: bytes) -> tuple[bytes, bytes]:
    """A ``Location`` header as a path (and query): the client resolves it against the URL it asked for."""
    if key.lower() != b"location":
        return key, value
    parts = urlsplit(value.decode("latin-1"))
    path = (parts.path or "/") + (f"?{parts.query}" if parts.query else "")
    if path.startswith("//"):  # a path that a browser would read as a host name
        path = "/" + path.lstrip("/")
    return key, path.encode("latin-1")


async def _answer(send: Any, status: int, message: str) -> None:
    """A JSON error answer, and the connection closed after it (an unread body is never waited for)."""
    body = orjson.dumps({"error": {"message": message}})
    await send({"type": "http.response.start", "status": status,
                "headers": [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode()),
                            (b"connection", b"close")]})
    await send({"type": "http.response.body", "body": body})


async def _refuse(send: Any, header: str) -> None:
    shown = header if len(header) <= 64 else header[:61] + "..."
    body = orjson.dumps({"error": {"message": f"this server does not answer for the host {shown!r} (Host header); "
                                              "open it at the address pendulab serve printed"}})
    await send({"type": "http.response.start", "status": 400,
                "headers": [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode()),
                            (b"connection", b"close")]})
    await send({"type": "http.response.body", "body": body})
