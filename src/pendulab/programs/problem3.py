"""Problem 3(b)-(d): the period from the simulation (3) of the group's pendulum.

z2 = theta' changes sign from + to - as the pendulum returns to P = (alpha, 0)
(Figure 2): T lies in [t_j, t_(j+1)]. A line (3(c)) and an inverse cubic (3(d))
through the points (z2_k, t_k) around the change estimate the t at which z2 = 0."""
import math
import sys

import mpmath

from agm import t_hat
from digits import beside, right, sci, sci_up
from length import group_length
from taylor import taylor

ALPHA = 4 * math.pi / 5
STEPS = [1e-2, 1e-3, 1e-4]  # 3(c): h = 10^-j, j = 2, 3, 4; 3(d) uses h = 1e-3
SEARCH = 4  # 3(b): the h = 0.2 simulation is searched over 4 T^
PLOT = 2  # 3(b): t_max spans 2 T^ of (8), as the coursework suggests
NEGLIGIBLE = 1e-3  # 3(d): an error below 1/1000 of the Taylor method's is negligible

def sign_change(z1, z2):
    """The first j with z2_j > 0 >= z2_(j+1) and z1_(j+1) > 0 (None if none), and
    the first index where |z1| >= pi: the discrete pendulum went over the top."""
    for j in range(len(z2) - 1):
        if abs(z1[j + 1]) >= math.pi:
            return None, j + 1
        if z2[j] > 0 >= z2[j + 1] and z1[j + 1] > 0:
            return j, None
    return None, None

def cubic_at_zero(x, y):
    """Newton's divided differences c = y[x0], y[x0,x1], ..., y[x0..x4] of the five
    points, p(0) for the cubic p through the first four, and (0-x0)...(0-x3)."""
    c = list(y)
    for k in range(1, 5):
        for i in range(4, k - 1, -1):
            c[i] = (c[i] - c[i - 1]) / (x[i] - x[i - k])
    p = c[3]
    for k in (2, 1, 0):  # Horner: p(0) = c0 + (0-x0)(c1 + (0-x1)(c2 + (0-x2) c3))
        p = p * (0 - x[k]) + c[k]
    return c, p, (0 - x[0]) * (0 - x[1]) * (0 - x[2]) * (0 - x[3])

def inverse_cubic(x, y):
    """p(0) for the cubic p through (x_k, y_k), k = 0..3, and the error estimate
    e(0) = f^(4)(xi)/4! (0-x0)(0-x1)(0-x2)(0-x3), f^(4)(xi)/4! ~ y[x0..x4]."""
    c, p, prod = cubic_at_zero(x, y)
    # y[x0..x4] = sum_k y_k / prod_(i!=k)(x_k - x_i): rounding each time y_k (half
    # an ulp) alone moves e(0) by up to this much
    rounding = abs(prod) * math.fsum(
        math.ulp(y[k]) / 2 / abs(math.prod(x[k] - x[i] for i in range(5) if i != k))
        for k in range(5))
    return {"p0": p, "coef": c, "dd4": c[4], "e0": c[4] * prod, "prod": prod,
            "rounding": rounding}

def period(l, h, reference):
    """3(c)-(d): the bracket, the zero of the line through j and j+1, and p(0)."""
    # up to 1.5 T^ (8) + 4h: the return to P and the two steps after it are in the lists
    t, z1, z2 = taylor(l, ALPHA, h, 1.5 * reference + 4 * h)
    j = sign_change(z1, z2)[0]
    nodes = [j - 1, j, j + 1, j + 2, j - 2]  # four around the change; a fifth for e(0)
    x, y = [z2[k] for k in nodes], [t[k] for k in nodes]
    return {"h": h, "j": j, "bracket": (t[j], t[j + 1]), "z2": x, "t": y,
            "linear": t[j] + h * z2[j] / (z2[j] - z2[j + 1]), **inverse_cubic(x, y)}

def rounding_errors(l_text, r, dps=30):
    """3(d): how far rounding moved the doubles of the table, its coefficients, p(0)
    and e(0): (3) and the divided differences again in dps-digit arithmetic (mpmath),
    from the inputs as written (l, h, g, alpha = 4 pi/5) and t_k = k h exactly."""
    nodes = [round(t / r["h"]) for t in r["t"]]
    with mpmath.workdps(dps):
        h, c = mpmath.mpf(repr(r["h"])), -mpmath.mpf("9.80665") / mpmath.mpf(l_text)
        z1, z2, at = 4 * mpmath.pi / 5, mpmath.mpf(0), {}
        for i in range(max(nodes) + 1):
            at[i] = z2
            s = mpmath.sin(z1)
            z1, z2 = (z1 + h * z2 + h * h / 2 * c * s,
                      z2 + h * c * s + h * h / 2 * c * z2 * mpmath.cos(z1))  # (3)
        x = [at[k] for k in nodes]
        coef, p0, prod = cubic_at_zero(x, [k * h for k in nodes])
        e = {"z2": [abs(float(a - b)) for a, b in zip(r["z2"], x)],
             "t": [abs(float(a - k * h)) for a, k in zip(r["t"], nodes)],
             "coef": [abs(float(a - b)) for a, b in zip(r["coef"], coef)],
             "p0": abs(float(r["p0"] - p0)), "e0": abs(float(r["e0"] - coef[4] * prod))}
    return e

