"""The period of the simple pendulum: small-angle, AGM (7)-(8), and to any number of digits.

The period of a pendulum of length ``l`` released at rest from amplitude
``alpha`` is ``T = 2 pi sqrt(l/g) / M(1, cos(alpha/2))`` with ``M`` the
arithmetic-geometric mean, equations (7)-(8) of the coursework.

References
----------
.. [1] C. G. Carvalhaes, P. Suppes, "Approximations for the period of the simple
   pendulum based on the arithmetic-geometric mean", Am. J. Phys. 76, 1150-1154 (2008).
.. [2] NIST DLMF 19.8.5: K(k) = pi / (2 M(1, sqrt(1 - k^2))).
"""
from __future__ import annotations

import math as _math
import numbers as _numbers
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any, SupportsFloat, TypeGuard, overload

from ..core import validate as _v
from ..core.cases import G_EXACT, G
from ..core.exact import Exact, arb_precision, below_pi
from ..core.interrupt import deferred
from ..engine.mean import FIXED, MAX_ITERATIONS, RTOL, agm
from .arrays import elementwise
from .results import Result

if TYPE_CHECKING:  # numpy loads only where arrays are handled
    import numpy as np
    from numpy.typing import ArrayLike, NDArray

__all__ = [
    "FIXED_ITERATIONS_ULPS",
    "agm_iterations",
    "agm_mean",
    "agm_period",
    "fixed_iterations_error",
    "fixed_iterations_limit",
    "nearest_period",
    "period_ball",
    "period_digits",
    "period_double",
    "periods",
    "small_angle_period",
]

# numpy and numba are imported only where arrays are handled: a scalar period (and
# ``pendulab period``) needs neither.

#: Arrays of at least this many elements run the AGM (7) compiled (``kernels.agm_means``),
#: shorter ones in the interpreter, element by element, which costs less than loading the
#: compiled kernel in a fresh process (numba's import, its threads: ``benchmarks/``). The
#: same loop (``pendulab.engine.mean.agm``) either way, so the same bits.
COMPILED_MIN = 10_000
#: How far (in ulps) the coursework's 7-iteration ``T^`` of (8), the loop (7) in double
#: precision, is at most from the correctly rounded period for every amplitude up to
#: :func:`fixed_iterations_limit`. Derived (``u = 2^-53``, relative errors to first order):
#: ``b0 = cos(alpha/2)`` within 1 ulp (libm), ``2u``; the AGM is homogeneous and
#: increasing in both arguments, so relative errors of ``a`` and ``b`` reach ``v`` with
#: weights summing to 1 and each step adds at most ``u`` to ``a`` (the sum) and ``1.5u``
#: to ``b`` (product ``u/2`` under the root, root ``u``): ``7 x 1.5u``; ``v = (a + b)/2``
#: ``u``; ``2 pi sqrt(l/g)`` ``0.35u + u/2 + u + u`` (``sqrt(l)/sqrt(g)`` where ``l/g``
#: over- or underflows: ``4.35u``); the quotient ``u``; the truncation at most ``u`` below
#: the limit. In all below ``19.85u T < 19.85`` ulps of ``T``, and the correctly rounded
#: period is within half an ulp of ``T``: at most 20 ulps. The largest found by an
#: adversarial search (``benchmarks/adversarial.py``, ``t_hat_search``; ``docs/accuracy.md``)
#: is well below it.
FIXED_ITERATIONS_ULPS = 20


#: Lengths and g in this range give ``2 pi sqrt(l/g)`` far inside the doubles, as the
#: checks (``validate.positive``, ``period_scale``) require; outside it they run first.
_SAFE_LO, _SAFE_HI = 1e-150, 1e150
_TWO_PI = 2 * _math.pi


def _scalar_period() -> Any:
    """:func:`pendulab.engine.agm.agm_period_dd`, imported on the first scalar period
    (numba loads then, not at ``import pendulab``)."""
    global _scalar_period_kernel
    if _scalar_period_kernel is None:
        from ..engine.agm import agm_period_dd

        with deferred():  # a signal while it compiles waits for its return (_interrupt)
            agm_period_dd(0.5, 1.0, 1.0)
        _scalar_period_kernel = agm_period_dd
    return _scalar_period_kernel


_scalar_period_kernel: Any = None


