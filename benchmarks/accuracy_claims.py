"""Measures every claim of the docs' accuracy page, against independent references.

References: mpmath at 40-80 digits from the inputs' exact doubles (AGM, elliptic K,
Jacobi elliptic functions), python-flint balls (certified digits), exact rationals (the
interpolation error estimate on exact times, significant digits). Each block prints the
numbers the docs quote; the stated bounds are measured by the adversarial searches of
``benchmarks/adversarial.py``.

Run: ``.venv/bin/python benchmarks/accuracy_claims.py`` (prints the measured figures), or
``--write-docs [--quick]``: run the adversarial searches and the figures and rewrite
everything between ``<!-- accuracy:begin -->`` and ``<!-- accuracy:end -->`` in
``docs/accuracy.md`` (a few minutes on one core; ``--quick``: the tests' small budgets).
"""
from __future__ import annotations

import math
import random
import sys
import time
from fractions import Fraction
from pathlib import Path

import mpmath
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import adversarial

from pendulab.numerics.crossing import estimate_period
from pendulab.numerics.lsq import EIGENVALUE_ERROR_FACTOR
from pendulab.numerics.motion import exact_motion, exact_motion_error_bound
from pendulab.numerics.period import (
    FIXED_ITERATIONS_ULPS,
    agm_mean,
    agm_period,
    fixed_iterations_limit,
    period_digits,
    small_angle_period,
)
from pendulab.numerics.quadrature import quadrature_period

DOC = Path(__file__).resolve().parents[1] / "docs" / "accuracy.md"
BEGIN, END = "<!-- accuracy:begin -->", "<!-- accuracy:end -->"

G = 9.80665
EPS = 2.0**-52


def mp_period(length: float, alpha, dps: int = 40):
    """``4 sqrt(l/g) K(k)`` (DLMF 19.2.8), ``1 - m = cos^2(alpha/2)``, from the exact double(s)."""
    with mpmath.workdps(dps):
        kp = mpmath.cos(mpmath.mpf(alpha) / 2)
        return 4 * mpmath.sqrt(mpmath.mpf(length) / mpmath.mpf(G)) * mpmath.ellipk(1 - kp * kp)


def seven_iterations(quick: bool = False) -> tuple[str, list[str], list[list[str]]]:
    """7 iterations of (7) against the converged loop and the correctly rounded period."""
    limit = fixed_iterations_limit()

    def converged(alpha):  # (7) until a - b <= 4 eps a: the double-precision loop, to convergence
        return small_angle_period(1.0, G) / agm_mean(math.cos(0.5 * alpha))

    rng = np.random.default_rng(7)
    size = 100 if quick else 2000
    bands = [("`[0, 3.1]`, uniform", None), ("`pi - [1.55e-13, 1e-6]`, log-uniform", (1.55e-13, 1e-6)),
             ("`pi - [3.24e-14, 1.55e-13]`, log-uniform", (3.24e-14, 1.55e-13)),
             ("`pi - [1e-15, 3.24e-14]`, log-uniform", (1e-15, 3.24e-14))]
    rows = []
    for name, gaps in bands:
        if gaps is None:
            alphas = rng.uniform(0.0, 3.1, size)
        else:
            alphas = math.pi - np.exp(rng.uniform(math.log(gaps[0]), math.log(gaps[1]), size))
        alphas = alphas[alphas < math.pi]
        t_hat = agm_period(1.0, alphas, iterations=7)
        same = np.mean([x == converged(a) for x, a in zip(t_hat, alphas)])
        ref = adversarial.correctly_rounded_periods(1.0, alphas)
        ulps = np.abs(t_hat - ref) / np.array([math.ulp(r) for r in ref])
        rows.append([name, str(len(alphas)), f"{same:.1%}", f"{np.mean(ulps == 0):.1%}", f"{ulps.max():.0f}"])
    title = (f"`T^`, 7 iterations of (7), `l = 1` (`fixed_iterations_limit()` = pi - {math.pi - limit:.3g}: the "
             "truncation is at most half an ulp below it)")
    return title, ["amplitudes", "how many", "same double as the converged loop", "correctly rounded",
                   "largest `abs(T^ - T)`, ulp"], rows


def certified_digits(quick: bool = False) -> tuple[str, list[str], list[list[str]]]:
    """``period_digits`` (Arb balls) against mpmath's elliptic K on random inputs as written."""
    rng = random.Random(3)
    n = ok = 0
    for _ in range(10 if quick else 200):
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
    return ("Certified digits (`period_digits`, Arb balls) against mpmath's elliptic K",
            ["inputs", "how many", "equal to mpmath's correctly rounded digits"],
            [["random `l = 1`, `alpha` a decimal multiple of pi (30 % within 1e-5 to 1e-40 of pi), 1 to 60 digits",
              str(n), str(ok)]])