def plot_t_max(l, reference, h=0.2):
    """3(b): t_max from (8) alone, the first multiple of h at or beyond 2 T^; and the
    h = 0.2 simulation over 4 T^: its return to P or the time it goes over the top."""
    t, z1, z2 = taylor(l, ALPHA, h, SEARCH * reference)
    j, over = sign_change(z1, z2)
    # rounded to 9 decimals first: a quotient such as 24.000000000000004 gives 24
    return h * math.ceil(round(PLOT * reference / h, 9)), j, over, t

def order(e0, e1, h0, h1):
    return math.log(e0 / e1) / math.log(h0 / h1)  # e ~ C h^p between two rows

if __name__ == "__main__":
    students = [int(s) for s in sys.argv[1:]] or [262, 407, 634]
    l_text = group_length(students)[2]
    l = float(l_text)
    reference = t_hat(l, ALPHA)
    t_max, j, over, t = plot_t_max(l, reference)
    print(f"3(b) l = {l_text} m, T^ = {reference:.15g} s,",
          f"t_max = {t_max:.6g} s, N = {round(t_max / 0.2)} steps of h = 0.2")
    if j is not None:  # where T^ lies: before t_j, inside [t_j, t_(j+1)] or after
        side = (f"{t[j] - reference:.3g} s before t_{j}" if reference < t[j] else
                f"{reference - t[j + 1]:.3g} s after t_{j + 1}" if reference > t[j + 1]
                else f"inside, {reference - t[j]:.3g} s after t_{j}")
        print(f"     j = {j}: T in [{t[j]:.6g}, {t[j + 1]:.6g}]; T^ {side}")
    elif over is not None:
        print(f"     over the top at t = {t[over]:.6g} = {t[over] / reference:.3g} T^")
    else:
        print(f"     no return up to t = {SEARCH * reference:.6g}")
    print("3(c)  h       j  bracket       linear        error    p(0)          error")
    rows = [period(l, h, reference) for h in STEPS]
    for r in rows:
        a, b = r["bracket"]
        print(f"{r['h']:6.0e} {r['j']:6d}  [{a:.8g}, {b:.8g}]",
              f"{r['linear']:<14.12g} {sci(abs(r['linear'] - reference), 3):<8}",
              f"{r['p0']:<14.12g} {sci(abs(r['p0'] - reference), 3)}")
    for a, b in zip(rows, rows[1:]):
        p = [order(abs(a[k] - reference), abs(b[k] - reference), a["h"], b["h"])
             for k in ("linear", "p0")]
        print(f"     order from h = {a['h']:.0e} to {b['h']:.0e}:",
              f"{p[0]:.2f} (linear), {p[1]:.2f} (p(0))")
    r = rows[STEPS.index(1e-3)]
    e = rounding_errors(l_text, r)  # only the digits rounding left right are printed
    print(f"3(d) h = 1e-3, j = {r['j']}: z2_k, t_k, divided differences",
          f"(steps {r['j'] - 1} to {r['j'] + 2}, then {r['j'] - 2})")
    for k in range(5):
        c = right(r["coef"][k], e["coef"][k]) if k else f"{r['t'][0]:.3f}"  # c0 = t_0
        print(f"    {right(r['z2'][k], e['z2'][k]):<18} {r['t'][k]:.3f}  {c}")
    error = abs(r["p0"] - reference)  # the Taylor method's error in the period
    bound = max(abs(r["e0"]), r["rounding"])
    print(f"    p(0) = {r['p0']:.12g}, (0-x0)...(0-x3) = {sci(r['prod'], 6)},",
          f"e(0) ~ {right(r['e0'], e['e0'])}")
    print(f"    rounding: e(0) by {sci_up(e['e0'], 1)}, p(0) by {sci_up(e['p0'], 1)},",
          f"the times' level {sci(r['rounding'], 2)};",
          f"at most about {sci_up(bound + e['e0'], 1)}")
    ratio = bound / error
    # one digit, on its side of NEGLIGIBLE, unless e(0)'s rounding leaves less
    shown = right(ratio, e["e0"] / error, 1)
    shown = beside(ratio, NEGLIGIBLE, 1) if shown == sci(ratio, 1) else shown
    print(f"    |p(0) - T^| = {sci(error, 3)}; ratio {shown}:",
          "negligible" if ratio < NEGLIGIBLE else "not negligible",
          f"(below {sci(NEGLIGIBLE, 1)})")
