"""Adversarial searches for the worst case of every error bound pendulab states.

Each search looks for the input that uses the largest share of its bound on purpose:
it starts where the error sources line up (zero crossings, where ``theta`` moves
fastest; amplitudes near pi and near 0; times of millions of periods; values just below
powers of ten and on rounding ties), then climbs: it perturbs the worst inputs found so
far by a few ulps up to a relative 1e-3 and keeps a perturbation that raises the ratio
of error to bound (random restarts plus local hill climbing). References are independent
of the code under test: mpmath at 60 to 80 digits from the inputs' exact doubles,
exact rationals (``fractions.Fraction``).

Each ``*_search(budget, seed)`` returns a dict: ``claim`` (the bound in words), ``worst``
(the largest ratio error/bound found, or the largest error in the claim's unit),
``where`` (the input that reached it), ``evaluations``. ``benchmarks/accuracy_claims.py``
runs them all and writes the table of ``docs/accuracy.md``; ``tests/test_bounds_adversarial.py``
runs them with small budgets.

Run one: ``.venv/bin/python benchmarks/adversarial.py [motion|launched|t_hat|digits|dense|...] [budget]``.
"""
from __future__ import annotations

import math
import random
import sys
from decimal import Decimal
from fractions import Fraction

import mpmath
import numpy as np

G = 9.80665
EPS = 2.0**-52


# ---------------------------------------------------------------------------- helpers
def nudge(x: float, rng: random.Random, lo: float = -math.inf, hi: float = math.inf, widest: float = -3) -> float:
    """``x`` moved by a few ulps or by a relative 1e-12 .. ``10^widest`` (half the time each), kept in ``[lo, hi]``."""
    if rng.random() < 0.5:
        y = x
        for _ in range(rng.randint(1, 8)):
            y = math.nextafter(y, math.inf if rng.random() < 0.5 else -math.inf)
    else:
        y = x * (1 + rng.choice((-1, 1)) * 10 ** rng.uniform(-12, widest))
    return min(max(y, lo), hi)


