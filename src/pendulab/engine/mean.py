"""The arithmetic-geometric mean (7) in double precision: the one loop, for one number and for arrays.

:func:`agm` is plain Python on floats: one period (``pendulab period``) runs it in the
interpreter and needs neither numpy nor numba. numba compiles the same function, inlined,
into :func:`pendulab.engine.kernels.agm_means` (arrays) and :func:`pendulab.engine.agm.block_iterations`
(the double-double kernel's iteration count). Its operations are IEEE double sums, products
and square roots, each correctly rounded and none fused, so the interpreter and the compiled
loop give the same bits. An edit here compiles those kernels again
(:data:`pendulab.engine.numba_cache.KERNEL_SOURCES`).
"""
from __future__ import annotations

from math import sqrt  # a global name, not math.sqrt: one lookup less per step in the interpreter

__all__ = ["FIXED", "MAX_ITERATIONS", "RTOL", "agm"]

#: Upper bound on the iterations to convergence: from b0 = 1e-300 the AGM converges in 17.
MAX_ITERATIONS = 64
#: Convergence: stop where ``a - b <= 4 eps a``; the next step would change ``v`` by less
#: than ``eps^2``.
RTOL = 4 * 2.0**-52
#: The ``rtol`` of a fixed count of iterations (the coursework's 7): a negative ``rtol``
#: skips the test, and the loop runs all of them (compiled, LLVM takes the test out of the
#: loop: no slower than a loop without it).
FIXED = -1.0


def agm(b0: float, iterations: int, rtol: float) -> tuple[float, int]:
    """``(v, k)``: ``v = (a_k + b_k)/2`` after ``k`` iterations of (7) from ``(a0, b0) = (1, b0)``.

    ``k`` is the first count at which ``a_k - b_k <= rtol a_k``, at most ``iterations``
    (exactly ``iterations`` where ``rtol < 0``):
    ``agm(b0, 7, FIXED)`` is the mean of the coursework's ``T^`` (8),
    ``agm(b0, MAX_ITERATIONS, RTOL)`` the mean to convergence in double precision.
    """
    a, b = 1.0, b0
    for k in range(iterations):
        if rtol >= 0.0 and a - b <= rtol * a:
            return 0.5 * (a + b), k
        a, b = 0.5 * (a + b), sqrt(a * b)  # (7)
    return 0.5 * (a + b), iterations
