"""The warm report against the import floor, side by side in one run, as a ratio.

``pendulab report`` for the example group (after a first run, not timed, that fills the
caches: the operating system's files, matplotlib's fonts) against ``python -c "import numpy, matplotlib.pyplot, typst"``: the least any
program that computes, draws and typesets must pay. The two commands take turns, and the
best of each is kept (wall time, then CPU time: user + sys of the child). On a machine
shared with other work the wall time mostly measures the wait for a core, the CPU time
what the command itself spent. Then where the report's own time goes, in one process
(CPU time of the imports, per section, of the figures alone, and of the typesetting).

Target: the warm report at most 2.5 times the floor.

Run: ``.venv/bin/python benchmarks/bench_report.py [--repeat N]``.
"""
from __future__ import annotations

import gc
import os
import sys
import tempfile
import time

from _peers import run

PY = sys.executable
EXAMPLE = (262, 407, 634)
#: Warm includes the modules' compiled bytecode (pip writes it on install, Python on an
#: editable install's first run): with PYTHONDONTWRITEBYTECODE set the report would pay
#: for compiling pendulab's sources on every run while the floor's packages do not.
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def report_rows(repeat: int = 5) -> list[dict]:
    with tempfile.TemporaryDirectory(prefix="pendulab-bench-report-") as out:
        cmds = {
            "report": [PY, "-m", "pendulab", "report", "--output", os.path.join(out, "report.pdf")],
            "floor": [PY, "-c", "import numpy, matplotlib.pyplot, typst"],
        }
        run(cmds["report"], ENV)  # fills the caches (bytecode, the OS's files, matplotlib's fonts): the warm report
        best = {k: [float("inf"), float("inf")] for k in cmds}
        for _ in range(repeat):  # taking turns, best of each
            for k, c in cmds.items():
                wall, cpu = run(c, ENV)
                best[k] = [min(best[k][0], wall), min(best[k][1], cpu)]
    peer = "import numpy, mpl.pyplot, typst"
    return [
        {"what": "pendulab report, warm (wall s)", "ours": best["report"][0], "peer_name": peer,
         "peer": best["floor"][0], "target": "<= 2.5", "lower": True},
        {"what": "  same, CPU time (user + sys, s)", "ours": best["report"][1], "peer_name": peer,
         "peer": best["floor"][1], "target": "<= 2.5", "lower": True},
    ]


def breakdown() -> dict[str, float]:
    """CPU time of the imports (those of the floor's command included), of each section, of
    the figures within them, and of the typesetting (s)."""
    from pathlib import Path

    t = time.process_time()
    import matplotlib.backends.backend_svg  # what the figures load
    import matplotlib.figure  # noqa: F401
    import typst  # noqa: F401

    from pendulab.jobs import coursework, problems  # noqa: F401  the engine's sections
    from pendulab.report import builder, figures, sections

    coursework.load()  # the programs: numpy, scipy.linalg, mpmath
    imports = time.process_time() - t
    drawn = [0.0]
    draw = figures.draw

    def timed(*args, **kwargs):
        t = time.process_time()
        try:
            return draw(*args, **kwargs)
        finally:
            drawn[0] += time.process_time() - t

    figures.draw = timed
    out = {"imports": imports}
    gc.disable()  # as ``pendulab report`` runs
    try:
        with tempfile.TemporaryDirectory() as folder:
            doc = builder.new_doc(EXAMPLE, "en", Path(folder))
            for label, section in sections.SECTIONS:
                t = time.process_time()
                section(doc, EXAMPLE)
                out[label] = time.process_time() - t
            t = time.process_time()
            builder.compile_pdf(doc, EXAMPLE)
            out["typesetting"] = time.process_time() - t
    finally:
        figures.draw = draw
        gc.enable()
    out["(of which figures)"] = drawn[0]
    return out


def main() -> None:
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from _peers import print_table

    repeat = int(sys.argv[sys.argv.index("--repeat") + 1]) if "--repeat" in sys.argv else 5
    print(f"load average {os.getloadavg()[0]:.2f} (1 min), {os.cpu_count()} CPUs")
    print_table(report_rows(repeat))
    print("\nWhere the report's time goes (CPU s, one process):")
    for label, seconds in breakdown().items():
        print(f"  {label:20s} {seconds:6.2f}")
    print(f"load average now {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