def _is_scalar(x: Any) -> TypeGuard[SupportsFloat]:
    if isinstance(x, _numbers.Real):
        return True
    import numpy as np

    return bool(np.ndim(x) == 0)


@overload
def small_angle_period(length: float | Exact, g: float | Exact = G) -> float: ...
@overload
def small_angle_period(length: ArrayLike, g: float | Exact = G) -> NDArray[np.float64]: ...
@elementwise(length=1.0)
def small_angle_period(length: float | Exact | ArrayLike, g: float | Exact = G) -> float | NDArray[np.float64]:
    """Small-angle period ``2 pi sqrt(l/g)`` (problem 1). Vectorised over ``length``.

    Parameters
    ----------
    length : float, Exact or array_like
        Pendulum length ``l`` > 0, m (an :class:`~pendulab.core.exact.Exact` is taken as its double).
    g : float or Exact
        Gravitational acceleration, m/s^2.

    Returns
    -------
    float or ndarray
        A float for a scalar ``length``, an array of its shape otherwise.
    """
    if _is_scalar(length):
        return _v.period_scale(_v.positive("length", length), _v.positive("g", g))
    import numpy as np

    lengths = np.asarray(length, dtype=float)
    if not np.all(np.isfinite(lengths) & (lengths > 0)):
        bad = lengths[~(np.isfinite(lengths) & (lengths > 0))][0]
        _v.positive("length", bad)
    g = _v.positive("g", g)
    if lengths.size:
        _v.positive("length", float(lengths.min()))  # no subnormal lengths
    for extreme in (lengths.min(initial=1.0), lengths.max(initial=1.0)):
        _v.period_scale(float(extreme), g)  # refuses an overflowing period by arithmetic
    with np.errstate(under="ignore", over="ignore"):  # r is only used when finite and normal
        r = lengths / g
    if np.all((r >= _v.TINY) & (r < np.inf)):
        return 2 * np.pi * np.sqrt(r)
    return 2 * np.pi * (np.sqrt(lengths) / _math.sqrt(g))


@overload
def agm_mean(b0: float | Exact, iterations: int | None = None) -> float: ...
@overload
def agm_mean(b0: ArrayLike, iterations: int | None = None) -> NDArray[np.float64]: ...
def agm_mean(b0: float | Exact | ArrayLike, iterations: int | None = None) -> float | NDArray[np.float64]:
    """The AGM value ``v`` of (7)-(8) started from ``(a0, b0) = (1, b0)``.

    Parameters
    ----------
    b0 : float, Exact or array_like, 0 < b0 <= 1
        ``cos(alpha/2)``.
    iterations : int, optional
        ``None`` iterates to convergence in double precision; ``7`` is the coursework's
        fixed count: ``v = (a7 + b7)/2``.

    Returns
    -------
    float or ndarray
        ``(a_n + b_n)/2`` after ``n`` iterations of (7).
    """
    if _is_scalar(b0):
        if iterations is None:
            return agm(float(b0), MAX_ITERATIONS, RTOL)[0]
        return agm(float(b0), iterations, FIXED)[0]
    return _means(b0, False, iterations)


def _count(iterations: int | None) -> tuple[int, float]:
    """``(iterations, rtol)`` of :func:`pendulab.engine.mean.agm`: to convergence for ``None``."""
    return (MAX_ITERATIONS, RTOL) if iterations is None else (iterations, FIXED)


def _means(x: Any, of_angle: bool, iterations: int | None) -> Any:
    """:func:`agm_mean` of each element of the array ``x``, or of ``cos(x/2)`` (the C
    library's ``cos``, as for one amplitude) where ``of_angle``: in the interpreter below
    :data:`COMPILED_MIN` elements, compiled from there."""
    import numpy as np

    x = np.asarray(x, dtype=float)
    n, rtol = _count(iterations)
    flat = np.ascontiguousarray(x).ravel()
    if flat.size < COMPILED_MIN:
        cos = _math.cos
        out = np.array([agm(cos(0.5 * v) if of_angle else v, n, rtol)[0] for v in flat.tolist()], dtype=float)
    else:
        from ..engine.kernels import agm_means

        with deferred():  # a signal while it compiles or runs waits for its return (_interrupt)
            out = agm_means(flat, of_angle, n, rtol)
    return out.reshape(x.shape)


