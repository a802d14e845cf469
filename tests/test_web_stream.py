"""The explorer's streamed pass (``engine.fold``) against a plain reference over a stored trajectory.

The reference stores every state (``simulation.simulate``, or the driver from a launched
state) and reduces it the obvious way, column by column with numpy; the pass must keep
the same steps and the same values, bit for bit, however the run is cut into pieces and
buffers.
"""
from __future__ import annotations

import math
import os
import signal

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pendulab.core.interrupt import CHUNK_COST
from pendulab.engine import fold, kernels
from pendulab.engine.kernels import drive
from pendulab.numerics import simulation
from pendulab.numerics.simulation import method_code
from pendulab.web import parameters, sampling
from signals import python_sigint


def reference(theta, omega, nb, samples, alpha, omega0, c):
    """Every column's extremes from the whole stored run: the smallest value's first step
    (NaN and +inf never count as smallest, as no value is below the +inf a column starts
    at), the largest value's last step (NaN never counts), ``-1`` for a column without one."""
    n = len(theta) - 1
    scale = 1.0 / (-2.0 * c)
    e0 = math.cos(alpha) - omega0 * omega0 * scale
    # C's cos (which math.cos calls), NaN at +-inf where math.cos raises.
    energy = np.array([w * w * scale - (math.cos(t) if math.isfinite(t) else math.nan) + e0
                       for t, w in zip(theta.tolist(), omega.tolist())])
    col = np.arange(n + 1) * nb // (n + 1)  # column b: the steps with floor(i nb/(n+1)) = b
    out = {k: np.full(nb, -1) for k in ("i_lo", "i_hi", "e_i_lo", "e_i_hi")}
    out |= {k: np.full(nb, np.nan) for k in ("th_lo", "th_hi", "om_lo", "om_hi", "e_lo", "e_hi")}
    for b in range(nb):
        steps = np.flatnonzero(col == b)
        for v, lo, hi, vlo, vhi in ((theta, "i_lo", "i_hi", "th_lo", "th_hi"), (energy, "e_i_lo", "e_i_hi", "e_lo", "e_hi")):
            vals = v[steps]
            low = steps[vals < np.inf]
            if len(low):
                out[lo][b] = low[np.argmin(v[low])]  # argmin: the first of equal ones
                out[vlo][b] = v[out[lo][b]]
            high = steps[~np.isnan(vals)]
            if len(high):
                out[hi][b] = high[::-1][np.argmax(v[high][::-1])]  # the last of equal ones
                out[vhi][b] = v[out[hi][b]]
        out["om_lo"][b] = omega[out["i_lo"][b]] if out["i_lo"][b] >= 0 else np.nan
        out["om_hi"][b] = omega[out["i_hi"][b]] if out["i_hi"][b] >= 0 else np.nan
    over = np.flatnonzero(~(np.abs(theta) < math.pi))
    bad = np.flatnonzero(~(np.isfinite(theta) & np.isfinite(omega)))
    out["left"] = int(over[0]) if len(over) else -1
    out["bad"] = int(bad[0]) if len(bad) else -1
    out["s_theta"], out["s_omega"] = theta[samples], omega[samples]
    return out


def assert_same(rec: fold.Record, ref) -> None:
    s = fold
    got = {"i_lo": rec.step[s.I_LO], "i_hi": rec.step[s.I_HI], "e_i_lo": rec.step[s.E_I_LO], "e_i_hi": rec.step[s.E_I_HI]}
    for k, v in got.items():
        assert np.array_equal(v, ref[k]), k
    for k, row, at in (("th_lo", s.TH_LO, s.I_LO), ("th_hi", s.TH_HI, s.I_HI), ("om_lo", s.OM_LO, s.I_LO),
                       ("om_hi", s.OM_HI, s.I_HI), ("e_lo", s.E_LO, s.E_I_LO), ("e_hi", s.E_HI, s.E_I_HI)):
        kept = rec.step[at] >= 0  # a column without a value keeps the +-inf it starts at
        # Bit for bit: the same doubles (NaN and the sign of zero included).
        assert np.array_equal(rec.value[row][kept].view(np.int64), ref[k][kept].view(np.int64)), k
    assert (int(rec.where[s.LEFT]), int(rec.where[s.BAD])) == (ref["left"], ref["bad"])
    assert np.array_equal(rec.s_theta.view(np.int64), ref["s_theta"].view(np.int64))
    assert np.array_equal(rec.s_omega.view(np.int64), ref["s_omega"].view(np.int64))


