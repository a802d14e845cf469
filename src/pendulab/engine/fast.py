"""The certified table step of (3): a table sine and cosine and the rounding test that proves
a step equal to the literal one.

:func:`certified_step` computes (3) with :func:`table_sin_cos` instead of the C library's
``sin`` and ``cos``, and says whether its result is, bit for bit, the one the C library's
values give. ``pendulab.engine.kernels.taylor2_fast_step`` returns it where it is, and the
literal step where it is not.

(3) as numba evaluates it (no fused multiply-add, no reassociation) is, with
``s = sin z1``, ``co = cos z1`` and ``K = ((0.5 h) h) c``::

    z1' = fl(fl(z1 + fl(h z2)) + fl(K s))
    z2' = fl(A(s) + B(co)),  A(s) = fl(z2 + fl(fl(h c) s)),  B(co) = fl(fl(K z2) co)

Rounding to nearest is monotone (``a <= b`` gives ``fl(a) <= fl(b)``), so ``z1'`` and
``A`` are monotone functions of ``s``, ``B`` of ``co``, and ``z2'`` is increasing in ``A``
and ``B``. The table's ``s, co`` lie within :data:`SIN_MARGIN` and :data:`COS_MARGIN` of
the C library's (less the rounding of ``s +- ds``: 32 units of 2^-52 against 1.0
measured). If ``z1'`` is the same double at ``s - ds`` and ``s + ds``, and ``z2'`` at the
smallest and the largest ``A + B`` over those ends and ``co +- dc``, then the C library's
``s`` and ``co``, which lie between the ends, give those doubles too. This is Ziv's
rounding test (as in :mod:`pendulab.engine.agm`) on a monotone formula.
"""
import math
from typing import Any

from llvmlite import ir  # type: ignore[import-untyped]
from numba import njit, types
from numba.extending import intrinsic

from .agm import COS_HI, N_TABLE, SIN_HI

#: Relative margin of the table's ``sin(z1)``: 32 units of 2^-52. Measured (1.3 * 10^7
#: angles in (-pi, pi), dense near 0, +-pi/2 and +-pi and at the table's nodes): the
#: table's sine is within 1.0 unit of 2^-52 (relative) of the C library's, and within 1/32
#: of the whole margin; ``tests/test_fast_step.py`` requires 1/4 (the safety factor), and
#: 1/8 against mpmath's.
SIN_MARGIN = 2.0**-47
#: Absolute part of the sine's margin for ``|z1| > 3``: near pi the table's sine is the
#: difference of nearly equal terms, so part of its error is absolute, not relative (the
#: worst measured there, both parts together, is also 1/32 of the margin).
SIN_MARGIN_ABS = 2.0**-56
#: Margin of the table's ``cos(z1)``: relative as the sine's, plus an absolute part for the
#: angles near +-pi/2, where the table's cosine is a difference of nearly equal terms, good
#: to about 2^-53 (largest measured: 1.1e-16, 1/40 of the margin).
COS_MARGIN, COS_MARGIN_ABS = 2.0**-47, 2.0**-50
#: The table step is tried only while ``|h^2 c / 2| <= FAST_MAX_K`` (``h sqrt|c| <= 5e-4``):
#: its test fails in about 1 step in 10^3 at ``h sqrt|c| = 5e-7`` and 1 in 10 at 5e-4, where
#: it stops paying (measured, c = -0.01 to -1000).
FAST_MAX_K = 1.25e-7
_ROUND = 1.5 * 2.0**52 / N_TABLE  # y + _ROUND - _ROUND: y rounded to a multiple of 1/N_TABLE
_S3, _S5, _C2, _C4 = -1.0 / 6, 1.0 / 120, -0.5, 1.0 / 24  # the series' coefficients


@intrinsic
def _likely_intrinsic(typingctx, cond):
    """``cond``, with the hint that it is almost always true (``llvm.expect``): LLVM lays the
    other branch out of the loop's way and keeps the loop's values in registers there."""
    if not isinstance(cond, types.Boolean):
        return None

    def codegen(context, builder, signature, args):
        i1 = ir.IntType(1)
        fn = builder.module.declare_intrinsic("llvm.expect", [i1], ir.FunctionType(i1, [i1, i1]))
        return builder.call(fn, [args[0], ir.Constant(i1, 1)])

    return types.boolean(cond), codegen