def nearest_period(length: float, amplitude: float, g: float) -> float:
    """The double nearest to the true period (8) of the doubles ``length, amplitude, g``.

    ``2 pi sqrt(l)/sqrt(g) / M(1, cos(alpha/2))`` in mpmath at 128 bits; when both ends of
    ``t (1 -+ 2^(16 - prec))`` round to the same double, it is the answer, else the
    precision doubles (Ziv's strategy). mpmath's ``sqrt``, ``cos`` and ``agm`` err by a few
    units of the last of ``prec`` bits, so the margin of 2^16 such units covers them many
    times over. Independent of the compiled double-double kernel, which calls it where
    its own rounding test fails.
    """
    import mpmath
    from mpmath.libmp import to_float

    prec = 128
    while True:
        with mpmath.workprec(prec):
            m = mpmath.mpf
            t = 2 * mpmath.pi * mpmath.sqrt(m(length)) / (mpmath.sqrt(m(g)) * mpmath.agm(1, mpmath.cos(m(amplitude) / 2)))
            margin = mpmath.ldexp(t, 16 - prec)
            lo, hi = to_float((t - margin)._mpf_, rnd="n"), to_float((t + margin)._mpf_, rnd="n")
        if lo == hi:
            return lo
        prec *= 2  # pragma: no cover - a period within 2^-112 of a rounding boundary


@overload
def agm_period(length: float | Exact, amplitude: float | Exact, g: float | Exact = G, iterations: int | None = None) -> float: ...
@overload
def agm_period(length: ArrayLike, amplitude: ArrayLike, g: float | Exact = G,
               iterations: int | None = None) -> NDArray[np.float64]: ...
def agm_period(length: float | Exact | ArrayLike, amplitude: float | Exact | ArrayLike, g: float | Exact = G,
               iterations: int | None = None) -> float | NDArray[np.float64]:
    """The period by the arithmetic-geometric mean, equations (7)-(8).

    Parameters
    ----------
    length : float, Exact or array_like
        Pendulum length ``l`` > 0, m. An :class:`~pendulab.core.exact.Exact` is taken as its
        double (:func:`period_double` computes from the number as written).
    amplitude : float, Exact or array_like
        Release angle ``alpha`` in ``[0, pi)``, rad. Broadcast against ``length``.
    g : float or Exact
        Gravitational acceleration, m/s^2.
    iterations : int, optional
        ``None`` (default): the AGM to convergence, and the result is the double nearest
        to the true period of the given doubles (correctly rounded), for every amplitude
        in ``[0, pi)``. ``7``: the coursework's ``T^`` bit for bit (the loop (7) in
        double precision), equal to the period only while ``alpha`` is not too close to ``pi`` (see
        :func:`fixed_iterations_limit`).

    Returns
    -------
    float or ndarray
        ``T^ = 2 pi sqrt(l/g) / v`` (8): a float for scalar inputs, else an array of their
        broadcast shape.

    Notes
    -----
    ``b0 = cos(alpha/2)`` is computed as ``sin((pi - alpha)/2)`` near ``alpha = pi``: small
    but with full relative accuracy; the AGM is multiplicatively well conditioned, so no
    digits are lost there (unlike ``scipy.special.ellipk(sin(alpha/2)**2)``, whose
    argument ``m`` rounds to 1). ``sqrt(l)/sqrt(g)`` keeps periods such as
    ``agm_period(1e-300, 1, g=1e300)`` representable. Arrays run the compiled
    double-double kernel :func:`pendulab.engine.agm.agm_periods_dd` (one core), one
    pendulum its one-element form :func:`pendulab.engine.agm.agm_period_dd` (under a
    microsecond; floats inside the ranges where every check passes skip the checks); where
    the kernels' rounding test fails (a few amplitudes in 10^6), :func:`nearest_period`
    (mpmath) gives the double. The first scalar call in a process loads numba.
    """
    # One pendulum given as floats inside the ranges where every check passes (NaN fails
    # them): the kernel without the checks or numpy's conventions (a notebook's loop of
    # calls). Anything else takes both.
    if (type(length) is float and type(amplitude) is float and type(g) is float
            and 0.0 <= amplitude < _math.pi and _SAFE_LO <= length <= _SAFE_HI and _SAFE_LO <= g <= _SAFE_HI):
        if iterations is None:
            t = _scalar_period()(amplitude, length, g)
            if t > 0.0:
                return t
        elif type(iterations) is int and 0 <= iterations <= 1000:
            return _TWO_PI * _math.sqrt(length / g) / agm(_math.cos(0.5 * amplitude), iterations, FIXED)[0]
    return _agm_period(length, amplitude, g, iterations)