def quadrature(quick: bool = False) -> tuple[str, list[str], list[list[str]]]:
    """``quadrature_period``: relative errors against mpmath's elliptic K."""
    rows = []
    for alpha in (1e-300, 1e-200, 1e-160):
        t = quadrature_period(1.0, alpha, 10**4)
        rows.append([f"`{alpha:g}`", "singular sum, n = 1e4", f"{abs(t / float(mp_period(1.0, alpha)) - 1):.2e}"])
    ns_equal = (10**3, 10**4) if quick else (10**3, 10**4, 10**5)
    for gap in (1e-2, 1e-3, 1e-6, 1e-9, 1e-12, 1e-15):
        alpha = math.pi - gap
        ref = float(mp_period(1.0, alpha, dps=60))
        equal = [abs(quadrature_period(1.0, alpha, n, substitution=True) / ref - 1) for n in ns_equal]
        graded = [abs(quadrature_period(1.0, alpha, n, substitution=True, graded=True) / ref - 1)
                  for n in (300, 1000, 3000)]
        rows.append([f"`pi - {gap:g}`", "substituted, equal panels, n = " + ", ".join(f"1e{round(math.log10(n))}" for n in ns_equal),
                     ", ".join(f"{e:.1e}" for e in equal)])
        rows.append([f"`pi - {gap:g}`", "substituted, graded, n = 300, 1000, 3000", ", ".join(f"{e:.1e}" for e in graded)])
    return ("Quadrature (problem 5), `l = 1`: relative error against mpmath's elliptic K",
            ["alpha", "rule", "relative error"], rows)


def motion(quick: bool = False) -> tuple[str, list[str], list[list[str]]]:
    """``exact_motion`` against ``mpmath.ellipfun`` over a few periods and around the 10^6th."""
    length = 2.0800838231
    rows = []
    points = (20, 6) if quick else (300, 60)
    for alpha in (1.0, 3.0, math.pi - 1e-9, math.pi - 1e-12):
        period = agm_period(length, alpha)
        for label, t in ((f"2.5 periods, {points[0]} points", np.linspace(0, 2.5 * period, points[0])),
                         (f"10^6th period, {points[1]} points", np.linspace(1e6 * period, (1e6 + 1) * period, points[1]))):
            ex = exact_motion(length, alpha, t)
            ref = np.array([adversarial.motion_reference(length, alpha, G, ti) for ti in t])
            bt, bo = exact_motion_error_bound(length, alpha, t)
            et, eo = np.abs(ex.theta - ref[:, 0]), np.abs(ex.omega - ref[:, 1])
            rows.append([f"`{alpha!r}`", label, f"{et.max():.1e} ({et.max() / EPS:.1f} eps)",
                         f"{np.max(et / bt):.2f}", f"{np.max(eo / bo):.2f}"])
    return ("The exact motion, `l = 2.0800838231`, against `mpmath.ellipfun` (60 digits)",
            ["alpha", "times", "largest theta error", "/ bound", "theta' / bound"], rows)


def interpolation(quick: bool = False) -> tuple[str, list[str], list[list[str]]]:
    """The 5-node error estimate of 3(d) against its rounding level and on exact times."""
    rows = []
    for h in (1e-2, 1e-3, 1e-4, 1e-5):
        est = estimate_period(2.0800838231, 4 * math.pi / 5, h)
        ip = est.interpolation
        x = [Fraction(float(z)) for z in (*ip.z2, ip.fifth[0])]
        ts = [(est.j - 2 + k) * Fraction(h) for k in (1, 2, 3, 4, 0)]  # t_k = k h, exactly
        dd = sum(ts[k] / math.prod(x[k] - x[i] for i in range(5) if i != k) for k in range(5))
        exact = float(dd * math.prod(-xi for xi in x[:4]))
        rows.append([f"{h:g}", f"{ip.error_estimate:.3e}" + ("" if ip.error_estimate_resolved else " (below)"),
                     f"{ip.rounding_level:.1e}", f"{exact:.2e}"])
    return ("The 5-node error estimate of 3(d), `l = 2.0800838231`, `alpha = 4pi/5`",
            ["h", "error estimate", "rounding level", "same formula on exact `t_k`"], rows)


