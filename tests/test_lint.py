"""ruff (src/, tests/, benchmarks/) and mypy (src/), as configured in pyproject.toml, are clean (``make test`` runs this)."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("tool", [["ruff", "check", "src", "tests", "benchmarks"], ["mypy"]], ids=["ruff", "mypy"])
def test_clean(tool):
    env = dict(os.environ, MYPY_CACHE_DIR=str(ROOT / ".mypy_cache"))
    res = subprocess.run([sys.executable, "-m", *tool], cwd=ROOT, capture_output=True, text=True, env=env, timeout=600)
    assert res.returncode == 0, res.stdout[-6000:] + res.stderr[-2000:]
