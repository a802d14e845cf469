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
from collections.abc import Iterator


def free_port() -> int:
    """A TCP port on 127.0.0.1 that nothing listens on now."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Served(str):
    """``http://127.0.0.1:N``, with the server process's ``pid`` (to read its memory)."""

    pid: int


@contextlib.contextmanager
def serve_in_child(timeout: float = 60.0) -> Iterator[Served]:
    """Start the real ``pendulab serve --port N``; yield ``http://127.0.0.1:N``; stop it.

    Waits until ``/api/config`` answers. Raises ``RuntimeError`` with the server's
    output when it exits or does not answer within ``timeout`` seconds.
    """
    port = free_port()
    cmd = [sys.executable, "-m", "pendulab", "serve", "--port", str(port)]
    base = f"http://127.0.0.1:{port}"
    with tempfile.TemporaryFile("w+") as log:
        proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT)
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
            served.pid = proc.pid
            yield served
        finally:
            proc.terminate()
            try:
                proc.wait(10)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait(10)
