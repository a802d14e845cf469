"""Correctly rounded periods (8): the AGM (7) in double-double arithmetic, compiled, for arrays and for one pendulum.

For each amplitude the kernel computes ``T = 2 pi sqrt(l)/sqrt(g) / M(1, cos(alpha/2))``
as an unevaluated sum ``th + tl`` of two doubles (double-double: Dekker, Numer. Math. 18
(1971) 224-242; the error-free transformations of Ogita, Rump, Oishi, SIAM J. Sci.
Comput. 26 (2005) 1955-1988) with a relative error below :data:`ERROR_BOUND`, then
rounds it. Where ``th + tl +- ERROR_BOUND th`` do not all round to the same double
(a few amplitudes in 10^6), the kernel flags the element and
:func:`pendulab.numerics.period.agm_period` computes it again with mpmath. The result is the
double nearest to the true period of the input doubles.

The loop is written so that LLVM vectorises it across amplitudes (eight per AVX-512
instruction): blocks of :data:`BLOCK` amplitudes share one iteration count (that of the
block's smallest ``cos(alpha/2)``; more iterations than an element needs do not change its
limit), ``cos(alpha/2)`` is a table and two short polynomials, not a call into libm, and
the AGM's square roots start from a single-precision estimate refined by Newton's method.
"""
from __future__ import annotations

import contextlib
import math
from fractions import Fraction
from typing import Any

import numpy as np
from llvmlite import ir  # type: ignore[import-untyped]
from numba import njit, types
from numba.extending import intrinsic

from . import mean
from .numba_cache import setup as cache_setup

cache_setup(__file__)  # before the first cache=True: a read-only install falls back

#: Amplitudes per block (one iteration count per block).
BLOCK = 32
#: Relative error bound of ``th + tl``. Derived: ``cos(alpha/2)`` within 2^-89
#: (:func:`half_angle_cos`; the AGM is multiplicatively well conditioned,
#: ``|d log M / d log b0| <= 1``), each compensated AGM step within 2^-100 (at most 8 steps),
#: the early stop's series term ``x/4 <= 2^-32`` with ``x`` good to 2^-50 (2^-82) and its
#: remainder ``O(x^3) < 2^-92``, the final quotient and ``2 pi sqrt(l/g)`` within 2^-100:
#: below 2^-81.5 in all. The test assumes 2^-72 (9.5 bits of margin); the largest error
#: measured (``benchmarks/agm_ulps.py``, 10^5 amplitudes) is printed by that script.
ERROR_BOUND = 2.0**-72

# error_model="numpy": a division by zero gives inf, not an exception (a branch that would
# stop the vectoriser). fastmath "contract" only: a * b + c may fuse into one rounding
# (more accurate); never reassociation, which would undo TwoSum.
_FLAGS = {"contract"}
_jit = njit(cache=True, nogil=True, error_model="numpy", fastmath=_FLAGS)
_inline = njit(cache=True, nogil=True, error_model="numpy", fastmath=_FLAGS, inline="always")


def _dd(q: Fraction) -> tuple[float, float]:
    """The double-double nearest to the rational ``q``: ``hi = fl(q)``, ``lo = fl(q - hi)``."""
    hi = float(q)
    return hi, float(q - Fraction(hi))


# pi to 250 bits, kept as three doubles: pi - alpha keeps its digits down to alpha = pi - 1e-16.
_PI_BITS = Fraction(0x3243F6A8885A308D313198A2E03707344A4093822299F31D0082EFA98EC4E6C8, 1 << 252)
PI_HI = float(_PI_BITS)
PI_MID = float(_PI_BITS - Fraction(PI_HI))
PI_LO = float(_PI_BITS - Fraction(PI_HI) - Fraction(PI_MID))
TWO_PI_HI, TWO_PI_LO = 2 * PI_HI, 2 * PI_MID

#: Table spacing of :func:`half_angle_cos`: ``y = i/N_TABLE + r``, ``|r| <= 1/(2 N_TABLE)``.
N_TABLE = 256