def samples_of(n: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return np.union1d([0, n], rng.integers(0, n + 1, size=min(n, 300)))


# n = t_max/h is never a multiple of the driver's buffer here; the pieces (size) cut
# across buffers; nb = n + 1 is a column per step, nb > n + 1 leaves columns empty.
CASES = [
    # method, length, alpha, h, t_max, nb, size
    ("taylor2", 2.08, 1.0, 1e-3, 10.007, 997, 3001),
    ("rk4", 1.0, 2.5, 1e-2, 50.0, 64, 1000),
    ("verlet", 1.0, 3.0, 0.05, 100.0, 333, 777),
    ("taylor:4", 3.5, 4 * math.pi / 5, 1e-2, 9.0, 901, 10**6),
    ("taylor:1", 1.0, 0.5, 1e-2, 30.0, 3001, 500),  # Euler: the energy grows, over the top
    ("taylor2", 1.0, 3.0, 0.5, 20.0, 41, 7),  # over the top
    ("taylor2", 1.0, 3.0, 1.0, 2000.0, 150, 2 * fold.BUFFER + 3),  # blows up: inf, then NaN
    ("taylor2", 1.0, 1.0, 0.1, 2.0, 500, 5),  # more columns than states: some stay empty
    ("rk4", 1.0, 1.0, 0.5, 1.0, 3, 1),  # two steps
    ("taylor2", 1.0, 0.0, 0.01, 3.0, 37, 100),  # at rest: every value ties, first and last kept
]


@pytest.mark.parametrize("method, length, alpha, h, t_max, nb, size", CASES)
def test_the_pass_keeps_what_the_stored_run_has(method, length, alpha, h, t_max, nb, size):
    g = 9.80665
    traj = simulation.simulate(length, alpha, h, t_max, g=g, method=method)
    n = len(traj.theta) - 1
    samples = samples_of(n, n)
    code, order = method_code(method)
    c = -g / length
    rec = kernels.folded(code, order, alpha, 0.0, c, h, n, nb, samples, size)
    assert_same(rec, reference(traj.theta, traj.omega, nb, samples, alpha, 0.0, c))


def test_the_blow_up_case_has_every_kind_of_value():
    # The case above that blows up reaches +-inf and NaN both, with finite steps before.
    th = simulation.simulate(1.0, 3.0, 1.0, 2000.0).theta
    assert np.isinf(th).any() and np.isnan(th).any() and np.isfinite(th[:5]).all()


@pytest.mark.parametrize("method, omega0", [("taylor2", 2.0), ("verlet", -7.0), ("rk4", 6.5)])
def test_a_launched_pass(method, omega0):
    # From (alpha, omega0): the stored run is the driver's from that state, kept whole.
    alpha, c, h, n = 0.5, -9.80665, 2e-3, 12_345
    code, order = method_code(method)
    th, om = np.empty(n + 1), np.empty(n + 1)
    th[0], om[0] = alpha, omega0
    drive(code, order, alpha, omega0, c, h, 0, n, 1, n, th[1:], om[1:])
    samples = samples_of(n, 1)
    rec = kernels.folded(code, order, alpha, omega0, c, h, n, 400, samples, 5000)
    assert_same(rec, reference(th, om, 400, samples, alpha, omega0, c))


@settings(max_examples=25, deadline=None)
@given(n=st.integers(1, 3 * fold.BUFFER), nb=st.integers(1, 400), size=st.integers(1, 10**5),
       alpha=st.sampled_from([0.0, 1e-3, 1.0, 3.0, 3.14159]), h=st.sampled_from([1e-3, 0.05, 0.9]))
def test_any_cut_keeps_the_same(n, nb, size, alpha, h):
    traj = simulation.simulate(9.80665, alpha, h, (n + 0.25) * h, g=9.80665)  # c = -g/l = -1
    n = len(traj.theta) - 1  # Round(t_max/h), as the web counts it
    samples = samples_of(n, size)
    rec = kernels.folded(*method_code("taylor2"), alpha, 0.0, -1.0, h, n, nb, samples, size)
    assert_same(rec, reference(traj.theta, traj.omega, nb, samples, alpha, 0.0, -1.0))


def test_simulate_arrays_draws_the_reference_columns():
    # The web's pass end to end: the kept steps and values are the reference's, in time order.
    q = parameters.simulation({"length": "1", "amplitude": "3", "step": "0.5", "t_max": "20"})
    sim = sampling.simulate_arrays(q, 30)
    traj = simulation.simulate(1.0, 3.0, 0.5, 20.0)
    ref = reference(traj.theta, traj.omega, sim["columns"], np.arange(41), 3.0, 0.0, -9.80665)
    idx = np.unique(np.r_[ref["i_lo"], ref["i_hi"]][np.r_[ref["i_lo"], ref["i_hi"]] >= 0])
    assert np.array_equal(sim["idx"], idx)
    assert np.array_equal(sim["theta"], traj.theta[idx]) and np.array_equal(sim["omega"], traj.omega[idx])
    assert sim["left"] == ref["left"] and sim["bad"] == ref["bad"] == -1


def test_ctrl_c_stops_the_pass_between_pieces(monkeypatch):
    """A real SIGINT sent while the third of 48 pieces runs: the pass ends after that piece
    (what it did is counted, not how long it took)."""
    code, order = method_code("taylor2")
    n = 200_000_000  # 48 pieces of CHUNK_COST steps
    real = kernels.drive
    calls = []

    def counted(*args):
        calls.append(args[6:8])  # (i0, i1)
        out = real(*args)
        if len(calls) == 3:
            os.kill(os.getpid(), signal.SIGINT)  # handled between two pieces (inside deferred)
        return out

    monkeypatch.setattr(kernels, "drive", counted)
    with python_sigint(), pytest.raises(KeyboardInterrupt):  # a run in the background inherits it ignored
        kernels.folded(code, order, 1.0, 0.0, -9.80665, 1e-5, n, 100, np.array([0, n]), CHUNK_COST)
    assert len(calls) == 3 and calls[-1][1] == 3 * CHUNK_COST < n
