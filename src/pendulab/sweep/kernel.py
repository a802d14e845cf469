"""The sweep's kernel: the streamed period search for many pendulums, on every core.

:func:`first_returns_serial` runs :func:`pendulab._kernels.first_return` for each pendulum
in turn and releases the GIL; :func:`first_returns` runs it on several threads at once.
"""
from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor

import numpy as np
from numba import get_num_threads, njit

from .._kernels import first_return


@njit(cache=True, nogil=True)
def first_returns_serial(method, order, alphas, cs, h, n_steps):
    """``first_return`` for each pendulum ``(alphas[i], cs[i])`` with ``n_steps[i]`` steps, in turn.

    Releases the GIL: :func:`first_returns` runs it on several threads at once, and a
    Dask worker runs it for one chunk.
    """
    m = len(alphas)
    status = np.empty(m, np.int64)
    j = np.empty(m, np.int64)
    z1w = np.empty((m, 5))
    z2w = np.empty((m, 5))
    for i in range(m):
        s, ji, w1, w2 = first_return(method, order, alphas[i], cs[i], h, n_steps[i])
        status[i] = s
        j[i] = ji
        z1w[i, :] = w1
        z2w[i, :] = w2
    return status, j, z1w, z2w


#: Pendulums per task of :func:`first_returns`: small enough that the threads finish
#: together (the periods differ by 5x between 1 and 179 degrees), large enough that a task
#: outlasts its scheduling.
BLOCK = 16
_POOL: list[ThreadPoolExecutor] = []


def first_returns(method, order, alphas, cs, h, n_steps, threads: int | None = None):
    """:func:`first_returns_serial` on ``threads`` threads (default: numba's thread count).

    Blocks of :data:`BLOCK` pendulums go to the threads as they become free. The serial
    kernel releases the GIL, so the threads run on separate cores; each pendulum gives
    the same result, bit for bit, as on one thread. (A ``parallel=True`` build of the
    same loop ran each thread about 1.5x slower than the serial kernel.)
    """
    threads = get_num_threads() if threads is None else threads
    m = len(alphas)
    if threads <= 1 or m <= BLOCK:
        return first_returns_serial(method, order, alphas, cs, h, n_steps)
    if not _POOL or _POOL[0]._max_workers != threads:
        _POOL[:] = [ThreadPoolExecutor(threads, thread_name_prefix="pendulab-sweep")]
    starts = range(0, m, BLOCK)
    parts = list(_POOL[0].map(
        lambda lo: first_returns_serial(method, order, alphas[lo:lo + BLOCK], cs[lo:lo + BLOCK], h,
                                        n_steps[lo:lo + BLOCK]), starts))
    return tuple(np.concatenate([p[k] for p in parts]) for k in range(4))
