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


def _compile(thinned: bool) -> None:
    try:
        import numpy as np

        from ._kernels import fill_thinned, fill_trajectory, first_return

        code, order, alpha, c, h = 0, 2, 1.0, -9.80665, 0.1
        z = np.empty(3)
        fill_trajectory(code, order, alpha, c, h, z, z.copy())
        first_return(code, order, alpha, c, h, 100)
        if thinned:
            fill_thinned(code, order, alpha, c, h, 2, 1, z, z.copy())
    except Exception:  # the command's own first call reports any failure
        pass


def warm_kernels(thinned: bool = True) -> threading.Thread:
    """Start compiling (or loading) the Taylor kernels on a daemon thread, once per process.

    ``thinned=False`` leaves out :func:`~pendulab._kernels.fill_thinned` (only long
    simulations call it): numba compiles one kernel at a time, so a kernel compiled that
    the command never calls delays the ones it is waiting for. The kernels are compiled in
    the order a command first calls them.
    """
    if not _STARTED:
        thread = threading.Thread(target=_compile, args=(thinned,), name="pendulab-warm", daemon=True)
        thread.start()
        _STARTED.append(thread)
    return _STARTED[0]