@elementwise(length=1.0, amplitude=0.0)
def _agm_period(length: Any, amplitude: Any, g: Any, iterations: int | None) -> Any:
    """:func:`agm_period` with its checks, numpy's conventions and the mpmath fallback."""
    if iterations is not None:
        iterations = _v.integer("iterations", iterations, 0, 1000)
    exact_array = iterations is None and not (_is_scalar(amplitude) and _is_scalar(length))
    # The compiled kernel checks an array of amplitudes itself (in the same pass).
    alpha: Any = amplitude if exact_array else _v.amplitudes("amplitude", amplitude)
    scalar = not exact_array and _is_scalar(alpha) and _is_scalar(length)
    if scalar and iterations is not None:
        return small_angle_period(length, g) / agm(_math.cos(0.5 * alpha), iterations, FIXED)[0]
    if scalar:
        small_angle_period(length, g)  # refuses a length or g whose period overflows
        lf, gf = _v.positive("length", length), float(g)
        if _SAFE_LO <= lf <= _SAFE_HI and _SAFE_LO <= gf <= _SAFE_HI:
            t = _scalar_period()(alpha, lf, gf)
            if t > 0.0:
                return t
        return nearest_period(lf, alpha, gf)  # the rounding test failed: a few in 10^6
    import numpy as np

    t0 = small_angle_period(length, g)  # checks the lengths and g
    if iterations is not None:
        return t0 / _means(alpha, True, iterations)
    from ..engine.agm import agm_periods_dd

    g = float(g)
    alpha, lengths = np.asarray(alpha, dtype=float), np.asarray(length, dtype=float)
    shape = np.broadcast_shapes(alpha.shape, lengths.shape)
    flat_a = np.ascontiguousarray(np.broadcast_to(alpha, shape)).ravel()
    # One length for all: the kernel computes 2 pi sqrt(l/g) once.
    flat_l = lengths.reshape(1) if lengths.size == 1 else np.ascontiguousarray(np.broadcast_to(lengths, shape)).ravel()
    out = np.empty(flat_a.size)
    hard = np.empty(flat_a.size, np.int64)  # pages only touched where written
    with deferred():  # a signal while it compiles or runs waits for its return (_interrupt)
        count, bad = agm_periods_dd(flat_a, flat_l, g, out, out[:0], hard)
    if bad >= 0:
        _v.amplitude("amplitude", float(flat_a[bad]))  # raises
    for i in hard[:count]:  # the rounding test failed: a few in 10^6
        out[i] = nearest_period(float(flat_l[i if flat_l.size > 1 else 0]), float(flat_a[i]), g)
    return out.reshape(shape)


def agm_iterations(amplitude: float) -> int:
    """How many iterations of (7) double precision needs at ``amplitude`` (to convergence)."""
    return agm(_math.cos(0.5 * _v.amplitude("amplitude", amplitude)), MAX_ITERATIONS, RTOL)[1]


def _exact_inputs(length: Any, amplitude: Any, g: Any) -> tuple[Exact, Exact, Exact]:
    """The three inputs as exact numbers, range-checked on their exact values.

    A string is parsed as written (``"4pi/5"`` with the true pi), a float is its exact
    binary value. The amplitude must satisfy ``0 <= alpha < pi`` exactly: the check runs
    on the rational coefficient (or a certified comparison with pi), never on a rounded
    value, so ``"0.9999999999999999999999999pi"`` is accepted at any precision.
    """
    from ..core.errors import InputError
    from ..core.inputs import parse_angle, parse_number

    def exact(name, x, parser):
        if isinstance(x, Exact):
            return x
        if isinstance(x, str):
            return parser(name, x)
        return Exact.of(_v.finite(name, x))

    l_ = exact("length", length, parse_number)
    a_ = exact("amplitude", amplitude, parse_angle)
    g_ = exact("g", g, parse_number)
    for name, x in (("length", l_), ("g", g_)):
        if not x.coef > 0:
            raise InputError(name, x.text or float(x), "a finite number > 0")
    if not (a_.coef >= 0 and below_pi(a_)):
        raise InputError("amplitude", a_.text or repr(float(a_)), "an angle in [0, pi) rad")
    return l_, a_, g_


