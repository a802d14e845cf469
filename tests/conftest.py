"""Shared test helpers."""
import json

import mpmath
import pytest

from pendulab.cli import main


class Run:
    def __init__(self, code, out, err):
        self.code, self.out, self.err = code, out, err

    @property
    def json(self):
        return json.loads(self.out)


@pytest.fixture
def cli(capsys):
    """Run ``pendulab ARGS`` in-process; return exit code, stdout, stderr."""

    def run(*args):
        code = main([str(a) for a in args])
        captured = capsys.readouterr()
        return Run(code, captured.out, captured.err)

    return run


def assert_one_line_error(res, *fragments):
    """Exit status 2, one line on stderr naming what is wrong, no traceback."""
    assert res.code == 2, (res.out, res.err)
    lines = res.err.strip().splitlines()
    assert len(lines) == 1, res.err
    assert "Traceback" not in res.err
    for f in fragments:
        assert f in lines[0], (f, lines[0])


def reference_period(length, alpha, g=9.80665, dps=50):
    """T = 4 sqrt(l/g) K(m), m = sin^2(alpha/2) (DLMF 19.2.8), in mpmath from the inputs' exact doubles.

    Independent of the library's AGM loop: the reference for every period test.
    """
    with mpmath.workdps(dps):
        m = mpmath.sin(mpmath.mpf(alpha) / 2) ** 2
        return 4 * mpmath.sqrt(mpmath.mpf(length) / mpmath.mpf(g)) * mpmath.ellipk(m)


def ellipk_period(length: float, alpha: float, g: float = 9.80665) -> float:
    """:func:`reference_period` at 30 digits, rounded to a double."""
    return float(reference_period(length, alpha, g, dps=30))
