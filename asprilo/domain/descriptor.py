"""What a problem domain is, as data: the descriptor every tool asks instead of testing a
domain's name.

A descriptor says which actions plans may use, what a delivery does, what the goal is,
which object kinds its instances use, which checker concerns judge its plans, which
reference encodings solve it, which lower bound and which anytime work model fit it, and
how the generator aligns its instances.  The built-in domains are the modules beside this
one (``a.py`` ... ``md.py``); docs/DOMAINS.md shows how to add one.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, fields
from enum import Enum
from typing import Any, ClassVar

from ..errors import InputError
from ..model import DIRECTIONS, Cell
from .templates import Resource


class Delivery(str, Enum):
    """What one ``deliver`` action does."""

    UNITS = "units"      # A: deliver(O,P,N) hands over N units; the line and the shelf's stock drop by N
    LINE = "line"        # B: deliver(O,P) closes the line (O,P) when the carried shelf holds P
    STATION = "station"  # C: one deliver closes every open line at the station that the carried shelf holds


class Goal(str, Enum):
    """What must hold at the horizon (and what the viewer frames as goals)."""

    LINES = "lines"                # every order line is fulfilled by deliveries
    SHELVES = "shelves"            # every order's shelf has a robot under it (M)
    DESTINATIONS = "destinations"  # every destination is occupied by a robot (Md)


class Bound(str, Enum):
    """Which admissible makespan bound applies (asprilo.bounds)."""

    MAPF = "mapf"          # the bottleneck assignment of robots to goal cells
    DELIVERY = "delivery"  # shelves brought to stations: arrivals, station schedules, trips


class Job(str, Enum):
    """What a robot's job is, for task assignment and the anytime planner."""

    GOALS = "goals"  # drive to a goal cell
    TRIPS = "trips"  # lift a shelf, bring it to stations, deliver, set it down


@dataclass(frozen=True)
class ReferenceEncoding:
    """A reference encoding: its name, its main file (relative to the ``asprilo/encodings/`` folder
    unless absolute), the clingo extension it needs (``"clingcon"``, ``"dl"`` or ``None``),
    whether it is incremental (``step(t)``/``check(t)`` parts, a ``query(t)`` external), a
    one-line summary, the program that names the robots of its anonymous models, and the
    clingo options it is solved with."""

    name: str
    program: str
    theory: str | None = None
    incremental: bool = False
    summary: str = ""
    names: str | None = None
    options: tuple[str, ...] = ()


@dataclass(frozen=True)
class Generation:
    """How ``gen`` makes instances of the domain: ``aligned`` to M (one single-unit line per
    order, one shelf per ordered product, as many orders as robots), with ``quantities`` or
    without, and the option values of an exercise-size instance (``asprilo demo``)."""

    aligned: bool = False
    quantities: bool = True
    exercise: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True, eq=False)
class Domain:
    """One problem domain.  Two descriptors are the same domain only if they are the same
    object: :func:`register` keeps one per name, and a pickled descriptor comes back as the
    registered one (in a process where its name is unknown, a child started by ``spawn``
    that never saw a domain registered at run time, it is registered there)."""

    value: str                           # the name on the command line: a, b, c, m, md
    label: str                           # the name in prose: A, B, C, M, Md
    summary: str
    actions: frozenset[str]              # the action names plans may use
    delivery: Delivery | None            # what deliver does (None: no deliveries)
    goal: Goal
    reads: frozenset[str]                # the object kinds its instances use
    checker: tuple[str, ...]             # checker concerns (asprilo/checker/<name>.lp, or absolute paths)
    encodings: tuple[ReferenceEncoding, ...]
    bound: Bound | None                  # None: no admissible bound known (a variant that relaxes the rules)
    work: Job
    generation: Generation | None        # None: gen does not make it (see ``made_by``)
    made_by: str = ""                    # how to get an instance when gen does not make one
    #: words for the domain's own checks: (module, check) -> describe(timeline, *params),
    #: which returns the sentence and what to highlight (see asprilo.simulate.messages)
    messages: Mapping[tuple[str, str], Callable[..., tuple[str, dict]]] = field(default_factory=dict)
    #: the moves robots may make, as (DX,DY): the four of SPEC.md unless a variant gives others
    directions: tuple[Cell, ...] = DIRECTIONS
    #: facts and constants the checker reads beside the instance and the plan (a variant's moves
    #: as ``direction/1`` facts, its costs as ``#const`` values)
    checker_facts: str = ""
    constants: tuple[tuple[str, int], ...] = ()
    #: per-robot resources that actions consume (a variant's energy): the timeline's levels
    resources: tuple[Resource, ...] = ()
    #: the rule variants that made this domain from its base, in order (``()`` for a built-in one)
    variants: tuple[str, ...] = ()
    #: attributes ``gen`` gives the objects: (kind, attribute, least, most), drawn uniformly
    attributes: tuple[tuple[str, str, int, int], ...] = ()

    A: ClassVar[Domain]
    B: ClassVar[Domain]
    C: ClassVar[Domain]
    M: ClassVar[Domain]
    MD: ClassVar[Domain]

    @property
    def delivers(self) -> bool:
        """Whether plans of this domain carry shelves to stations and deliver there."""
        return self.delivery is not None

    @property
    def counts_units(self) -> bool:
        """Whether quantities count: lines and stock drop by the units delivered."""
        return self.delivery is Delivery.UNITS

    @classmethod
    def parse(cls, text: str | Domain) -> Domain:
        """``a``/``B``/``md``... -> the registered domain; an unknown name is bad input."""
        if isinstance(text, Domain):
            return text
        found = _REGISTRY.get(str(text).lower())
        if found is None:
            names = ", ".join(_REGISTRY)
            raise InputError(f"unknown domain '{text}' (choose one of {names})")
        return found

    def __reduce__(self) -> tuple[Any, ...]:
        return _restored, (self.value, {item.name: getattr(self, item.name) for item in fields(self)})

    def __repr__(self) -> str:
        return f"Domain({self.label})"


_REGISTRY: dict[str, Domain] = {}


def _restored(name: str, values: dict[str, Any]) -> Domain:
    """An unpickled descriptor: the one registered under ``name``, else this one, registered."""
    return _REGISTRY.get(name) or register(Domain(**values))


def register(domain: Domain) -> Domain:
    """Make ``domain`` known to every tool under its name (a second one of the same name
    replaces the first)."""
    _REGISTRY[domain.value] = domain
    return domain


def unregister(domain: Domain) -> None:
    """Forget a domain registered for a while (a test's variant)."""
    if _REGISTRY.get(domain.value) is domain:
        del _REGISTRY[domain.value]


def domains() -> tuple[Domain, ...]:
    """Every registered domain, in the order of registration."""
    return tuple(_REGISTRY.values())
