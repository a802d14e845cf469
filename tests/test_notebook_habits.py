"""What a notebook user meets first: the names of ``dir(pendulab)``, typed signatures, plots
and tables that say how to install what they need, the way this copy was installed."""
import inspect
import sys

import pytest

import pendulab
from pendulab import MissingExtraError, estimate_period, simulate
from pendulab.core import extras


def test_dir_shows_only_the_public_names():
    assert dir(pendulab) == sorted(pendulab.__all__)
    assert not {"TYPE_CHECKING", "annotations", "lazy", "_WHERE"} & set(dir(pendulab))
    for name in pendulab.__all__:
        assert getattr(pendulab, name) is not None


def test_every_public_signature_is_typed_without_any():
    for name in pendulab.__all__:
        f = getattr(pendulab, name)
        if inspect.isfunction(f):
            text = str(inspect.signature(f))
            assert "Any" not in text and "->" not in text.split(")")[0], (name, text)
            assert all(p.annotation is not inspect.Parameter.empty for p in inspect.signature(f).parameters.values()), name
            assert inspect.signature(f).return_annotation is not inspect.Signature.empty, name


def test_a_plot_without_matplotlib_says_how_to_install_it(monkeypatch):
    from pendulab.plots import time_series

    tr = simulate(1.0, 0.5, 0.1, 1.0)
    for name in [m for m in sys.modules if m == "matplotlib" or m.startswith("matplotlib.")] + ["matplotlib"]:
        monkeypatch.setitem(sys.modules, name, None)
    with pytest.raises(MissingExtraError, match=r"pendulab.plots needs matplotlib, which is not installed: .*\[report\]'"):
        time_series(tr)


def test_a_plot_of_the_wrong_result_says_what_it_draws():
    from pendulab.plots import phase_portrait, time_series

    est = estimate_period(1.0, 0.5, step=0.01)
    for f in (time_series, phase_portrait):
        with pytest.raises(TypeError, match=r"draws a Trajectory \(pendulab.simulate\(...\)\), not PeriodEstimate"):
            f(est)


def test_the_install_hint_fits_a_clone_and_a_package(monkeypatch, tmp_path):
    # This checkout: src/ beside pyproject.toml, so the extra goes into it, editable, with this Python.
    root = extras.install_command("pandas")
    assert root.endswith("-m pip install -e '.[pandas]'") or "-m pip install -e '/" in root
    assert sys.executable in root or root.startswith(".") or "/" in root.split()[0]
    # A package installed by pip (no pyproject.toml beside it): pip install 'pendulab[pandas]'.
    fake = tmp_path / "site-packages" / "pendulab" / "core"
    fake.mkdir(parents=True)
    monkeypatch.setattr(extras, "__file__", str(fake / "extras.py"))
    assert extras.install_command("pandas") == "pip install 'pendulab[pandas]'"