likely: Any = _likely_intrinsic  # called without the typing context


@intrinsic
def _bits_intrinsic(typingctx, x):
    """The bits of the double ``x`` as an int64 (no conversion: a move between registers)."""
    if not isinstance(x, types.Float):
        return None

    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.IntType(64))

    return types.int64(types.float64), codegen


_bits: Any = _bits_intrinsic  # called without the typing context


#: ``sin(k/256), cos(k/256)``, ``k = 0..805`` (``k/256`` up to pi): the nearest doubles, the
#: leading parts of :mod:`pendulab.engine.agm`'s double-double table.
FAST_SIN, FAST_COS = SIN_HI, COS_HI


@njit(cache=True, nogil=True, inline="always")
def table_sin_cos(z1):
    """``sin(z1), cos(z1)`` for ``|z1| < pi`` from a table and two short series (no call).

    ``|z1| = k/256 + r``, ``|r| <= 2^-9`` with ``r`` exact (Sterbenz), the table's
    ``sin(k/256), cos(k/256)`` (:data:`FAST_SIN`, :data:`FAST_COS`) and ``sin r = r + r u (-1/6 + u/120)``,
    ``cos r = 1 + u (-1/2 + u/24)``, ``u = r^2`` (truncation below 2^-66 and 2^-63 of the
    value); the sums add the table's value last. ``k`` is read from the bits of
    ``|z1| + 1.5 * 2^44`` (whose last bit is worth 1/256), off the angle's path.
    Near pi the sine is the difference of nearly equal terms: its error there is absolute
    (below 2^-61), hence the absolute part of :func:`margins` above 3.
    """
    x = abs(z1)
    t = x + _ROUND
    k = _bits(t) & 1023
    r = x - (t - _ROUND)
    st = FAST_SIN[k]
    ct = FAST_COS[k]
    u = r * r
    ps = _S3 + u * _S5
    pc = _C2 + u * _C4
    cr = ct * r
    sr = st * r
    sin_x = st + (cr + (cr * u * ps + st * u * pc))
    cos_x = ct - (sr - (ct * u * pc - sr * u * ps))
    return math.copysign(sin_x, z1), cos_x


@njit(cache=True, nogil=True, inline="always")
def margins(z1, s, co):
    """``(ds, dc)``: how far the C library's ``sin z1``, ``cos z1`` may lie from the table's
    ``s``, ``co`` (:data:`SIN_MARGIN`, :data:`SIN_MARGIN_ABS`, :data:`COS_MARGIN`, :data:`COS_MARGIN_ABS`)."""
    ds = abs(s) * SIN_MARGIN + (SIN_MARGIN_ABS if abs(z1) > 3.0 else 1e-300)
    return ds, abs(co) * COS_MARGIN + COS_MARGIN_ABS


@njit(cache=True, nogil=True)
def certified_step(z1, z2, h, c, K):
    """``(certified, z1', z2')``: (3) with the table's ``sin`` and ``cos`` (``|z1| < pi``,
    ``K = 0.5 h h c``), and whether the rounding test above shows it equal, bit for bit, to
    (3) with the C library's.

    A call, not inlined: compiled once for all the drivers (inlined into each, numba's
    typing of it made a driver's first compilation about 0.7 s longer).
    """
    s, co = table_sin_cos(z1)
    a1 = z1 + h * z2
    z1_next = a1 + K * s
    hc = h * c
    kz2 = K * z2
    z2_next = (z2 + hc * s) + kz2 * co
    ds, dc = margins(z1, s, co)
    a_lo, a_hi = z2 + hc * (s - ds), z2 + hc * (s + ds)
    b_lo, b_hi = kz2 * (co - dc), kz2 * (co + dc)
    if a_hi < a_lo:
        a_lo, a_hi = a_hi, a_lo
    if b_hi < b_lo:
        b_lo, b_hi = b_hi, b_lo
    certified = (a1 + K * (s - ds) == a1 + K * (s + ds) and z1_next != 0.0 and z2_next != 0.0
                 and a_lo + b_lo == a_hi + b_hi)
    return certified, z1_next, z2_next
