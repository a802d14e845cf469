"""Start-up: wall times of whole commands, side by side with their peers, as ratios.

1. ``pendulab period -l 3.5 -a 4pi/5`` against ``python -c "import numpy"`` (the floor of
   any numpy program): the scalar path imports neither numpy nor numba.
2. The first ``pendulab estimate`` (defaults) with an empty numba cache (a fresh install:
   ``NUMBA_CACHE_DIR`` set to a new folder) against the second (cache filled); best of 3
   such pairs.
3. The same for ``pendulab report``, best of 2 pairs (skipped without the report extra).

For the cold starts the CPU time of the command (user + sys, ``RUSAGE_CHILDREN``) is
given too: on a machine shared with other work the wall time mostly measures the wait for
a core, the CPU time what the command itself spent.

Run: ``.venv/bin/python benchmarks/bench_start.py``. ``benchmarks/run.py`` prints these
rows in its table.
"""
from __future__ import annotations

import importlib.util
import os
import sys
import tempfile

from _peers import run

PY = sys.executable


def wall(cmd: list[str], env: dict | None = None) -> float:
    return run(cmd, env)[0]


def period_row(repeat: int = 7) -> dict:
    cmds = {"period": [PY, "-m", "pendulab", "period", "-l", "3.5", "-a", "4pi/5"],
            "numpy": [PY, "-c", "import numpy"]}
    best = {k: float("inf") for k in cmds}
    for _ in range(repeat):  # taking turns, best of each
        for k, c in cmds.items():
            best[k] = min(best[k], wall(c))
    return {"what": "pendulab period -l 3.5 -a 4pi/5 (s, lower is better)", "ours": best["period"],
            "peer_name": 'python -c "import numpy"', "peer": best["numpy"], "target": "<= 1.2", "lower": True}


def cold_rows(name: str, args: list[str], target: str, rounds: int = 3) -> list[dict]:
    """Runs with an empty numba cache against runs with it filled, taking turns: each round
    a new empty cache, a cold run that fills it, then a warm run; the best of each (wall
    time, then CPU time), as for every other row (one cold run alone measured mostly the
    load of the moment: 2.5 s and 4.1 s for the same commit)."""
    cold, warm = [], []
    for _ in range(rounds):
        with tempfile.TemporaryDirectory(prefix="pendulab-numba-") as cache:
            env = dict(os.environ, NUMBA_CACHE_DIR=cache)
            cmd = [PY, "-m", "pendulab", *args]
            cold.append(run(cmd, env))
            warm.append(run(cmd, env))
    return [
        {"what": f"first pendulab {name}, empty numba cache (s)", "ours": min(c[0] for c in cold),
         "peer_name": "the same, cache filled", "peer": min(w[0] for w in warm), "target": target, "lower": True},
        {"what": "  same, CPU time (user + sys, s)", "ours": min(c[1] for c in cold),
         "peer_name": "the same, cache filled", "peer": min(w[1] for w in warm), "target": "", "lower": True},
    ]


def start_rows() -> list[dict]:
    rows = [period_row(), *cold_rows("estimate", ["estimate"], "<= 3 s cold")]
    if importlib.util.find_spec("typst") and importlib.util.find_spec("matplotlib"):
        with tempfile.TemporaryDirectory(prefix="pendulab-report-") as out:
            rows += cold_rows("report", ["report", "--output", os.path.join(out, "report.pdf")], "<= 1.3", rounds=2)
    return rows


def main() -> None:
    from _peers import print_table

    print_table(start_rows())


if __name__ == "__main__":
    main()
