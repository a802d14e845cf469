"""The integrators, as data: one registry for the kernels, the library, the CLI and the web.

A :class:`Method` is a name, the kernel branch that runs it (:class:`Kernel`), its order
and one line of description. :func:`resolve` turns what a person typed (``"rk4"``,
``"taylor:4"``) into a Method or raises :class:`~pendulab.core.errors.InputError` naming the
allowed names. :data:`METHODS` holds the named ones (the menus offer them, in order);
``taylor:P`` is the Taylor method of any order ``1 <= P <= MAX_TAYLOR_ORDER``.

The kernels' status codes (:class:`Status`) live here too, so ``engine.kernels``,
``crossing`` and ``sweep`` read the same numbers. This module imports nothing heavy.
"""
from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum

from .errors import InputError, shown

#: The largest order of the Taylor method of any order (size of its scratch arrays).
MAX_TAYLOR_ORDER = 30


class Kernel(IntEnum):
    """The branch of ``kernels.step`` that runs a method."""

    TAYLOR2 = 0  # the coursework's algorithm (3)
    RK4 = 1
    VERLET = 2
    TAYLOR = 3  # any order, by the recurrences of ``kernels.taylor_step``


class Status(IntEnum):
    """What ``kernels.first_return`` found."""

    FOUND = 0  # the sign change of theta' near P, with two points on either side
    NO_RETURN = 1  # no return to P within the steps allowed
    LEFT_OSCILLATION = 2  # |theta| reached pi: the discrete pendulum went over the top
    TOO_EARLY = 3  # the sign change came before two earlier points existed
    NODES_COINCIDE = 4  # theta' moves in subnormal steps: two of the five interpolation nodes z2 coincide
    UNTRUSTED = 5  # a return, but the energy error exceeds the distance to the separatrix or the estimate is a quarter period off


@dataclass(frozen=True)
class Method:
    """An integrator: ``name`` as typed, kernel ``code``, ``order`` and a description."""

    name: str
    code: Kernel
    order: int
    description: str


#: The named integrators, in the order the menus show them.
METHODS: dict[str, Method] = {
    m.name: m
    for m in (
        Method("taylor2", Kernel.TAYLOR2, 2, "the coursework's second-order Taylor algorithm (3)"),
        Method("rk4", Kernel.RK4, 4, "classical Runge-Kutta, order 4"),
        Method("verlet", Kernel.VERLET, 2, "Stormer-Verlet (velocity form), symplectic, order 2"),
    )
}

_FAMILY = "taylor:"


def allowed() -> str:
    """The allowed method names, in words (for messages and help)."""
    return "one of " + ", ".join(METHODS) + f", taylor:P (P an integer in [1, {MAX_TAYLOR_ORDER}])"


def resolve(name: object, argument: str = "method") -> Method:
    """The :class:`Method` called ``name``: a key of :data:`METHODS` or ``taylor:P``.

    ``taylor:2`` is (3) computed by the general recurrences. Anything else raises
    :class:`InputError` naming ``argument``.
    """
    if isinstance(name, Method):
        return name
    if isinstance(name, str):
        if name in METHODS:
            return METHODS[name]
        if name.startswith(_FAMILY):
            p = name[len(_FAMILY):]
            if p.isascii() and p.isdigit() and len(p) <= 3 and 1 <= int(p) <= MAX_TAYLOR_ORDER:
                return Method(name, Kernel.TAYLOR, int(p), f"Taylor method of order {int(p)}")

    raise InputError(argument, shown(name) if isinstance(name, str) else repr(name), allowed())


#: The cost of one step of each named method, relative to one step of (3) (taylor2):
#: measured by ``benchmarks/method_cost.py`` (the period search's kernel, CPU time), rounded.
STEP_COST: dict[Kernel, float] = {Kernel.TAYLOR2: 1.0, Kernel.RK4: 2.2, Kernel.VERLET: 1.1}
#: ``taylor:P`` costs ``a + b P + c P^2`` steps of (3): the fit of the same measurements
#: (its recurrences take ``O(P^2)`` operations; the fit is within 5% of each of P = 1..30).
TAYLOR_COST = (2.9, 0.40, 0.028)


def cost_per_step(method: object) -> float:
    """What one step of ``method`` costs, in steps of (3) (taylor2): the weight of every work limit.

    A limit of ``N`` steps of (3) allows ``N / cost_per_step(method)`` steps of ``method``.
    """
    m = resolve(method)
    if m.code == Kernel.TAYLOR:
        a, b, c = TAYLOR_COST
        return max(1.0, a + b * m.order + c * m.order * m.order)
    return STEP_COST[m.code]


def menu() -> list[Method]:
    """The methods a menu offers (the CLI's help, the web page's list): the named ones now."""
    return list(METHODS.values())
