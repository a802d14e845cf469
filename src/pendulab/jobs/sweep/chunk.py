"""One chunk of a sweep: the AGM periods, the kernel, and the estimates of problem 3(d).

The window of five points around the sign change gives the linear and the inverse cubic
estimates, vectorised over the pendulums by the functions :func:`pendulab.numerics.crossing.estimate_period`
uses (:func:`pendulab.numerics.interpolation.linear_zero`, :func:`pendulab.numerics.interpolation.inverse_cubic_rows`).
:func:`run_chunk` is pure: a Dask worker runs it as it is.
"""
from __future__ import annotations

import numpy as np

from ...core.methods import Status
from ...engine.lanes import first_returns
from ...numerics.crossing import untrusted
from ...numerics.interpolation import inverse_cubic_rows, linear_zero
from ...numerics.period import agm_period


def run_chunk(code: int, order: int, alphas: np.ndarray, lengths: np.ndarray, g: float, h: float,
               parallel: bool = True) -> dict[str, np.ndarray]:
    """The period search for one chunk of pendulums with one method and step (pure)."""
    from ...numerics.crossing import default_t_max
    from ...numerics.simulation import step_count

    periods = np.asarray(agm_period(lengths, alphas, g), dtype=float)
    n_steps = np.array([step_count(0.0, default_t_max(float(T), h), h) for T in periods], dtype=np.int64)
    cs = -g / lengths
    # One thread on a Dask worker (the worker's own threads run the chunks); the same kernel
    # as on all cores, so the same results bit for bit.
    status, j, z1w, z2w = first_returns(code, order, alphas, cs, h, n_steps, threads=None if parallel else 1)
    # As search_period: where theta' moves in subnormal steps two nodes z2 can coincide
    coincide = np.any(np.diff(np.sort(z2w, axis=1), axis=1) == 0, axis=1)
    status = np.where((status == Status.FOUND) & coincide, int(Status.NODES_COINCIDE), status)
    t = (j[:, None] - 2 + np.arange(5)) * h  # t_k = k h (6): nodes j-2 .. j+2
    with np.errstate(invalid="ignore", divide="ignore"):
        linear = linear_zero(t[:, 2], h, z2w[:, 2], z2w[:, 3])
        cubic, err_est, *_ = inverse_cubic_rows(z2w[:, 1:5], t[:, 1:5], z2w[:, 0], t[:, 0])
        # As search_period: a return whose energy error exceeds the distance to the separatrix,
        # or whose estimate is a quarter period off, is untrusted (its estimates are kept).
        a = alphas[:, None]
        drift = np.max(np.abs(0.5 * z2w * z2w - 2 * cs[:, None] * np.sin(0.5 * (z1w + a)) * np.sin(0.5 * (z1w - a))),
                       axis=1)
        distance = -2 * cs * np.cos(0.5 * alphas) ** 2
        doubt = (status == Status.FOUND) & untrusted(drift, distance, cubic, periods)
    status = np.where(doubt, int(Status.UNTRUSTED), status)
    found = (status == Status.FOUND) | doubt
    nan = np.full(len(alphas), np.nan)
    linear = np.where(found, linear, nan)
    cubic = np.where(found, cubic, nan)
    err_est = np.where(found, err_est, nan)
    # Steps taken: j + 2 when it returns (one past the sign change), else the index reported.
    steps = np.where(found, j + 2, np.where(status == Status.LEFT_OSCILLATION, j + 1, j))
    return {
        "period": periods,
        "status": status,
        "steps": steps,
        "linear": linear,
        "cubic": cubic,
        "cubic_error_estimate": err_est,
    }