def _arb_of(x: Exact):
    from flint import arb, fmpq

    value = arb(fmpq(x.coef.numerator, x.coef.denominator))
    return value * arb.pi() ** x.pi_power if x.pi_power else value


def period_ball(length: Any, amplitude: Any, g: Any = G_EXACT, prec: int = 128):
    """The period as an Arb ball (``flint.arb``) that contains the true period of the inputs.

    ``T = 2 pi sqrt(l/g) / M(1, cos(alpha/2))`` (8) in ball arithmetic ([3]_): every
    operation returns an interval guaranteed to contain the exact result, so the ball
    proves the digits it determines. ``cos(alpha/2)`` of ``alpha = c pi`` is computed as
    ``sin(pi (1 - c)/2)`` from the exact rational ``1 - c``, so an amplitude within
    ``1e-25`` of pi costs no extra precision.

    Parameters
    ----------
    length, amplitude, g
        Taken exactly: a string as written (``"4pi/5"`` with the true pi), a float as its
        binary value, an :class:`~pendulab.core.exact.Exact` as it is.
    prec : int
        Working precision in bits.

    References
    ----------
    .. [3] F. Johansson, "Arb: efficient arbitrary-precision midpoint-radius interval
       arithmetic", IEEE Trans. Computers 66 (2017) 1281-1292.
    """
    from flint import arb, fmpq

    l_, a_, g_ = _exact_inputs(length, amplitude, g)
    prec = _v.integer("prec", prec, 16, 1 << 26)
    with arb_precision(prec):
        if a_.pi_power == 1:
            c = (1 - a_.coef) / 2
            b0 = arb.sin_pi_fmpq(fmpq(c.numerator, c.denominator))
        else:
            b0 = (_arb_of(a_) / 2).cos()
        t0 = 2 * arb.pi() * (_arb_of(l_) / _arb_of(g_)).sqrt()
        return t0 / arb(1).agm(b0)


def _round_significant(x: Fraction, digits: int) -> tuple[int, int]:
    """``x > 0`` rounded to ``digits`` significant decimal digits (half even), exactly:
    ``(n, e)`` with ``10^(digits-1) <= n < 10^digits`` and the value ``n 10^e``."""
    e = (x.numerator.bit_length() - x.denominator.bit_length()) * 30103 // 100000 - digits
    while True:
        n = round(x / Fraction(10) ** e)  # Fraction rounding is exact, half to even
        if n >= 10**digits:
            e += 1
        elif n < 10 ** (digits - 1):
            e -= 1
        else:
            return n, e


def _int_text(n: int) -> str:
    """``str(n)`` for an ``n >= 0`` of any length: ``str`` refuses integers of more than
    ``sys.get_int_max_str_digits()`` digits (4300 by default), so longer ones go in blocks."""
    block = 10**1000
    if n < block:
        return str(n)
    parts = []
    while n >= block:
        n, low = divmod(n, block)
        parts.append(f"{low:01000d}")
    return str(n) + "".join(reversed(parts))


