"""The horizon search along a task assignment (``assign``): a probe without one first
(A/B/C), the assignment (computed, or the caller's), the search along it, and the
tightening without it.

The probe looks for a plan without an assignment from the lower bound up, within a conflict
budget: a horizon it refutes is refuted for every assignment, and a plan it finds is
minimal.  After a plan along the assignment, shorter plans are tried without it for a while
(``tighten``): plans only get shorter when robots wait, so "no plan at H-1" proves H minimal.
"""

from __future__ import annotations

import time
from dataclasses import replace
from typing import TYPE_CHECKING

from asprilo.bounds import INFINITE, assigned_bound
from asprilo.domain import Bound, Job
from asprilo.model import Plan
from asprilo.solver import Result, Status

from ...assignment import Assignment, assign_tasks, assignment_of_plan
from ...bounds import assignment_bound
from ..outcome import Outcome
from ..status import WITHOUT_ASSIGNMENT, Attempt, SolveStatus
from .program import carriers

if TYPE_CHECKING:
    from .exact import HorizonSearch

#: the share of the time limit the task assignment may spend optimising, and its cap
ASSIGNMENT_SHARE = 0.2
ASSIGNMENT_SECONDS = 10.0
#: after a plan along an assignment, how long to look for shorter plans without it
TIGHTEN_SECONDS = 10.0
#: before an A/B/C task assignment, the probe without one: its conflict budget, smaller for
#: big programs (at most PROBE_WORK / (robots x cells x horizon): 2,500 to 10,000 conflicts on
#: the medium paper instances, 10,000 on the small ones)
PROBE_CONFLICTS = 10_000
PROBE_WORK = 250_000_000
#: the note of the probe's plan found again along its own assignment
ALONG_THE_PLAN = "along the plan's assignment"
#: the message of an assignment no plan can follow
UNFOLLOWABLE = "no plan can follow the task assignment (a shelf cannot reach its station)"


