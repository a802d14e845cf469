"""Sweeps of many pendulums: equal to one-at-a-time estimates, files, Dask, CLI."""
import json
import math

import mpmath
import numpy as np
import pyarrow.csv as pacsv
import pyarrow.parquet as pq
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pendulab.cli import main
from pendulab.core.errors import InputError
from pendulab.jobs.sweep import sweep
from pendulab.numerics.crossing import estimate_period
from pendulab.numerics.interpolation import inverse_cubic, inverse_cubic_rows
from pendulab.numerics.period import agm_period
from reference import EXAMPLE_LENGTH, G

AMPLITUDES = np.radians([5.0, 45.0, 120.0, 170.0, 179.0])


@pytest.mark.slow
@pytest.mark.parametrize("method", ["rk4", "verlet", "taylor:4"])
def test_sweep_equals_estimate_period_bit_for_bit(method):
    lengths = np.array([0.5, 1.0, EXAMPLE_LENGTH, 3.5, 1.0])
    r = sweep(AMPLITUDES, [1e-2, 1e-3], [method], lengths)
    assert len(r) == 10
    for row in range(len(r)):
        est = estimate_period(r["length"][row], r["amplitude"][row], r["step"][row], method=method)
        assert r["status"][row] == "found"
        assert r["steps"][row] == est.j + 2
        assert r["linear"][row] == est.linear
        assert r["cubic"][row] == est.cubic
        assert r["cubic_error_estimate"][row] == est.cubic_error_estimate
        assert r["period"][row] == agm_period(r["length"][row], r["amplitude"][row])


def test_inverse_cubic_rows_equals_inverse_cubic():
    rng = np.random.default_rng(1)
    z2 = np.sort(rng.normal(size=(20, 5)), axis=1)[:, ::-1]  # decreasing, distinct
    t = np.cumsum(rng.uniform(0.1, 1, size=(20, 5)), axis=1)
    p, err, *_ = inverse_cubic_rows(z2[:, 1:], t[:, 1:], z2[:, 0], t[:, 0])
    for i in range(20):
        ref = inverse_cubic(z2[i, 1:], t[i, 1:], (z2[i, 0], t[i, 0]))
        assert p[i] == pytest.approx(ref.value, rel=1e-14)
        assert err[i] == pytest.approx(ref.error_estimate, rel=1e-12)


def test_error_falls_with_the_step_and_failures_are_reported():
    r = sweep(np.radians([30.0, 179.5]), [0.2, 1e-2, 1e-3], ["taylor2"])
    big = r.select("taylor2", 0.2)
    # h = 0.2 and 1e-2 at 179.5 degrees: taylor2's energy error takes the discrete pendulum
    # over the top; the row says so (status) and carries NaN, not a guess.
    assert big["status"][1] == "left_oscillation"
    assert math.isnan(big["cubic"][1]) and math.isnan(big["cubic_signed_error"][1])
    e2 = abs(r.select("taylor2", 1e-2)["cubic_signed_error"][0])
    e3 = abs(r.select("taylor2", 1e-3)["cubic_signed_error"][0])
    assert 50 < e2 / e3 < 200  # order 2: a factor 100 for h / 10
    summary = r.summary()
    assert [s["step"] for s in summary] == [0.2, 1e-2, 1e-3]
    assert [s["found"] for s in summary] == [1, 1, 2]
    assert r.to_dict() == {"g": G, "summary": summary}  # not the rows: write() and to_frame() give them


def test_progress_counts_every_pendulum():
    seen = []
    sweep(np.radians(np.linspace(10, 80, 25)), [1e-2, 5e-3], ["rk4", "verlet"], progress=seen.append, chunk=7)
    assert sum(seen) == 25 * 2 * 2 and max(seen) == 7


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_write_round_trip(tmp_path, suffix):
    r = sweep(np.radians([20.0, 60.0]), [1e-2], ["taylor2", "rk4"])
    path = tmp_path / f"sweep{suffix}"
    r.write(path)
    table = pacsv.read_csv(path) if suffix == ".csv" else pq.read_table(path)
    assert table.column("method").to_pylist() == ["taylor2", "taylor2", "rk4", "rk4"]
    assert np.array_equal(table.column("cubic").to_numpy(), r["cubic"])  # full precision
    assert [p.name for p in tmp_path.iterdir()] == [path.name]  # no temporary left behind


