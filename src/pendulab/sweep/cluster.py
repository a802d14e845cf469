"""A sweep on a Dask cluster: one task per chunk of pendulums, the results in job order."""
from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ..errors import InputError
from .chunk import run_chunk

#: Seconds to wait for a Dask scheduler before giving up with one clear error.
CONNECT_TIMEOUT = 10


def run_on_cluster(scheduler: Any, jobs: Sequence, alpha: np.ndarray, length: np.ndarray, g: float,
              progress: Callable[[int], None] | None) -> list[dict[str, np.ndarray]]:
    """Submit one task per chunk to a Dask cluster; results come back in job order."""
    try:
        from dask.distributed import Client, as_completed
    except ImportError:  # pragma: no cover - the dask extra is part of the test extra
        raise InputError("scheduler", scheduler, "usable only with dask.distributed installed "
                         "(pip install 'pendulab[dask]')") from None
    own = not hasattr(scheduler, "submit")
    try:
        client = Client(scheduler, timeout=CONNECT_TIMEOUT) if own else scheduler
    except (OSError, TimeoutError, ValueError) as exc:
        raise InputError("scheduler", scheduler, f"the address of a reachable Dask scheduler ({exc})") from None
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