class AssignedSearch:
    """A :class:`~.exact.HorizonSearch` that follows a task assignment."""

    def __init__(self, search: HorizonSearch):
        self.search, self.request, self.watch = search, search.request, search.watch
        self.program, self.outcome = search.program, search.outcome
        self.bound = 0.0  # every horizon below is refuted (the lower bound, or more after a probe)
        # a minimal plan the probe found but could not find again along its own assignment
        self.probe_plan: tuple[Plan, Assignment] | None = None

    def run(self) -> Outcome:
        outcome = self._search()
        if self.probe_plan is not None:
            kept, _ = self.probe_plan
            if outcome.plan is None or (self.request.tighten and outcome.plan.horizon > kept.horizon):
                return self._return_probe_plan()
        return outcome

    def _search(self) -> Outcome:
        outcome, request, search = self.outcome, self.request, self.search
        bound = request.lower_bound
        if search.unreachable():
            return outcome
        if request.assignment is None and request.horizon is None and request.domain.work is Job.TRIPS:
            bound = self._probe(int(bound))
            if outcome.plan is not None or search.stopped():
                return outcome
        self.bound = bound
        if not self._assign():
            return outcome
        first = self._first_horizon(bound)
        if first is None:
            outcome.message = UNFOLLOWABLE
            return outcome
        search.upward(first, search.last_horizon(first))
        if outcome.plan is not None:
            self._found(bound)
        return outcome

    def _found(self, bound: float) -> None:
        """A plan along the assignment: how minimal it is; tightened where it may not be."""
        outcome, request = self.outcome, self.request
        outcome.horizon = outcome.plan.horizon
        outcome.minimal = outcome.horizon <= bound
        outcome.minimal_along_assignment = self.search.searched_up() or outcome.minimal
        if request.tighten and request.horizon is None and not outcome.minimal and not self.probe_plan:
            self._tighten()

    def _first_horizon(self, bound: float) -> int | None:
        """The first horizon to search; ``None`` when no plan can follow the task assignment."""
        request = self.request
        if request.horizon is not None:
            return request.horizon
        instance, floor = request.instance, self.program.floor
        along = assignment_bound(instance, self.outcome.assignment.facts, floor)
        if along == INFINITE:
            return None
        first = max(int(bound), int(along))
        if request.domain.bound is Bound.DELIVERY:
            first = int(assigned_bound(instance, request.domain, floor, carriers(self.outcome.assignment), first))
        return first

    # --- the probe ---------------------------------------------------------------------------

    def _probe(self, bound: int) -> int:
        """Before a task assignment: look for a plan without one from the lower bound up, within
        a conflict budget; return the first horizon not refuted.

        A refuted horizon is refuted for every assignment.  A plan found is minimal, and the
        assignment read off it costs no makespan at all (where the whole problem is easy at
        its bound, an optimised assignment can only make it longer or harder).
        """
        horizon, instance = bound, self.request.instance
        size = len(instance.robots) * len(self.program.floor.cells) * bound
        budget = allowance = min(PROBE_CONFLICTS, PROBE_WORK // max(1, size))
        while budget > 0 and not self.watch.cancelled and not self.watch.expired:
            result, used, plan = self._probe_at(horizon, budget)
            budget -= used
            if result.status is Status.UNSAT:
                horizon += 1
                continue
            if plan is not None:
                self._probe_found(plan, horizon, allowance)
            return horizon
        return horizon

    def _probe_found(self, plan: Plan, horizon: int, allowance: int) -> None:
        """The probe's plan: kept when it follows the assignment read off it, or found again
        along it.  A plan that moves more shelves than it delivers from may not be found again
        (some plans must move a shelf out of the way, which no assignment allows): it is then
        kept in case no plan along an assignment turns up (``probe_plan``)."""
        outcome, program = self.outcome, self.program
        outcome.assignment, exact = assignment_of_plan(self.request.instance, self.request.domain, plan)
        program.assignment = outcome.assignment
        if not exact:
            _, _, again = self._probe_at(horizon, allowance)
            if again is not None:
                plan = again
            else:
                self.probe_plan, plan = (plan, outcome.assignment), None
        if plan is not None:
            outcome.status, outcome.plan, outcome.horizon = SolveStatus.FOUND, plan, plan.horizon
            outcome.minimal = outcome.minimal_along_assignment = True
        else:
            outcome.assignment = program.assignment = None

    def _probe_at(self, horizon: int, conflicts: int) -> tuple[Result, int, Plan | None]:
        """One try of the probe (along the assignment when one is followed): the result, the
        conflicts it used and the plan found (which goes with its report)."""
        started = time.perf_counter()
        result, used = self.program.probe(horizon, conflicts)
        note = ALONG_THE_PLAN if self.program.assignment is not None else WITHOUT_ASSIGNMENT
        plan = self.program.plan(result) if result.status is Status.SAT else None
        self.search.record(Attempt(horizon, result.status.value, time.perf_counter() - started, note, plan))
        return result, used, plan

    def _return_probe_plan(self) -> Outcome:
        """The probe's plan, when no plan along an assignment was found, or (``tighten``) one
        was but the probe's is shorter: it is minimal, though it also moves shelves (or hands
        them over) beyond the assignment read off its deliveries, so it is not minimal *along*
        an assignment."""
        outcome = self.outcome
        outcome.plan, assignment = self.probe_plan
        outcome.assignment = replace(assignment, origin="read off a plan that also moves other shelves")
        outcome.status, outcome.horizon, outcome.message = SolveStatus.FOUND, outcome.plan.horizon, ""
        outcome.minimal, outcome.minimal_along_assignment = True, False
        return outcome

    # --- the assignment and the tightening -----------------------------------------------------

    def _assign(self) -> bool:
        """Compute the task assignment the program will follow (or take the caller's); whether
        there is one."""
        outcome, watch, request = self.outcome, self.watch, self.request
        if request.assignment is not None:
            outcome.assignment = self.program.assignment = request.assignment
            return True
        budget = watch.remaining()
        budget = ASSIGNMENT_SECONDS if budget is None else min(ASSIGNMENT_SECONDS, ASSIGNMENT_SHARE * budget)
        watch.phase("assigning", 0)
        outcome.assignment = assign_tasks(request.instance, request.domain, budget, watch.attach)
        if not outcome.assignment.facts:
            outcome.status = SolveStatus.CANCELLED if watch.cancelled else (
                SolveStatus.NONE if outcome.assignment.status is Status.UNSAT else SolveStatus.LIMIT)
            outcome.message = "no task assignment"
            return False
        self.program.assignment = outcome.assignment
        return True

    def _tighten(self) -> None:
        """After a plan along the assignment: try one step shorter without it, for a while.

        Plans only get shorter when robots wait, so "no plan at H-1" proves H minimal; a
        plan at H-1 replaces the one found and the next step down is tried.
        """
        outcome, watch = self.outcome, self.watch
        self.program.assignment = None
        budget_end = time.perf_counter() + TIGHTEN_SECONDS
        while outcome.horizon > self.bound and not watch.cancelled and not watch.expired:
            limit = budget_end - time.perf_counter()
            if limit <= 0:
                return
            horizon = outcome.horizon - 1
            started = time.perf_counter()
            result = self.program.solve_at(horizon, limit)
            plan = self.program.plan(result) if result.status is Status.SAT else None
            self.search.record(Attempt(horizon, result.status.value, time.perf_counter() - started,
                                       WITHOUT_ASSIGNMENT, plan))
            if result.status is Status.UNSAT:
                outcome.minimal = True
                return
            if plan is None:
                return
            outcome.plan, outcome.horizon = plan, horizon
            outcome.minimal = horizon <= self.bound
