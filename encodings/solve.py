"""Find a plan of minimal makespan: a reference encoding over growing horizons, or max-flow.

Without a horizon, the search starts at an admissible lower bound (:mod:`.bounds`) and
goes up one step at a time.  Single-shot encodings are grounded afresh for every horizon
(their pruning depends on it); incremental ones ground one more ``step(t)`` part and move
the ``query(t)`` external instead.  The first horizon with a plan is the minimal makespan
when every horizon below it was proven to have none.  Every plan is checked before it is
returned.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path
from typing import Any

import clingo

from asprilo.bounds import Floor
from asprilo.checker import check
from asprilo.checker.report import Report
from asprilo.domain import Domain, detect_domain
from asprilo.errors import InputError
from asprilo.model import Instance, Plan
from asprilo.reader import plan_from_atoms, read_instance
from asprilo.solver import Result, Solver, Statistics, Status
from asprilo.writer import format_instance

from .assignment import Assignment, assign_tasks
from .bounds import assignment_bound, lower_bound, unusable_goals
from .flow import flow_plan
from .registry import Encoding, find_encoding

#: the share of the time limit the task assignment may spend optimising, and its cap
ASSIGNMENT_SHARE = 0.2
ASSIGNMENT_SECONDS = 10.0
#: after a plan along an assignment, how long to look for shorter plans without it
TIGHTEN_SECONDS = 10.0


class SolveStatus(str, Enum):
    FOUND = "found"          # a plan, checked
    NONE = "none"            # proven: no plan (at the given horizon, or at any horizon)
    LIMIT = "limit"          # the time limit or the largest horizon came first
    CANCELLED = "cancelled"  # stopped by the caller
    INVALID = "invalid"      # the plan failed the check (a bug in an encoding)


@dataclass
class Attempt:
    """One horizon tried: ``sat``, ``unsat`` or ``unknown`` (stopped), and how long it took.

    ``note`` is ``"without assignment"`` for the tries that follow a plan found along a task
    assignment, looking for a shorter plan or the proof that there is none.
    """

    horizon: int
    result: str
    seconds: float
    note: str = ""


@dataclass
class Outcome:
    """What :func:`solve` found.

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
    check: Report | None = None  # the ASP checker's verdict on the plan
    message: str = ""
    history: list[dict[str, Any]] = field(default_factory=list)  # method anytime: the plans reported

    @property
    def found(self) -> bool:
        return self.status is SolveStatus.FOUND


Progress = Callable[[Attempt], None]


class _Watch:
    """Time budget and cancellation of one :func:`solve` call.

    A helper thread interrupts the running clingo solver as soon as ``cancel`` is set;
    grounding is not interruptible, so a cancelled search stops at its next solve call.
    """

    def __init__(self, time_limit: float | None, cancel: threading.Event | None):
        self.started = time.perf_counter()
        self.deadline = None if time_limit is None else self.started + time_limit
        self.cancel = cancel
        self.current: Solver | None = None
        self.done = threading.Event()
        self.stats = Statistics()
        if cancel is not None:
            threading.Thread(target=self._watch, daemon=True).start()

    def _watch(self) -> None:
        while not self.done.is_set():
            if self.cancel.wait(0.05):
                solver = self.current
                if solver is not None:
                    solver.control.interrupt()
                return

    def attach(self, solver: Solver) -> None:
        self.current = solver
        if self.cancelled:
            solver.control.interrupt()

    @property
    def cancelled(self) -> bool:
        return self.cancel is not None and self.cancel.is_set()

    def remaining(self) -> float | None:
        return None if self.deadline is None else max(0.0, self.deadline - time.perf_counter())

    @property
    def expired(self) -> bool:
        return self.deadline is not None and time.perf_counter() >= self.deadline

    def solve(self, solver: Solver, limit: float | None = None) -> Result:
        self.attach(solver)
        before = Statistics(**solver.stats.as_dict())
        remaining = self.remaining()
        if limit is not None:
            remaining = limit if remaining is None else min(limit, remaining)
        result = solver.solve(time_limit=remaining)
        after = solver.stats
        self.stats.solve_time += after.solve_time - before.solve_time
        self.stats.choices += after.choices - before.choices
        self.stats.conflicts += after.conflicts - before.conflicts
        self.stats.rules, self.stats.atoms = after.rules, after.atoms
        return result

    def ground(self, solver: Solver, parts=(("base", ()),)) -> None:
        started = time.perf_counter()
        solver.ground(parts)
        self.stats.ground_time += time.perf_counter() - started

    def close(self) -> None:
        self.done.set()


