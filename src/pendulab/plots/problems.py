"""Figures of problems 2, 4 and 5, drawn from the results of :mod:`pendulab.problems`."""
from __future__ import annotations

import numpy as np


def fit(ax, result, show_exact: bool = False):
    """4(d)(i): the data ``(t_j, z1_j)`` and the least-squares ``phi~`` on one plot.

    ``result`` is a :class:`pendulab.problems.Problem4`. Returns ``(points, curve)``.
    """
    t, y = result.data.t, result.data.theta
    stride = max(1, len(t) // 200)  # keep the markers readable; the fit uses every point
    (points,) = ax.plot(t[::stride], y[::stride], "o", markersize=3, color="C0",
                        label=f"data $(t_j, z_{{1,j}})$, {len(t)} points" + (f" (every {stride})" if stride > 1 else ""))
    (curve,) = ax.plot(result.curve_t, result.curve_phi, "-", color="C3", linewidth=1.2,
                       label=r"least squares $\tilde\phi(t)$, basis (10)")
    if show_exact:
        ax.plot(result.curve_t, result.curve_exact, ":", color="0.3", linewidth=1, label=r"exact $\theta(t)$")
    ax.set_xlabel("t (s)")
    ax.set_ylabel(r"$\theta$ (rad)")
    ax.set_title(
        rf"$l = {result.length:g}$, $\alpha = {result.amplitude:.6g}$, $h = {result.step:g}$; "
        rf"SSD = {result.fit.ssd:.3e}, max dev. = {result.fit.max_deviation:.2e}",
        fontsize="medium",
    )
    ax.legend(fontsize="small")
    return points, curve


def fit_residuals(ax, result):
    """The deviations ``z1_j - phi~(t_j)`` of problem 4 and the 1e-5 threshold of 4(d)(ii)."""
    (line,) = ax.plot(result.data.t, result.fit.residuals, "-", color="C0", linewidth=1)
    for s in (1, -1):
        ax.axhline(s * result.tolerance, color="C3", linestyle="--", linewidth=0.8)
    ax.set_xlabel("t (s)")
    ax.set_ylabel(r"$z_{1,j} - \tilde\phi(t_j)$ (rad)")
    return line


def quadrature_convergence(ax, result):
    """5(d): ``|S_n - T^|`` against ``n`` on log-log axes, with an ``n^(-1/2)`` guide.

    ``result`` is a :class:`pendulab.problems.Problem5`. Returns the lines drawn.
    """
    rows = result.rows
    n = np.array([r.n for r in rows], dtype=float)
    err = np.array([r.error for r in rows])
    lines = [ax.loglog(n, err, "o-", color="C0", label="rule (11), integral (1)")[0]]
    guide = err[0] * (n / n[0]) ** -0.5
    lines.append(ax.loglog(n, guide, ":", color="0.4", label=r"slope $-1/2$")[0])
    sub = [(r.n, r.substitution_error) for r in rows if r.substitution_error is not None]
    if sub:
        floor = np.finfo(float).eps * result.exact
        ns, es = zip(*sub)
        shown = np.maximum(np.array(es), floor)  # an error of exactly 0 sits on the rounding floor
        lines.append(ax.loglog(ns, shown, "s-", color="C2",
                               label=r"after $\sin(\theta/2) = \sin(\alpha/2)\sin\varphi$")[0])
    ax.set_xlabel("n (subintervals)")
    ax.set_ylabel(r"$|S_n$-based $T - \hat T|$ (s)")
    ax.grid(True, which="both", linewidth=0.3)
    ax.legend(fontsize="small")
    return lines


def newton_corrections(ax, result):
    """2(b): ``|x[k+1] - x[k]|`` against ``k`` (semilog): the exponent doubles each step.

    ``result`` is a :class:`pendulab.problems.Problem2`. Returns the line drawn.
    """
    d = np.abs(np.array(result.run.corrections))
    k = np.arange(len(d))
    keep = d > 0
    (line,) = ax.semilogy(k[keep], d[keep], "o-", color="C0")
    ax.axhline(result.run.rounding_level, color="C3", linestyle="--", linewidth=0.8, label="rounding level")
    ax.set_xlabel("k")
    ax.set_ylabel(r"$|x_{k+1} - x_k|$ (rad)")
    ax.legend(fontsize="small")
    return line
