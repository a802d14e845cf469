"""Measures every claim of the README's accuracy section, against independent references.

References: mpmath at 40-60 digits from the inputs' exact doubles (AGM, elliptic K,
Jacobi elliptic functions), python-flint balls (certified digits), exact rationals (the
interpolation error estimate on exact times). Each block prints the numbers the README
quotes. The double-precision AGM's distance to the correctly rounded period is measured
by ``benchmarks/agm_ulps.py``.

Run: ``.venv/bin/python benchmarks/accuracy_claims.py`` (about two minutes on one core).
"""
from __future__ import annotations

import math
import random
import time
from fractions import Fraction

import mpmath
import numpy as np

from pendulab.crossing import estimate_period
from pendulab.motion import exact_motion, exact_motion_error_bound
from pendulab.period import agm_period, fixed_iterations_limit, period_digits
from pendulab.quadrature import quadrature_period

G = 9.80665
EPS = 2.0**-52


def mp_period(length: float, alpha, dps: int = 40):
    """``4 sqrt(l/g) K(k)`` (DLMF 19.2.8), ``1 - m = cos^2(alpha/2)``, from the exact double(s)."""
    with mpmath.workdps(dps):
        kp = mpmath.cos(mpmath.mpf(alpha) / 2)
        return 4 * mpmath.sqrt(mpmath.mpf(length) / mpmath.mpf(G)) * mpmath.ellipk(1 - kp * kp)


def seven_iterations() -> None:
    """7 iterations of (7) against the converged loop and the correctly rounded period."""
    print("== 7 iterations of (7) (--iterations 7)")
    limit = fixed_iterations_limit()
    print(f"fixed_iterations_limit() = {limit!r} = pi - {math.pi - limit:.3g} (truncation <= half an ulp below it)")

    def converged(alpha):  # (7) until a - b <= 4 eps a: the plain loop, iterated to convergence
        a, b = 1.0, math.cos(0.5 * alpha)
        for _ in range(64):
            if a - b <= 4 * EPS * a:
                break
            a, b = 0.5 * (a + b), math.sqrt(a * b)
        return 2 * math.pi * math.sqrt(1.0 / G) / (0.5 * (a + b))

    rng = np.random.default_rng(7)
    bands = [("[0, 3.1]", None), ("pi - [1.55e-13, 1e-6]", (1.55e-13, 1e-6)),
             ("pi - [3.24e-14, 1.55e-13]", (3.24e-14, 1.55e-13)), ("pi - [1e-15, 3.24e-14]", (1e-15, 3.24e-14))]
    for name, gaps in bands:
        if gaps is None:
            alphas = rng.uniform(0.0, 3.1, 2000)
        else:
            alphas = math.pi - np.exp(rng.uniform(math.log(gaps[0]), math.log(gaps[1]), 2000))
        alphas = alphas[alphas < math.pi]
        t7 = agm_period(1.0, alphas, iterations=7)
        same = np.mean([x == converged(a) for x, a in zip(t7, alphas)])
        ref = np.array([float(mp_period(1.0, a)) for a in alphas])
        ulps = np.abs(t7 - ref) / np.array([math.ulp(r) for r in ref])
        print(f"  {name:27} {len(alphas)} amplitudes ({'uniform' if gaps is None else 'log-uniform in pi - alpha'}): "
              f"same double as the converged loop {same:6.1%}, correctly rounded {np.mean(ulps == 0):6.1%}, "
              f"at most {ulps.max():.0f} ulp off")


def certified_digits() -> None:
    print("== period_digits (Arb balls) against mpmath's elliptic K")
    rng = random.Random(3)
    n = ok = 0
    for _ in range(200):
        places = 12
        coef = Fraction(rng.randrange(0, 10**12), 10**12)
        if rng.random() < 0.3:
            places = rng.randrange(5, 41)
            coef = 1 - Fraction(1, 10**places)  # within 1e-5 .. 1e-40 of pi
        digits = rng.choice([1, 5, 15, 30, 60])
        # As a decimal multiple of pi, "0.99...9pi": a fraction of 40-digit integers would
        # pass the inputs' 64-character limit.
        got = period_digits("1", f"0.{coef.numerator * 10**places // coef.denominator:0{places}d}pi", digits=digits)
        with mpmath.workdps(digits + 100):
            kp = mpmath.sin(mpmath.pi * (1 - mpmath.mpf(coef.numerator) / coef.denominator) / 2)
            ref = 4 * mpmath.sqrt(1 / mpmath.mpf("9.80665")) * mpmath.ellipk(1 - kp * kp)
            ok += got == mpmath.nstr(ref, digits, strip_zeros=False)
        n += 1
    print(f"  {ok} of {n} random inputs (30% within 1e-5 to 1e-40 of pi) equal mpmath's correctly rounded digits")
    t = time.perf_counter()
    period_digits("3.5", "4pi/5", digits=10000)
    print(f"  10000 digits of l = 3.5, alpha = 4pi/5 in {time.perf_counter() - t:.2f} s")


