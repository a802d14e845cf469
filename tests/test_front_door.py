"""A newcomer's path: the README's first screen, the bare command, the CLI's shared
conventions (--json, units, short options) and the notebook API."""
import inspect
import json
import math
import re
from pathlib import Path

import click
import numpy as np
import pytest

from pendulab.cli import SECTIONS, LazyGroup, cli, main
from reference import EXAMPLE_LENGTH
from test_glossary import json_keys

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
DOCS = ROOT / "docs"

# Words that tell how or when something was developed, not what it does.
HISTORY = re.compile(r"\b(previously|now|was fixed|used to|session|earlier run|"
                     r"nothing else running|the aim was|it was|they were)\b", re.IGNORECASE)


def _commands():
    ctx = click.Context(cli)
    return {name: cli.get_command(ctx, name) for name in cli.list_commands(ctx)}


# ------------------------------------------------------------------ the README

def test_readme_is_a_front_page():
    lines = README.read_text().splitlines()
    assert len(lines) <= 250
    assert lines[2:5] == [  # the first screen starts with the report's and the notebook's commands
        "```sh",
        "make report     # sets up .venv/ and writes report.pdf for the built-in example group (262, 407, 634)",
        "make notebook   # sets up .venv/ with JupyterLab and opens the tutorial (make tutorial: runs it headless)",
    ]
    text = "\n".join(lines)
    assert ".venv/bin/pendulab" in text and "source .venv/bin/activate" in text
    for target in re.findall(r"\]\(([^)#]+)\)", text):  # every relative link leads somewhere
        if "://" not in target:
            assert (ROOT / target).exists(), target


@pytest.mark.parametrize("path", [README, *sorted(DOCS.glob("*.md"))], ids=lambda p: p.name)
def test_no_history_in_readme_and_docs(path):
    found = HISTORY.findall(path.read_text())
    assert not found, found


#: Phrases that tell the code's history, in a comment or a docstring: the code says what
#: it does, the history is in git.
CODE_HISTORY = re.compile(
    r"\b(previously|formerly|until now|these days|was fixed|earlier run|the aim was"
    r"|used to (be|cost|take|run|give|return|print|fail|say|raise|hold|call|load)"
    r"|(it|they|this|that) (was|were) (-?inf|nan|fixed|wrong|broken|slower|faster|changed|removed|added"
    r"|echoed|printed|returned)"
    r"|before (it|they|these|this) (ran|were|was|had)|a checkout without|the old (code|version|way|loop)"
    r"|no longer (flattens|underflows|fails|raises|prints|returns|uses|calls|loads|takes|costs|needs|imports)"
    r"|(is|are) now (faster|slower|\w+ed)\b)|^#\s*(was|were) (-?inf|nan)\b", re.IGNORECASE | re.MULTILINE)

#: A timing in the package's prose (``6 ms``, ``0.7 us``, ``1.3x faster``, ``in two runs``):
#: measurements belong to ``benchmarks/`` and docs/performance.md, where a run writes them.
TIMING = re.compile(r"\b\d+(\.\d+)?(-\d+(\.\d+)?)? (ns|us|µs|ms)\b|\b\d+(\.\d+)?x (faster|slower)\b"
                    r"|\bin (two|three|four|\d+) runs\b|\bload (average )?\d")


def _prose(path: Path):
    """``(line, text)`` of each comment and docstring of a Python file; the whole of any other."""
    import io
    import tokenize

    text = path.read_text()
    if path.suffix != ".py":
        yield 1, text
        return
    for tok in tokenize.generate_tokens(io.StringIO(text).readline):
        if tok.type == tokenize.COMMENT or (
                tok.type == tokenize.STRING and tok.string.lstrip("rbfuRBFU").startswith(('"""', "'''"))):
            yield tok.start[0], tok.string


