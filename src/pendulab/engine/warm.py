"""Compile the kernels ahead of their first use, on a background thread.

After a fresh install numba compiles each kernel the first time it runs (seconds); the
compiled code is then cached on disk. Commands that will certainly need the Taylor
kernels (``pendulab serve``) start this thread first, so that the
compilation overlaps their imports and set-up instead of delaying the first result. With
a filled cache the thread only loads the kernels. The calls below use the argument types
of the real calls (Python int and float, C-contiguous float64 arrays), so they compile the
very specialisations the library uses.
"""
from __future__ import annotations

import threading

_STARTED: list[threading.Thread] = []


def _compile() -> None:
    try:
        import numpy as np

        from .kernels import drive, search_return

        code, order, alpha, c, h = 0, 2, 1.0, -9.80665, 0.1
        z = np.zeros(5)
        drive(code, order, alpha, 0.0, c, h, 0, 2, 1, 2, z[1:], z[1:].copy())  # a piece of a trajectory
        search_return(code, order, c, h, 100, 0, 100, z, z.copy())
    except Exception:  # the command's own first call reports any failure
        pass


def warm_kernels() -> threading.Thread:
    """Start compiling (or loading) the Taylor kernels on a daemon thread, once per process:
    :func:`~pendulab.engine.kernels.drive` (every simulation, in pieces) and
    :func:`~pendulab.engine.kernels.search_return` (every period search), in that order.
    """
    if not _STARTED:
        thread = threading.Thread(target=_compile, name="pendulab-warm", daemon=True)
        thread.start()
        _STARTED.append(thread)
    return _STARTED[0]
