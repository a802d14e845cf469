"""Problem 3's plain reference for the tests: the coursework programs themselves.

The programs (``pendulab/programs/*.py``) are written from the coursework's formulas in
plain Python and never import pendulab; ``test_programs.py`` runs them with pendulab out
of reach. This module gives test_report.py and test_key.py their answers by name.
"""
from __future__ import annotations

from pendulab.jobs.coursework import load

_P = load()
length, agm, taylor, problem3 = (_P[f"{n}.py"] for n in ("length", "agm", "taylor", "problem3"))
ALPHA = problem3.ALPHA


def length_text(numbers) -> str:
    """3(b): the group's length as the program writes it (10 decimals)."""
    return length.group_length(list(numbers))[2]


def t_hat(length: float, alpha: float = ALPHA) -> float:
    """T^ of (8), 7 iterations."""
    return agm.t_hat(length, alpha)


def first_event(length: float, h: float, t_end: float):
    """("returns", j, points j-2 .. j+2) or ("leaves", t) or ("none", None): what comes first."""
    t, z1, z2 = taylor.taylor(length, ALPHA, h, t_end)
    j, over = problem3.sign_change(z1, z2)
    if j is not None:
        return "returns", j, list(zip(z1, z2))[j - 2:j + 3]
    if over is not None:
        return "leaves", t[over]
    return "none", None


def estimate(length: float, h: float):
    """3(c)-(d) for step ``h``: j, bracket, linear and cubic estimates, the error estimate."""
    r = problem3.period(length, h, agm.t_hat(length, ALPHA))
    return {"j": r["j"], "bracket": r["bracket"], "linear": r["linear"], "cubic": r["p0"],
            "error_estimate": r["e0"], "rounding_level": r["rounding"], "nodes": r["z2"][:4],
            "times": r["t"][:4], "coefficients": r["coef"][:4]}