def _found(pattern, roots, suffixes):
    for root in roots:
        for path in sorted((ROOT / root).rglob("*")):
            if path.suffix in suffixes and ".min." not in path.name:
                for line, text in _prose(path):
                    for m in pattern.finditer(text):
                        yield f"{path.relative_to(ROOT)}:{line + text.count(chr(10), 0, m.start())}: {m.group(0)}"


@pytest.mark.parametrize("text, history", [
    ("# it was echoed as a repr", True), ("# Was inf at 1e-200", True), ("its rounding used to cost 2e-13", True),
    ("the kernels before they ran in pieces", True), ("run against a checkout without that branch", True),
    ("one method no longer flattens the others", True), ("the bound used to count digits", False),
    ("a process that no longer runs", False), ("a scalar argument was NaN", False), ("every file is as it was", False), ("S_n no longer depends on alpha", False),
])
def test_the_history_pattern(text, history):
    assert bool(CODE_HISTORY.search(text)) == history


@pytest.mark.parametrize("root", ["src", "tests", "benchmarks", "docs"])
def test_no_history_in_comments_and_docstrings(root):
    found = list(_found(CODE_HISTORY, [root], {".py", ".js", ".md", ".html", ".typ"}))
    assert not found, found


@pytest.mark.parametrize("text, timing", [
    ("about 0.7 us each", True), ("5.6 ms, 2.9 kB", True), ("512 bits run about 1.3x faster", True),
    ("rk4 2.16-2.23x in two runs", True), ("``10ms``, ``2s``", False), ("tens of ms", False),
])
def test_the_timing_pattern(text, timing):
    assert bool(TIMING.search(text)) == timing


def test_no_measurement_logs_in_the_packages_prose():
    found = list(_found(TIMING, ["src"], {".py", ".js", ".html", ".typ"}))
    assert not found, found


def _console_examples(text):
    """The ``$ pendulab ...`` lines of the README's console blocks, each with the output shown under it."""
    examples = []
    for block in re.findall(r"```console\n(.*?)```", text, re.DOTALL):
        for chunk in re.split(r"^(?=\$ )", block, flags=re.MULTILINE):
            if chunk.startswith("$ "):
                command, *output = chunk.rstrip("\n").split("\n")
                examples.append((command[2:], output))
    return examples


EXAMPLES = _console_examples(README.read_text())


def test_the_readme_shows_commands_with_their_output():
    assert len(EXAMPLES) >= 2 and all(cmd.startswith("pendulab ") for cmd, _ in EXAMPLES)


@pytest.mark.parametrize("command, shown", EXAMPLES, ids=[c for c, _ in EXAMPLES])
def test_readme_command_prints_what_the_readme_shows(cli_run, command, shown):
    res = cli_run(*command.split()[1:])
    assert res.code == 0, res.err
    printed = res.out.rstrip("\n").split("\n")
    assert [line.rstrip() for line in printed] == [line.rstrip() for line in shown]


@pytest.fixture
def cli_run(capfd):
    def run(*args):
        code = main(list(args))
        out, err = capfd.readouterr()
        return type("Run", (), {"code": code, "out": out, "err": err})

    return run


# ------------------------------------------------------------------ the command line

def test_bare_pendulab_shows_the_grouped_help_and_succeeds(cli_run):
    res = cli_run()
    assert res.code == 0 and res.err == ""
    for title in SECTIONS:
        assert f"{title} commands:" in res.out
    assert "Examples:" in res.out and "_PENDULAB_COMPLETE" in res.out
    # Each description whole: click's "..." marks a cut one.
    listing = res.out.split("Options:")[1].split("Examples:")[0]
    assert "..." not in listing
    for name in _commands():
        assert re.search(rf"^  {name} ", res.out, re.MULTILINE), name


def test_every_command_is_in_a_section_of_the_help():
    listed = {n for section in SECTIONS.values() for n in section}
    assert set(_commands()) <= listed


def test_every_command_but_serve_takes_json():
    commands = _commands()
    assert len(commands) >= 13
    for name, cmd in commands.items():
        flags = {opt for p in cmd.params for opt in getattr(p, "opts", ())}
        assert ("--json" in flags) == (name != "serve"), name