def test_bad_inputs(tmp_path):
    with pytest.raises(InputError, match="method"):
        sweep([0.5], [1e-2], ["taylor:0"])
    with pytest.raises(InputError, match="step"):
        sweep([0.5], [0.0], ["rk4"])
    with pytest.raises(InputError, match="amplitude"):
        sweep([0.5, math.pi], [1e-2])
    with pytest.raises(InputError, match="amplitude"):
        sweep([], [1e-2])
    with pytest.raises(InputError, match="lengths"):
        sweep([0.5, 0.6], [1e-2], lengths=[1.0, 2.0, 3.0])
    r = sweep([0.5], [1e-2])
    with pytest.raises(InputError, match="output"):
        r.write(tmp_path / "x.txt")
    with pytest.raises(InputError, match="output"):
        r.write(tmp_path / "missing" / "x.csv")


@pytest.mark.slow
def test_dask_cluster_gives_the_same_result():
    import dask.distributed as distributed  # part of the test extra
    amplitudes = np.radians(np.linspace(1, 179, 23))
    local = sweep(amplitudes, [1e-2, 2e-3], ["taylor2", "rk4"], lengths=1.3, chunk=5)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False, protocol="tcp",
                                  host="127.0.0.1", dashboard_address=None) as cluster:
        assert cluster.scheduler_address.startswith("tcp://127.0.0.1:")
        seen = []
        remote = sweep(amplitudes, [1e-2, 2e-3], ["taylor2", "rk4"], lengths=1.3, chunk=5,
                       scheduler=cluster.scheduler_address, progress=seen.append)
    assert sum(seen) == len(local)
    assert local.columns.keys() == remote.columns.keys()
    for key, col in local.columns.items():
        assert np.array_equal(col, remote.columns[key], equal_nan=col.dtype.kind == "f"), key


@pytest.mark.slow
def test_unreachable_scheduler_is_one_clear_error(monkeypatch):
    monkeypatch.setattr("pendulab.jobs.sweep.cluster.CONNECT_TIMEOUT", 1)
    with pytest.raises(InputError, match="scheduler"):
        sweep([0.5], [1e-2], scheduler="tcp://127.0.0.1:9")  # port 9 (discard): nothing listens


@pytest.mark.slow
def test_cli_sweep(tmp_path, capsys):
    out, plot = tmp_path / "s.parquet", tmp_path / "s.png"
    args = ["sweep", "--amplitude", "10deg:170deg:9", "--step", "1e-2,1e-3", "--method", "taylor2,taylor:3",
            "--output", str(out), "--plot", str(plot), "--json"]
    assert main(args) == 0
    doc = json.loads(capsys.readouterr().out)
    assert [(s["method"], s["step"]) for s in doc["summary"]] == [
        ("taylor2", 0.01), ("taylor2", 0.001), ("taylor:3", 0.01), ("taylor:3", 0.001)]
    assert pq.read_table(out).num_rows == 36 and plot.read_bytes().startswith(b"\x89PNG")


