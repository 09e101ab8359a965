"""What a solve found (:class:`Outcome`), whichever method ran it."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from asprilo.checker import Report
from asprilo.domain import Domain
from asprilo.model import Plan

from ..assignment import Assignment
from .status import WITHOUT_ASSIGNMENT, Attempt, SolveStatus


@dataclass
class Outcome:
    """What :func:`~asprilo.encodings.solve` found.

    ``minimal`` says that no shorter plan exists: proven by the search or the lower bound;
    with an assignment, by the lower bound or by a try one step shorter without it.
    ``stats`` holds ground and solve time (seconds), rules, atoms (of the last program),
    choices and conflicts (summed over all solve calls).
    """

    status: SolveStatus
    domain: Domain
    method: str
    encoding: str
    plan: Plan | None = None
    horizon: int | None = None
    minimal: bool = False
    lower_bound: float = 0.0
    horizons_tried: list[Attempt] = field(default_factory=list)
    stats: dict[str, Any] = field(default_factory=dict)
    assignment: Assignment | None = None
    minimal_along_assignment: bool = False  # no shorter plan follows the assignment
    check: Report | None = None  # the ASP checker's verdict on the plan
    message: str = ""
    history: list[dict[str, Any]] = field(default_factory=list)  # method anytime: the plans reported
    warnings: list[str] = field(default_factory=list)  # clingo's warnings on a user's encoding

    @property
    def found(self) -> bool:
        return self.status is SolveStatus.FOUND

    @property
    def refuted(self) -> list[int]:
        """The horizons proven to have no plan (with an assignment: only those tried without)."""
        return sorted({a.horizon for a in self.horizons_tried
                       if a.result == "unsat" and (a.note == WITHOUT_ASSIGNMENT or self.assignment is None)})

    @property
    def proven_bound(self) -> float:
        """No plan is shorter: the lower bound raised past every horizon refuted in a row."""
        bound = self.lower_bound
        for horizon in self.refuted:
            if horizon == bound:
                bound += 1
        return bound
