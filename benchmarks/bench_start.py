"""Start-up: wall times of whole commands, side by side with their peers, as ratios.

1. ``pendulab period -l 3.5 -a 4pi/5`` against ``python -c "import numpy"`` (the floor of
   any numpy program): the scalar path imports neither numpy nor numba.
2. The first ``pendulab estimate`` (defaults) with an empty numba cache (a fresh install:
   ``NUMBA_CACHE_DIR`` set to a new folder) against the second (cache filled).
3. The same for ``pendulab report`` (skipped without the report extra).

Run: ``.venv/bin/python benchmarks/bench_start.py``. ``benchmarks/run.py`` prints these
rows in its table.
"""
from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
import tempfile
import time

PY = sys.executable


def wall(cmd: list[str], env: dict | None = None) -> float:
    t = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
    return time.perf_counter() - t


def period_row(repeat: int = 7) -> dict:
    cmds = {"period": [PY, "-m", "pendulab", "period", "-l", "3.5", "-a", "4pi/5"],
            "numpy": [PY, "-c", "import numpy"]}
    best = {k: float("inf") for k in cmds}
    for _ in range(repeat):  # taking turns, best of each
        for k, c in cmds.items():
            best[k] = min(best[k], wall(c))
    return {"what": "pendulab period -l 3.5 -a 4pi/5 (s, lower is better)", "ours": best["period"],
            "peer_name": 'python -c "import numpy"', "peer": best["numpy"], "target": "<= 1.2", "lower": True}


def cold_row(name: str, args: list[str], target: str, warm_runs: int = 2) -> dict:
    """First run with an empty numba cache, against the second run with it filled."""
    with tempfile.TemporaryDirectory(prefix="pendulab-numba-") as cache, \
            tempfile.TemporaryDirectory(prefix="pendulab-out-") as out:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        cmd = [PY, "-m", "pendulab", *args]
        cold = wall(cmd, env)
        warm = min(wall(cmd, env) for _ in range(warm_runs))
    del out
    return {"what": f"first pendulab {name}, empty numba cache (s)", "ours": cold,
            "peer_name": "the same, cache filled", "peer": warm, "target": target, "lower": True}


def start_rows() -> list[dict]:
    rows = [period_row(), cold_row("estimate", ["estimate"], "<= 3 s cold")]
    if importlib.util.find_spec("typst") and importlib.util.find_spec("matplotlib"):
        pdf = os.path.join(tempfile.mkdtemp(prefix="pendulab-report-"), "report.pdf")
        rows.append(cold_row("report", ["report", "--output", pdf], "<= 1.3", warm_runs=1))
    return rows


def main() -> None:
    from run import print_table

    print_table(start_rows())


if __name__ == "__main__":
    main()
