"""The result objects' notebook conventions: identity equality, read-only arrays, dicts, frames, HTML."""
import dataclasses
import html
import importlib
import math
import sys

import numpy as np
import pytest

from pendulab.core.errors import MissingExtraError
from pendulab.jobs.problems import problem2, problem5
from pendulab.numerics.crossing import estimate_period
from pendulab.numerics.interpolation import inverse_cubic
from pendulab.numerics.motion import global_error
from pendulab.numerics.results import Result, to_frame
from pendulab.numerics.simulation import simulate


@pytest.fixture(scope="module")
def tr():
    return simulate(1.0, math.pi / 4, 0.1, 2.1)


def test_equality_is_identity_and_hash_works(tr):
    twin = simulate(1.0, math.pi / 4, 0.1, 2.1)
    assert np.array_equal(tr.theta, twin.theta)
    assert (tr == twin) is False  # no "truth value of an array is ambiguous"
    assert tr == tr
    assert len({tr, twin, tr}) == 2


def test_arrays_are_read_only(tr):
    with pytest.raises(ValueError, match="read-only"):
        tr.theta[0] = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        tr.theta = np.zeros(3)


def test_the_callers_array_keeps_its_flags():
    z2 = np.array([0.3, 0.1, -0.1, -0.3])
    t = np.array([1.0, 1.1, 1.2, 1.3])
    r = inverse_cubic(z2, t, (0.5, 0.9))
    assert z2.flags.writeable and t.flags.writeable
    assert not r.z2.flags.writeable
    z2[0] = 7.0  # the caller may still change its own array


def test_every_result_class_is_a_frozen_identity_dataclass():
    for name in ("numerics.approximations", "numerics.group", "numerics.lsq", "numerics.newton", "jobs.problems",
                 "numerics.quadrature", "numerics.uncertainty"):
        importlib.import_module(f"pendulab.{name}")  # every result class is defined
    classes = list(_subclasses(Result))
    assert len(classes) >= 15
    for cls in classes:
        params = cls.__dataclass_params__
        assert params.frozen and not params.eq, cls


def _subclasses(cls):
    for sub in cls.__subclasses__():
        yield sub
        yield from _subclasses(sub)


@pytest.mark.slow
def test_to_dict_and_to_frame_of_a_trajectory(tr):
    d = tr.to_dict()
    assert list(d) == [f.name for f in dataclasses.fields(tr)] + ["n_steps"]  # the fields, then derived numbers
    assert d["n_steps"] == len(tr.t) - 1
    assert d["theta"] is tr.theta and d["method"] == "taylor2"
    df = tr.to_frame()
    assert list(df.columns) == ["t", "theta", "omega"]
    assert len(df) == 22
    # Figure 3 of the coursework: t = 2.1 -> z1 = 0.796774928412, z2 = -0.297068336875 (12 digits).
    assert df["theta"].iloc[-1] == pytest.approx(0.796774928412, abs=5e-13)
    assert df["omega"].iloc[-1] == pytest.approx(-0.297068336875, abs=5e-13)


def test_nested_results_become_dicts_and_rows_become_a_frame():
    est = estimate_period(1.0, math.pi / 4, 1e-3)
    d = est.to_dict()
    assert isinstance(d["interpolation"], dict)
    assert d["interpolation"]["value"] == est.cubic
    row = est.to_frame()
    assert len(row) == 1
    assert row["cubic"].iloc[0] == est.cubic
    assert (row["bracket_0"].iloc[0], row["bracket_1"].iloc[0]) == est.bracket

    p5 = problem5(ns=(10, 100))
    table = to_frame(p5.rows)
    assert table["n"].tolist() == [10, 100]
    assert table["estimate"].tolist() == [r.estimate for r in p5.rows]


def test_global_error_frame(tr):
    ge = global_error(tr)
    df = ge.to_frame()
    assert list(df.columns) == ["t", "theta_error", "omega_error", "energy_drift"]
    assert df["theta_error"].abs().max() == ge.max_theta_error


def test_to_frame_without_pandas_names_the_extra(monkeypatch, tr):
    monkeypatch.setitem(sys.modules, "pandas", None)
    # The tests run from a clone: the hint installs the extra into it, editable, with this Python.
    with pytest.raises(MissingExtraError, match=r"to_frame\(\) needs pandas, which is not installed: "
                                                r"\S*python\S* -m pip install -e '\S*\[pandas\]'"):
        tr.to_frame()


def test_html_shows_every_field_and_floats_in_full():
    p2 = problem2()
    page = p2._repr_html_()
    for f in dataclasses.fields(p2):
        assert f"<th style='text-align:left'>{f.name}</th>" in page
    assert f"<code>{p2.alpha!r}</code>" in page  # the shortest repr: every digit of the double
    # The result carries the decision; its words come from the catalogues (pendulab.report.words).
    from pendulab.report.words import sentence

    words = sentence("p2.justification." + ("positive" if p2.curvature_positive else "negative"))
    assert "curvature_positive" in page and html.escape(words) not in page
    assert "<details><summary>NewtonResult</summary>" in page


def test_a_sweep_is_a_table():
    from pendulab.jobs.sweep import sweep

    r = sweep(np.radians([30.0, 60.0]), [1e-3], ["taylor2"])
    assert not r["cubic"].flags.writeable
    df = r.to_frame()
    assert list(df.columns) == list(r.columns) and len(df) == len(r) == 2
    assert df["cubic_signed_error"].tolist() == r["cubic_signed_error"].tolist()
    assert r == r and r != sweep(np.radians([30.0, 60.0]), [1e-3], ["taylor2"])
