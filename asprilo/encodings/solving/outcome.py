"""What a solve found (:class:`Outcome`), whichever method ran it."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from asprilo.checker import Report
from asprilo.domain import Domain
from asprilo.model import Plan

from ..assignment import Assignment
from .status import Attempt, SolveStatus


@dataclass
class Outcome:
    """What :func:`~asprilo.encodings.solve` found.

    ``minimal`` says that no shorter plan exists: proven by the search or the lower bound;
    with an assignment, by the lower bound or by a try one step shorter without it.  For a
    user's own encoding its search proves ``encoding_minimal`` only (no shorter plan of this
    encoding), ``minimal`` where the plan meets the lower bound or the problem's ``minimum``
    (:mod:`.minimality`); its refuted horizons are not ``trusted`` for the problem.
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
    history: list[dict[str, Any]] = field(default_factory=list)  # anytime, auto: the plans reported
    warnings: list[str] = field(default_factory=list)  # clingo's warnings on a user's encoding
    found_by: str = ""  # method auto: the method whose plan is the answer (asp or anytime)
    stage: str = ""  # the files of a first stage (``--stage``), in words; "" without one
    staged: list[str] | None = None  # the atoms of its first answer, as text (None: it had no answer)
    encoding_minimal: bool = False  # a valid plan, and the encoding (or method) allows none shorter
    minimum: int | None = None  # the problem's minimal makespan, where it is known
    minimum_by: str = ""  # who proved ``minimum``, in words, where not the search itself
    trusted: bool = True  # the horizons refuted hold for the problem (not so for a user's own encoding)

    @property
    def found(self) -> bool:
        return self.status is SolveStatus.FOUND

    @property
    def refuted(self) -> list[int]:
        """The horizons proven to have no plan at all (not those refuted only along a task
        assignment: see :attr:`refuted_along`)."""
        return sorted({a.horizon for a in self.horizons_tried if a.refutes})

    @property
    def refuted_along(self) -> list[int]:
        """The horizons with no plan along the task assignment followed (not refuted for the
        problem, unless :attr:`refuted` has them too)."""
        return sorted({a.horizon for a in self.horizons_tried if a.result == "unsat" and a.along})

    @property
    def proven_bound(self) -> float:
        """No plan is shorter: the lower bound raised past every horizon refuted (by a trusted
        encoding: a user's own proves nothing for the problem), or the problem's minimum."""
        bound = proven_bound(self.lower_bound, self.refuted if self.trusted else [])
        return bound if self.minimum is None else max(bound, self.minimum)

    @property
    def gap(self) -> float | None:
        """How many steps the plan may be longer than a minimal one (``None``: no plan)."""
        if self.plan is None or self.horizon is None:
            return None
        return max(0.0, self.horizon - self.proven_bound)


def proven_bound(lower_bound: float, refuted: list[int]) -> float:
    """The lower bound raised past the horizons ``refuted``: a plan is a plan at every larger
    horizon too (its robots may wait at the end), so no horizon below a refuted one has a
    plan either; an upward search refutes them in a row from the lower bound."""
    return max([lower_bound, *(horizon + 1 for horizon in refuted)])