def _sin_cos_table() -> np.ndarray:
    """Rows ``(sin y_i, cos y_i)`` as double-doubles, ``y_i = i/N_TABLE``, ``0 <= y_i <= pi/2 + 1/N``
    (:func:`half_angle_cos` reads them up to ``y = pi/2``).

    In 50-digit decimal arithmetic (the standard library's): the series of
    ``sin h, cos h`` at ``h = 1/N_TABLE`` (exact in decimal), then the rotation
    ``(s, c) -> (s cos h + c sin h, c cos h - s sin h)``, whose 400 steps lose about 6
    digits; each value then rounds to its nearest double-double. ``tests/test_agm_rounding.py``
    checks every entry against mpmath.
    """
    from decimal import Decimal, localcontext

    rows = []
    with localcontext() as ctx:
        ctx.prec = 50
        h = Decimal(1) / N_TABLE
        sin_h = cos_h = Decimal(0)
        term = Decimal(1)  # h^k / k!
        for k in range(30):
            if k % 2 == 0:
                cos_h += term if k % 4 == 0 else -term
            else:
                sin_h += term if k % 4 == 1 else -term
            term = term * h / (k + 1)
        s, c = Decimal(0), Decimal(1)
        for _ in range(int(math.pi / 2 * N_TABLE) + 2):
            row = []
            for d in (s, c):
                hi = float(d)
                row += [hi, float(d - Decimal(hi))]
            rows.append(row)
            s, c = s * cos_h + c * sin_h, c * cos_h - s * sin_h
    return np.array(rows)


_TABLE = _sin_cos_table()
SIN_HI, SIN_LO, COS_HI, COS_LO = (np.ascontiguousarray(_TABLE[:, j]) for j in range(4))
# Taylor coefficients of 1 - cos r = u/2 - u^2/24 + u^3/720 - u^4/8! and of
# sin r = r + r u (-1/6 + u/120 - u^2/5040 + u^3/9!), u = r^2 <= 2^-18.
K2, K3, K4 = -1.0 / 24, 1.0 / 720, -1.0 / 40320
S1H, S1L = _dd(Fraction(-1, 6))
S2, S3, S4 = 1.0 / 120, -1.0 / 5040, 1.0 / 362880


@intrinsic
def _fma(typingctx, a, b, c):
    """``a * b + c`` rounded once (the hardware's fused multiply-add, ``llvm.fma``)."""
    sig = types.float64(types.float64, types.float64, types.float64)

    def codegen(context, builder, signature, args):
        d = ir.DoubleType()
        fn = builder.module.declare_intrinsic("llvm.fma", [d], ir.FunctionType(d, [d, d, d]))
        return builder.call(fn, args)

    return sig, codegen


#: ``fma(a, b, c)`` in compiled code (called without the typing context).
fma: Any = _fma


@intrinsic
def _prefer_512_bit_vectors(typingctx):
    """Let LLVM vectorise the calling function with 512-bit registers where the CPU has them.

    LLVM's tuning for Intel's AVX-512 CPUs prefers 256-bit vectors (``prefer-256-bit``)
    unless a function carries ``"prefer-vector-width"="512"`` (clang's
    ``-mprefer-vector-width=512``); numba sets no such attribute, and llvmlite accepts only
    the attributes it knows, hence ``set.add``. On this kernel 512 bits run faster
    (``benchmarks/bench_agm.py``); a CPU without AVX-512 ignores the attribute.
    """
    def codegen(context, builder, signature, args):
        with contextlib.suppress(TypeError):  # a later llvmlite's attribute set: default width
            set.add(builder.function.attributes, '"prefer-vector-width"="512"')
        return context.get_dummy_value()

    return types.void(), codegen


prefer_512_bit_vectors: Any = _prefer_512_bit_vectors


@_inline
def two_sum(a, b):
    """``s + e = a + b`` exactly, ``s = fl(a + b)`` (Knuth's TwoSum)."""
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


@_inline
def fast_two_sum(a, b):
    """``s + e = a + b`` exactly when ``|a| >= |b|`` (Dekker's FastTwoSum)."""
    s = a + b
    return s, b - (s - a)


@_inline
def dd_mul(ah, al, bh, bl):
    """Double-double product (TwoProd by FMA, then the cross terms)."""
    p = ah * bh
    e = fma(ah, bh, -p) + (ah * bl + al * bh)
    return fast_two_sum(p, e)


@_inline
def dd_add(ah, al, bh, bl):
    """Double-double sum."""
    s, e = two_sum(ah, bh)
    return fast_two_sum(s, e + (al + bl))