def test_the_sweep_table_prints_only_right_digits(tmp_path, capsys):
    """rk4 at h = 1e-4, errors near 1e-13: the printed largest |T_cubic - T| and relative
    error within one unit of their last digit of the true ones (mpmath's period of each
    pendulum), which the doubles' half ulp moves by up to 9 units of a 4th digit."""
    out = tmp_path / "s.csv"
    assert main(["sweep", "--amplitude", "0.1:3:7", "--step", "1e-3,1e-4", "--method", "rk4",
                 "--output", str(out)]) == 0
    lines = capsys.readouterr().out.splitlines()[1:3]
    rows = pacsv.read_csv(out).to_pydict()
    with mpmath.workdps(40):
        for line, h in zip(lines, (1e-3, 1e-4)):
            cells = line.split()
            assert float(cells[1]) == h
            mine = [i for i, step in enumerate(rows["step"]) if step == h]
            true = [2 * mpmath.pi * mpmath.sqrt(1 / mpmath.mpf("9.80665")) / mpmath.agm(1, mpmath.cos(mpmath.mpf(rows["amplitude"][i]) / 2))
                    for i in mine]
            err = [abs(mpmath.mpf(rows["cubic"][i]) - t) for i, t in zip(mine, true)]
            for text, want in ((cells[3], max(err)), (cells[4], max(e / t for e, t in zip(err, true)))):
                place = int(text.split("e")[1]) - len(text.split("e")[0].split(".")[1])
                assert abs(mpmath.mpf(text) - want) <= mpmath.mpf(10) ** place, (text, mpmath.nstr(want, 8))


def test_plot_draws_one_line_per_method_and_step():
    """What sweep_errors draws: for each (method, step), the found pendulums' |cubic error|
    against the amplitude in degrees, floored at 1e-17 for the log scale."""
    import matplotlib.pyplot as plt

    from pendulab.plots.beyond import sweep_errors

    r = sweep(np.radians([10, 90, 179.9]), [1e-2, 0.5], methods=["taylor2"])
    fig, given = plt.subplots()
    ax = sweep_errors(r, given)
    plt.close(fig)
    assert ax is given
    assert [line.get_label() for line in ax.lines] == ["taylor2, h = 0.01", "taylor2, h = 0.5"]
    for line, row in zip(ax.lines, r.summary()):
        sel = r.select(row["method"], row["step"])
        ok = sel["status"] == "found"
        x, y = line.get_data()
        assert np.array_equal(x, np.degrees(sel["amplitude"][ok]))
        assert np.array_equal(y, np.maximum(np.abs(sel["cubic_signed_error"][ok]), 1e-17))
    assert len(ax.lines[1].get_xdata()) < 3  # h = 0.5 at 179.9 deg goes over the top: not drawn


@pytest.mark.parametrize("args,needle", [
    (["--amplitude", "170deg:10deg:9"], "--amplitude = 170deg:10deg:9"),  # reversed
    (["--amplitude", "10deg:10deg:9"], "empty or reversed"),
    (["--amplitude", "1deg:180deg:9"], "--amplitude"),
    (["--method", "taylor:0"], "--method = taylor:0 is"),  # as typed, no quotes
    (["--step", "0"], "--step"),
    (["--output", "out.xlsx"], "--output"),
])
def test_cli_sweep_bad_input(args, needle, capsys):
    assert main(["sweep", *args]) == 2
    err = capsys.readouterr().err
    assert needle in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err


@pytest.mark.slow
@pytest.mark.parametrize("threads", [1, 2, 3])
@pytest.mark.parametrize("code", [0, 1])  # taylor2 (lock-step lanes), rk4 (serial kernel)
def test_threads_give_one_thread_bit_for_bit(threads, code):
    from pendulab.jobs.sweep import BLOCK, first_returns, first_returns_lanes, first_returns_serial

    m = 3 * BLOCK + 5  # blocks of unequal size
    rng = np.random.default_rng(7)
    alphas = rng.uniform(0.1, 3.1, m)  # unsorted: first_returns sorts by step count
    cs = -G / rng.uniform(0.5, 3, m)
    n = rng.integers(1000, 4000, m)
    one = first_returns_lanes(alphas, cs, 1e-2, n) if code == 0 else first_returns_serial(code, 4, alphas, cs, 1e-2, n)
    many = first_returns(code, 4, alphas, cs, 1e-2, n, threads=threads)
    assert len(one[0]) == m
    for a, b in zip(one, many):
        assert np.array_equal(a, b)


