"""What a caller asks :func:`~asprilo.encodings.solve` for: one :class:`SolveRequest`.

A request names the instance and its domain, the method and what the method needs (the
encoding of the horizon search), the horizons, the task assignment, the limits and whether
to run in a child process.  It may carry the lower bounds (:class:`.LowerBounds`) when the
caller knows them; otherwise they are computed once at the start of the solve and the
request handed to the method carries them.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TypedDict

import clingo

from asprilo.domain import Domain, Job
from asprilo.errors import InputError
from asprilo.model import Instance, Plan

from ..assignment import Assignment
from ..registry import Encoding
from .bounds import LowerBounds


@dataclass(frozen=True)
class SolveRequest:
    """One solve: ``instance`` in ``domain`` by ``method`` (a name of the method table).

    ``encoding``: the program of the horizon search (``None``: the domain's ``plain``
    reference encoding; a user's own :class:`~asprilo.encodings.Encoding` works as well).
    ``horizon``: solve at this makespan only; without it, search the minimal makespan upwards
    from the lower bound, up to ``max_horizon``.  ``assign``: compute a task assignment first
    and follow it, then (unless ``tighten`` is false) try shorter plans without it for a
    while; ``assignment``: follow this one instead (implies ``assign``).  ``time_limit``
    (seconds) and ``memory_limit`` (MB, with ``isolate``) bound the whole solve; ``isolate``
    runs it in a child process, so that the limits hold while clingo grounds.  ``bounds``:
    the lower bounds, when the caller has them.

    ``stage``: a first stage of a two-stage encoding (the exact search only), e.g. a task
    assignment of one's own: a program solved once with the instance and the encoding's
    constants (and the horizon, when one is given); the shown atoms of its first answer become
    facts of the encoding at every horizon, as ``clingo stage.lp inst.lp | clingo - plan.lp
    inst.lp`` pipes them (:mod:`.stage`).  A horizon refuted then is refuted along that answer
    only.  Make it with :func:`asprilo.encodings.choice.stage_encoding`.

    ``start``: a plan of this reading to start from (the anytime planner reports it first and
    only shorter ones after it; :func:`given_start` makes one of a file, or of a plan under a
    stronger reading).
    """

    instance: Instance
    domain: Domain
    method: str = "asp"
    encoding: Encoding | None = None
    horizon: int | None = None
    max_horizon: int | None = None
    assign: bool = False
    assignment: Assignment | None = None
    tighten: bool = True
    time_limit: float | None = None
    memory_limit: int | None = None
    isolate: bool = False
    bounds: LowerBounds | None = None
    stage: Encoding | None = None
    start: Plan | None = None

    @property
    def lower_bound(self) -> float:
        """The makespan bound (the request a method runs carries its bounds)."""
        if self.bounds is None:
            raise ValueError("the request carries no lower bounds yet")
        return self.bounds.makespan


class SolveOptions(TypedDict, total=False):
    """The keywords of :func:`~asprilo.encodings.solve` that make its request, as the
    caller gives them: ``encoding`` by name (or an :class:`Encoding`) and ``assignment`` as
    ``assign`` facts (an earlier outcome's ``assignment.facts``); ``encoding`` ``None``: the
    domain's default (:func:`~asprilo.encodings.registry.default_encoding`); ``stage`` as an
    :class:`Encoding` or its files; ``start`` as a :class:`Plan` or its file."""

    method: str
    encoding: str | Encoding | None
    horizon: int | None
    max_horizon: int | None
    assign: bool
    assignment: Sequence[str] | None
    tighten: bool
    time_limit: float | None
    memory_limit: int | None
    isolate: bool
    bounds: LowerBounds | None
    stage: Encoding | Sequence[str | Path] | None
    start: Plan | str | Path | None


def given_assignment(instance: Instance, domain: Domain, facts: Sequence[str]) -> Assignment:
    """A caller's assignment facts, each checked to name this instance's robots and goals."""
    if not facts:
        raise InputError("the given assignment is empty")
    shapes = [["robot", "shelf", "pickingStation"]] if domain.work is Job.TRIPS else [["robot", "shelf"],
                                                                              ["robot", "destination"]]
    tables = {"robot": instance.robots, "shelf": instance.shelves, "pickingStation": instance.stations,
              "destination": instance.destinations}
    for fact in facts:
        try:
            term = clingo.parse_term(fact)
            names = [(argument.name, argument.arguments[0].number) for argument in term.arguments]
        except (RuntimeError, IndexError, AttributeError):
            raise InputError(f"not an assignment fact: {fact!r}") from None
        if term.name != "assign" or [kind for kind, _ in names] not in shapes:
            raise InputError(f"not an assignment fact of domain {domain.label}: {fact}")
        for kind, number in names:
            if number not in tables[kind]:
                raise InputError(f"the assignment names {kind} {number}, which the instance lacks")
    return Assignment(sorted(facts), origin="given")


def given_start(instance: Instance, domain: Domain, start: Plan | str | Path) -> Plan:
    """A plan to start from (a :class:`Plan` or its file), as a plan of ``domain``: one of
    this reading, or of a stronger one turned into this one
    (:func:`asprilo.encodings.anytime.readings.reading_plan`).  A file that cannot be read,
    a plan for another instance or one valid under no such reading is bad input, said in
    one sentence naming the file."""
    from asprilo.reader import read_plan, require_plan_fits_instance
    from asprilo.sources import as_sources

    from ..anytime.readings import reading_plan

    name = None
    if not isinstance(start, Plan):
        sources = as_sources(start)
        name = sources[0].name
        start = read_plan(sources, robots=len(instance.robots))
        require_plan_fits_instance(start, instance, sources, domain)
    return reading_plan(instance, domain, start, name)