def solve(instance: Instance | str | Path, domain: Domain | str | None = None, encoding: str = "plain",
          horizon: int | None = None, assign: bool = False, time_limit: float | None = None,
          method: str = "asp", on_progress: Progress | None = None,
          cancel: threading.Event | None = None, max_horizon: int | None = None) -> Outcome:
    """Find a plan for ``instance`` (an :class:`Instance` or a path).

    ``domain``: a|b|c|m|md or a :class:`Domain` (default: detected).  ``encoding``: a name
    from :data:`ENCODINGS` (``method="asp"``).  ``horizon``: solve at this makespan only;
    without it, search the minimal makespan upwards from a lower bound, up to
    ``max_horizon``.  ``assign``: compute a task assignment first and make the planner
    follow it.  ``method="flow"``: the exact max-flow solver of M/Md.  ``method="anytime"``:
    a checked plan fast, then better ones until ``time_limit`` (default 60 s) or the lower
    bound (:mod:`.anytime`); ``on_progress`` hears of each.  ``on_progress`` is called after
    every horizon; setting ``cancel`` stops the search from another thread.
    """
    if not isinstance(instance, Instance):
        instance = read_instance(instance)
    domain = detect_domain(instance) if domain is None else Domain.parse(domain)
    if horizon is not None and horizon < 0:
        raise InputError(f"the horizon must be at least 0, got {horizon}")
    if method not in ("asp", "flow", "anytime"):
        raise InputError(f"unknown method '{method}' (choose asp, flow or anytime)")
    if method == "flow" and domain.delivers:
        raise InputError(f"the flow method solves domains M and Md only, not {domain.label}")
    if instance.assignment and method == "flow":
        raise InputError("the instance assigns goals to robots; the flow method solves anonymous "
                         "goals only (use --method asp)")
    if instance.assignment and assign:
        raise InputError("the instance assigns goals to robots already; leave out --assign")
    program = find_encoding(domain, encoding) if method == "asp" else None
    watch = _Watch(time_limit, cancel)
    try:
        if method in _OTHER_METHODS:
            outcome = _OTHER_METHODS[method](instance, domain, horizon, watch, on_progress)
        else:
            outcome = _Search(instance, domain, program, horizon, assign, watch, on_progress,
                              max_horizon).run()
    finally:
        watch.close()
    outcome.stats = outcome.stats or watch.stats.as_dict()
    outcome.stats.pop("models", None)
    if outcome.plan is not None and outcome.check is None:
        outcome.check = check_plan(instance, outcome.plan, domain)
        if not outcome.check.valid:
            outcome.status = SolveStatus.INVALID
            outcome.message = "the plan failed the check: " + "; ".join(
                error.message for error in outcome.check.errors[:3])
    return outcome


def check_plan(instance: Instance, plan: Plan, domain: Domain) -> Report:
    """The ASP checker's report on ``plan`` (``.valid``, ``.errors`` with ``.message``)."""
    return check(instance, plan, domain)


# --- max-flow ------------------------------------------------------------------------------

def _solve_flow(instance: Instance, domain: Domain, horizon: int | None, watch: _Watch,
                on_progress: Progress | None) -> Outcome:
    def report(attempt) -> None:
        tried = Attempt(attempt.horizon, "sat" if attempt.feasible else "unsat", attempt.seconds)
        outcome.horizons_tried.append(tried)
        watch.stats.solve_time += attempt.seconds
        if on_progress is not None:
            on_progress(tried)

    outcome = Outcome(SolveStatus.LIMIT, domain, "flow", "flow")
    search = flow_plan(instance, horizon, watch.remaining(), lambda: watch.cancelled, report)
    outcome.lower_bound = search.lower_bound
    if search.plan is not None:
        outcome.status, outcome.plan = SolveStatus.FOUND, search.plan
        outcome.horizon, outcome.minimal = search.plan.horizon, search.minimal
    elif search.stopped == "cancelled":
        outcome.status = SolveStatus.CANCELLED
    elif search.stopped is None:
        outcome.status = SolveStatus.NONE
    return outcome


# --- anytime -------------------------------------------------------------------------------

