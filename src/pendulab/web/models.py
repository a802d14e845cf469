"""The shape of every answer the page reads: pydantic models, published in ``/openapi.json``.

The routes declare them as their response models, so the schema is the contract between
the server (:mod:`pendulab.web.views`) and the page (``static/app.js``); a test checks
real answers against it. No model allows a key it does not list. ``null`` in a list of
numbers is a value that is not a finite number (a simulation that blew up), or in the
phase portrait a break between two orbits.
"""
from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

Values = list[float | None]


class _Model(BaseModel):
    model_config = ConfigDict(extra="forbid")


class MethodEntry(_Model):
    name: str = Field(description="as typed in a query: taylor2, rk4, verlet, taylor:P")
    order: int
    description: str


class Limits(_Model):
    max_steps: int = Field(description="work of one request, in steps of the coursework's method (3); "
                                       "a dearer method gets proportionally fewer steps")
    max_points: int = Field(description="points of one /api/simulate answer")
    plot_points: int = Field(description="points of an /api/simulate answer that does not ask")


class Problem5(_Model):
    length: float
    amplitude: float


class ConfigAnswer(_Model):
    """``GET /api/config``."""

    methods: list[MethodEntry] = Field(description="the named methods of the registry, in menu order")
    family: list[MethodEntry] = Field(description="the Taylor method of every order, taylor:1 .. taylor:30")
    g_presets: dict[str, float] = Field(description="m/s^2")
    limits: Limits
    defaults: dict[str, str] = Field(description="the default view's query values, as text")
    problem5: Problem5
    lang: str = Field(description="the language of words: en or pt")
    words: dict[str, str] = Field(description="the catalogue's web. entries of lang, without the prefix")


class PeriodAnswer(_Model):
    """``GET /api/period``: the pendulum as read, its AGM and small-angle periods."""

    length: float = Field(description="m")
    amplitude: float = Field(description="rad")
    amplitude_deg: float
    g: float = Field(description="m/s^2")
    period: float = Field(description="the AGM period, equations (7)-(8), converged, s")
    small_angle_period: float = Field(description="2 pi sqrt(l/g), s")


class EstimateErrors(_Model):
    bracket_mid: float
    linear: float | None
    cubic: float | None


class EstimateShown(_Model):
    linear: str | None
    cubic: str | None
    linear_error: str | None
    cubic_error: str | None
    linear_relative: str | None
    cubic_relative: str | None


class Estimate(_Model):
    step: float
    method: str
    j: int = Field(description="index of the step after which theta' changes sign")
    bracket: list[float] = Field(min_length=2, max_length=2, description="[t_j, t_j+1], s")
    bracket_mid: float
    linear: float | None
    cubic: float | None = Field(description="the inverse-cubic estimate of problem 3(d), s")
    cubic_error_estimate: float | None
    errors: EstimateErrors = Field(description="absolute errors against the AGM period, s")
    shown: EstimateShown = Field(description="linear and cubic with only the digits their errors against the AGM "
                                             "period leave right (pendulab.core.digits.estimate_of), and their absolute and "
                                             "relative errors to 3 digits and those the period's half ulp leaves, as the "
                                             "page prints them")
    period: float = Field(description="the AGM period (converged), s")


#: The period search's outcome (``crossing.PeriodSearch.status``), or ``not_run`` where the
#: search does not run (the period too long for the step, a pendulum at rest, a launch).
SearchStatus = Literal["found", "no_return", "left_oscillation", "too_early", "nodes_coincide", "untrusted", "not_run"]


class PeriodWithEstimate(PeriodAnswer):
    estimate: Estimate | None
    status: SearchStatus
    reason: str | None = Field(description="why there is no estimate (no return, over the top, too long)")


class Input(_Model):
    length: float
    amplitude: float
    step: float
    t_max: float
    g: float
    method: str
    amplitude_deg: float
    damping: float = Field(description="gamma of theta'' = -(g/l) sin(theta) - gamma theta' - beta theta'|theta'|, 1/s")
    drag: float = Field(description="beta of the same equation, 1/rad")
    mass: float = Field(description="the bob's mass, kg: the energies in J are m g l times those in units of m g l; "
                                    "the motion does not depend on it")


class Units(_Model):
    t: str
    theta: str
    omega: str
    period: str
    energy: str


class Curve(_Model):
    t: list[float]
    theta: Values


