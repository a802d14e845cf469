"""Simulation of the pendulum (2) by the coursework's second-order Taylor algorithm (3), (6).

With ``damping`` ``gamma`` (1/s) and ``drag`` ``beta`` (1/rad) the equation is
``theta'' = -(g/l) sin(theta) - gamma theta' - beta theta'|theta'|``: a linear damping (a
viscous friction at the pivot) and a quadratic one (air drag on the bob), each per unit of
``m l^2`` so that the mass does not enter (:func:`pendulab.engine.kernels.damped_step`).

:func:`simulate` gives a :class:`Trajectory`: the lists ``(t_i, z1_i)`` and
``(z1_i, z2_i)`` of problem 3. The loop itself is :func:`pendulab.engine.kernels.trajectory`.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core import methods as _methods
from ..core import validate as v
from ..core.cases import G
from .results import Result

#: The largest trajectory kept in memory (points); longer runs stream (crossing.py).
MAX_POINTS = 10_000_001
#: The most steps of (3) one simulation may take (seconds on one core); other methods'
#: steps count by their cost (:func:`pendulab.core.methods.cost_per_step`).
MAX_STEPS = 2_000_000_000


def method_code(method: str) -> tuple[int, int]:
    """The kernel code and order of the integrator named ``method`` (:func:`pendulab.core.methods.resolve`)."""
    m = _methods.resolve(method)
    return int(m.code), m.order


def step_count(t0: float, t_max: float, step: float) -> int:
    """``N = Round((t_max - t0)/h)``, equation (6) (round half to even, like Mathematica's Round)."""
    return int(round((t_max - t0) / step))


@dataclass(frozen=True, eq=False)
class Trajectory(Result):
    """The points ``Z_j = (z1_j, z2_j)`` at times ``t_j = t0 + j h``, ``j = 0..N``.

    Attributes
    ----------
    t, theta, omega : ndarray, shape (N+1,)
        ``t_j``, ``z1_j ~ theta(t_j)`` and ``z2_j ~ theta'(t_j)``.
    length, amplitude, g, step, t0 : float
        The inputs.
    method : str
        The integrator's name.
    damping, drag : float
        ``gamma`` (1/s) and ``beta`` (1/rad) of the damped equation (module docstring); 0: (2).
    """

    t: np.ndarray
    theta: np.ndarray
    omega: np.ndarray
    length: float
    amplitude: float
    g: float
    step: float
    t0: float
    method: str = "taylor2"
    damping: float = 0.0
    drag: float = 0.0

    @property
    def n_steps(self) -> int:
        """``N`` of (6): the steps simulated (more than ``len(t) - 1`` when thinned)."""
        return int(round((self.t[-1] - self.t0) / self.step))

    def _columns(self) -> dict[str, np.ndarray]:
        return {"t": self.t, "theta": self.theta, "omega": self.omega}

    def time_series(self) -> np.ndarray:
        """List (i) of problem 3: the points ``(t_i, z1_i)``, shape (N+1, 2)."""
        return np.column_stack([self.t, self.theta])

    def phase_points(self) -> np.ndarray:
        """List (ii) of problem 3: the points ``(z1_i, z2_i)``, shape (N+1, 2)."""
        return np.column_stack([self.theta, self.omega])


def kept_steps(n: int, stride: int, lo: int = 0, hi: int | None = None) -> np.ndarray:
    """The steps of a run of ``n`` steps kept at ``stride``, from ``lo`` to ``hi`` (default ``n``).

    The trajectory driver's rule (``kernels.drive``): every multiple of ``stride``, and the
    last step ``n`` where ``hi`` is ``n``. Over the whole run, sorted, without repeats, ``0``
    and ``n`` kept: ``n // stride + 1`` steps, one more where ``stride`` does not divide ``n``.
    """
    hi = n if hi is None else hi
    idx = np.arange(-(-lo // stride) * stride, hi + 1, stride, dtype=np.int64)
    if hi == n and n % stride:
        idx = np.append(idx, np.int64(n))
    return idx


def stride_for(n: int, points: int) -> int:
    """The smallest stride at which :func:`kept_steps` keeps at most ``points`` (at least 2)
    of the steps ``0 .. n``: ``ceil(n / (points - 1))``, and 1 where all fit."""
    return max(1, -(-n // (points - 1)))


def simulate(
    length: float,
    amplitude: float,
    step: float,
    t_max: float,
    t0: float = 0.0,
    g: float = G,
    method: str = "taylor2",
    stride: int = 1,
    damping: float = 0.0,
    drag: float = 0.0,
) -> Trajectory:
    """Simulate ``theta'' = c sin(theta)``, ``c = -g/l`` (2), from rest at ``alpha``.

    Parameters
    ----------
    length : float
        ``l`` > 0, m.
    amplitude : float
        ``alpha`` in ``[0, pi)``, rad.
    step : float
        ``h``, with ``0 < h < t_max - t0``.
    t_max, t0 : float
        The interval ``[t0, t_max]``; ``N = Round((t_max - t0)/h)`` steps (6).
    g : float
        m/s^2.
    method : str
        ``"taylor2"``: the coursework's algorithm (3) (default); ``"rk4"``, ``"verlet"``,
        ``"taylor:P"``: see :func:`method_code`.

    stride : int
        Keep every ``stride``-th point (and the last): the steps are all taken, only
        the storage is thinned, e.g. for plotting a run with a small step.
    damping, drag : float
        ``gamma >= 0`` (1/s) and ``beta >= 0`` (1/rad): the damped equation of the module's
        docstring (0 and 0: the pendulum (2), the same points bit for bit).

    Returns
    -------
    Trajectory
    """
    length, alpha, g = v.pendulum(length, amplitude, g)
    t0, t_max, step = v.time_span(t0, t_max, step)
    code, order = method_code(method)
    stride = v.integer("stride", stride, 1)
    damping = v.non_negative("damping", damping)
    drag = v.non_negative("drag", drag)
    # Work and memory by arithmetic, before anything is allocated.
    limit = v.steps_for(method, MAX_STEPS)  # weighed by the method's cost
    n = v.steps_within("step", t0, t_max, step, limit, v.steps_of(method))
    kept = n // stride + 1 + (n % stride != 0)
    if kept > MAX_POINTS:
        raise v.step_limit("step", step, t0, t_max, MAX_POINTS - 1, "points kept", kept - 1,
                           "or a shorter t_max, or a stride")
    index = kept_steps(n, stride)
    from ..engine.kernels import thinned, trajectory

    if stride == 1:
        z1, z2 = trajectory(code, order, alpha, -g / length, step, n, damping, drag)
    else:
        z1, z2 = thinned(code, order, alpha, -g / length, step, n, stride, len(index), damping, drag)
    t = t0 + step * index
    return Trajectory(t, z1, z2, length, alpha, g, step, t0, method, damping, drag)