def _solve_anytime(instance: Instance, domain: Domain, horizon: int | None, watch: _Watch,
                   on_progress: Progress | None) -> Outcome:
    """The anytime planner (:mod:`.anytime`); its improvements are the attempts reported."""
    from .anytime import plan_anytime

    if horizon is not None:
        raise InputError("the anytime method searches the makespan itself; leave out --horizon")

    def report(better) -> None:
        gap = "" if better.gap is None else f", {100 * better.gap:.1f}% above the lower bound"
        attempt = Attempt(better.makespan, "improved", better.seconds, f"sum of costs {better.sum_of_costs}{gap}")
        outcome.horizons_tried.append(attempt)
        if on_progress is not None:
            on_progress(attempt)

    outcome = Outcome(SolveStatus.LIMIT, domain, "anytime", "anytime")
    result = plan_anytime(instance, domain, watch.remaining(), watch.cancel, report)
    outcome.status = SolveStatus(result.status)
    outcome.plan, outcome.check, outcome.minimal = result.plan, result.check, result.minimal
    outcome.horizon = result.plan.horizon if result.plan is not None else None
    outcome.lower_bound, outcome.message = result.bound, result.message
    outcome.history = [better.__dict__ for better in result.history]
    outcome.stats = dict(result.stats)
    return outcome


#: the methods that use no reference encoding
_OTHER_METHODS = {"flow": _solve_flow, "anytime": _solve_anytime}


# --- answer set programming ------------------------------------------------------------------

def _with_values(symbol: clingo.Symbol, values: dict[str, int]) -> clingo.Symbol:
    """``symbol`` with every subterm that names a theory variable replaced by its value
    (clingcon encodings print deliveries as ``deliver(O,P,given(S,O,P))``)."""
    if not values or symbol.type is not clingo.SymbolType.Function:
        return symbol
    name = str(symbol)
    if name in values:
        return clingo.Number(values[name])
    if not symbol.arguments:
        return symbol
    return clingo.Function(symbol.name, [_with_values(a, values) for a in symbol.arguments], symbol.positive)


