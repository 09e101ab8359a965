"""Find a plan of minimal makespan: a reference encoding over growing horizons, or max-flow.

Without a horizon, the search starts at an admissible lower bound (:func:`asprilo.bounds.
makespan_bound`) and goes up one step at a time.  Every horizon is grounded afresh (the
encodings prune with distances to the horizon); incremental encodings instead ground one
more ``step(t)`` part and move the ``query(t)`` external.  The first horizon with a plan
is the minimal makespan when every horizon below it was refuted.  With a task assignment
(``assign``) in A/B/C, a short probe without it comes first (``_Search._probe``).  Every plan
is checked before it is returned.

clingo cannot be interrupted while it grounds, so ``solve(..., isolate=True)`` runs the
whole search in a child process that is killed at the time limit: the limit then holds in
every phase, and the horizons refuted so far still prove a bound.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from enum import Enum
from pathlib import Path
from typing import Any

import clingo

from asprilo.bounds import Floor, makespan_bound
from asprilo.checker import Report, check
from asprilo.delivery_bound import assigned_bound, delivery_schedule
from asprilo.domain import Bound, Domain, Job, detect_domain
from asprilo.errors import InputError
from asprilo.isolation import run_isolated
from asprilo.model import Instance, Plan
from asprilo.reader import plan_from_atoms, read_instance
from asprilo.solver import Result, Solver, Statistics, Status
from asprilo.writer import format_instance

from .assignment import Assignment, assign_tasks, assignment_of_plan
from .bounds import assignment_bound, unusable_goals
from .flow import flow_plan
from .registry import Encoding, find_encoding

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
WITHOUT_ASSIGNMENT = "without assignment"
#: M/Md instances with this many robots get ruled_out/2 hints (they ground big programs faster)
HINTED_ROBOTS = 20
#: with hints, a horizon is searched in turns with and without them, each turn twice as long
#: as the turn before last, starting with this many conflicts (counted, not timed, so that a
#: search takes the same path on every machine and under any load); learned clauses are kept
FIRST_TURN = 1_000


class SolveStatus(str, Enum):
    FOUND = "found"          # a plan, checked
    NONE = "none"            # proven: no plan (at the given horizon, or at any horizon)
    LIMIT = "limit"          # the time or memory limit, or the largest horizon, came first
    CANCELLED = "cancelled"  # stopped by the caller
    INVALID = "invalid"      # the plan failed the check (a bug in an encoding)


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
    plan: Plan | None = field(default=None, repr=False)


@dataclass
class Phase:
    """What the search is doing now: ``grounding``, ``solving`` or ``assigning`` (horizon 0)."""

    name: str
    horizon: int


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
    minimal_along_assignment: bool = False  # no shorter plan follows the assignment
    check: Report | None = None  # the ASP checker's verdict on the plan
    message: str = ""
    history: list[dict[str, Any]] = field(default_factory=list)  # method anytime: the plans reported

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


Progress = Callable[[Attempt], None]
PhaseListener = Callable[[Phase], None]


def solve(instance: Instance | str | Path, domain: Domain | str | None = None, encoding: str = "plain",
          horizon: int | None = None, assign: bool = False, time_limit: float | None = None,
          method: str = "asp", on_progress: Progress | None = None,
          cancel: threading.Event | None = None, max_horizon: int | None = None,
          on_phase: PhaseListener | None = None, isolate: bool = False,
          memory_limit: int | None = None, tighten: bool = True,
          assignment: Sequence[str] | None = None) -> Outcome:
    """Find a plan for ``instance`` (an :class:`Instance` or a path).

    ``domain``: a|b|c|m|md or a :class:`Domain` (default: detected).  ``encoding``: a name
    from :data:`ENCODINGS` (``method="asp"``).  ``horizon``: solve at this makespan only;
    without it, search the minimal makespan upwards from a lower bound, up to
    ``max_horizon``.  ``assign``: compute a task assignment first and make the planner
    follow it; then (unless ``tighten`` is false) try shorter plans without it for a while.
    ``assignment``: follow these ``assign`` facts (an earlier outcome's
    ``assignment.facts``) instead of computing them; implies ``assign``.
    ``method="flow"``: the exact max-flow solver of M/Md; ``method="anytime"``: a checked
    plan fast, then better ones until ``time_limit`` (default 60 s) or the lower bound
    (:mod:`.anytime`).  ``on_progress`` is
    called after every horizon, ``on_phase`` when grounding or solving starts; setting
    ``cancel`` stops the search from another thread.  ``isolate``: search in a child
    process, so that ``time_limit`` and ``memory_limit`` (MB) hold while clingo grounds.
    """
    if not isinstance(instance, Instance):
        instance = read_instance(instance)
    domain = detect_domain(instance) if domain is None else Domain.parse(domain)
    assign = assign or assignment is not None
    _check_request(instance, domain, horizon, assign, method)
    given = None if assignment is None else _given_assignment(instance, domain, assignment)
    program = find_encoding(domain, encoding) if method == "asp" else None
    request = _Request(horizon, assign, tighten, time_limit, max_horizon, given)
    if isolate:
        return _solve_isolated(instance, domain, program, request, method, on_progress, on_phase, cancel,
                               memory_limit)
    return _solve_here(instance, domain, program, request, method, on_progress, on_phase, cancel)


@dataclass(frozen=True)
class _Request:
    """What the caller asked :func:`solve` for, besides instance, domain and method."""

    horizon: int | None
    assign: bool
    tighten: bool
    time_limit: float | None
    max_horizon: int | None
    assignment: Assignment | None = None  # given by the caller: followed, not computed


def ground(instance: Instance, domain: Domain | str, horizon: int, encoding: str = "plain") -> Solver:
    """The program :func:`solve` grounds for ``horizon`` (encoding, instance, distances, hints),
    grounded and ready to solve: for measurements and experiments."""
    domain = Domain.parse(domain)
    watch = _Watch(None, None, None, None)
    return _Search(instance, domain, find_encoding(domain, encoding), _Request(horizon, False, False, None, None),
                   watch).grounded(horizon)[0]


def _given_assignment(instance: Instance, domain: Domain, facts: Sequence[str]) -> Assignment:
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


def _check_request(instance: Instance, domain: Domain, horizon: int | None, assign: bool, method: str) -> None:
    if horizon is not None and horizon < 0:
        raise InputError(f"the horizon must be at least 0, got {horizon}")
    if method not in ("asp", "flow", "anytime"):
        raise InputError(f"unknown method '{method}' (choose asp, flow or anytime)")
    if method == "anytime" and horizon is not None:
        raise InputError("the anytime method searches the makespan itself; leave out --horizon")
    if method == "flow" and domain.work is not Job.GOALS:
        raise InputError(f"the flow method solves domains M and Md only, not {domain.label}")
    if instance.assignment and method == "flow":
        raise InputError("the instance assigns goals to robots; the flow method solves anonymous "
                         "goals only (use --method asp)")
    if instance.assignment and assign:
        raise InputError("the instance assigns goals to robots already; leave out --assign")


def _solve_here(instance: Instance, domain: Domain, program: Encoding | None, request: _Request, method: str,
                on_progress: Progress | None, on_phase: PhaseListener | None,
                cancel: threading.Event | None) -> Outcome:
    watch = _Watch(request.time_limit, cancel, on_progress, on_phase)
    try:
        if method == "flow":
            outcome = _solve_flow(instance, domain, request.horizon, watch)
        elif method == "anytime":
            outcome = _solve_anytime(instance, domain, watch)
        else:
            outcome = _Search(instance, domain, program, request, watch).run()
    finally:
        watch.close()
    outcome.stats = outcome.stats or watch.totals()
    if outcome.plan is not None and outcome.check is None:
        outcome.check = check(instance, outcome.plan, domain)
        if not outcome.check.valid:
            outcome.status = SolveStatus.INVALID
            outcome.message = "the plan failed the check: " + "; ".join(
                error.message for error in outcome.check.errors[:3])
    return outcome


def _solve_isolated(instance: Instance, domain: Domain, program: Encoding | None, request: _Request,
                    method: str, on_progress: Progress | None, on_phase: PhaseListener | None,
                    cancel: threading.Event | None, memory_limit: int | None) -> Outcome:
    def forward(message: Attempt | Phase) -> None:
        if isinstance(message, Attempt) and on_progress is not None:
            on_progress(message)
        elif isinstance(message, Phase) and on_phase is not None:
            on_phase(message)

    time_limit = request.time_limit
    child = run_isolated(_search_in_child, (instance, domain, program, request, method),
                         time_limit=None if time_limit is None else time_limit + 0.5,
                         memory_mb=memory_limit, on_message=forward, cancel=cancel)
    if child.done:
        return child.value
    outcome = Outcome(SolveStatus.CANCELLED if cancel is not None and cancel.is_set() else SolveStatus.LIMIT,
                      domain, method, program.name if program else method)
    outcome.horizons_tried = [m for m in child.messages if isinstance(m, Attempt)]
    outcome.lower_bound = makespan_bound(instance, domain)
    best = [attempt for attempt in outcome.horizons_tried if attempt.plan is not None]
    if best:  # the anytime method stopped from outside: its last plan reported (checked) is the answer
        outcome.status, outcome.plan, outcome.horizon = SolveStatus.FOUND, best[-1].plan, best[-1].horizon
        outcome.check = check(instance, outcome.plan, domain)
        outcome.minimal = outcome.horizon <= outcome.lower_bound
        outcome.history = [{"seconds": a.seconds, "makespan": a.horizon} for a in best]
        return outcome
    outcome.stats = {key: value for key, value in Statistics().as_dict().items() if key != "models"}
    outcome.message = {"timeout": f"stopped at the time limit ({time_limit:g} s)" if time_limit else "stopped",
                       "memout": f"stopped at the memory limit ({memory_limit} MB)",
                       "crashed": f"the solver process died ({child.detail})"}[child.status]
    if outcome.status is SolveStatus.CANCELLED:
        outcome.message = "cancelled"
    return outcome


def _search_in_child(instance, domain, program, request, method, report) -> Outcome:
    return _solve_here(instance, domain, program, request, method, report, report, None)


# --- time, cancellation, statistics ------------------------------------------------------

class _Watch:
    """Time budget, cancellation, progress and statistics of one search.

    A helper thread interrupts the running clingo solver as soon as ``cancel`` is set;
    grounding is not interruptible, so a cancelled search stops at its next solve call.
    """

    def __init__(self, time_limit: float | None, cancel: threading.Event | None,
                 on_progress: Progress | None, on_phase: PhaseListener | None):
        self.started = time.perf_counter()
        self.deadline = None if time_limit is None else self.started + time_limit
        self.cancel = cancel
        self.on_progress, self.on_phase = on_progress, on_phase
        self.current: Solver | None = None
        self.solvers: list[Statistics] = []
        self.done = threading.Event()
        if cancel is not None:
            threading.Thread(target=self._watch, daemon=True).start()

    def _watch(self) -> None:
        while not self.done.is_set():
            if self.cancel.wait(0.05):
                if self.current is not None:
                    self.current.control.interrupt()
                return

    def attach(self, solver: Solver) -> None:
        self.current = solver
        self.solvers.append(solver.stats)
        if self.cancelled:
            solver.control.interrupt()

    def phase(self, name: str, horizon: int) -> None:
        if self.on_phase is not None:
            self.on_phase(Phase(name, horizon))

    def progress(self, attempt: Attempt) -> None:
        if self.on_progress is not None:
            self.on_progress(attempt)

    @property
    def cancelled(self) -> bool:
        return self.cancel is not None and self.cancel.is_set()

    def remaining(self) -> float | None:
        return None if self.deadline is None else max(0.0, self.deadline - time.perf_counter())

    @property
    def expired(self) -> bool:
        return self.deadline is not None and time.perf_counter() >= self.deadline

    def totals(self) -> dict[str, Any]:
        """Ground and solve time, choices and conflicts of all solvers; rules and atoms of the last."""
        total = Statistics()
        for stats in self.solvers:
            total.ground_time += stats.ground_time
            total.solve_time += stats.solve_time
            total.choices += stats.choices
            total.conflicts += stats.conflicts
        if self.solvers:
            total.rules, total.atoms = self.solvers[-1].rules, self.solvers[-1].atoms
        figures = total.as_dict()
        figures.pop("models", None)
        return figures

    def close(self) -> None:
        self.done.set()


# --- anytime -------------------------------------------------------------------------------

def _solve_anytime(instance: Instance, domain: Domain, watch: _Watch) -> Outcome:
    """The anytime planner (:mod:`.anytime`); each plan it reports is an ``improved`` attempt."""
    from .anytime import plan_anytime

    outcome = Outcome(SolveStatus.LIMIT, domain, "anytime", "anytime")

    def report(better) -> None:
        gap = "" if better.gap is None else f", {100 * better.gap:.1f}% above the lower bound"
        attempt = Attempt(better.makespan, "improved", better.seconds, f"sum of costs {better.sum_of_costs}{gap}",
                          plan=better.plan)
        outcome.horizons_tried.append(attempt)
        watch.progress(attempt)

    result = plan_anytime(instance, domain, watch.remaining(), watch.cancel, report)
    outcome.status = SolveStatus(result.status)
    outcome.plan, outcome.check, outcome.minimal = result.plan, result.check, result.minimal
    outcome.horizon = result.plan.horizon if result.plan is not None else None
    outcome.lower_bound, outcome.message = result.bound, result.message
    outcome.history = [better.figures() for better in result.history]
    outcome.stats = dict(result.stats)
    return outcome


# --- max-flow ------------------------------------------------------------------------------

def _solve_flow(instance: Instance, domain: Domain, horizon: int | None, watch: _Watch) -> Outcome:
    flow_stats = Statistics()
    watch.solvers.append(flow_stats)

    def report(attempt) -> None:
        tried = Attempt(attempt.horizon, "sat" if attempt.feasible else "unsat", attempt.seconds)
        outcome.horizons_tried.append(tried)
        flow_stats.solve_time += attempt.seconds
        watch.progress(tried)

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


# --- answer set programming ------------------------------------------------------------------

def _with_values(symbol: clingo.Symbol, values: dict[str, int]) -> clingo.Symbol:
    """``symbol`` with every subterm that names a theory variable replaced by its value
    (clingcon encodings show deliveries as ``serve(O,P,given(S,O,P),T)``)."""
    if not values or symbol.type is not clingo.SymbolType.Function:
        return symbol
    name = str(symbol)
    if name in values:
        return clingo.Number(values[name])
    if not symbol.arguments:
        return symbol
    return clingo.Function(symbol.name, [_with_values(a, values) for a in symbol.arguments], symbol.positive)


def name_robots(encoding: Encoding, facts: str, symbols: list[clingo.Symbol]) -> Plan:
    """The plan of a model: its ``occurs/3`` atoms, or -- for an encoding with anonymous
    robots -- the plan its ``names`` program makes of the model's atoms."""
    if encoding.names is None:
        return plan_from_atoms(symbols)
    solver = Solver(options=["--warn=none"])
    solver.load(encoding.names)
    solver.add(facts)
    solver.add_facts(symbols)
    solver.ground()
    return plan_from_atoms(solver.solve().symbols)