class ErrorCurve(_Model):
    t: list[float]
    theta: Values = Field(description="theta_sim - theta_exact, rad")
    samples: int
    per_period: float | None


class Energy(_Model):
    t: list[float]
    drift: Values = Field(description="(E - E0)/(m g l)")


class Phase(_Model):
    theta: Values
    omega: Values
    t_first: float
    t_last: float
    stride: int
    orbits: int


class Frames(_Model):
    t: list[float]
    theta: Values
    omega: Values
    per_period: float | None


class Note(_Model):
    kind: Literal["blow-up", "over-the-top", "energy-growth", "energy-decay", "energy-drift",
                  "energy-oscillation", "energy-oscillation-large", "phase", "damped"] = Field(
        description="a finding of pendulab.numerics.diagnosis (its thresholds in docs/explorer.md)")
    severity: Literal["wrong", "warn", "note"] = Field(
        description="wrong: not the pendulum's motion; warn: out of step with the exact motion; "
                    "note: a small bounded energy error")
    text: str = Field(description="the finding in words, in the language asked for (lang)")


class Flags(_Model):
    left_oscillation_t: float | None
    nonfinite_t: float | None
    max_energy_drift: float | None
    energy_drift_relative: float | None
    energy_drift_kind: Literal["growth", "decay", "bounded"] | None = Field(
        description="growth, decay (numerical damping) or a bounded error, from the data "
                    "(null: a run too short to tell, or over the top or blown up)")
    max_theta_error: float | None = Field(description="max |theta_sim - theta_exact| over the error samples, rad")
    trustworthy: bool
    warnings: list[str] = Field(description="the texts of the notes of severity wrong or warn")
    notes: list[Note]


class State(_Model):
    theta: Values
    omega: Values


class Launch(_Model):
    """A pendulum released with an angular velocity (``omega0`` given and not 0): pendulab.numerics.launched."""

    omega0: float = Field(description="theta'(0), rad/s")
    k: float = Field(description="sqrt(E0/(2 m g l)): below 1 it swings, above 1 it goes round")
    circulates: bool
    period: float = Field(description="s: the period by the AGM (7)-(8), or the time for one turn when it goes round")
    turning_angle: float | None = Field(description="2 asin(k), rad, where it swings; null when it goes round")
    turning_angle_deg: float | None


class SimulateAnswer(_Model):
    """``GET /api/simulate``: what the page draws; every list at most ``limits.max_points`` long."""

    input: Input
    units: Units
    n_steps: int
    columns: int
    thinning: Literal["none", "min/max per column"]
    points: int
    t: list[float]
    theta: Values
    omega: Values
    exact: Curve = Field(description="the exact motion, drawn with the same column rule")
    error: ErrorCurve
    energy: Energy
    phase: Phase
    frames: Frames
    exact_frames: State = Field(description="the exact motion's state at the frames' times")
    exact_phase: State = Field(description="one period of the exact orbit in the phase plane")
    launch: Launch | None = Field(description="null for a release at rest")
    flags: Flags
    period: PeriodWithEstimate


class ConvergenceRow(_Model):
    step: float
    estimate: Estimate | None
    status: SearchStatus
    reason: str | None


class ConvergenceAnswer(_Model):
    """``GET /api/convergence``."""

    method: str
    order: int
    period: PeriodAnswer
    rows: list[ConvergenceRow]


class MotionAnswer(PeriodAnswer):
    """``GET /api/motion``: a pendulum's exact motion alone, its state 16 times a period."""

    frames: Frames


class Approximation(_Model):
    name: str = Field(description="a key of pendulab.numerics.approximations.FORMULAS")
    label: str
    source: str
    ratio: Values = Field(description="T_approx/T0 at each amplitude")


class PeriodCurveAnswer(_Model):
    """``GET /api/period_curve``: T(alpha)/T0 from 0 to 179 deg."""

    amplitude_deg: list[float]
    period_ratio: list[float] = Field(description="the AGM period over 2 pi sqrt(l/g)")
    approximations: list[Approximation]


class ErrorDetail(_Model):
    field: str
    value: int | float | str | None = Field(description="as typed")
    allowed: str = Field(description="the allowed range, in the request's lang")
    message: str = Field(description="one line in the request's lang: '<field> = <value> is not allowed: must be <allowed>' "
                                     "(pt: '<the field's word> = <value> não é permitido: deve ser <allowed>')")


class ErrorAnswer(_Model):
    """Status 422: the first bad parameter."""

    error: ErrorDetail