def quadrature() -> None:
    print("== quadrature_period, relative error against mpmath's elliptic K")
    for alpha in (1e-300, 1e-200, 1e-160):
        t = quadrature_period(1.0, alpha, 10**4)
        print(f"  alpha = {alpha:g}: singular sum S_n, n = 1e4, relative error {abs(t / float(mp_period(1.0, alpha)) - 1):.2e} "
              "(the n^(-1/2) truncation, as at any small amplitude)")
    for gap in (1e-2, 1e-3, 1e-6, 1e-9, 1e-12, 1e-15):
        alpha = math.pi - gap
        ref = float(mp_period(1.0, alpha, dps=60))
        equal = [abs(quadrature_period(1.0, alpha, n, substitution=True) / ref - 1) for n in (10**3, 10**4, 10**5)]
        graded = [abs(quadrature_period(1.0, alpha, n, substitution=True, graded=True) / ref - 1)
                  for n in (300, 1000, 3000)]
        print(f"  pi - {gap:g}: equal panels n = 1e3, 1e4, 1e5: " + ", ".join(f"{e:.1e}" for e in equal)
              + "; graded n = 300, 1000, 3000: " + ", ".join(f"{e:.1e}" for e in graded))


def motion() -> None:
    print("== exact_motion against mpmath.ellipfun (60 digits): largest error / bound 4 eps (omega0 |t| + K)")
    length = 2.0800838231
    for alpha in (1.0, 3.0, math.pi - 1e-9, math.pi - 1e-12):
        period = agm_period(length, alpha)
        for label, t in (("2.5 periods, 1500 points", np.linspace(0, 2.5 * period, 1500)),
                         ("1000th period, 150 points", np.linspace(1000 * period, 1001 * period, 150))):
            ex = exact_motion(length, alpha, t)
            ref = []
            with mpmath.workdps(60):
                a = mpmath.mpf(alpha)
                k = mpmath.sin(a / 2)
                m = k * k
                w = mpmath.sqrt(mpmath.mpf(G) / mpmath.mpf(length))
                big_k = mpmath.ellipk(m)
                for ti in t:
                    u = big_k - w * mpmath.mpf(ti)
                    sn, cn, dn = (mpmath.ellipfun(f, u, m=m) for f in ("sn", "cn", "dn"))
                    ref.append((float(2 * mpmath.atan2(k * sn, dn)), float(-2 * k * w * cn)))
            ref = np.array(ref)
            bt, bo = exact_motion_error_bound(length, alpha, t)
            et, eo = np.abs(ex.theta - ref[:, 0]), np.abs(ex.omega - ref[:, 1])
            print(f"  alpha = {alpha!r:20} {label:26} max |theta error| {et.max():.2e}, "
                  f"/bound {np.max(et / bt):.2f}; theta' /bound {np.max(eo / bo):.2f}")


def interpolation() -> None:
    print("== the 5-node error estimate of 3(d) against its rounding level (l = 2.0800838231, alpha = 4pi/5)")
    for h in (1e-2, 1e-3, 1e-4, 1e-5):
        est = estimate_period(2.0800838231, 4 * math.pi / 5, h)
        ip = est.interpolation
        x = [Fraction(float(z)) for z in (*ip.z2, ip.fifth[0])]
        ts = [(est.j - 2 + k) * Fraction(h) for k in (1, 2, 3, 4, 0)]  # t_k = k h, exactly
        dd = sum(ts[k] / math.prod(x[k] - x[i] for i in range(5) if i != k) for k in range(5))
        exact = float(dd * math.prod(-xi for xi in x[:4]))
        print(f"  h = {h:g}: estimate {ip.error_estimate:.3e}, rounding level {ip.rounding_level:.2e}, "
              f"on exact t_k {exact:.2e} -> {'interpolation error' if ip.error_estimate_resolved else 'below rounding'}")
    for alpha in (1e-100, 1e-160, 1e-300):
        est = estimate_period(1.0, alpha, 1e-3)
        print(f"  alpha = {alpha:g}, h = 1e-3: cubic {est.cubic!r}, error {est.cubic_error:.2e}, "
              f"estimate {est.cubic_error_estimate:.2e}")


def main() -> None:
    for block in (seven_iterations, certified_digits, quadrature, interpolation, motion):
        t = time.perf_counter()
        block()
        print(f"  ({time.perf_counter() - t:.0f} s)")


if __name__ == "__main__":
    main()