class _Search:
    """The horizon search of one encoding on one instance."""

    def __init__(self, instance: Instance, domain: Domain, encoding: Encoding, horizon: int | None,
                 assign: bool, watch: _Watch, on_progress: Progress | None, max_horizon: int | None):
        self.instance, self.domain, self.encoding = instance, domain, encoding
        self.horizon, self.assign, self.watch = horizon, assign, watch
        self.on_progress = on_progress
        self.floor = Floor(instance.cells)
        self.facts = format_instance(instance, [])
        self.outcome = Outcome(SolveStatus.LIMIT, domain, "asp", encoding.name)
        self.max_horizon = max_horizon
        self.follow_assignment = False

    def run(self) -> Outcome:
        outcome, watch = self.outcome, self.watch
        outcome.lower_bound = bound = lower_bound(self.instance, self.domain, self.floor)
        if bound == float("inf") and self.horizon is None:
            outcome.status, outcome.minimal = SolveStatus.NONE, True
            outcome.message = "some goal or order line can never be reached"
            return outcome
        if self.assign and not self._assign():
            return outcome
        if self.horizon is not None:
            first = last = self.horizon
        else:
            first = int(bound)
            if self.assign:
                first = max(first, int(assignment_bound(self.instance, outcome.assignment.facts, self.floor)))
            last = self.max_horizon if self.max_horizon is not None else self._largest_horizon(first)
        if self.encoding.incremental:
            self._incremental(first, last)
        else:
            self._single_shot(first, last)
        if outcome.plan is not None:
            outcome.horizon = outcome.plan.horizon
            proven = (self.horizon is None and not self.assign
                      and all(a.result == "unsat" for a in outcome.horizons_tried[:-1]))
            outcome.minimal = proven or outcome.horizon <= bound
            if self.assign and self.horizon is None and not outcome.minimal:
                self._tighten()
        return outcome

    def _assign(self) -> bool:
        """Compute the task assignment the planner will follow; whether there is one."""
        outcome, watch = self.outcome, self.watch
        budget = watch.remaining()
        budget = ASSIGNMENT_SECONDS if budget is None else min(ASSIGNMENT_SECONDS, ASSIGNMENT_SHARE * budget)
        outcome.assignment = assign_tasks(self.instance, self.domain, budget, watch.attach)
        watch.stats.ground_time += outcome.assignment.stats.ground_time
        watch.stats.solve_time += outcome.assignment.stats.solve_time
        if not outcome.assignment.facts:
            outcome.status = SolveStatus.CANCELLED if watch.cancelled else (
                SolveStatus.NONE if outcome.assignment.status is Status.UNSAT else SolveStatus.LIMIT)
            outcome.message = "no task assignment"
            return False
        self.follow_assignment = True
        return True

    def _tighten(self) -> None:
        """After a plan along the assignment: try one step shorter without it, for a while.

        Plans only get shorter when robots wait, so "no plan at H-1" proves H minimal; a
        plan at H-1 replaces the one found and the next step down is tried.
        """
        outcome, watch = self.outcome, self.watch
        self.follow_assignment = False
        budget_end = time.perf_counter() + TIGHTEN_SECONDS
        while outcome.horizon > outcome.lower_bound and not watch.cancelled and not watch.expired:
            limit = budget_end - time.perf_counter()
            if limit <= 0:
                return
            horizon = outcome.horizon - 1
            started = time.perf_counter()
            result = self._solve_at(horizon, limit)
            self._record(Attempt(horizon, result.status.value, time.perf_counter() - started,
                                 "without assignment"))
            if result.status is Status.UNSAT:
                outcome.minimal = True
                return
            if result.status is not Status.SAT:
                return
            outcome.plan, outcome.horizon = self._plan(result), horizon

    def _largest_horizon(self, first: int) -> int:
        """Where an upward search gives up: no plan needs this many steps in practice."""
        lines = sum(len(order.lines) for order in self.instance.orders.values())
        return first + len(self.instance.cells) + len(self.instance.robots) + 2 * lines

    def _program(self, solver: Solver, horizon: int | None) -> None:
        solver.add(self.facts)
        if self.follow_assignment:
            solver.add(self.outcome.assignment.text())
        elif horizon is not None and not self.domain.delivers:
            hints = unusable_goals(self.instance, horizon, self.floor)
            solver.add("".join(f"ruled_out({r},({x},{y})).\n" for r, (x, y) in hints))
        solver.load(self.encoding.program)

    def _record(self, attempt: Attempt) -> None:
        self.outcome.horizons_tried.append(attempt)
        if self.on_progress is not None:
            self.on_progress(attempt)

    @staticmethod
    def _plan(result: Result) -> Plan:
        return plan_from_atoms([_with_values(symbol, result.assignment) for symbol in result.symbols])

    def _tried(self, horizon: int, result: Result, seconds: float) -> bool:
        """Record one horizon of the search; whether the search goes on."""
        outcome = self.outcome
        self._record(Attempt(horizon, result.status.value, seconds))
        if result.status is Status.SAT:
            outcome.status, outcome.plan = SolveStatus.FOUND, self._plan(result)
            return False
        if result.status is Status.UNSAT:
            outcome.status = SolveStatus.NONE
            return True
        outcome.status = SolveStatus.CANCELLED if self.watch.cancelled else SolveStatus.LIMIT
        return False

    def _stopped(self) -> bool:
        if self.watch.cancelled:
            self.outcome.status = SolveStatus.CANCELLED
            return True
        if self.watch.expired:
            self.outcome.status = SolveStatus.LIMIT
            return True
        return False

    def _solve_at(self, horizon: int, limit: float | None = None) -> Result:
        """Ground and solve the encoding for exactly this horizon, in a fresh solver."""
        if self.encoding.incremental:
            solver = Solver(self.encoding.theory)
            self._program(solver, None)
            self.watch.attach(solver)
            steps = [("step", [t]) for t in range(1, horizon + 1)]
            self.watch.ground(solver, [("base", []), *steps, ("check", [horizon])])
            solver.assign_external(f"query({horizon})", True)
        else:
            solver = Solver(self.encoding.theory, constants={"horizon": horizon})
            self._program(solver, horizon)
            self.watch.attach(solver)
            self.watch.ground(solver)
        return self.watch.solve(solver, limit)

    def _single_shot(self, first: int, last: int) -> None:
        for horizon in range(first, last + 1):
            if self._stopped():
                return
            started = time.perf_counter()
            if not self._tried(horizon, self._solve_at(horizon), time.perf_counter() - started):
                return
        if self.horizon is None:
            self.outcome.status = SolveStatus.LIMIT

    def _incremental(self, first: int, last: int) -> None:
        """One solver for all horizons: ground one more step, move the query, solve again."""
        solver = Solver(self.encoding.theory)
        self._program(solver, None)
        self.watch.attach(solver)
        started = time.perf_counter()
        self.watch.ground(solver, [("base", [])] + [("step", [t]) for t in range(1, first + 1)])
        for horizon in range(first, last + 1):
            if self._stopped():
                return
            if horizon > first:
                started = time.perf_counter()
                self.watch.ground(solver, [("step", [horizon])])
            self.watch.ground(solver, [("check", [horizon])])
            solver.assign_external(f"query({horizon})", True)
            going_on = self._tried(horizon, self.watch.solve(solver), time.perf_counter() - started)
            solver.release_external(f"query({horizon})")
            if not going_on:
                return
        if self.horizon is None:
            self.outcome.status = SolveStatus.LIMIT