@_inline
def dd_sqrt(xh, xl):
    """``sqrt(xh + xl)``: one Newton correction of the double square root (residual by FMA)."""
    r = math.sqrt(xh)
    return fast_two_sum(r, (fma(-r, r, xh) + xl) / (2.0 * r))


@_inline
def dd_div(ah, al, bh, bl):
    """Double-double quotient ``a / b``: the double quotient and one correction."""
    q = ah / bh
    r = fma(-q, bh, ah) + (al - q * bl)
    return fast_two_sum(q, r / bh)


@_inline
def last_step(a, ea, b, eb, th, tl):
    """``T = T0 / M(a, b)`` in double-double from the AGM's last pair ``a + ea, b + eb`` (close
    together) and ``T0 = th + tl``: the scalar and the array kernels' one last step."""
    # M = A (1 - x/4 - 5 x^2/64 + O(x^3)): the AGM's own series for a ~ b
    # (one step of (7), then M(1, 1 - e) = 1 - e/2 - e^2/16 - ...).
    s, es = two_sum(a, b)
    inv_s = 1.0 / s
    t = ((a - b) + (ea - eb)) * inv_s
    x = t * t
    mh, ml = two_sum(0.5 * s, -0.5 * s * (x * (0.25 + x * (5.0 / 64.0))))
    ml += 0.5 * (es + (ea + eb))
    # T = T0 / M: q = T0 * (1/M), 1/M = (2/s)(1 + x/4 + O(x^2)) within 2^-51,
    # corrected by the residual T0 - q M (error of the correction: 2^-51 * 2^-51).
    inv = (2.0 * inv_s) * (1.0 + 0.25 * x)
    q = th * inv
    return fast_two_sum(q, (fma(-q, mh, th) + (tl - q * ml)) * inv)


@_inline
def half_angle_cos(alpha):
    """``b0 = cos(alpha/2) = sin(y)``, ``y = (pi - alpha)/2``, for ``0 <= alpha < pi``, as a
    double-double with a relative error below 2^-89.

    Table-based reduction (Tang, ACM TOMS 15 (1989) 144-157; Muller, *Elementary
    Functions*, 3rd ed. (2016), ch. 6): ``y = y_i + r``, ``y_i = i/N_TABLE``,
    ``|r| <= 2^-9``, and ``sin y = sin(y_i) cos(r) + cos(y_i) sin(r)`` with ``sin y_i``,
    ``cos y_i`` from :data:`SIN_HI` ... (double-doubles, error <= 2^-107). ``y`` is
    ``((PI_HI - alpha) + PI_MID + PI_LO)/2`` by error-free sums, so it keeps its relative
    accuracy (2^-104) however close ``alpha`` is to pi; ``y - y_i`` is exact (Sterbenz).

    Error (relative to ``b0``): ``1 - cos r`` is ``u/2`` (double-double) plus
    ``u^2 (-1/24 + u/720 - u^2/8!)`` in double (``u^2/24 <= 2^-40.6``, its rounding
    ``<= 2^-91.6``, truncation ``u^5/10! < 2^-111``); ``sin r - r = r u W``,
    ``W = -1/6 + u (1/120 - ...)`` with ``-1/6`` a double-double and the rest in double
    (``u/120 <= 2^-24.9``: ``W`` within 2^-73, ``sin r`` within 2^-93); the leading sums
    and products are error-free transformations (2^-104 each). The two products are
    positive or of opposite signs, ``|P cos r| + |Q sin r| <= 3 b0`` (worst at ``i = 1``,
    ``r = -2^-9``), so b0's error is below ``3 (2^-91.6 + 2^-93 + 2^-100) < 2^-89``
    (measured: 2^-91.6, ``tests/test_agm_rounding.py``). One table row per element is
    gathered; no branch, so the loop over amplitudes vectorises.
    """
    s, e = two_sum(PI_HI, -alpha)
    d, de = two_sum(s, PI_MID)
    yh, yl = 0.5 * d, 0.5 * (de + (e + PI_LO))
    i = int(yh * N_TABLE + 0.5)
    rh, rl = two_sum(yh - i * (1.0 / N_TABLE), yl)
    uh = rh * rh
    ul = fma(rh, rh, -uh) + 2.0 * rh * rl
    # cos r = 1 - c, c = u/2 + ct, the high part of c absorbing ct (so that c keeps 2^-107).
    ct = uh * uh * (K2 + uh * (K3 + uh * K4))
    ch, cl = fast_two_sum(0.5 * uh, ct)
    bh, bl = fast_two_sum(1.0, -ch)
    bl -= cl + 0.5 * ul
    # sin r = r + (r u) W.
    wh, wl = fast_two_sum(S1H, uh * (S2 + uh * (S3 + uh * S4)))
    wl += S1L
    th = rh * uh
    tl = fma(rh, uh, -th) + (rh * ul + rl * uh)
    sh = th * wh
    sl = fma(th, wh, -sh) + (th * wl + tl * wh)
    ah, al = fast_two_sum(rh, sh)
    al += rl + sl
    # sin(y_i) cos(r) + cos(y_i) sin(r)
    ph, pl, qh, ql = SIN_HI[i], SIN_LO[i], COS_HI[i], COS_LO[i]
    xh = ph * bh
    xl = fma(ph, bh, -xh) + (ph * bl + pl * bh)
    zh = qh * ah
    zl = fma(qh, ah, -zh) + (qh * al + ql * ah)
    return dd_add(xh, xl, zh, zl)


