"""``pendulab serve`` in a child process on a free loopback port (for tests and benchmarks)."""
from __future__ import annotations

import contextlib
import socket
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
from collections.abc import Callable, Iterator
from typing import IO


def free_port() -> int:
    """A TCP port on 127.0.0.1 that nothing listens on now."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Served(str):
    """``http://127.0.0.1:N``, with the server process's ``pid`` (to read its memory) and ``port``."""

    pid: int
    port: int
    _log: IO[str]

    def output(self) -> str:
        """What the server has written to stdout and stderr so far."""
        self._log.flush()
        self._log.seek(0)
        return self._log.read()


def _descriptors(limit: int) -> Callable[[], None]:
    def set_limit() -> None:
        import resource

        resource.setrlimit(resource.RLIMIT_NOFILE, (limit, limit))

    return set_limit


@contextlib.contextmanager
def serve_in_child(timeout: float = 60.0, descriptors: int | None = None,
                   args: tuple[str, ...] = ()) -> Iterator[Served]:
    """Start the real ``pendulab serve --port N`` (and ``args``); yield ``http://127.0.0.1:N``; stop it.

    ``descriptors``: the child's limit on open files (``ulimit -n``). Waits until
    ``/api/config`` answers. Raises ``RuntimeError`` with the server's output when it
    exits or does not answer within ``timeout`` seconds.
    """
    port = free_port()
    cmd = [sys.executable, "-m", "pendulab", "serve", "--port", str(port), *args]
    base = f"http://127.0.0.1:{port}"
    with tempfile.TemporaryFile("w+") as log:
        proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT,
                                preexec_fn=None if descriptors is None else _descriptors(descriptors))
        try:
            deadline = time.monotonic() + timeout
            while True:
                try:
                    with urllib.request.urlopen(base + "/api/config", timeout=2) as r:
                        if r.status == 200:
                            break
                except (urllib.error.URLError, ConnectionError, TimeoutError):
                    pass
                if proc.poll() is not None or time.monotonic() > deadline:
                    log.seek(0)
                    raise RuntimeError(f"pendulab serve did not start: {log.read().strip() or 'timeout'}")
                time.sleep(0.2)
            served = Served(base)
            served.pid, served.port, served._log = proc.pid, port, log
            yield served
        finally:
            proc.terminate()
            try:
                proc.wait(10)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait(10)
