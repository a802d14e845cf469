"""What a simulation's numbers do: blow-up, over the top, its energy's behaviour, its phase.

:func:`diagnose` reads a simulated trajectory's energy error ``(E - E0)/(m g l)`` and its
global error ``theta_sim - theta_exact`` (both as sampled values with their times) and
returns a :class:`Diagnosis`: the facts, each finding as a code with its numbers, and no
sentence (a presenter has the words, in the catalogues).

The energy's behaviour is read from the data, in units of the swing's energy ``E0`` (above
the bottom). A release at rest is a turning point, where a bounded energy error
(a symplectic method's: Hairer, Lubich & Wanner, "Geometric Numerical Integration", 2nd
ed., Springer 2006, IX.8) comes back to ``E0`` at every turn; so over the run's last
window (:data:`WINDOW_FRACTION` of the run and at least a period):

- ``decay`` (numerical damping) when the energy stays below ``E0 (1 -`` :data:`RETURN` ``)``
  all through it, ``growth`` when it stays above ``E0 (1 +`` :data:`RETURN` ``)``;
- else ``growth`` or ``decay`` (by the sign of its largest error) when the window's largest
  ``|E - E0|`` exceeds :data:`GROWTH` times that of the run's first window;
- else ``bounded``.

A damped run (``damping`` or ``drag`` of :func:`pendulab.numerics.simulation.simulate`)
loses its energy by design and has no exact motion to compare with: its energy and phase
are not judged, and one note, ``damped``, says so.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from .results import Result

__all__ = ["BOUNDED_LARGE", "ENERGY_WARN", "GROWTH", "PHASE_WARN", "RETURN", "WINDOW_FRACTION",
           "Diagnosis", "Finding", "diagnose", "energy_kind"]

#: An energy error above this fraction of the swing's energy ``E0`` is a finding.
ENERGY_WARN = 0.01
#: A bounded energy error above this fraction of ``E0`` is not the pendulum's motion.
BOUNDED_LARGE = 0.1
#: The energy "comes back" to ``E0`` when within this fraction of it.
RETURN = 0.01
#: The last window's largest error over the first's beyond which the error grows.
GROWTH = 1.5
#: Each window is this fraction of the run (and at least one period).
WINDOW_FRACTION = 0.25
#: A simulation further than this from the exact motion (rad, about 6 deg) is a finding.
PHASE_WARN = 0.1

EnergyKind = Literal["growth", "decay", "bounded"]
Kind = Literal["blow-up", "over-the-top", "energy-growth", "energy-decay", "energy-drift",
               "energy-oscillation", "energy-oscillation-large", "phase", "damped"]
Severity = Literal["wrong", "warn", "note"]


@dataclass(frozen=True, eq=False)
class Finding(Result):
    """One thing a simulation's numbers do.

    Attributes
    ----------
    kind : str
        ``blow-up`` (not a finite number from ``t`` on), ``over-the-top`` (``|theta| >= pi``
        at ``t``, which the real pendulum does not reach), ``energy-growth``, ``energy-decay``
        (numerical damping), ``energy-drift`` (a run too short to tell which),
        ``energy-oscillation`` (bounded, at most :data:`BOUNDED_LARGE`),
        ``energy-oscillation-large`` (bounded, above it), ``phase`` (beyond
        :data:`PHASE_WARN` of the exact motion from ``t`` on), ``damped`` (a damped run:
        energy and phase not judged).
    severity : str
        ``wrong`` (not the pendulum's motion), ``warn`` (out of step with the exact motion),
        ``note`` (a small bounded energy error).
    t : float or None
        When it starts (s); None for the energy's notes (the whole run).
    value : float or None
        ``max |E - E0| / E0`` for the energy's notes, ``max |theta_sim - theta_exact|``
        (rad) for ``phase``; None for the others.
    """

    kind: Kind
    severity: Severity
    t: float | None
    value: float | None


@dataclass(frozen=True, eq=False)
class Diagnosis(Result):
    """The findings of :func:`diagnose` (its notes), with the numbers they come from.

    Attributes
    ----------
    left_oscillation_t, nonfinite_t : float or None
        The first time over the top (not counted for a launch that goes round) and the
        first time not a finite number.
    max_energy_drift : float or None
        ``max |E - E0|`` in ``m g l`` (None where no sample is finite).
    energy_drift_relative : float or None
        The same over the swing's energy ``E0`` (None for a swing of no energy).
    energy_drift_kind : str or None
        ``growth``, ``decay`` or ``bounded`` (:func:`energy_kind`); None for a run shorter
        than two windows, or once over the top or blown up (the energy then says nothing more).
    max_theta_error : float or None
        ``max |theta_sim - theta_exact|`` over the error samples, rad.
    notes : tuple of Finding
        In order: blow-up, over the top, energy, phase; once over the top or blown up, the
        energy's and the phase's notes are left out (the motion is already not the pendulum's).
    """

    left_oscillation_t: float | None
    nonfinite_t: float | None
    max_energy_drift: float | None
    energy_drift_relative: float | None
    energy_drift_kind: EnergyKind | None
    max_theta_error: float | None
    notes: tuple[Finding, ...]

    @property
    def trustworthy(self) -> bool:
        """No finding of severity ``wrong`` or ``warn``."""
        return all(f.severity == "note" for f in self.notes)


def energy_kind(t: Any, drift: Any, period: float, t_end: float) -> EnergyKind | None:
    """``growth``, ``decay`` or ``bounded``: how ``drift = (E - E0)/E0`` at times ``t`` behaves.

    The rule of the module's docstring, over windows of ``max(period, WINDOW_FRACTION t_end)``;
    None when the run holds fewer than two windows or a window has no sample or a sample
    that is not finite.
    """
    t = np.asarray(t, dtype=float)
    r = np.asarray(drift, dtype=float)
    window = max(period, WINDOW_FRACTION * t_end)
    if not 2 * window <= t_end or not len(r):
        return None
    early, late = r[t <= window], r[t >= t_end - window]
    if not (len(early) and len(late)) or not (np.all(np.isfinite(early)) and np.all(np.isfinite(late))):
        return None
    lo, hi = float(np.min(late)), float(np.max(late))
    if hi < -RETURN:
        return "decay"
    if lo > RETURN:
        return "growth"
    if max(hi, -lo) > GROWTH * float(np.max(np.abs(early))):
        return "growth" if hi >= -lo else "decay"
    return "bounded"


def diagnose(swing: float, energy_t: Any, energy: Any, period: float, t_end: float,
             left_t: float | None = None, nonfinite_t: float | None = None,
             error_t: Any = None, error: Any = None, damped: bool = False) -> Diagnosis:
    """The findings of a simulated run (its notes).

    Parameters
    ----------
    swing : float
        The swing's energy ``E0`` above the bottom, in ``m g l`` (``1 - cos(alpha)`` from rest).
    energy_t, energy : array_like
        Times and energy errors ``(E - E0)/(m g l)`` (every extreme of the run among them:
        a min/max reduction of it will do).
    period : float
        The motion's period (s), the shortest window.
    t_end : float
        The run's last time (s).
    left_t, nonfinite_t : float or None
        The first time over the top (None where none, or where going round is right) and
        the first time not finite.
    error_t, error : array_like or None
        Times and ``theta_sim - theta_exact`` (rad).
    damped : bool
        A damped run: its energy falls by design, the exact motion is the undamped one; the
        energy's and the phase's findings give way to one note ``damped``.
    """
    e_t = np.asarray(energy_t, dtype=float)
    e = np.asarray(energy, dtype=float)
    ok = np.isfinite(e)
    drift = float(np.max(np.abs(e[ok]))) if ok.any() else None
    rel = drift / swing if drift is not None and swing > 0 else None
    gone = left_t is not None or nonfinite_t is not None  # the energy then says nothing more
    judged = not gone and not damped
    kind = energy_kind(e_t, e / swing, period, t_end) if rel is not None and judged else None
    notes: list[Finding] = []
    if nonfinite_t is not None:
        notes.append(Finding("blow-up", "wrong", nonfinite_t, None))
    if left_t is not None:
        notes.append(Finding("over-the-top", "wrong", left_t, None))
    if damped and not gone:
        notes.append(Finding("damped", "note", None, None))
    if rel is not None and rel > ENERGY_WARN and judged:
        if kind == "bounded":
            large = rel > BOUNDED_LARGE
            notes.append(Finding("energy-oscillation-large" if large else "energy-oscillation",
                                    "wrong" if large else "note", None, rel))
        else:
            notes.append(Finding(f"energy-{kind}" if kind else "energy-drift", "wrong", None, rel))  # type: ignore[arg-type]
    phase = None
    if error is not None and error_t is not None:
        err = np.asarray(error, dtype=float)
        fine = np.isfinite(err)
        if fine.any():
            phase = float(np.max(np.abs(err[fine])))
            if phase > PHASE_WARN and judged:
                first = float(np.asarray(error_t, dtype=float)[int(np.argmax(fine & (np.abs(np.where(fine, err, 0.0)) > PHASE_WARN)))])
                notes.append(Finding("phase", "warn", first, phase))
    return Diagnosis(left_oscillation_t=left_t, nonfinite_t=nonfinite_t,
                     max_energy_drift=drift if drift is None or math.isfinite(drift) else None,
                     energy_drift_relative=rel, energy_drift_kind=kind, max_theta_error=phase,
                     notes=tuple(notes))