@pytest.mark.parametrize("threads", [1, 2])
@pytest.mark.parametrize(("code", "order"), [(0, 2), (1, 4), (3, 6)])  # taylor2 (lanes), rk4, taylor:6
def test_blocks_run_in_small_pieces_give_one_call_bit_for_bit(monkeypatch, threads, code, order):
    """Each block of the sweep runs in pieces (so that Ctrl+C stops it between two); with
    pieces of a few hundred steps, each pendulum (n = 0 .. 6000, found or not, over the top
    for (3)) equals the kernels' one call over all the steps, bit for bit."""
    from pendulab.engine import kernels
    from pendulab.engine import lanes as sweep_kernel
    from pendulab.jobs.sweep import BLOCK, first_returns, first_returns_lanes, first_returns_serial

    rng = np.random.default_rng(11)
    m = 2 * BLOCK + 7
    alphas = np.concatenate([[0.0, 1e-3, 3.1, 3.14159, 2.0, 1.0, 1.0], rng.uniform(0.1, 3.1, m - 7)])
    cs = -G / rng.uniform(0.3, 3.0, m)
    n = np.concatenate([[1000, 1000, 3000, 5000, 0, 1, 3], rng.integers(10, 6000, m - 7)])
    one = first_returns_lanes(alphas, cs, 1e-2, n) if code == 0 else first_returns_serial(code, order, alphas, cs, 1e-2, n)
    if code != 0:  # the serial searches are the scalar kernel's one call per pendulum
        for i in range(m):
            ref = kernels.first_return(code, order, alphas[i], cs[i], 1e-2, n[i])
            assert (one[0][i], one[1][i]) == ref[:2] and np.array_equal(one[2][i], ref[2]) and np.array_equal(one[3][i], ref[3])
    monkeypatch.setattr(sweep_kernel, "CHUNK_COST", 997)  # lock-step pieces of 997 // 16 steps
    monkeypatch.setattr(kernels, "CHUNK_COST", 997)  # the scalar searches' pieces
    cut = first_returns(code, order, alphas, cs, 1e-2, n, threads=threads)
    for a, b in zip(one, cut, strict=True):
        assert np.array_equal(a, b)
    assert {0, 1} <= set(one[0].tolist()) and (code != 0 or 2 in one[0])  # found, no return, over the top


def test_lanes_sincos_within_one_ulp():
    """The lock-step kernel's sine and cosine against mpmath, over the range theta takes."""
    from pendulab.engine.lanes import sincos

    xs = np.concatenate([np.random.default_rng(3).uniform(-3.2, 3.2, 3000),
                         [0.0, 1e-300, -1e-8, np.pi / 4, np.pi / 2, 3 * np.pi / 4, np.pi, -np.pi, 3.2]])
    for x in xs:
        s, c = sincos(x)
        with mpmath.workdps(40):
            for got, ref in ((s, mpmath.sin(x)), (c, mpmath.cos(x))):
                assert abs(mpmath.mpf(got) - ref) <= np.spacing(abs(float(ref))), (x, got)


def test_lanes_follow_the_serial_search_in_every_case():
    """Status and j as first_return's for every outcome (found, no return, too early, over
    the top, n = 0 .. 3); the windows agree to rounding."""
    from pendulab.jobs.sweep import first_returns_lanes, first_returns_serial

    alphas = np.repeat([0.0, 1e-3, 1.0, 2.5, 3.1, 3.14159], 2 * 3 * 7)
    cs = np.tile(np.repeat(-G / np.array([1.0, 0.02]), 3 * 7), 6)
    hs = np.tile(np.repeat([1e-1, 1e-2, 1e-3], 7), 12)
    n = np.tile([0, 1, 2, 3, 10, 1000, 100000], 36)
    outcomes = set()
    for h in (1e-1, 1e-2, 1e-3):
        k = hs == h
        a = first_returns_serial(0, 2, alphas[k], cs[k], h, n[k])
        b = first_returns_lanes(alphas[k], cs[k], h, n[k])
        assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])
        assert np.allclose(a[2], b[2], rtol=0, atol=1e-11) and np.allclose(a[3], b[3], rtol=0, atol=1e-9)
        outcomes |= set(a[0].tolist())
    assert outcomes == {0, 1, 2}  # found, no return, left the oscillation