class _Search:
    """The horizon search of one encoding on one instance."""

    def __init__(self, instance: Instance, domain: Domain, encoding: Encoding, request: _Request, watch: _Watch):
        self.instance, self.domain, self.encoding = instance, domain, encoding
        self.horizon, self.assign, self.watch = request.horizon, request.assign, watch
        self.tighten, self.given = request.tighten, request.assignment
        self.floor = Floor(instance.cells)
        self.facts = format_instance(instance, [])
        self.outcome = Outcome(SolveStatus.LIMIT, domain, "asp", encoding.name)
        self.max_horizon = request.max_horizon
        self.follow_assignment = False
        self.bound = 0.0  # every horizon below is refuted (the lower bound, or more after a probe)
        # a minimal plan the probe found but could not find again along its own assignment
        self.probe_plan: tuple[Plan, Assignment] | None = None
        self.options = encoding.options
        self._distances: str | None = None

    def run(self) -> Outcome:
        outcome = self._search()
        if self.probe_plan is not None:
            kept, _ = self.probe_plan
            if outcome.plan is None or (self.tighten and outcome.plan.horizon > kept.horizon):
                return self._return_probe_plan()
        return outcome

    def _search(self) -> Outcome:
        outcome = self.outcome
        outcome.lower_bound = bound = makespan_bound(self.instance, self.domain, self.floor)
        if bound == float("inf") and self.horizon is None:
            outcome.status, outcome.minimal = SolveStatus.NONE, True
            outcome.message = "some goal or order line can never be reached"
            return outcome
        if self.assign and self.given is None and self.horizon is None and self.domain.work is Job.TRIPS:
            bound = self._probe(int(bound))
            if outcome.plan is not None or self._stopped():
                return outcome
        self.bound = bound
        if self.assign and not self._assign():
            return outcome
        horizons = self._horizons(bound)
        if horizons is None:
            outcome.message = "no plan can follow the task assignment (a shelf cannot reach its station)"
        elif self.encoding.incremental:
            self._incremental(*horizons)
        else:
            self._single_shot(*horizons)
        if outcome.plan is not None:
            outcome.horizon = outcome.plan.horizon
            along = [attempt for attempt in outcome.horizons_tried if not attempt.note]  # not the probe's
            searched_up = self.horizon is None and all(a.result == "unsat" for a in along[:-1])
            outcome.minimal = outcome.horizon <= bound or (searched_up and not self.assign)
            outcome.minimal_along_assignment = self.assign and (searched_up or outcome.minimal)
            if self.assign and self.tighten and self.horizon is None and not outcome.minimal and not self.probe_plan:
                self._tighten()
        return outcome

    def _horizons(self, bound: float) -> tuple[int, int] | None:
        """The horizons to search; ``None`` when no plan can follow the task assignment."""
        if self.horizon is not None:
            return self.horizon, self.horizon
        first = int(bound)
        if self.assign:
            along = assignment_bound(self.instance, self.outcome.assignment.facts, self.floor)
            if along == float("inf"):
                return None
            first = max(first, int(along))
            if self.domain.bound is Bound.DELIVERY:
                first = int(assigned_bound(self.instance, self.domain, self.floor, self._carriers(), first))
        last = self.max_horizon if self.max_horizon is not None else self._largest_horizon(first)
        return first, last

    def _probe(self, bound: int) -> int:
        """Before a task assignment: look for a plan without one from the lower bound up, within
        a conflict budget; return the first horizon not refuted.

        A refuted horizon is refuted for every assignment.  A plan found is minimal, and the
        assignment read off it costs no makespan at all (where the whole problem is easy at
        its bound, an optimised assignment can only make it longer or harder).  A plan that
        moves more shelves than it delivers from is found again along its assignment; where
        that fails (some plans must move a shelf out of the way, which no assignment allows),
        the plan is kept in case no plan along an assignment turns up (``probe_plan``).
        """
        outcome, horizon = self.outcome, bound
        size = len(self.instance.robots) * len(self.floor.cells) * bound
        budget = allowance = min(PROBE_CONFLICTS, PROBE_WORK // max(1, size))
        while budget > 0 and not self.watch.cancelled and not self.watch.expired:
            result, used = self._probe_at(horizon, budget)
            budget -= used
            if result.status is Status.UNSAT:
                horizon += 1
                continue
            if result.status is Status.SAT:
                plan = self._plan(result)
                outcome.assignment, exact = assignment_of_plan(self.instance, self.domain, plan)
                self.follow_assignment = True
                if not exact:
                    again, _ = self._probe_at(horizon, allowance)
                    if again.status is Status.SAT:
                        plan = self._plan(again)
                    else:
                        self.probe_plan, plan = (plan, outcome.assignment), None
                if plan is not None:
                    outcome.status, outcome.plan, outcome.horizon = SolveStatus.FOUND, plan, plan.horizon
                    outcome.minimal = outcome.minimal_along_assignment = True
                else:
                    outcome.assignment, self.follow_assignment = None, False
            return horizon
        return horizon

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

    def _probe_at(self, horizon: int, conflicts: int) -> tuple[Result, int]:
        """One try of the probe (along the assignment when one is followed): the result and
        the conflicts it used."""
        started = time.perf_counter()
        solver, hinted = self.grounded(horizon)
        solver.assign_external("use_hints", hinted)
        self.watch.phase("solving", horizon)
        result = solver.solve(time_limit=self.watch.remaining(), conflicts=conflicts)
        note = "along the plan's assignment" if self.follow_assignment else WITHOUT_ASSIGNMENT
        self._record(Attempt(horizon, result.status.value, time.perf_counter() - started, note))
        return result, max(1, solver.stats.conflicts)

    def _assign(self) -> bool:
        """Compute the task assignment the planner will follow; whether there is one."""
        outcome, watch = self.outcome, self.watch
        if self.given is not None:
            outcome.assignment, self.follow_assignment = self.given, True
            return True
        budget = watch.remaining()
        budget = ASSIGNMENT_SECONDS if budget is None else min(ASSIGNMENT_SECONDS, ASSIGNMENT_SHARE * budget)
        watch.phase("assigning", 0)
        outcome.assignment = assign_tasks(self.instance, self.domain, budget, watch.attach)
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
        while outcome.horizon > self.bound and not watch.cancelled and not watch.expired:
            limit = budget_end - time.perf_counter()
            if limit <= 0:
                return
            horizon = outcome.horizon - 1
            started = time.perf_counter()
            result = self._solve_at(horizon, limit)
            self._record(Attempt(horizon, result.status.value, time.perf_counter() - started,
                                 WITHOUT_ASSIGNMENT))
            if result.status is Status.UNSAT:
                outcome.minimal = True
                return
            if result.status is not Status.SAT:
                return
            outcome.plan, outcome.horizon = self._plan(result), horizon
            outcome.minimal = horizon <= self.bound

    def _largest_horizon(self, first: int) -> int:
        """Where an upward search gives up: no plan needs this many steps in practice."""
        lines = sum(len(order.lines) for order in self.instance.orders.values())
        return first + len(self.instance.cells) + len(self.instance.robots) + 2 * lines

    def _program(self, solver: Solver, horizon: int | None) -> bool:
        """Load the encoding and the instance; whether the program has search hints."""
        solver.add(self.facts)
        hinted = False
        if self.follow_assignment:
            solver.add(self.outcome.assignment.text())
        elif horizon is not None and self.domain.work is Job.GOALS and len(self.instance.robots) >= HINTED_ROBOTS:
            hints = unusable_goals(self.instance, horizon, self.floor)
            solver.add("".join(f"ruled_out({r},({x},{y})).\n" for r, (x, y) in hints))
        if self.domain.work is Job.TRIPS:
            solver.add(self._station_distances())
        if horizon is not None and self.domain.bound is Bound.DELIVERY:
            carriers = self._carriers() if self.follow_assignment else None
            schedule = delivery_schedule(self.instance, self.domain, self.floor, horizon, carriers)
            solver.add("".join(f"hint_serve({o},{p},{t}).\n" for o, p, t in schedule))
            hinted = bool(schedule)
        solver.load(self.encoding.program)
        return hinted

    def _carriers(self) -> dict[int, int]:
        """Shelf -> robot of the task assignment (``assign(robot(R),shelf(S),pickingStation(P))``)."""
        carriers = {}
        for fact in self.outcome.assignment.facts:
            robot, shelf = clingo.parse_term(fact).arguments[:2]
            carriers[shelf.arguments[0].number] = robot.arguments[0].number
        return carriers

    def _station_distances(self) -> str:
        """``to_station/3`` facts (abc/distance.lp would compute them layer by layer)."""
        if self._distances is None:
            stations = sorted({station.at for station in self.instance.stations.values()})
            table = self.floor.distances(stations, self.floor.cells)
            facts = ["distances_given."]
            for row, (px, py) in enumerate(stations):
                for column, (x, y) in enumerate(self.floor.cells):
                    if table[row, column] != float("inf"):
                        facts.append(f"to_station(({px},{py}),({x},{y}),{int(table[row, column])}).")
            self._distances = "\n".join(facts)
        return self._distances

    def _record(self, attempt: Attempt) -> None:
        self.outcome.horizons_tried.append(attempt)
        self.watch.progress(attempt)

    def _plan(self, result: Result) -> Plan:
        symbols = [_with_values(symbol, result.assignment) for symbol in result.symbols]
        return name_robots(self.encoding, self.facts, symbols)

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

    def _solve(self, solver: Solver, horizon: int, limit: float | None = None, hinted: bool = False) -> Result:
        remaining = self.watch.remaining()
        if limit is not None:
            remaining = limit if remaining is None else min(limit, remaining)
        self.watch.phase("solving", horizon)
        if not hinted:
            return solver.solve(time_limit=remaining)
        return self._solve_in_turns(solver, remaining)

    def _solve_in_turns(self, solver: Solver, limit: float | None) -> Result:
        """Search with and without hints in turns on one grounding (turns of 1,000, 1,000,
        2,000, 2,000, ... conflicts)."""
        end = None if limit is None else time.perf_counter() + limit
        turn, hints = FIRST_TURN, True
        while True:
            left = None if end is None else max(end - time.perf_counter(), 0.0)
            solver.assign_external("use_hints", hints)
            result = solver.solve(time_limit=left, conflicts=turn)
            if result.status is not Status.UNKNOWN or result.timed_out or self.watch.cancelled:
                return result
            if not hints:
                turn *= 2
            hints = not hints

    def grounded(self, horizon: int) -> tuple[Solver, bool]:
        """The encoding grounded for exactly this horizon in a fresh solver, and whether it has hints."""
        if self.encoding.incremental:
            solver = Solver(self.encoding.theory, self.options)
            self._program(solver, None)
            self.watch.attach(solver)
            self.watch.phase("grounding", horizon)
            steps = [("step", [t]) for t in range(1, horizon + 1)]
            solver.ground([("base", []), *steps, ("check", [horizon])])
            solver.assign_external(f"query({horizon})", True)
            return solver, False
        solver = Solver(self.encoding.theory, self.options, constants={"horizon": horizon})
        hinted = self._program(solver, horizon)
        self.watch.attach(solver)
        self.watch.phase("grounding", horizon)
        solver.ground()
        return solver, hinted

    def _solve_at(self, horizon: int, limit: float | None = None) -> Result:
        """Ground and solve the encoding for exactly this horizon, in a fresh solver."""
        solver, hinted = self.grounded(horizon)
        return self._solve(solver, horizon, limit, hinted)

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
        solver = Solver(self.encoding.theory, self.options)
        self._program(solver, None)
        self.watch.attach(solver)
        started = time.perf_counter()
        self.watch.phase("grounding", first)
        solver.ground([("base", [])] + [("step", [t]) for t in range(1, first + 1)])
        for horizon in range(first, last + 1):
            if self._stopped():
                return
            if horizon > first:
                started = time.perf_counter()
                self.watch.phase("grounding", horizon)
                solver.ground([("step", [horizon])])
            solver.ground([("check", [horizon])])
            solver.assign_external(f"query({horizon})", True)
            going_on = self._tried(horizon, self._solve(solver, horizon), time.perf_counter() - started)
            solver.release_external(f"query({horizon})")
            if not going_on:
                return
        if self.horizon is None:
            self.outcome.status = SolveStatus.LIMIT
