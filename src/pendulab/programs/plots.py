"""Figures R1-R5 of the report with matplotlib, from the programs' own data: R1 and R2
are the coursework's Figures 1 and 2 for the group (3(b)), R3 and R4 the fit of 4(d)(i)
and its deviations, R5 the error of S_n against n (5(d)). Each function draws on the
axes it is given; run alone, the program writes R1.png to R5.png."""
import math
import sys

import numpy as np

import problem3
import problem4
import problem5
from agm import t_hat
from length import group_length
from taylor import taylor

WORDS = {"t": "t (s)", "z1j": "z1_j ~ theta(t_j) (rad)", "z1": "z1 ~ theta (rad)",
         "z2": "z2 ~ theta' (rad/s)", "P": "P = (alpha, 0)", "data": "data Y_j",
         "fit": "phi~", "fit_y": "z1_j, phi~(t) (rad)", "dev": "z1_j - phi~(t_j) (rad)",
         "n": "n", "error": "|S_n - T^| (s)", "rule": "(11) on (1)",
         "guide": "~ 1/sqrt(n)"}
GUIDE = 4.0  # R5: the n^(-1/2) guide drawn 4 times above the first error, beside it

def figure1(ax, t, z1, words=WORDS):
    """R1, the coursework's Figure 1: the points (t_j, z1_j)."""
    ax.plot(t, z1, "o", markersize=3, color="C0")
    ax.axhline(0, color="0.7", linewidth=0.6)
    ax.set(xlabel=words["t"], ylabel=words["z1j"])

def figure2(ax, z1, z2, alpha, words=WORDS):
    """R2, the coursework's Figure 2: Z_j = (z1_j, z2_j) joined by arrows, P circled."""
    x, y = np.asarray(z1), np.asarray(z2)
    ax.quiver(x[:-1], y[:-1], np.diff(x), np.diff(y), angles="xy", scale_units="xy",
              scale=1, width=0.006, headwidth=3.5, headlength=4.5, color="C0")
    ax.plot(x, y, "o", markersize=2, color="C0")
    ax.plot([alpha], [0.0], "o", markersize=12, markerfacecolor="none",
            markeredgecolor="C3", markeredgewidth=1.3, label=words["P"])
    ax.axhline(0, color="0.7", linewidth=0.6)
    ax.axvline(0, color="0.7", linewidth=0.6)
    ax.set(xlabel=words["z1"], ylabel=words["z2"])
    ax.legend(loc="upper left", markerscale=0.5)  # the circle, not its size, in the key

def figure3(ax, t, z1, coef, words=WORDS):
    """R3, 4(d)(i): every data point (t_j, z1_j) over phi~ of (10), on 801 points."""
    fine = np.linspace(t[0], t[-1], 801)
    ax.plot(fine, problem4.basis(fine) @ coef, "-", color="C3", alpha=0.35,
            linewidth=4, label=words["fit"])
    # the 401 points, dark and small over the wide pale curve: both show
    ax.plot(t, z1, "o", markersize=1.6, markeredgewidth=0, color="C0",
            label=words["data"], zorder=3)
    ax.set(xlabel=words["t"], ylabel=words["fit_y"])
    ax.legend(loc="best", frameon=False, markerscale=3)

def figure4(ax, t, deviations, tol, words=WORDS):
    """R4: z1_j - phi~(t_j), shaded +-tol of 4(d)(ii); the axis linear inside +-tol and
    logarithmic beyond it, so that the band and the deviations show together."""
    ax.axhspan(-tol, tol, color="C3", alpha=0.18, linewidth=0)
    ax.axhline(0, color="0.6", linewidth=0.5)
    ax.plot(t, deviations, "-", color="C2", linewidth=0.8)
    ax.set_yscale("symlog", linthresh=tol)
    ax.set(xlabel=words["t"], ylabel=words["dev"])

def figure5(ax, n, errors, words=WORDS):
    """R5, 5(d): |S_n - T^| against n on log-log axes, with the slope n^(-1/2)."""
    n, errors = np.asarray(n, dtype=float), np.asarray(errors)
    ax.loglog(n, errors, "o-", markersize=3, color="C0", label=words["rule"])
    ax.loglog(n, GUIDE * errors[0] * (n / n[0]) ** -0.5, ":", color="0.4",
              label=words["guide"])
    ax.minorticks_off()  # only n = 10^k carry points
    ax.set(xlabel=words["n"], ylabel=words["error"])
    ax.legend(loc="best", frameon=False)

def figures(students):
    """Each figure's function and data, computed by the programs for the group."""
    l = float(group_length(students)[2])
    t, z1, z2 = taylor(l, problem3.ALPHA, 0.2,
                       problem3.plot_t_max(l, t_hat(l, problem3.ALPHA))[0])
    t4, y4, _ = taylor(problem4.L, problem4.ALPHA, problem4.H,
                       math.ceil(t_hat(problem4.L, problem4.ALPHA)))
    coef, res = problem4.fit(t4, y4)[3:]
    rows = problem5.table(t_hat(problem5.L, problem5.ALPHA))[1:]  # n = 10 .. 10^5
    return {"R1": (figure1, (t, z1)), "R2": (figure2, (z1, z2, problem3.ALPHA)),
            "R3": (figure3, (t4, y4, coef)), "R4": (figure4, (t4, res, problem4.TOL)),
            "R5": (figure5, ([r[0] for r in rows], [r[2] for r in rows]))}

if __name__ == "__main__":
    from matplotlib.figure import Figure
    students = [int(s) for s in sys.argv[1:]] or [262, 407, 634]
    print(f"R5: the guide n^(-1/2) is drawn {GUIDE:g} times above the first error")
    for name, (draw, data) in figures(students).items():
        fig = Figure(figsize=(4.5, 3), layout="constrained")
        draw(fig.add_subplot(), *data)
        fig.savefig(f"{name}.png", dpi=150)
        print(f"{name}.png")