@pytest.mark.slow
def test_lanes_vectorise():
    """The lock-step loop compiles to packed (SIMD) double-precision arithmetic."""
    import platform

    from numba import njit

    from pendulab.engine.lanes import _lanes

    if platform.machine() not in ("x86_64", "AMD64"):
        pytest.skip(f"the check reads x86-64 assembly; this machine is {platform.machine()}")
    # Compiled afresh (a kernel loaded from numba's cache has no assembly text to show).
    fresh = njit(nogil=True)(_lanes.py_func)
    z = np.zeros((6, 1))
    z[0] = 1.0
    fresh(np.array([-9.8]), 0.1, np.array([10]), 0, 11, z, *(np.zeros(1, np.int64),) * 3,
          np.zeros((1, 5)), np.zeros((1, 5)))
    asm = "".join(fresh.inspect_asm().values())
    assert "mulpd" in asm and "addpd" in asm


def test_lanes_estimates_within_the_stated_bound_of_estimate_period():
    """The sweep's (3) runs the lock-step kernel: its estimates differ from estimate_period's
    (the scalar kernel) by rounding only. Bound (the sweep kernel's documentation): relative
    1e-9 up to 179.9 degrees, 2e-7 up to 179.99, and 5 % of the estimate's own error up to
    179.999 (the adversarial search is tests/test_bounds_adversarial.py)."""
    alphas = np.radians(np.concatenate([np.linspace(0.5, 179.5, 40), [179.9, 179.99, 179.999]]))
    lengths = np.linspace(0.3, 5, len(alphas))
    for h in (1e-2, 1e-3, 1e-4):
        r = sweep(alphas, [h], ["taylor2"], lengths)
        found = np.flatnonzero(r["status"] == "found")
        assert len(found) >= len(alphas) - 3
        for i in found:
            est = estimate_period(r["length"][i], r["amplitude"][i], h)
            for key in ("linear", "cubic"):
                ours, theirs = r[key][i], getattr(est, key)
                if r["amplitude"][i] <= np.radians(179.9):
                    assert abs(ours - theirs) <= 1e-9 * theirs, (h, i, key)
                if r["amplitude"][i] <= np.radians(179.99):
                    assert abs(ours - theirs) <= 2e-7 * theirs, (h, i, key)
                assert abs(ours - theirs) <= 5e-2 * abs(theirs - est.period), (h, i, key)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.integers(0, 10**6), min_size=0, max_size=200), st.integers(1, 20), st.integers(1, 10**7))
def test_tasks_cut_the_pendulums_into_whole_groups_that_hold_the_work(n, block, work):
    """The sweep's tasks: in order, covering every pendulum once, whole groups of ``block``
    (but the last), each the fewest groups whose steps reach ``work`` (or the rest)."""
    from pendulab.engine.lanes import tasks

    n = np.array(n, dtype=np.int64)
    cut = tasks(n, block, work)
    if len(n) == 0:
        assert cut == []
        return
    assert [lo for lo, _ in cut] == [0] + [hi for _, hi in cut[:-1]] and cut[-1][1] == len(n)
    for lo, hi in cut:
        assert lo % block == 0 and (hi % block == 0 or hi == len(n)) and hi > lo
        groups = [n[g:min(g + block, hi)].sum() for g in range(lo, hi, block)]
        assert sum(groups[:-1]) < work  # one group fewer would not hold the work
        assert sum(groups) >= work or hi == len(n)