LENGTH_NAMES = {"length"}
TIME_NAMES = {"step", "steps", "t_max", "t0", "period", "target"}


def _options(names):
    for cmd_name, cmd in _commands().items():
        for p in cmd.params:
            if isinstance(p, click.Option) and p.name in names:
                yield cmd_name, cmd, p


def test_a_length_with_a_unit_is_accepted_wherever_a_length_is_typed():
    found = list(_options(LENGTH_NAMES))
    assert {c for c, _, _ in found} >= {"period", "simulate", "estimate", "gravity", "newton", "fit", "quadrature",
                                       "sweep"}
    for cmd_name, cmd, p in found:
        assert "-l" in p.opts, cmd_name  # the same short option everywhere
        ctx = click.Context(cmd)
        for text, metres in (("75cm", 0.75), ("750mm", 0.75), ("0.75m", 0.75), ("0.75", 0.75)):
            assert float(p.type.convert(text, p, ctx)) == metres, (cmd_name, text)


def test_a_time_with_a_unit_is_accepted_wherever_a_time_is_typed():
    found = list(_options(TIME_NAMES))
    assert len(found) >= 8
    for cmd_name, cmd, p in found:
        ctx = click.Context(cmd)
        value = p.type.convert("2s", p, ctx)
        assert (value == [2.0] if isinstance(value, list) else float(value) == 2.0), (cmd_name, p.name)
        value = p.type.convert("10ms", p, ctx)
        assert (value == [0.01] if isinstance(value, list) else float(value) == 0.01), (cmd_name, p.name)


def test_lengths_and_times_with_units_give_the_same_answers(cli_run):
    # l = 75 cm is l = 0.75 m; --step 100ms is 0.1 s: the same bytes on stdout.
    a = cli_run("simulate", "-l", "75cm", "--step", "100ms", "--t-max", "2.1s", "--json")
    b = cli_run("simulate", "-l", "0.75", "--step", "0.1", "--t-max", "2.1", "--json")
    assert a.code == b.code == 0 and a.out == b.out
    newton = cli_run("newton", "-l", "50cm", "--json")
    assert newton.code == 0 and json.loads(newton.out)["length"] == 0.5


def test_period_has_defaults_like_its_siblings(cli_run):
    res = cli_run("period")
    assert res.code == 0 and "6.21265033491832" in res.out  # problem 5's pendulum, 3.5 m at 4pi/5 (spec)


def test_every_command_names_its_defaults_in_help():
    for name, cmd in _commands().items():
        text = cmd.get_help(click.Context(cmd, info_name=name))
        for p in cmd.params:
            if isinstance(p, click.Option) and p.name in LENGTH_NAMES | {"amplitude"} and p.default is not None:
                assert p.show_default, (name, p.name)
        assert "Usage:" in text


def test_the_group_loads_commands_lazily():
    assert isinstance(cli, LazyGroup)


# ------------------------------------------------------------------ the notebook API

def test_the_notebook_names_import_from_the_package():
    import pendulab
    from pendulab import agm_period, estimate_period, period_digits, problem1, problem5, simulate

    assert simulate.__module__ == "pendulab.numerics.simulation" and estimate_period.__module__ == "pendulab.numerics.crossing"
    assert agm_period(1.0, 0.0) == pendulab.small_angle_period(1.0)
    assert period_digits("1", "0", digits=5) == "2.0064"  # 2 pi sqrt(1/9.80665) = 2.00640929...
    assert problem1.__module__ == problem5.__module__ == "pendulab.jobs.problems"
    assert set(pendulab.__all__) <= set(dir(pendulab))
    with pytest.raises(AttributeError):
        pendulab.no_such_name  # noqa: B018