def climb(evaluate, starts: list[tuple], perturb, steps: int, rng: random.Random):
    """Hill climbing on ``evaluate(x) -> ratio`` from the best of ``starts``: returns ``(ratio, x, n)``.

    The best few starts each get ``steps // 4`` perturbations; a perturbation is kept
    when it raises the ratio (ties too, so that plateaus are crossed).
    """
    scored = sorted(((evaluate(x), x) for x in starts), key=lambda p: -p[0])
    n = len(starts)
    best = scored[0]
    for ratio, x in scored[:4]:
        for _ in range(max(1, steps // 4)):
            y = perturb(x, rng)
            r = evaluate(y)
            n += 1
            if r >= ratio:
                ratio, x = r, y
        if ratio > best[0]:
            best = (ratio, x)
    return best[0], best[1], n


# ---------------------------------------------------------------------------- exact motion
def motion_reference(length: float, alpha: float, g: float, t: float, dps: int = 60) -> tuple[float, float]:
    """``theta, theta'`` from mpmath: ``sin(theta/2) = k sn(K - omega0 t | k^2)``, ``theta' = -2 k omega0 cn``.

    Everything from the exact doubles: ``K`` by ``mpmath.ellipk`` of ``m = sin^2(alpha/2)``,
    ``u`` reduced modulo ``4K`` before ``mpmath.ellipfun``. ``dps`` grows with
    ``omega0 t`` so the reduction keeps 40 digits.
    """
    with mpmath.workdps(dps + int(math.log10(1 + abs(t) * math.sqrt(g / length)))):
        a = mpmath.mpf(alpha)
        k = mpmath.sin(a / 2)
        m = k * k
        w = mpmath.sqrt(mpmath.mpf(g) / mpmath.mpf(length))
        big_k = mpmath.ellipk(m)
        u = big_k - w * mpmath.mpf(t)
        u -= 4 * big_k * mpmath.floor((u + 2 * big_k) / (4 * big_k))
        sn, cn, dn = (mpmath.ellipfun(f, u, m=m) for f in ("sn", "cn", "dn"))
        return float(2 * mpmath.atan2(k * sn, dn)), float(-2 * k * w * cn)


def motion_ratio(x: tuple[float, float, float, float]) -> float:
    """The larger of ``|theta error| / bound`` and ``|theta' error| / bound'`` at ``x = (l, g, alpha, t)``."""
    from pendulab.numerics.motion import exact_motion, exact_motion_error_bound

    length, g, alpha, t = x
    ex = exact_motion(length, alpha, [t], g)
    bt, bo = exact_motion_error_bound(length, alpha, [t], g)
    theta, omega = motion_reference(length, alpha, g, t)
    return max(abs(ex.theta[0] - theta) / bt[0], abs(ex.omega[0] - omega) / bo[0])


def motion_starts(rng: random.Random, n: int) -> list[tuple[float, float, float, float]]:
    """Where the error sources line up: amplitudes near pi and 0, times at zero crossings
    (a quarter and three quarters of a period, where ``|d theta/du| = 2k`` is largest) and
    turning points, after up to 10^10 periods (a fifth before 0), lengths and g over decades."""
    from pendulab.numerics.period import agm_period

    near_pi = [math.pi - 10.0**-e for e in range(1, 16)] + [math.nextafter(math.pi, 0)]
    starts = [(7.456720155578, 30.186002204269425, 3.1409621881538863, 188157.06928849473)]  # a known hard case
    for _ in range(n):
        alpha = rng.choice([rng.choice(near_pi), rng.uniform(0, math.pi), 10 ** rng.uniform(-8, 0)])
        alpha = min(alpha, math.nextafter(math.pi, 0))
        length = 10 ** rng.uniform(-3, 3)
        g = rng.choice([G, 10 ** rng.uniform(-1, 3)])
        period = float(agm_period(length, alpha, g))
        cycles = rng.choice([0, rng.randrange(1, 10), 10 ** rng.uniform(1, 10)])
        phase = rng.choice([0.25, 0.75, 0.0, 0.5, rng.random()])
        sign = -1 if rng.random() < 0.2 else 1  # the motion is even in t: negative times too
        starts.append((length, g, alpha, sign * (math.floor(cycles) + phase) * period))
    return starts


def motion_perturb(x, rng: random.Random):
    length, g, alpha, t = x
    i = rng.randrange(4)
    if i == 0:
        length = nudge(length, rng, 1e-300)
    elif i == 1:
        g = nudge(g, rng, 1e-300)
    elif i == 2:
        alpha = nudge(alpha, rng, 0.0, math.nextafter(math.pi, 0))
    else:
        t = nudge(t, rng)
    return length, g, alpha, t


def motion_search(budget: int = 400, seed: int = 1) -> dict:
    rng = random.Random(seed)
    ratio, where, n = climb(motion_ratio, motion_starts(rng, budget // 2), motion_perturb, budget // 2, rng)
    return {"claim": "exact_motion within exact_motion_error_bound (theta and theta')",
            "worst": ratio, "unit": "of the bound", "where": "l, g, alpha, t = " + ", ".join(map(repr, where)),
            "evaluations": n}


# ---------------------------------------------------------------------------- launched motion
def launched_reference(length: float, alpha: float, omega0: float, t: float, g: float = G,
                       dps: int = 50) -> tuple[float, float]:
    """``theta, theta'`` of the launch from mpmath: ``m' = cos^2(alpha/2) - omega0^2/(4 w^2)`` at
    ``dps`` digits beyond those it loses to cancellation; libration by ``mpmath.ellipfun`` of
    ``m = 1 - m'`` at ``u = w t + F(phi0 | m)`` reduced modulo ``4K`` (DLMF 22.19.2); circulation by
    ``am(u | 1/k^2)`` as ``2K j + atan2(sn, cn)`` of ``u`` reduced modulo ``2K`` (DLMF 22.19.3, 22.16.1)."""
    with mpmath.workdps(40):
        w = mpmath.sqrt(mpmath.mpf(g) / length)
        r, c = mpmath.mpf(omega0) / (2 * w), mpmath.cos(mpmath.mpf(alpha) / 2)
        mp = c * c - r * r
        lost = 40 if mp == 0 else max(0, int(-mpmath.log10(abs(mp) / (c * c + r * r))))
    with mpmath.workdps(dps + lost + int(math.log10(2 + abs(t)))):
        mpf = mpmath.mpf
        w = mpmath.sqrt(mpf(g) / mpf(length))
        r, al, t = mpf(omega0) / (2 * w), mpf(alpha), mpf(t)
        mp = mpmath.cos(al / 2) ** 2 - r * r
        if mp > 0:
            turns = mpmath.floor((al + mpmath.pi) / (2 * mpmath.pi))
            a = al - 2 * mpmath.pi * turns
            m = 1 - mp
            k, big_k = mpmath.sqrt(m), mpmath.ellipk(m)
            u = w * t + mpmath.ellipf(mpmath.atan2(mpmath.sin(a / 2), r), m)
            u -= 4 * big_k * mpmath.floor((u + 2 * big_k) / (4 * big_k))
            sn, cn, dn = (mpmath.ellipfun(f, u, m=m) for f in ("sn", "cn", "dn"))
            return float(2 * mpmath.pi * turns + 2 * mpmath.atan2(k * sn, dn)), float(2 * k * w * cn)
        k = mpmath.sqrt(1 - mp)
        m, s = 1 / (k * k), 1 if omega0 > 0 else -1
        big_k = mpmath.ellipk(m)
        u = s * k * w * t + mpmath.ellipf(al / 2, m)
        j = mpmath.floor((u + big_k) / (2 * big_k))
        ur = u - 2 * big_k * j
        sn, cn, dn = (mpmath.ellipfun(f, ur, m=m) for f in ("sn", "cn", "dn"))
        return float(2 * mpmath.pi * j + 2 * mpmath.atan2(sn, cn)), float(2 * s * k * w * dn)


def launched_ratio(x: tuple[float, float, float, float, float]) -> float:
    """The larger of ``|theta error| / bound`` and ``|theta' error| / bound'`` at ``x = (l, g, alpha, omega0, t)``."""
    from pendulab.numerics.launched import launched_motion, launched_motion_error_bound

    length, g, alpha, omega0, t = x
    theta, omega = launched_motion(length, alpha, omega0, [t], g)
    bt, bo = launched_motion_error_bound(length, alpha, omega0, [t], g)
    ref_theta, ref_omega = launched_reference(length, alpha, omega0, t, g)
    return max(abs(theta[0] - ref_theta) / bt[0], abs(omega[0] - ref_omega) / bo[0])


def separatrix_launch(length: float, alpha: float, g: float, delta: float, sign: float) -> float:
    """The double ``omega0`` nearest to the launch from ``alpha`` with ``k^2 = 1 - delta``
    (``k = 1 - delta/2``: above the separatrix for ``delta < 0``), ``omega0 = 2 w sqrt(cos^2(alpha/2) - delta)``;
    above it where ``cos^2(alpha/2) <= delta``."""
    with mpmath.workdps(60):
        w = mpmath.sqrt(mpmath.mpf(g) / mpmath.mpf(length))
        c2 = mpmath.cos(mpmath.mpf(alpha) / 2) ** 2
        return sign * float(2 * w * mpmath.sqrt(c2 - delta if c2 > delta else c2 + abs(delta)))


def launched_starts(rng: random.Random, n: int) -> list[tuple[float, float, float, float, float]]:
    """Launches with ``k`` within 1e-15 .. 1e-3 of 1 from both sides, releases at rest from within
    1e-1 .. 0 of pi (down to the last doubles below it), any launch; times at zero crossings and
    turning points after up to 10^4 periods, forwards and backwards; lengths and g over decades."""
    from pendulab.numerics.launched import launch

    near_pi = [math.pi - 10.0**-e for e in range(1, 16)] + [math.nextafter(math.pi, 0), math.pi]
    starts = [(0.537, G, 2.731, 1.7423259334447145, 6.952431466495199)]  # issue 32: k = 1 - 1e-12 at P/2
    for i in range(n):
        length, g = 10 ** rng.uniform(-2, 2), rng.choice([G, 10 ** rng.uniform(-1, 2)])
        kind = i % 3
        if kind == 0:  # near the separatrix, either side
            alpha = rng.choice([rng.uniform(0, math.pi), math.pi - 10 ** rng.uniform(-8, 0), 0.0])
            delta = rng.choice((-1, 1)) * 10 ** rng.uniform(-15, -3)
            omega0 = separatrix_launch(length, alpha, g, delta, rng.choice((-1.0, 1.0)))
        elif kind == 1:  # at rest near pi
            alpha, omega0 = rng.choice(near_pi), 0.0
        else:
            alpha = rng.uniform(-10, 10)
            omega0 = rng.choice((-1, 1)) * 10 ** rng.uniform(-2, 1.5) * math.sqrt(g / length)
        period = launch(length, alpha, omega0, g).period
        if not math.isfinite(period):
            period = 40 / math.sqrt(g / length)
        cycles = rng.choice([0, rng.randrange(1, 10), 10 ** rng.uniform(1, 4)])
        phase = rng.choice([0.25, 0.75, 0.0, 0.5, rng.random()])
        sign = -1 if rng.random() < 0.2 else 1
        starts.append((length, g, alpha, omega0, sign * (math.floor(cycles) + phase) * period))
    return starts


def launched_perturb(x, rng: random.Random):
    x = list(x)
    i = rng.randrange(5)
    x[i] = nudge(x[i], rng, 1e-300) if i < 2 else nudge(x[i], rng)
    return tuple(x)


def launched_search(budget: int = 400, seed: int = 1) -> dict:
    rng = random.Random(seed)
    ratio, where, n = climb(launched_ratio, launched_starts(rng, budget // 2), launched_perturb, budget // 2, rng)
    return {"claim": "launched_motion within launched_motion_error_bound (theta and theta')",
            "worst": ratio, "unit": "of the bound",
            "where": "l, g, alpha, omega0, t = " + ", ".join(map(repr, where)), "evaluations": n}


# ---------------------------------------------------------------------------- T^ (7 iterations)
def correctly_rounded_periods(length: float, alphas: np.ndarray, g: float = G) -> np.ndarray:
    """The double nearest to ``4 sqrt(l/g) K(m)``, ``1 - m = cos^2(alpha/2)``, by mpmath's
    elliptic K (rounded once): independent of the AGM code.

    ``m`` is held to 40 digits beyond ``1 - m`` (which is 2e-32 at the last double below
    pi): at a fixed 40 digits ``1 - m`` would keep 9 digits there and ``K`` be 6e4 ulps off.
    """
    out = np.empty(len(alphas))
    for i, a in enumerate(alphas):
        gap = max(math.pi - float(a), 1e-17)
        with mpmath.workdps(40 + int(-2 * math.log10(gap)) if gap < 1 else 40):
            kp = mpmath.cos(mpmath.mpf(float(a)) / 2)
            scale = 4 * mpmath.sqrt(mpmath.mpf(length) / mpmath.mpf(g))
            out[i] = float(scale * mpmath.ellipk(1 - kp * kp))
    return out


def t_hat_ulps(length: float, alphas: np.ndarray, g: float = G) -> np.ndarray:
    """``|T^ - T|`` in ulps of ``T``: ``T^`` the coursework's 7 iterations (array kernel and
    scalar loop, the larger), ``T`` correctly rounded."""
    from pendulab.numerics.period import agm_period

    alphas = np.asarray(alphas, dtype=float)
    ref = correctly_rounded_periods(length, alphas, g)
    arr = np.asarray(agm_period(length, alphas, g, iterations=7))
    one = np.array([agm_period(length, float(a), g, iterations=7) for a in alphas])
    ulp = np.array([math.ulp(r) for r in ref])
    return np.maximum(np.abs(arr - ref), np.abs(one - ref)) / ulp


def t_hat_search(budget: int = 200_000, seed: int = 1) -> dict:
    """The largest ``|T^ - T|`` in ulps of ``T`` for ``alpha <= fixed_iterations_limit()``.

    A relative error counts most in ulps where the mantissa of ``T`` is near 2, so half of
    the lengths put ``T`` just below a power of two (the other half: 1 m, 3.5 m and random).
    Amplitudes: log-uniform in ``pi - alpha`` from the limit to 1 and uniform. Screening
    with the compiled kernels (``agm_period`` of arrays: ``T^`` and the correctly rounded
    period) over ``budget`` pendulums; the worst 20 and their neighbouring doubles
    (``alpha`` within 64 ulps) are then measured against mpmath's elliptic K, scalar loop included.
    """
    from pendulab.numerics.period import agm_period, fixed_iterations_limit

    rng = np.random.default_rng(seed)
    limit = fixed_iterations_limit()
    gap = math.pi - limit
    n = budget
    alphas = np.where(rng.random(n) < 0.75, math.pi - np.exp(rng.uniform(math.log(gap), 0.0, n)),
                      rng.uniform(0, limit, n))
    alphas = np.minimum(alphas, limit)
    t1 = np.asarray(agm_period(1.0, alphas))
    target = 2.0 ** rng.integers(-1, 5, n) * (1 - 10 ** rng.uniform(-12, -2, n))  # just below 2^e
    lengths = np.where(np.arange(n) % 2 == 0, (target / t1) ** 2,
                       rng.choice([1.0, 3.5, 2.0800838231], n) * np.where(rng.random(n) < 0.5, 1.0, 10 ** rng.uniform(-2, 2, n)))
    t_hat = np.asarray(agm_period(lengths, alphas, iterations=7))
    tc = np.asarray(agm_period(lengths, alphas))
    d = np.abs(t_hat - tc) / np.array([math.ulp(x) for x in tc])
    worst, where, count = 0.0, None, n
    for i in np.argsort(-d)[:20]:
        length, alpha = float(lengths[i]), float(alphas[i])
        nbrs = [alpha] + [alpha + k * math.ulp(alpha) for k in (-64, -8, -3, -2, -1, 1, 2, 3, 8, 64)]
        nbrs = np.array([a for a in nbrs if a <= limit])
        ulps = t_hat_ulps(length, nbrs)
        count += len(nbrs)
        j = int(np.argmax(ulps))
        if ulps[j] > worst:
            worst, where = float(ulps[j]), (length, float(nbrs[j]))
    return {"claim": "T^ (7 iterations) from the correctly rounded period, alpha <= fixed_iterations_limit()",
            "worst": worst, "unit": "ulp", "where": f"l = {where[0]!r}, alpha = {where[1]!r}", "evaluations": count}


def t_hat_near_pi() -> list[tuple[str, float]]:
    """``|T^ - T|`` in ulps at ``l = 1`` and ``3.5`` beyond the limit: ``pi - 1e-13 .. pi - 1e-15``
    and the last double below pi (mpmath references)."""
    alphas = [math.pi - 1e-13, math.pi - 1e-14, math.pi - 1e-15, math.nextafter(math.pi, 0)]
    rows = []
    for length in (1.0, 3.5):
        for a, u in zip(alphas, t_hat_ulps(length, np.array(alphas))):
            where = "the last double below pi" if a == alphas[-1] else f"pi - {math.pi - a:.2g}"
            rows.append((f"l = {length:g}, alpha = {where}", float(u)))
    return rows


# ---------------------------------------------------------------------------- significant digits
def digits_rule(value: float, error: float, max_digits: int = 15) -> int:
    """The rule on exact decimals, written independently: the largest ``n <= max_digits`` with
    ``|error| <= 0.5 10^(k - n + 1)``, ``10^k <= |value| < 10^(k+1)``, by string and ``Decimal``
    arithmetic on the exact value of each double."""
    if value == 0 or not math.isfinite(error):
        return 0
    if error <= 0:
        return max_digits
    v = Fraction(abs(value))
    k = len(str(int(v))) - 1 if v >= 1 else -len(str(int(1 / v)))  # a first guess ...
    while Fraction(10) ** k > v:  # ... made exact
        k -= 1
    while Fraction(10) ** (k + 1) <= v:
        k += 1
    e = Fraction(error)
    n = 0
    while n < max_digits and e <= Fraction(1, 2) * Fraction(10) ** (k - n):
        n += 1
    return n


def digit_probes(rng: random.Random, n: int) -> list[tuple[float, float]]:
    """Values just below, at and above powers of ten (and 5 10^k), errors on and beside the
    half-unit ties ``0.5 10^j`` (as doubles, then a few ulps either side), and random ones."""
    probes = []
    for _ in range(n):
        p = rng.randrange(-12, 16)
        base = rng.choice([10.0**p, 5 * 10.0**p, rng.uniform(1, 10) * 10.0**p])
        value = base
        for _ in range(rng.randint(0, 3)):
            value = math.nextafter(value, rng.choice((0.0, math.inf)))
        if rng.random() < 0.5:
            value = -value
        j = p - rng.randrange(0, 16)
        error = rng.choice([0.5 * 10.0**j, 0.5 * 10.0 ** (j + 1), rng.uniform(0.05, 5) * 10.0**j])
        for _ in range(rng.randint(0, 2)):
            error = math.nextafter(error, rng.choice((0.0, math.inf)))
        probes.append((value, error))
    return probes


def digits_search(budget: int = 5000, seed: int = 1) -> dict:
    """``significant_digits`` against :func:`digits_rule` on :func:`digit_probes`; ``round_significant``
    never in E-notation for a leading digit in ``10^-7 .. 10^20`` and equal, as a number,
    to the exact value rounded half away from zero."""
    from pendulab.numerics.uncertainty import round_significant, significant_digits

    rng = random.Random(seed)
    wrong, text_wrong, first = 0, 0, None
    for value, error in digit_probes(rng, budget):
        n = significant_digits(value, error)
        if n != digits_rule(value, error):
            wrong += 1
            first = first or (value, error)
        if n:
            text = round_significant(value, n)
            exact = Decimal(value)
            ok = Decimal(text) - exact  # the rounding error of the text: within half a unit of digit n
            k = exact.adjusted()
            half = Decimal(5).scaleb(k - n)
            if abs(ok) > half or ("E" in text and -7 <= Decimal(text).adjusted() <= 20):
                text_wrong += 1
                first = first or (value, n, text)
    return {"claim": "significant_digits is the rule on exact decimals; round_significant rounds the exact value",
            "worst": wrong + text_wrong, "unit": "wrong counts or texts", "where": repr(first) if first else "-",
            "evaluations": budget}


# ---------------------------------------------------------------------------- dense output
def turning_time(z1: float, z2: float, c: float, forward: bool) -> mpmath.mpf:
    """Time from the state ``(z1, z2)`` of ``theta'' = c sin(theta)`` to its next (``forward``) or
    previous turning point, exactly (mpmath, 50 digits): the energy fixes the amplitude
    ``a`` of the flow through that very point, ``sin(theta/2) = k sn(u)`` with
    ``k = sin(a/2)``, and the time is ``(K - F(phi | k^2))/omega0``,
    ``sin(phi) = +-sin(z1/2)/k`` (DLMF 22.19.2, 19.2.4)."""
    with mpmath.workdps(50):
        z1, z2, w2 = mpmath.mpf(z1), mpmath.mpf(z2), -mpmath.mpf(c)
        cos_a = mpmath.cos(z1) - z2 * z2 / (2 * w2)  # energy: z2^2/2 - w2 cos(z1) = -w2 cos(a)
        k = mpmath.sqrt((1 - cos_a) / 2)
        m = k * k
        s = 1 if (z2 > 0) == forward else -1
        phi = mpmath.asin(min(mpmath.mpf(1), s * mpmath.sin(z1 / 2) / k))
        return (mpmath.ellipk(m) - mpmath.ellipf(phi, m)) / mpmath.sqrt(w2)


def dense_error(x: tuple[float, float, float]) -> float:
    """:func:`~pendulab.numerics.dense.dense_crossing` as :func:`~pendulab.numerics.crossing.estimate_period`
    calls it, over its bound :func:`~pendulab.numerics.dense.crossing_bound`, at ``x = (alpha, l, h)``:
    the bracket ``t_j = j h``, ``t_(j+1)`` around the first return ``T`` (``g = G``), its points
    the exact motion at the real times ``j h`` and ``(j + 1) h`` (:func:`motion_reference`), ``t_j``
    passed as the double ``j h``; the reference is the real ``j h`` plus the exact flow's time
    from the nearer point (:func:`turning_time`)."""
    from pendulab.numerics.dense import crossing_bound, dense_crossing

    alpha, length, h = x
    c, w = -G / length, math.sqrt(G / length)
    with mpmath.workdps(60):
        kp = mpmath.cos(mpmath.mpf(alpha) / 2)
        period = 4 * mpmath.sqrt(mpmath.mpf(length) / G) * mpmath.ellipk(1 - kp * kp)
        j = max(2, int(mpmath.floor(period / h)))
        ta, tb = mpmath.mpf(j) * h, mpmath.mpf(j + 1) * h  # exact: j < 2^40, h has 53 bits
    z1a, z2a = motion_reference(length, alpha, G, ta)
    z1b, z2b = motion_reference(length, alpha, G, tb)
    got = dense_crossing((z1a, z1b), (z2a, z2b), c, h, j * h)
    lin = z2a / (z2a - z2b)
    with mpmath.workdps(60):
        ref = ta + turning_time(z1a, z2a, c, True) if lin <= 0.5 else tb - turning_time(z1b, z2b, c, False)
        return float(abs(got - ref)) / crossing_bound(got, w, h)


#: The steps callers type (the coursework's 1e-2 .. 1e-4 and the plots' 0.2 and 0.1).
REAL_STEPS = (0.2, 0.1, 0.05, 0.02, 0.01, 1e-3, 1e-4)


def dense_search(budget: int = 40, seed: int = 1, max_step: float = 1.0) -> dict:
    """The dense-output crossing against its bound (:func:`dense_error`), fed as ``estimate_period``
    feeds it: the real ``t_j = j h`` of the first return, steps as typed (:data:`REAL_STEPS`) and
    steps that put the crossing half a step from both points (where the series is used farthest
    from its point) or just before or after the middle, up to ``omega0 h = max_step``; amplitudes
    from 0.1 to ``pi - 1e-8``, lengths over four decades."""
    hi = math.nextafter(math.pi, 0)
    rng = random.Random(seed)

    def tuned(alpha: float, length: float, wh: float, frac: float) -> tuple[float, float, float]:
        """The step near ``wh/omega0`` that puts the return at ``frac`` of the step after ``t_j``."""
        period = float(agm_half(alpha)) * math.sqrt(length)
        j = max(2, math.floor(period / (wh / math.sqrt(G / length))))
        return alpha, length, min(period / (j + frac), max_step / math.sqrt(G / length))

    starts = []
    for i in range(max(2, budget // 2)):
        alpha = rng.choice([rng.uniform(0.1, 3.1), math.pi - 10 ** rng.uniform(-8, -1)])
        length = 10 ** rng.uniform(-2, 2)
        w = math.sqrt(G / length)
        typed = [h for h in REAL_STEPS if w * h <= max_step]
        if i % 2 and typed:
            starts.append((alpha, length, rng.choice(typed)))
        else:
            wh = max_step if i % 4 == 0 else rng.uniform(0.05, max_step)
            starts.append(tuned(alpha, length, wh, rng.choice([0.5, math.nextafter(0.5, 0), 0.5 + 1e-9, rng.random()])))

    def perturb(x, r):
        alpha, length, h = x
        k = r.randrange(3)
        if k == 0:
            alpha = nudge(alpha, r, 0.01, hi, widest=-0.7)
        elif k == 1:
            length = nudge(length, r, 1e-3, 1e3)
        else:
            h = nudge(h, r, 1e-6, max_step / math.sqrt(G / length))
        return alpha, length, min(h, max_step / math.sqrt(G / length))

    worst, where, n = climb(dense_error, starts, perturb, budget // 2, rng)
    return {"claim": f"dense output: the returned crossing time within crossing_bound, omega0 h <= {max_step:g}",
            "worst": worst, "unit": "of the bound",
            "where": "alpha, l, h = " + repr(where), "evaluations": n}


def agm_half(alpha: float) -> float:
    """The period of ``l = 1`` (mpmath's elliptic K, 40 digits)."""
    with mpmath.workdps(40):
        kp = mpmath.cos(mpmath.mpf(alpha) / 2)
        return 4 * mpmath.sqrt(1 / mpmath.mpf(G)) * mpmath.ellipk(1 - kp * kp)


# ---------------------------------------------------------------------------- graded quadrature
def quadrature_error(alpha: float, n: int = 3000) -> float:
    """Relative error of ``quadrature_period(1, alpha, n, substitution=True, graded=True)``
    against the correctly rounded period (mpmath's elliptic K)."""
    from pendulab.numerics.quadrature import quadrature_period

    ref = correctly_rounded_periods(1.0, np.array([alpha]))[0]
    return abs(quadrature_period(1.0, alpha, n, substitution=True, graded=True) / ref - 1)


def quadrature_search(budget: int = 300, seed: int = 1) -> dict:
    """The largest relative error of the graded substituted rule with ``n = 3000`` panels:
    amplitudes log-uniform in ``pi - alpha`` from the last double below pi to 1, the 8
    doubles below pi, uniform ones, then climbing over ``alpha``."""
    rng = random.Random(seed)
    below = [math.pi]
    for _ in range(8):
        below.append(math.nextafter(below[-1], 0))
    starts = [(a,) for a in below[1:]]
    starts += [(math.pi - 10 ** rng.uniform(-15.5, 0),) for _ in range(budget // 3)]
    starts += [(rng.uniform(1e-3, math.pi - 1e-3),) for _ in range(budget // 6)]
    hi = math.nextafter(math.pi, 0)
    ratio, where, n = climb(lambda x: quadrature_error(x[0]), starts,
                            lambda x, r: (nudge(x[0], r, 0.0, hi),), budget // 2, rng)
    return {"claim": "graded substituted rule (11), n = 3000: relative error at every amplitude",
            "worst": ratio, "unit": "relative", "where": f"alpha = {where[0]!r}", "evaluations": n}


# ---------------------------------------------------------------------------- correctly rounded AGM
def agm_search(budget: int = 2000, seed: int = 1) -> dict:
    """The double-double kernel's relative error against :data:`pendulab.engine.agm.ERROR_BOUND`, and
    how many periods ``agm_period`` misrounds: amplitudes within 1e-16 .. 1 of pi, the 8
    doubles below pi, tiny ones (1e-300 .. 1e-8) and uniform ones; lengths putting ``T``
    just below a power of two, and random. Reference: mpmath's elliptic K rounded once."""
    from pendulab.engine.agm import ERROR_BOUND, agm_periods_dd
    from pendulab.numerics.period import agm_period

    rng = np.random.default_rng(seed)
    below = [math.pi]
    for _ in range(8):
        below.append(math.nextafter(below[-1], 0))
    n = max(budget, 16)
    kind = rng.integers(0, 3, n)
    alphas = np.where(kind == 0, math.pi - 10 ** rng.uniform(-16, 0, n),
                      np.where(kind == 1, 10 ** rng.uniform(-300, -8, n), rng.uniform(0, math.pi, n)))
    alphas[:8] = below[1:]
    alphas = np.minimum(alphas, below[1])
    t1 = np.asarray(agm_period(1.0, alphas))
    lengths = np.where(np.arange(n) % 2 == 0, (2.0 ** rng.integers(-1, 5, n) * (1 - 10 ** rng.uniform(-15, -2, n)) / t1) ** 2,
                       10 ** rng.uniform(-2, 2, n))
    got = np.asarray(agm_period(lengths, alphas))
    hi, lo, hard = np.empty(n), np.empty(n), np.empty(n, np.int64)
    agm_periods_dd(alphas, lengths, G, hi, lo, hard)
    worst, where, wrong = 0.0, None, 0
    for a, length, x, h, e in zip(alphas, lengths, got, hi, lo):
        gap = max(math.pi - float(a), 1e-17)
        with mpmath.workdps(40 + int(-2 * math.log10(gap)) if gap < 1 else 40):
            kp = mpmath.cos(mpmath.mpf(float(a)) / 2)
            ref = 4 * mpmath.sqrt(mpmath.mpf(float(length)) / mpmath.mpf(G)) * mpmath.ellipk(1 - kp * kp)
            wrong += x != float(ref)
            err = float(abs((mpmath.mpf(float(h)) + mpmath.mpf(float(e))) / ref - 1)) / ERROR_BOUND
        if err > worst:
            worst, where = err, (float(length), float(a))
    return {"claim": "agm_period: double-double within ERROR_BOUND (then rounded, mpmath where the test fails)",
            "worst": worst, "unit": "of ERROR_BOUND", "wrong": int(wrong),
            "where": f"l = {where[0]!r}, alpha = {where[1]!r}", "evaluations": n}


# ---------------------------------------------------------------------------- the sweep's sine and cosine
def sincos_search(budget: int = 20_000, seed: int = 1) -> dict:
    """``pendulab.engine.lanes.sincos`` against mpmath (correctly rounded sin and cos of the
    exact double), in ulps of the result: ``x`` next to the multiples of ``pi/4`` in
    ``|x| < 4`` (zeros of sin and cos, where the reduction cancels; the quadrant boundaries,
    where ``q`` rounds at a tie), within a few ulps and within 1e-12 .. 1e-3, and uniform."""
    from mpmath.libmp import to_float

    from pendulab.engine.lanes import sincos

    rng = random.Random(seed)
    worst, where = 0.0, None
    with mpmath.workprec(200):
        for i in range(budget):
            j = rng.randrange(-5, 6)
            if i % 3 == 2:
                x = rng.uniform(-4, 4)
            else:
                x = float(j * mpmath.pi / 4)
                if i % 3 == 0:
                    for _ in range(rng.randint(0, 6)):
                        x = math.nextafter(x, rng.choice((-math.inf, math.inf)))
                else:
                    x += rng.choice((-1, 1)) * 10 ** rng.uniform(-12, -3)
            if not abs(x) < 4:
                continue
            s, c = sincos(x)
            for got, ref in ((s, mpmath.sin(mpmath.mpf(x))), (c, mpmath.cos(mpmath.mpf(x)))):
                nearest = to_float(ref._mpf_, rnd="n")
                if nearest == 0:
                    continue
                err = float(abs(mpmath.mpf(got) - ref)) / math.ulp(nearest)
                if err > worst:
                    worst, where = err, x
    return {"claim": "sweep kernel sin, cos within 1 ulp for |x| < 4", "worst": worst, "unit": "ulp",
            "where": f"x = {where!r}", "evaluations": budget}


# ---------------------------------------------------------------------------- the sweep's estimates
def sweep_differences(alphas, lengths, h: float) -> tuple[np.ndarray, np.ndarray]:
    """For (3) with step ``h``: the sweep's lock-step estimates against ``estimate_period``'s
    (the scalar kernel), the larger of the linear and cubic ones: the relative difference,
    and the difference over the scalar estimate's own error (NaN where either finds no return;
    an untrusted return is compared too: the two kernels agree on its numbers as well)."""
    from pendulab.jobs.sweep import sweep
    from pendulab.numerics.crossing import search_period

    r = sweep(np.asarray(alphas, dtype=float), [h], ["taylor2"], np.asarray(lengths, dtype=float))
    rel, share = np.full(len(alphas), np.nan), np.full(len(alphas), np.nan)
    for i in np.flatnonzero(np.isin(r["status"], ("found", "untrusted"))):
        est = search_period(float(r["length"][i]), float(r["amplitude"][i]), h).estimate
        if est is None:
            continue
        rel[i] = max(abs(r[key][i] - getattr(est, key)) / abs(getattr(est, key)) for key in ("linear", "cubic"))
        share[i] = max(abs(r[key][i] - getattr(est, key)) / abs(getattr(est, key) - est.period)
                       for key in ("linear", "cubic"))
    return rel, share


def sweep_search(budget: int = 400, seed: int = 1, top_degrees: float = 179.99) -> dict:
    """The sweep's estimates against ``estimate_period``'s, ``h`` = 1e-2 .. 1e-4, amplitudes up to
    ``top_degrees``: the largest relative difference and the largest share of the scalar
    estimate's own error. Amplitudes mostly within 0.001 .. 100 degrees below the top (where
    the motion amplifies rounding), lengths over two decades; then a round of perturbations of
    the worst amplitudes and lengths (each round one sweep per step)."""
    rng = np.random.default_rng(seed)
    top = np.radians(top_degrees)
    n = max(8, budget // 6)
    worst_rel, worst_share, where_rel, where_share, count = 0.0, 0.0, None, None, 0
    for h in (1e-2, 1e-3, 1e-4):
        alphas = np.where(rng.random(n) < 0.8, np.radians(top_degrees - 10 ** rng.uniform(-3, 2.2, n)),
                          rng.uniform(0.01, top, n))
        alphas = np.clip(alphas, 1e-3, top)
        lengths = 10 ** rng.uniform(-1, 1, n)
        for _ in range(2):  # a screening round, then one round around the worst
            rel, share = sweep_differences(alphas, lengths, h)
            count += n
            inside = np.where(alphas <= top, rel, np.nan)
            if np.any(np.isfinite(inside)) and np.nanmax(inside) > worst_rel:
                i = int(np.nanargmax(inside))
                worst_rel, where_rel = float(inside[i]), (float(np.degrees(alphas[i])), float(lengths[i]), h)
            share = np.where(alphas <= top, share, np.nan)
            if np.any(np.isfinite(share)) and np.nanmax(share) > worst_share:
                i = int(np.nanargmax(share))
                worst_share, where_share = float(share[i]), (float(np.degrees(alphas[i])), float(lengths[i]), h)
            best = np.argsort(-np.nan_to_num(inside, nan=-1.0))[:4]
            alphas = np.minimum(np.repeat(alphas[best], n // 4 + 1)[:n] * (1 + 10 ** rng.uniform(-9, -4, n)
                                                                          * rng.choice([-1, 1], n)), top)
            lengths = np.repeat(lengths[best], n // 4 + 1)[:n] * (1 + 10 ** rng.uniform(-6, -1, n))
    return {"claim": f"sweep's (3) against estimate_period, h = 1e-2 .. 1e-4, up to {top_degrees:g} degrees",
            "worst": worst_rel, "worst_share": worst_share, "unit": "relative",
            "where": f"degrees, l, h = {where_rel}", "where_share": f"degrees, l, h = {where_share}",
            "evaluations": count}


# ---------------------------------------------------------------------------- eigenvalues of the normal matrix
def eigenvalue_ratio(a: np.ndarray) -> float:
    """``max |lambda~ - lambda| / eigenvalue_error`` for ``definiteness(a)``: numpy's ``eigvalsh``
    against mpmath's ``eigsy`` at 60 digits on the exact entries of ``a``."""
    from pendulab.numerics.lsq import definiteness

    d = definiteness(a)
    with mpmath.workdps(60):
        exact = sorted(mpmath.eigsy(mpmath.matrix(a.tolist()), eigvals_only=True))
    return max(float(abs(mpmath.mpf(float(x)) - e)) for x, e in zip(d.eigenvalues, exact)) / d.eigenvalue_error


def eigenvalue_search(budget: int = 200, seed: int = 1) -> dict:
    """:attr:`pendulab.numerics.lsq.Definiteness.eigenvalue_error` (``c n u ||A||_2``) against the computed
    eigenvalues' error: the normal matrices of basis (10) on time grids (4 to 400 points,
    short and long spans, where the columns are nearly dependent) and symmetric matrices
    with eigenvalues spread over 1 .. 1e-16, clustered or of mixed sign."""
    from pendulab.numerics.lsq import TRIG_BASIS, design_matrix

    rng = np.random.default_rng(seed)
    worst, where = 0.0, None
    for i in range(budget):
        kind = i % 3
        if kind == 0:
            t = np.sort(rng.uniform(0, 10 ** rng.uniform(-1, 1.5), int(rng.integers(4, 400))))
            x = design_matrix(t, TRIG_BASIS)
            a = x.T @ x
            what = f"basis (10) on {len(t)} times in [0, {t[-1]:.3g}]"
        else:
            n = int(rng.integers(2, 9))
            q, _ = np.linalg.qr(rng.standard_normal((n, n)))
            lam = 10 ** rng.uniform(-16, 0, n)
            if kind == 2:
                lam = np.where(rng.random(n) < 0.5, lam, -lam) if rng.random() < 0.5 else np.full(n, lam[0]) * (1 + 1e-12 * rng.standard_normal(n))
            a = (q * lam) @ q.T
            a = 0.5 * (a + a.T)
            what = f"n = {n}, eigenvalues {np.min(np.abs(lam)):.1e} .. {np.max(np.abs(lam)):.1e}"
        r = eigenvalue_ratio(a)
        if r > worst:
            worst, where = r, what
    return {"claim": "eigenvalue_error bounds the error of eigvalsh", "worst": worst,
            "unit": "of the bound", "where": where, "evaluations": budget}


# ---------------------------------------------------------------------------- K(k) of the motion
def quarter_period_error(alpha: float) -> float:
    """Relative error of ``quarter_period(alpha)``, in ``eps``, against mpmath's elliptic K of the
    exact double (``m`` held to 40 digits beyond ``1 - m``)."""
    from pendulab.numerics.motion import quarter_period

    gap = max(math.pi - alpha, 1e-17)
    with mpmath.workdps(40 + int(-2 * math.log10(gap)) if gap < 1 else 40):
        kp = mpmath.cos(mpmath.mpf(alpha) / 2)
        ref = mpmath.ellipk(1 - kp * kp)
        return float(abs(mpmath.mpf(quarter_period(alpha)) / ref - 1)) / EPS


def quarter_period_search(budget: int = 2000, seed: int = 1) -> dict:
    """``quarter_period``: amplitudes log-uniform within 1e-16 .. 1 of pi, tiny and uniform, then
    climbing over ``alpha``."""
    rng = random.Random(seed)
    hi = math.nextafter(math.pi, 0)
    starts = [(min(hi, rng.choice([math.pi - 10 ** rng.uniform(-16, 0), rng.uniform(0, math.pi),
                                   10 ** rng.uniform(-300, 0)])),) for _ in range(budget // 2)]
    worst, where, n = climb(lambda x: quarter_period_error(x[0]), starts,
                            lambda x, r: (nudge(x[0], r, 0.0, hi),), budget // 2, rng)
    return {"claim": "quarter_period within 2 eps of K", "worst": worst, "unit": "eps",
            "where": f"alpha = {where[0]!r}", "evaluations": n}


SEARCHES = {"motion": motion_search, "launched": launched_search, "t_hat": t_hat_search, "digits": digits_search, "dense": dense_search,
            "quadrature": quadrature_search, "agm": agm_search, "sincos": sincos_search, "sweep": sweep_search,
            "eigenvalues": eigenvalue_search, "quarter_period": quarter_period_search}


def main() -> None:
    names = sys.argv[1:2] or list(SEARCHES)
    budget = int(sys.argv[2]) if len(sys.argv) > 2 else None
    for name in names:
        result = SEARCHES[name](budget) if budget else SEARCHES[name]()
        print(f"{name}: {result}")


if __name__ == "__main__":
    main()
