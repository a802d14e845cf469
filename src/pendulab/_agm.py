"""Correctly rounded periods (8) for arrays: the AGM (7) in double-double arithmetic, compiled.

For each amplitude the kernel computes ``T = 2 pi sqrt(l)/sqrt(g) / M(1, cos(alpha/2))``
as an unevaluated sum ``th + tl`` of two doubles (double-double: Dekker, Numer. Math. 18
(1971) 224-242; the error-free transformations of Ogita, Rump, Oishi, SIAM J. Sci.
Comput. 26 (2005) 1955-1988) with a relative error below :data:`ERROR_BOUND`, then
rounds it. Where ``th + tl +- ERROR_BOUND th`` do not all round to the same double
(a few amplitudes in 10^6), the kernel flags the element and
:func:`pendulab.period.agm_period` computes it again with mpmath. The result is the
double nearest to the true period of the input doubles.

The loop is written so that LLVM vectorises it across amplitudes: blocks of
:data:`BLOCK` amplitudes share one iteration count (that of the block's smallest
``cos(alpha/2)``; more iterations than an element needs do not change its limit), and
``cos(alpha/2)`` is a polynomial, not a call into libm.
"""
from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import numpy as np
from llvmlite import ir  # type: ignore[import-untyped]
from numba import njit, types
from numba.extending import intrinsic

#: Amplitudes per block (one iteration count per block).
BLOCK = 32
#: Relative error bound of ``th + tl``: the cos/sin series truncated below 2^-87,
#: the AGM stopped where its series remainder is below 2^-84, and about a hundred
#: double-double operations of about 2^-104 each. The largest error measured
#: (``benchmarks/agm_ulps.py``, 10^5 amplitudes) is printed by that script.
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
# Taylor coefficients (-1)^n/(2n)! of cos and (-1)^n/(2n+1)! of sin in u = x^2. Terms
# n <= 5 (down to 2^-26 on |x| <= pi/4) in double-double, n = 6..11 in double; the first
# term left out is below 2^-87 (relative).
_COS = [_dd(Fraction((-1) ** n, math.factorial(2 * n))) for n in range(12)]
_SIN = [_dd(Fraction((-1) ** n, math.factorial(2 * n + 1))) for n in range(12)]
C0H, C0L = _COS[0]
C1H, C1L = _COS[1]
C2H, C2L = _COS[2]
C3H, C3L = _COS[3]
C4H, C4L = _COS[4]
C5H, C5L = _COS[5]
C6, C7, C8, C9, C10, C11 = (c[0] for c in _COS[6:])
S0H, S0L = _SIN[0]
S1H, S1L = _SIN[1]
S2H, S2L = _SIN[2]
S3H, S3L = _SIN[3]
S4H, S4L = _SIN[4]
S5H, S5L = _SIN[5]
S6, S7, S8, S9, S10, S11 = (c[0] for c in _SIN[6:])


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
def half_angle_cos(alpha):
    """``b0 = cos(alpha/2)`` for ``0 <= alpha < pi`` as a double-double.

    Up to ``alpha = pi/2``: ``cos(x)``, ``x = alpha/2``; above, ``sin(y)`` with
    ``y = (pi - alpha)/2``, where ``PI_HI - alpha`` is exact (Sterbenz's lemma), so ``b0``
    keeps its full relative accuracy however close ``alpha`` is to pi. Both are Taylor
    series in ``u = z^2``, ``|z| <= pi/4``, evaluated by one Horner loop whose coefficients
    are chosen per element (so that the loop over amplitudes vectorises).
    """
    c = alpha <= 0.5 * PI_HI
    dh, dl = two_sum(PI_HI - alpha, PI_MID)
    dh, dl = fast_two_sum(dh, dl + PI_LO)
    zh = 0.5 * alpha if c else 0.5 * dh
    zl = 0.0 if c else 0.5 * dl
    uh = zh * zh
    ul = fma(zh, zh, -uh) + 2.0 * zh * zl
    p = C11 if c else S11
    p = p * uh + (C10 if c else S10)
    p = p * uh + (C9 if c else S9)
    p = p * uh + (C8 if c else S8)
    p = p * uh + (C7 if c else S7)
    p = p * uh + (C6 if c else S6)
    rh, rl = dd_add(p * uh, 0.0, C5H if c else S5H, C5L if c else S5L)
    rh, rl = dd_mul(rh, rl, uh, ul)
    rh, rl = dd_add(rh, rl, C4H if c else S4H, C4L if c else S4L)
    rh, rl = dd_mul(rh, rl, uh, ul)
    rh, rl = dd_add(rh, rl, C3H if c else S3H, C3L if c else S3L)
    rh, rl = dd_mul(rh, rl, uh, ul)
    rh, rl = dd_add(rh, rl, C2H if c else S2H, C2L if c else S2L)
    rh, rl = dd_mul(rh, rl, uh, ul)
    rh, rl = dd_add(rh, rl, C1H if c else S1H, C1L if c else S1L)
    rh, rl = dd_mul(rh, rl, uh, ul)
    rh, rl = dd_add(rh, rl, 1.0, 0.0)
    return dd_mul(rh, rl, 1.0 if c else zh, 0.0 if c else zl)