@_inline
def t0_dd(length, gh, gl):
    """``2 pi sqrt(l) / sqrt(g)`` as a double-double, from ``sqrt(g) = gh + gl``.

    Two square roots, not ``sqrt(l/g)``: ``l/g`` can under- or overflow while the period
    is representable.
    """
    rh, rl = dd_sqrt(length, 0.0)
    qh, ql = dd_div(rh, rl, gh, gl)
    return dd_mul(TWO_PI_HI, TWO_PI_LO, qh, ql)


#: :func:`pendulab.engine.mean.agm`, the AGM (7) in double precision, compiled and inlined into its
#: callers here and in :mod:`pendulab.engine.kernels`: the interpreter's loop, bit for bit.
agm = njit(cache=True, nogil=True, inline="always")(mean.agm)


@_jit
def block_iterations(b0):
    """Steps of (7) from ``(1, b0)`` until ``a - b <= 2^-14 a`` (:data:`agm`).

    Then ``M = A (1 - x/4 - 5x^2/64 + O(x^3))`` with ``A = (a+b)/2``,
    ``x = ((a-b)/(a+b))^2 <= 2^-30`` has a remainder below 2^-84. The count only grows as
    ``b0`` falls (the AGM preserves order), so the block's smallest ``b0`` sets it.
    """
    return agm(b0, mean.MAX_ITERATIONS, 2.0**-14)[1]


@_inline
def period_dd(alpha, length, g):
    """The period ``th + tl`` of one pendulum as a double-double, within :data:`ERROR_BOUND`:
    the steps of :func:`agm_periods_dd` for one element, with the double's own square root
    (correctly rounded, its residual by FMA) where the array kernel refines a
    single-precision estimate."""
    gh, gl = dd_sqrt(g, 0.0)
    th, tl = t0_dd(length, gh, gl)
    b, eb = half_angle_cos(alpha)
    a, ea = 1.0, 0.0
    for _ in range(block_iterations(b)):
        s, es = two_sum(a, b)
        p = a * b
        ep = fma(a, b, -p) + (a * eb + b * ea)
        r = math.sqrt(p)
        a, ea = 0.5 * s, 0.5 * (es + (ea + eb))
        b, eb = r, (fma(-r, r, p) + ep) / (2.0 * r)
    return last_step(a, ea, b, eb, th, tl)


@_jit
def agm_period_dd(alpha, length, g):
    """The period of one pendulum (:func:`period_dd`) rounded, or -1.0 where the rounding
    test fails (the caller computes it again). The caller checks ``0 <= alpha < pi`` and
    that ``length``, ``g`` are normal. Called from the interpreter in well under a microsecond."""
    ph, pl = period_dd(alpha, length, g)
    err = ERROR_BOUND * ph
    ok = (ph + (pl + err) == ph) & (ph + (pl - err) == ph) & (ph > 1e-290) & (ph < 1e290)
    return ph if ok else -1.0