FIGURES = (seven_iterations, quadrature, interpolation, certified_digits, motion)


def markdown(title: str, header: list[str], rows: list[list[str]]) -> str:
    lines = [f"**{title}**", "", "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return "\n".join(lines + ["| " + " | ".join(r) + " |" for r in rows])


# ---------------------------------------------------------------------------- the docs' table
#: Budgets of each search: full (the docs) and quick (the tests).
BUDGETS = {"full": {"motion": 1000, "launched": 1000, "t_hat": 1_000_000, "digits": 20_000, "dense": 60, "quadrature": 200, "agm": 20_000,
                    "sincos": 20_000, "sweep": 600, "eigenvalues": 1000,
                    "quarter_period": 3000},
           "quick": {"motion": 12, "launched": 12, "t_hat": 20_000, "digits": 1000, "dense": 6, "quadrature": 12, "agm": 200,
                     "sincos": 300, "sweep": 48, "eigenvalues": 30,
                     "quarter_period": 40}}


def claims(quick: bool = False) -> list[dict]:
    """One row per stated bound: where it is stated, the bound, how it is known, and the
    worst case its adversarial search found (``worst`` in the unit of ``bound``)."""
    b = BUDGETS["quick" if quick else "full"]
    rows = []
    for search, budget, claim, text in (
            (adversarial.motion_search, b["motion"], "`exact_motion`: theta, theta' (`exact_motion_error_bound`)",
             "`16 eps + 2^-100 omega0 abs(t)` rad (theta' times `omega0`)"),
            (adversarial.launched_search, b["launched"],
             "`launched_motion`: theta, theta' (`launched_motion_error_bound`)",
             "`16 eps max(1, abs(theta)) + 2^-100 max(1, k) w abs(t)` rad (theta' times `2 max(1, k) w`)")):
        r = search(budget)
        rows.append({"claim": claim, "bound_text": text, "kind": "phase term derived; 16 measured", "bound": 1.0,
                     "worst": r["worst"], "worst_text": f"{r['worst']:.2f} of the bound ({16 * r['worst']:.0f} eps)",
                     "where": r["where"], "evaluations": r["evaluations"]})
    r = adversarial.t_hat_search(b["t_hat"])
    rows.append({"claim": "`T^` (7 iterations) up to `fixed_iterations_limit()` (`FIXED_ITERATIONS_ULPS`)",
                 "bound_text": f"{FIXED_ITERATIONS_ULPS} ulp from the correctly rounded period", "kind": "derived",
                 "bound": float(FIXED_ITERATIONS_ULPS), "worst": r["worst"], "worst_text": f"{r['worst']:.0f} ulp",
                 "where": r["where"], "evaluations": r["evaluations"]})
    r = adversarial.agm_search(b["agm"])
    rows.append({"claim": "`agm_period` correctly rounded (`pendulab.engine.agm.ERROR_BOUND`)",
                 "bound_text": "double-double within `2^-72`; then rounded", "kind": "derived",
                 "bound": 1.0, "worst": r["worst"] if r["wrong"] == 0 else math.inf,
                 "worst_text": f"2^{math.log2(r['worst']) - 72:.1f}; {r['wrong']} misrounded", "where": r["where"],
                 "evaluations": r["evaluations"]})
    r = adversarial.digits_search(b["digits"])
    rows.append({"claim": "`significant_digits`, `round_significant` (problem 1)",
                 "bound_text": "the rule on the exact decimal value of each double", "kind": "exact (rationals)",
                 "bound": 0.0, "worst": float(r["worst"]), "worst_text": f"{r['worst']} wrong", "where": r["where"],
                 "evaluations": r["evaluations"]})
    for step, text in ((0.4, "`2^-52/omega0 + 2^-52 (abs(t) + h)` s"), (1.0, "`1e-10/omega0 + 2^-52 (abs(t) + h)` s")):
        r = adversarial.dense_search(b["dense"], max_step=step)
        rows.append({"claim": f"dense output's returned time, `omega0 h <= {step:g}` (`pendulab.numerics.dense.crossing_bound`)",
                     "bound_text": text, "kind": "series measured; roundings derived", "bound": 1.0, "worst": r["worst"],
                     "worst_text": f"{r['worst']:.2f} of the bound", "where": r["where"], "evaluations": r["evaluations"]})
    r = adversarial.quadrature_search(b["quadrature"])
    rows.append({"claim": "graded substituted rule (11), `n = 3000` (`quadrature_period`)",
                 "bound_text": "`2e-15` relative, every amplitude", "kind": "measured", "bound": 2e-15,
                 "worst": r["worst"], "worst_text": f"{r['worst']:.1e}", "where": r["where"],
                 "evaluations": r["evaluations"]})
    r = adversarial.sincos_search(b["sincos"])
    rows.append({"claim": "the sweep kernel's `sincos`, `abs(x) < 4` (`pendulab.engine.lanes`)",
                 "bound_text": "1 ulp", "kind": "measured (fdlibm's polynomials: 2^-58)", "bound": 1.0,
                 "worst": r["worst"], "worst_text": f"{r['worst']:.2f} ulp", "where": r["where"],
                 "evaluations": r["evaluations"]})
    for top, bound in ((179.9, 1e-9), (179.99, 2e-7)):
        r = adversarial.sweep_search(b["sweep"], top_degrees=top)
        rows.append({"claim": f"the sweep's (3) against `estimate_period`, up to {top:g} degrees (`pendulab.engine.lanes`)",
                     "bound_text": f"`{bound:g}` relative", "kind": "measured", "bound": bound, "worst": r["worst"],
                     "worst_text": f"{r['worst']:.1e}", "where": r["where"], "evaluations": r["evaluations"]})
    r = adversarial.sweep_search(b["sweep"], top_degrees=179.999)
    rows.append({"claim": "the sweep's (3) against `estimate_period`, up to 179.999 degrees (`pendulab.engine.lanes`)",
                 "bound_text": "5 % of the scalar estimate's own error", "kind": "measured", "bound": 5e-2,
                 "worst": r["worst_share"], "worst_text": f"{r['worst_share']:.1e}", "where": r["where_share"],
                 "evaluations": r["evaluations"]})
    r = adversarial.eigenvalue_search(b["eigenvalues"])
    rows.append({"claim": "eigenvalues of the normal matrix (`pendulab.numerics.lsq.EIGENVALUE_ERROR_FACTOR`)",
                 "bound_text": f"`{EIGENVALUE_ERROR_FACTOR} n u norm(A, 2)`", "kind": "measured (LAPACK: `p(n) u norm(A, 2)`)",
                 "bound": 1.0, "worst": r["worst"], "worst_text": f"{r['worst']:.2f} of the bound", "where": r["where"],
                 "evaluations": r["evaluations"]})
    r = adversarial.quarter_period_search(b["quarter_period"])
    rows.append({"claim": "`K(k)` of the motion (`pendulab.numerics.motion.quarter_period`)",
                 "bound_text": "`2 eps` relative", "kind": "measured", "bound": 2.0, "worst": r["worst"],
                 "worst_text": f"{r['worst']:.2f} eps", "where": r["where"], "evaluations": r["evaluations"]})
    return rows


def table(rows: list[dict], near_pi: list[tuple[str, float]], figures: list[str] = ()) -> str:
    """The markdown written between the markers of ``docs/accuracy.md``: the claims, ``T^``
    beyond its limit, then the measured figures (each a :func:`markdown` table)."""
    lines = ["| claim (where stated) | stated bound | known by | worst found | where | inputs tried |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['claim']} | {r['bound_text']} | {r['kind']} | {r['worst_text']} | {r['where']} | "
                     f"{r['evaluations']} |")
    lines += ["", "Beyond `fixed_iterations_limit()` (7 iterations have not converged; the bound above does "
              "not apply):", "", "| pendulum | `abs(T^ - T)`, ulp |", "|---|---|"]
    lines += [f"| {what} | {u:.0f} |" for what, u in near_pi]
    if figures:
        lines += ["", "## Measured figures", ""]
        lines += [line for f in figures for line in (f, "")][:-1]
    return "\n".join(lines)


def write_docs(quick: bool = False, path: Path = DOC) -> str:
    """Run the searches and rewrite the table between the markers of ``path``; returns the table."""
    text = table(claims(quick), adversarial.t_hat_near_pi(), [markdown(*block(quick)) for block in FIGURES])
    doc = path.read_text(encoding="utf-8")
    head, rest = doc.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    path.write_text(f"{head}{BEGIN}\n{text}\n{END}{tail}", encoding="utf-8")
    return text


def main() -> None:
    if "--write-docs" in sys.argv:
        print(write_docs(quick="--quick" in sys.argv))
        return
    for block in FIGURES:
        t = time.perf_counter()
        print(markdown(*block()))
        print(f"({time.perf_counter() - t:.0f} s)\n")


if __name__ == "__main__":
    main()