def test_plots_draw_without_an_axes():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from pendulab import simulate
    from pendulab.plots import phase_portrait, time_series

    tr = simulate(1.0, math.pi / 4, step=0.1, t_max=2.1)
    fig = plt.figure()  # a new current figure: what an earlier test drew is not in it
    ax = time_series(tr)
    assert ax.figure is fig
    x, y = ax.lines[0].get_data()
    assert np.array_equal(x, tr.t) and np.array_equal(y, tr.theta)  # the 22 points of Figure 3
    assert ax.get_xlabel() == "t (s)"
    ax2 = phase_portrait(tr, ax=ax.figure.add_subplot(2, 1, 2))
    assert ax2 is not ax and len(ax2.collections) == 1  # the arrows
    long = simulate(1.0, math.pi / 4, step=1e-3, t_max=5.0)  # 5001 points: thinned to 400 arrows at most
    arrows = phase_portrait(long, ax=plt.figure().add_subplot()).collections[0]
    assert 300 <= len(arrows.get_offsets()) <= 400
    x, y = arrows.axes.lines[0].get_data()  # the points: the first and the last step among them
    assert (x[0], y[0]) == (long.theta[0], long.omega[0]) and (x[-1], y[-1]) == (long.theta[-1], long.omega[-1])
    circled = [line for line in ax2.lines if line.get_label().startswith("$P")]
    assert circled and circled[0].get_xdata()[0] == tr.amplitude


def test_plots_are_exported_with_the_result_first():
    import pendulab.plots as plots

    for name in plots.__all__:
        f = getattr(plots, name)
        params = list(inspect.signature(f).parameters.values())
        assert params[1].name == "ax" and params[1].default is None, name


def test_to_frame_and_the_notebook_view_show_the_errors():
    from pendulab import estimate_period

    est = estimate_period(EXAMPLE_LENGTH, 4 * math.pi / 5, step=1e-3)
    row = est.to_frame().iloc[0]
    for name in ("linear_error", "cubic_error", "dense_error"):
        assert row[name] == getattr(est, name)
        assert getattr(type(est), name).__doc__, name  # help() says what it is
        assert f"{name} <small>(derived)</small>" in est._repr_html_()
    # Problem 3(c): the error at h = 1e-3 is about 6.2e-7 s (the spec's T from (8) against the simulation).
    assert 1e-7 < row["cubic_error"] < 1e-6


def test_result_arrays_cannot_be_made_writeable_again():
    from pendulab import simulate

    tr = simulate(1.0, math.pi / 4, step=0.1, t_max=2.1)
    for arr in (tr.t, tr.theta, tr.omega):
        with pytest.raises(ValueError):
            arr.flags.writeable = True
        with pytest.raises(ValueError):
            arr[0] = 0.0


@pytest.mark.parametrize("args", [
    ["period", "--iterations", "7"], ["estimate", "--step", "1e-2,1e-3"], ["quadrature", "--substitution", "--n", "10,100"],
    ["fit"], ["newton"], ["gravity"], ["length", "262", "407", "634"],
], ids=lambda a: a[0])
def test_no_json_key_exact_names_a_period(cli_run, args):
    res = cli_run(*args, "--json")
    assert res.code == 0, res.err
    keys = set(json_keys(json.loads(res.out)))
    assert "exact" not in keys  # the glossary's names: period, t_hat, period_as_written
    assert keys & {"period", "t_hat", "length_text", "g", "alpha"}, keys


def test_public_functions_have_real_type_hints():
    from pendulab import estimate_period, period_digits, simulate

    for f in (period_digits, simulate, estimate_period):
        sig = str(inspect.signature(f))
        assert "Any" not in sig and "->" in sig, (f.__name__, sig)


def test_no_stray_public_names_in_the_period_module():
    import pendulab.numerics.period as period

    public = {n for n in dir(period) if not n.startswith("_")}
    assert not public & {"v", "sys", "threading", "math", "numbers"}
    assert set(period.__all__) <= public and "agm_period" in period.__all__
    assert "v" not in {n for n, _ in inspect.getmembers(period)}