@_jit
def agm_periods_dd(alpha, lengths, g, out, lo, hard):
    """``out[i]`` = the period of ``(lengths[i or 0], alpha[i])``, rounded. Returns
    ``(count, bad)``: ``hard[:count]`` are the indices where the rounding test failed (the
    caller computes those again); ``bad`` is the index of the first amplitude outside
    ``[0, pi)`` (NaN included), or -1. Where ``bad >= 0`` the kernel stopped there and
    ``out`` is not filled.

    ``lengths`` has one element (all pendulums share it) or as many as ``alpha``. ``lo``
    (as long as ``alpha``, or empty) receives the low parts ``tl`` (for measuring the error).
    ``hard`` is as long as ``alpha`` (untouched beyond ``count``).
    """
    prefer_512_bit_vectors()
    n = alpha.size
    gh, gl = dd_sqrt(g, 0.0)
    shared = lengths.size == 1
    s0h, s0l = t0_dd(lengths[0], gh, gl)
    # One scratch array in rows of BLOCK, not eight arrays: LLVM then sees that the rows
    # never overlap, and every loop below has the constant trip count BLOCK.
    B = BLOCK
    w = np.zeros(8 * B)
    A, EA, BB, EB, TH, TL, AL, OK = 0, B, 2 * B, 3 * B, 4 * B, 5 * B, 6 * B, 7 * B
    count = 0
    for start in range(0, n, B):
        m = min(B, n - start)
        nbad = 0
        for k in range(m):
            a = alpha[start + k]
            nbad += not ((a >= 0.0) & (a < PI_HI))
            w[AL + k] = a
        if nbad:  # checked before any use: an index into the table must be in range
            for k in range(m):
                a = alpha[start + k]
                if not ((a >= 0.0) & (a < PI_HI)):
                    return count, start + k
        for k in range(m, B):  # the last block: padded with alpha = 0
            w[AL + k] = 0.0
        if not shared:
            for k in range(m):
                w[TH + k], w[TL + k] = t0_dd(lengths[start + k], gh, gl)
        for k in range(B):
            bh, bl = half_angle_cos(w[AL + k])
            w[A + k] = 1.0
            w[EA + k] = 0.0
            w[BB + k] = bh
            w[EB + k] = bl
        bmin = 1.0
        for k in range(B):  # a loop of its own: fused into the one above, it stops the vectoriser
            bmin = min(bmin, w[BB + k])
        for _ in range(block_iterations(bmin)):
            for k in range(B):
                # a' = (a + b)/2, b' = sqrt(a b), each with its rounding error carried to
                # first order in ea, eb (a compensated AGM: TwoSum, TwoProd, sqrt residual).
                a, ea, b, eb = w[A + k], w[EA + k], w[BB + k], w[EB + k]
                s, es = two_sum(a, b)
                p = a * b
                ep = fma(a, b, -p) + (a * eb + b * ea)
                # y ~ 1/sqrt(p): single precision (2^-22.4), then two Newton steps
                # y (3 - p y^2)/2 (relative error d -> 1.5 d^2, then the steps' own
                # rounding): 2^-51.4. r = p y within 2^-51 of sqrt(p); the residual
                # p - r^2 (by FMA) times y/2 corrects it to first order, the second-order
                # term (2^-51)^2/8 and the factor's error 2^-51.4 * 2^-51 leave below 2^-100.
                y = np.float64(np.float32(1.0) / np.sqrt(np.float32(p)))
                y = y * (1.5 - 0.5 * p * y * y)
                y = y * (1.5 - 0.5 * p * y * y)
                r = p * y
                w[A + k] = 0.5 * s
                w[EA + k] = 0.5 * (es + (ea + eb))
                w[BB + k] = r
                w[EB + k] = (fma(-r, r, p) + ep) * (0.5 * y)
        nfail = 0
        for k in range(B):
            th = s0h if shared else w[TH + k]
            tl = s0l if shared else w[TL + k]
            ph, pl = last_step(w[A + k], w[EA + k], w[BB + k], w[EB + k], th, tl)
            # Round: th + tl +- ERROR_BOUND th must all round to the same double.
            err = ERROR_BOUND * ph
            ok = (ph + (pl + err) == ph) & (ph + (pl - err) == ph) & (ph > 1e-290) & (ph < 1e290)
            nfail += not ok
            w[A + k] = ph
            w[EA + k] = pl
            w[OK + k] = 1.0 if ok else 0.0
        for k in range(m):
            out[start + k] = w[A + k]
        if nfail:
            for k in range(m):
                if w[OK + k] == 0.0:
                    hard[count] = start + k
                    count += 1
        if lo.size == n:
            for k in range(m):
                lo[start + k] = w[EA + k]
    return count, -1