def _decimal_text(n: int, e: int, digits: int) -> str:
    """The decimal ``n 10^e`` (``n`` of ``digits`` digits) as text, in the layout of
    ``mpmath.nstr(x, digits, strip_zeros=False)``: fixed point while the leading digit's
    exponent ``p`` satisfies ``min(-(digits // 3), -5) < p < digits``, else ``d.ddde+pp``."""
    text, p = _int_text(n), e + digits - 1
    if not min(-(digits // 3), -5) < p < digits:
        return f"{text[0]}.{text[1:]}e{p:+}"
    if p < 0:
        return f"0.{'0' * (-p - 1)}{text}"
    return f"{text[:p + 1]}.{text[p + 1:]}"


def _arb_fraction(x) -> Fraction:
    """The exact value of an exact ``arb`` (a ball's midpoint or radius), as a fraction."""
    man, exp = (int(p) for p in x.man_exp())
    return Fraction(man) * Fraction(2) ** exp


def period_digits(length: float | str | Exact, amplitude: float | str | Exact, g: float | str | Exact = G_EXACT,
                  digits: int = 30) -> str:
    """The period to ``digits`` significant digits, correctly rounded, proved by ball arithmetic.

    The period of the inputs as written is enclosed in an Arb ball (:func:`period_ball`);
    when both ends of the ball round to the same ``digits``-digit decimal, every real
    number in it, the true period included, rounds to that decimal: it is the correctly
    rounded period, and every digit printed is proved. Otherwise the precision is doubled.
    """
    from ..core.errors import NumericalError

    digits = _v.integer("digits", digits, 1, 100000)
    _exact_inputs(length, amplitude, g)
    prec = int(digits * 3.33) + 64
    while prec <= 1 << 24:
        ball = period_ball(length, amplitude, g, prec)
        if ball.is_finite() and ball > 0:
            mid, rad = _arb_fraction(ball.mid()), _arb_fraction(ball.rad())  # both exact
            lo = _round_significant(mid - rad, digits)
            hi = _round_significant(mid + rad, digits)
            if lo == hi:
                return _decimal_text(*lo, digits)
        prec *= 2
    raise NumericalError(f"the period could not be enclosed to {digits} digits within 2^24 bits")


def period_double(length: float | str | Exact, amplitude: float | str | Exact,
                  g: float | str | Exact = G_EXACT) -> float:
    """The double nearest to the true period of the inputs as written (correctly rounded).

    Unlike :func:`agm_period`, which takes doubles, the inputs are exact (see
    :func:`period_ball`): ``"0.9999999999999999999999999pi"`` has a period although its
    double is pi. The ball is narrowed until both its ends round to the same double
    (``float`` of a fraction rounds correctly, half to even).
    """
    from ..core.errors import NumericalError

    _exact_inputs(length, amplitude, g)
    prec = 128
    while prec <= 1 << 16:
        ball = period_ball(length, amplitude, g, prec)
        if ball.is_finite() and ball > 0:
            mid, rad = _arb_fraction(ball.mid()), _arb_fraction(ball.rad())
            try:
                lo, hi = float(mid - rad), float(mid + rad)
            except OverflowError:
                raise NumericalError("the period is beyond the largest double") from None
            if lo == hi:
                return lo
        prec *= 2
    raise NumericalError("the period could not be rounded to a double within 2^16 bits")  # pragma: no cover


def fixed_iterations_error(amplitude: Any, iterations: int = 7, guard: int = 30):
    """Relative truncation error ``v_n / M - 1`` of ``n`` iterations of (7), as an ``mpmath.mpf``.

    The error is evaluated by running (7) in mpmath, at a working precision chosen from
    the size of the error so that it is resolved to ``guard`` digits: with ``q`` the nome
    of ``k = sin(alpha/2)``, ``a_n = M theta_3(q^(2^n))^2`` (Jacobi's theta functions,
    DLMF 20.2 and 22.2; Borwein & Borwein, *Pi and the AGM*, ch. 2), so
    ``v_n / M - 1 = theta_3(q^(2^(n+1)))^2 - 1 ~ 4 q^(2^(n+1))``: after 7 iterations
    about 1e-513 at ``alpha = pi/4`` and 1e-216 at ``4 pi/5``.

    Parameters
    ----------
    amplitude : float, str, Exact or mpmath.mpf
        ``alpha`` in ``[0, pi)``; a string (``"4pi/5"``) or an :class:`~pendulab.core.exact.Exact`
        is taken exactly, a float is its binary value, an ``mpf`` as given.
    iterations : int
        ``n``.
    guard : int
        Correct digits wanted in the error itself.
    """
    import mpmath

    n = _v.integer("iterations", iterations, 0, 1000)

    def angle(dps: int):
        if isinstance(amplitude, mpmath.mpf):
            return amplitude
        if isinstance(amplitude, str):
            from ..core.inputs import parse_angle

            return parse_angle("amplitude", amplitude).mpf(dps)
        return Exact.of(amplitude).mpf(dps)

    with mpmath.workdps(guard + 20):
        k_prime = mpmath.cos(angle(guard + 20) / 2)
        m = 1 - k_prime**2
        if not 0 <= m <= 1:
            _v.amplitude("amplitude", float(angle(20)))
        if m == 0:
            return mpmath.mpf(0)  # b0 = 1: the AGM is 1 from the start
        q = mpmath.qfrom(m=m)
        log_size = mpmath.log10(4) + 2 ** (n + 1) * mpmath.log10(q) if q < 1 else mpmath.mpf(0)
    dps = guard + 10 + max(0, int(-log_size))
    with mpmath.workdps(dps):
        b0 = mpmath.cos(angle(dps) / 2)
        a, b = mpmath.mpf(1), b0
        for _ in range(n):
            a, b = (a + b) / 2, mpmath.sqrt(a * b)
        return (a + b) / 2 / mpmath.agm(1, b0) - 1


def fixed_iterations_limit(iterations: int = 7, rtol: float = 2.0**-53) -> float:
    """The largest amplitude at which the truncation error of ``iterations`` steps of (7) is at most ``rtol``.

    Returns the amplitude (rad) below which the relative truncation error of (8) after
    ``iterations`` steps, computed exactly in mpmath (:func:`fixed_iterations_error`), is
    at most ``rtol`` (default: half an ulp, 1.1e-16). Found by bisection on
    ``log(pi - alpha)``; the truncation error grows monotonically with ``alpha``.

    This bounds the truncation alone. It does not make the double-precision ``T^`` the
    same double as the converged AGM: both loops round, and a truncation error ``d``
    below half an ulp still moves the result across a rounding boundary for a fraction of
    about ``d/ulp`` of the amplitudes (measured by ``benchmarks/accuracy_claims.py``).
    """
    import mpmath

    lo, hi = -60.0, 1.0  # log(pi - alpha): hi is alpha = pi - e, error small
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        alpha = mpmath.pi - mpmath.e**mid
        if abs(fixed_iterations_error(alpha, iterations)) > rtol:
            lo = mid
        else:
            hi = mid
    return float(mpmath.pi - mpmath.e**hi)


@dataclass(frozen=True, eq=False)
class Periods(Result):
    """The periods of one pendulum, each under its glossary name (``pendulab period --json``).

    Attributes
    ----------
    length, amplitude, g : float
        The inputs' doubles.
    amplitude_text : str
        The amplitude as written (``4pi/5``, ``0.9999999999999999999999999pi``).
    iterations : int or None
        The fixed AGM iterations asked for (``period_iterated``).
    period : float or None
        (8) to convergence on the doubles, correctly rounded (:func:`agm_period`); ``None``
        where the amplitude is below pi but its double is not (see
        :attr:`amplitude_double_below_pi`).
    period_as_written : float
        The double nearest to the true period of the inputs as written (:func:`period_double`).
    small_angle_period : float
        ``2 pi sqrt(l/g)`` of the doubles.
    period_iterated : float or None
        (8) after ``iterations`` iterations on the doubles (7: the coursework's ``T^``);
        ``None`` without ``iterations`` or where ``period`` is ``None``.
    period_digits : str or None
        The period of the inputs as written to the ``digits`` asked for, every digit proved
        (:func:`period_digits`); ``None`` where no digits were asked for.
    small_angle_period_digits : str or None
        ``2 pi sqrt(l/g)`` of the inputs as written to the same digits, every digit proved.
    """

    length: float
    amplitude: float
    g: float
    amplitude_text: str
    iterations: int | None
    period: float | None
    period_as_written: float
    small_angle_period: float
    period_iterated: float | None
    period_digits: str | None
    small_angle_period_digits: str | None

    @property
    def amplitude_double_below_pi(self) -> bool:
        """Whether the amplitude's double is below pi, so that (8) on doubles has a value."""
        return self.period is not None


def periods(length: float | str | Exact, amplitude: float | str | Exact, g: float | str | Exact = G_EXACT,
            iterations: int | None = None, digits: int | None = None) -> Periods:
    """Every period of one pendulum (:class:`Periods`): converged, as written, small-angle,
    after ``iterations`` iterations, and to ``digits`` proved digits."""
    l_, a_, g_ = _exact_inputs(length, amplitude, g)
    lf, af, gf = float(l_), float(a_), float(g_)
    on_doubles = af < _math.pi  # below pi as written, its double may be pi
    return Periods(
        length=lf,
        amplitude=af,
        g=gf,
        amplitude_text=str(a_),
        iterations=iterations,
        # agm_period's value (the double nearest to the period of the doubles), by Arb as the
        # others: no mpmath to load for one pendulum (the command line, the page).
        period=period_double(lf, af, gf) if on_doubles else None,
        period_as_written=period_double(l_, a_, g_),
        small_angle_period=small_angle_period(lf, gf),
        period_iterated=(agm_period(lf, af, gf, iterations=iterations)
                         if on_doubles and iterations is not None else None),
        period_digits=None if digits is None else period_digits(l_, a_, g_, digits),
        small_angle_period_digits=None if digits is None else period_digits(l_, Exact.of(0), g_, digits),
    )