@_inline
def t0_dd(length, gh, gl):
    """``2 pi sqrt(l) / sqrt(g)`` as a double-double, from ``sqrt(g) = gh + gl``.

    Two square roots, not ``sqrt(l/g)``: ``l/g`` can under- or overflow while the period
    is representable.
    """
    rh, rl = dd_sqrt(length, 0.0)
    qh, ql = dd_div(rh, rl, gh, gl)
    return dd_mul(TWO_PI_HI, TWO_PI_LO, qh, ql)


@_jit
def block_iterations(b0):
    """Steps of (7) from ``(1, b0)`` until ``a - b <= 2^-14 a``.

    Then ``M = A (1 - x/4 - 5x^2/64 + O(x^3))`` with ``A = (a+b)/2``,
    ``x = ((a-b)/(a+b))^2 <= 2^-30`` has a remainder below 2^-84. The count only grows as
    ``b0`` falls (the AGM preserves order), so the block's smallest ``b0`` sets it.
    """
    a, b = 1.0, b0
    for k in range(64):
        if a - b <= 2.0**-14 * a:
            return k
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return 64


@_jit
def agm_periods_dd(alpha, lengths, g, out, lo, flags):
    """``out[i]`` = the period of ``(lengths[i or 0], alpha[i])``, rounded; ``flags[i] = 1``
    where the rounding test fails (the caller computes those again).

    ``lengths`` has one element (all pendulums share it) or as many as ``alpha``. ``lo``
    (as long as ``alpha``, or empty) receives the low parts ``tl`` (for measuring the error).
    """
    n = alpha.size
    gh, gl = dd_sqrt(g, 0.0)
    shared = lengths.size == 1
    s0h, s0l = t0_dd(lengths[0], gh, gl)
    # One scratch array in rows of BLOCK, not eight arrays: LLVM then sees that the rows
    # never overlap, and every loop below has the constant trip count BLOCK.
    B = BLOCK
    w = np.zeros(8 * B)
    A, EA, BB, EB, TH, TL, AL, OK = 0, B, 2 * B, 3 * B, 4 * B, 5 * B, 6 * B, 7 * B
    for start in range(0, n, B):
        m = min(B, n - start)
        for k in range(m):
            w[AL + k] = alpha[start + k]
        for k in range(m, B):  # the last block: padded with alpha = 0
            w[AL + k] = 0.0
        if shared:
            for k in range(B):
                w[TH + k] = s0h
                w[TL + k] = s0l
        else:
            for k in range(m):
                w[TH + k], w[TL + k] = t0_dd(lengths[start + k], gh, gl)
        for k in range(B):
            bh, bl = half_angle_cos(w[AL + k])
            w[A + k] = 1.0
            w[EA + k] = 0.0
            w[BB + k] = bh
            w[EB + k] = bl
        bmin = 1.0
        for k in range(B):
            bmin = min(bmin, w[BB + k])
        for _ in range(block_iterations(bmin)):
            for k in range(B):
                # a' = (a + b)/2, b' = sqrt(a b), each with its rounding error carried to
                # first order in ea, eb (a compensated AGM: TwoSum, TwoProd, sqrt residual).
                a, ea, b, eb = w[A + k], w[EA + k], w[BB + k], w[EB + k]
                s, es = two_sum(a, b)
                p = a * b
                ep = fma(a, b, -p) + (a * eb + b * ea)
                r = math.sqrt(p)
                w[A + k] = 0.5 * s
                w[EA + k] = 0.5 * (es + (ea + eb))
                w[BB + k] = r
                w[EB + k] = (fma(-r, r, p) + ep) / (2.0 * r)
        for k in range(B):
            # M = A (1 - x/4 - 5 x^2/64 + O(x^3)): the AGM's own series for a ~ b
            # (one step of (7), then M(1, 1 - e) = 1 - e/2 - e^2/16 - ...).
            a, ea, b, eb = w[A + k], w[EA + k], w[BB + k], w[EB + k]
            s, es = two_sum(a, b)
            t = ((a - b) + (ea - eb)) / s
            x = t * t
            mh, ml = two_sum(0.5 * s, -0.5 * s * (x * (0.25 + x * (5.0 / 64.0))))
            ml += 0.5 * (es + (ea + eb))
            # T = T0 / M: one division for 1/M, the quotient corrected by its residual.
            th, tl = w[TH + k], w[TL + k]
            inv = 1.0 / mh
            q = th * inv
            ph, pl = fast_two_sum(q, (fma(-q, mh, th) + (tl - q * ml)) * inv)
            # Round: th + tl +- ERROR_BOUND th must all round to the same double.
            err = ERROR_BOUND * ph
            ok = (ph + (pl + err) == ph) & (ph + (pl - err) == ph) & (ph > 1e-290) & (ph < 1e290)
            w[A + k] = ph
            w[EA + k] = pl
            w[OK + k] = 1.0 if ok else 0.0
        for k in range(m):
            out[start + k] = w[A + k]
            flags[start + k] = 0 if w[OK + k] == 1.0 else 1
        if lo.size == n:
            for k in range(m):
                lo[start + k] = w[EA + k]
