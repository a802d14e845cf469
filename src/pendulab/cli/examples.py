"""The examples at the end of each command's ``--help``: command lines that run as shown.

``tests/test_cli_examples.py`` runs every one (in a folder holding ``groups.txt``, the
file the ``key`` examples read).
"""
from __future__ import annotations

#: command -> (command line, what it shows); the command lines start with ``pendulab``.
EXAMPLES: dict[str, tuple[tuple[str, str], ...]] = {
    "period": (
        ("pendulab period -l 75cm -a 30deg", "your pendulum's period"),
        ("pendulab period -a 0.9999999pi --iterations 7", "near 180 deg: as typed, of the doubles, T^"),
        ("pendulab period --digits 40 --json", "40 proved digits, as JSON"),
    ),
    "simulate": (
        ("pendulab simulate", "Figure 3's table: l = 1, alpha = pi/4, h = 0.1 to t = 2.1"),
        ("pendulab simulate --step 10ms --t-max 5 --csv", "CSV t,theta,omega at full precision"),
        ("pendulab simulate --plot fig1.png --phase fig2.png", "Figures 1 and 2"),
    ),
    "estimate": (
        ("pendulab estimate", "problem 3(c)-(d) for the example group"),
        ("pendulab estimate -l 1 -a pi/4 --step 1e-2 1e-3 --dense", "two steps, with dense output"),
    ),
    "length": (
        ("pendulab length 262 407 634", "the example group's length"),
        ("pendulab length 12345,23456,34567 --json", "another group, as JSON"),
    ),
    "gravity": (
        ("pendulab gravity", "problem 1 with the coursework's measurements"),
        ("pendulab gravity -l 99.4cm --period 2.0 --period-error 0.01", "your own measurements"),
    ),
    "newton": (
        ("pendulab newton", "problem 2: T~(alpha) = 1.5 s for l = 0.5 m"),
        ("pendulab newton --target 1.6 --x0 60deg", "another target and start"),
    ),
    "fit": (
        ("pendulab fit", "problem 4: the normal equations and the coefficients"),
        ("pendulab fit --round none --plot fit.png", "unrounded, with the plot"),
    ),
    "quadrature": (
        ("pendulab quadrature", "problem 5(d): n = 1 to 10^5"),
        ("pendulab quadrature --n 1 10 100 --substitution", "three n, also after the substitution"),
    ),
    "programs": (
        ("pendulab programs -o programs", "the programs, with English comments"),
        ("pendulab programs -o programas --lang pt", "with Portuguese comments"),
    ),
    "approximations": (
        ("pendulab approximations", "the table of relative errors"),
        ("pendulab approximations --plot formulas.png", "with the plot"),
    ),
    "sweep": (
        ("pendulab sweep -a 10deg:170deg:9 --step 1e-2 --method taylor2 rk4", "9 amplitudes, 2 methods"),
        ("pendulab sweep -a 1deg:179deg:100 -o sweep.csv", "every pendulum's row to a file"),
    ),
    "report": (
        ("pendulab report --students 262 407 634", "report.pdf for the example group"),
        ("pendulab report --students 262,407,634 --lang pt -o relatorio.pdf", "in Portuguese"),
    ),
    "key": (
        ("pendulab key --groups groups.txt", "the key as a table (groups.txt: one group a line, 262 407 634)"),
        ("pendulab key --groups groups.txt -o key.csv", "as CSV, for a spreadsheet"),
    ),
    "mark": (
        ("pendulab mark --groups groups.txt --answers answers.csv",
         "each answer marked (answers.csv: pendulab key --groups groups.txt --template answers -o answers.csv)"),
        ("pendulab mark --groups groups.txt --answers answers.csv -o marked.pdf", "the marked sheet as a PDF"),
    ),
    "serve": (
        ("pendulab serve", "the explorer at http://127.0.0.1:8000/"),
        ("pendulab serve --port 8001", "on another port"),
    ),
}


def epilog(command: str) -> str | None:
    """The ``Examples:`` block of ``command``'s help (``\\b``: click keeps its lines as written)."""
    rows = EXAMPLES.get(command)
    if not rows:
        return None
    width = max(len(line) for line, _ in rows) + 2
    return "\b\nExamples:\n" + "\n".join(f"  {line:{width}}{what}" for line, what in rows)
