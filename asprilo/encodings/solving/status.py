"""The words every solving method uses: how a solve ended (:class:`SolveStatus`), what a
method reports along the way (:class:`Attempt`, one record for every method: the max-flow
solver and the anytime planner report subclasses with their own figures), and what it is
doing now (:class:`Phase`), and what went wrong beside it (:class:`Note`)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from enum import Enum
from typing import Any

from asprilo.model import Plan


class SolveStatus(str, Enum):
    """How a solve ended, whichever method ran it."""

    FOUND = "found"          # a plan, checked
    NONE = "none"            # proven: no plan (at the given horizon, or at any horizon)
    LIMIT = "limit"          # the time or memory limit, or the largest horizon, came first
    CANCELLED = "cancelled"  # stopped by the caller
    INVALID = "invalid"      # the plan failed the check (a bug in an encoding)


#: the note of the tries that do not follow the task assignment of a search with one
WITHOUT_ASSIGNMENT = "without assignment"
#: the result of an attempt that is a better plan (the anytime method)
IMPROVED = "improved"


@dataclass
class Attempt:
    """One horizon tried: ``sat``, ``unsat`` or ``unknown`` (stopped), and how long it took.

    ``note`` is ``"without assignment"`` (:data:`WITHOUT_ASSIGNMENT`) for the tries that do
    not follow the task assignment of a search with one: the probe before the assignment, and
    the tries after a plan along it, looking for a shorter plan or the proof that there is
    none; ``"along the plan's assignment"`` for the probe's plan found again.  The anytime
    method reports each better plan as ``improved`` at its makespan; every plan a method
    finds travels in ``plan`` as it is found (so that a search stopped from outside still has
    it).  ``along``: the try followed a task assignment, so ``unsat`` refutes the horizon only
    along that assignment, not for the problem.
    """

    horizon: int
    result: str
    seconds: float
    note: str = ""
    plan: Plan | None = field(default=None, repr=False, compare=False)
    along: bool = False

    @property
    def refutes(self) -> bool:
        """Whether this try proves that no plan of its horizon exists at all."""
        return self.result == "unsat" and not self.along

    def as_json(self) -> dict[str, Any]:
        """The attempt as plain data (``asprilo solve --json``: ``horizons_tried``)."""
        return {"horizon": self.horizon, "result": self.result, "seconds": self.seconds, "note": self.note,
                "along_assignment": self.along}


@dataclass
class Phase:
    """What the search is doing now: ``bounding`` (computing the lower bounds, horizon 0),
    ``grounding``, ``solving`` or ``assigning`` (horizon 0).

    A long solve says the same phase again now and then with the ``conflicts`` of this
    horizon so far (the search runs in slices of conflicts: see ``methods/program.py``).
    """

    name: str
    horizon: int
    conflicts: int | None = None


@dataclass(frozen=True)
class Note:
    """A sentence on something that went wrong beside the search, said when it happens (so
    that a search stopped from outside has said it): ``the process computing the strong
    lower bound ran out of memory; the lower bound is the cheap one``."""

    text: str


@dataclass
class Totals:
    """The statistics of a solve so far (ground and solve time, rules, atoms, choices,
    conflicts): said after every attempt, so that a search stopped from outside has them."""

    figures: dict[str, Any]


Progress = Callable[[Attempt], None]
PhaseListener = Callable[[Phase], None]
