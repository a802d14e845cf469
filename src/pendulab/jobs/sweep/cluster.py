"""A sweep on a Dask cluster: one task per chunk of pendulums, the results in job order."""
from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ...core.errors import InputError
from .chunk import run_chunk

#: Seconds to wait for a Dask scheduler before giving up with one clear error.
CONNECT_TIMEOUT = 10


def _connect(client_class: Any, address: str) -> Any:
    """A Dask client of the scheduler at ``address``, or one clear error within
    :data:`CONNECT_TIMEOUT` seconds (and a few more).

    ``Client(timeout=...)`` bounds the connection, not the handshake: a port where some
    other server listens may answer nothing (the client then waits for ever) or bytes that
    Dask reads as a frame length (an allocation of exabytes). The client is made on a
    daemon thread, and a silence past the timeout is that error.
    """
    import threading

    box: dict[str, Any] = {}

    def connect() -> None:
        try:
            box["client"] = client_class(address, timeout=CONNECT_TIMEOUT)
        except BaseException as exc:
            box["error"] = exc

    thread = threading.Thread(target=connect, name="pendulab-dask-connect", daemon=True)
    thread.start()
    thread.join(CONNECT_TIMEOUT + 5)
    if "client" in box:
        return box["client"]
    exc = box.get("error")
    why = (f"no Dask handshake within {CONNECT_TIMEOUT + 5} s: is a Dask scheduler listening there?" if exc is None
           else "that port does not speak Dask's protocol" if isinstance(exc, (MemoryError, OverflowError))
           else " ".join(str(exc).split()) or type(exc).__name__)
    raise InputError("scheduler", address, f"the address of a reachable Dask scheduler ({why})")


def run_on_cluster(scheduler: Any, jobs: Sequence, alpha: np.ndarray, length: np.ndarray, g: float,
              progress: Callable[[int], None] | None) -> list[dict[str, np.ndarray]]:
    """Submit one task per chunk to a Dask cluster; results come back in job order."""
    try:
        from dask.distributed import Client, as_completed
    except ImportError:  # pragma: no cover - the dask extra is part of the test extra
        raise InputError("scheduler", scheduler, "usable only with dask.distributed installed "
                         "(pip install 'pendulab[dask]')") from None
    own = not hasattr(scheduler, "submit")
    client = _connect(Client, scheduler) if own else scheduler
    try:
        futures = [
            client.submit(run_chunk, code, order, alpha[lo:hi], length[lo:hi], g, h, False, pure=True)
            for _, code, order, h, lo, hi in jobs
        ]
        index = {f.key: i for i, f in enumerate(futures)}
        parts: list = [None] * len(futures)
        for fut in as_completed(futures):
            i = index[fut.key]
            parts[i] = fut.result()
            if progress is not None:
                _, _, _, _, lo, hi = jobs[i]
                progress(hi - lo)
        return parts
    finally:
        if own:
            client.close()
