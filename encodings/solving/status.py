"""The words every solving method uses: how a solve ended (:class:`SolveStatus`), what a
method reports along the way (:class:`Attempt`, one record for every method: the max-flow
solver and the anytime planner report subclasses with their own figures), and what it is
doing now (:class:`Phase`)."""

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
    method reports each better plan as ``improved`` at its makespan, the plan itself in
    ``plan`` (so that a search stopped from outside still has its best plan).
    """

    horizon: int
    result: str
    seconds: float
    note: str = ""
    plan: Plan | None = field(default=None, repr=False, compare=False)

    def as_json(self) -> dict[str, Any]:
        """The attempt as plain data (``asprilo solve --json``: ``horizons_tried``)."""
        return {"horizon": self.horizon, "result": self.result, "seconds": self.seconds, "note": self.note}


@dataclass
class Phase:
    """What the search is doing now: ``grounding``, ``solving`` or ``assigning`` (horizon 0)."""

    name: str
    horizon: int


Progress = Callable[[Attempt], None]
PhaseListener = Callable[[Phase], None]
