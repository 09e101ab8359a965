"""The exact method (``asp``): a logic program over growing horizons (:class:`HorizonSearch`).

Without a horizon, the search starts at the admissible lower bound the request carries and
goes up one step at a time.  Every horizon is grounded afresh (the encodings prune with
distances to the horizon); incremental encodings instead ground one more ``step(t)`` part
and move the ``query(t)`` external.  The first horizon with a plan is the minimal makespan
when every horizon below it was refuted.  With a task assignment the search follows it
(:mod:`.assigned`: the probe, the assignment, the tightening).

The search takes an :class:`~asprilo.encodings.Encoding`, not a name: a reference encoding
or a user's own program (single-shot with a ``horizon`` constant, or incremental with
``step(t)``/``check(t)``/``query(t)``, with or without a clingcon/clingo-dl theory).
"""

from __future__ import annotations

import time

from asprilo.bounds import INFINITE
from asprilo.domain import Domain, domains
from asprilo.errors import InputError
from asprilo.solver import Result, Solver, Status

from ...registry import Encoding, default_encoding
from ..method import Method, spec_rules
from ..outcome import Outcome
from ..request import SolveRequest
from ..status import Attempt, SolveStatus
from ..watch import Watch
from .program import Program, incmode_parts

#: the message of a search that cannot start: the lower bound is infinite
UNREACHABLE = "some goal or order line can never be reached"
#: what a user's encoding must show (said when a model shows none of it)
INTERFACE = ("its model has no occurs(object(robot,R),action(Name,Args),T) atoms: an encoding reads the "
             "instance's init/2 facts and shows the plan as occurs/3 (e.g. #show occurs/3.)")


class HorizonSearch:
    """The search over horizons of one encoding on one instance: the program, the outcome
    it fills in, and the attempts it reports."""

    def __init__(self, request: SolveRequest, encoding: Encoding, watch: Watch):
        self.request, self.watch = request, watch
        self.program = Program(request.instance, request.domain, encoding, watch)
        self.outcome = Outcome(SolveStatus.LIMIT, request.domain, ExactSearch.name, encoding.name)
        self.outcome.lower_bound = request.lower_bound
        self.gave_up = False  # every horizon up to the last was refuted
        #: whether a horizon the encoding refutes has no plan under the domain's rules (not so
        #: for the model solution of a variant composed after one that relaxes the rules)
        self.sound = refutes_for(request.domain, encoding)

    def run(self) -> Outcome:
        """The search without a task assignment (after the first stage, where there is one)."""
        outcome, bound = self.outcome, self.request.lower_bound
        fixed = self.program.encoding.fixed  # solved once, as it is, whatever the bound
        if (not fixed and self.unreachable()) or not self.staged():
            return outcome
        if fixed:
            return self.once()
        first = int(bound) if self.request.horizon is None else self.request.horizon
        last = self.last_horizon(first)
        self.upward(first, last)
        if outcome.plan is not None:
            outcome.horizon = outcome.plan.horizon
            searched = self.searched_up()
            if self.program.staged is not None:  # refuted along the first stage's answer only
                outcome.minimal, outcome.minimal_along_assignment = outcome.horizon <= bound, searched
            else:
                outcome.minimal = outcome.horizon <= bound or (searched and self.sound)
        elif outcome.status is SolveStatus.NONE and self.program.staged is not None:
            outcome.message = (f"no plan at horizon {last} along the first stage's answer (not refuted for the "
                               "problem)")
        elif outcome.status is SolveStatus.NONE and not self.sound:
            outcome.message = (f"no plan at horizon {last} for the encoding '{self.program.encoding.name}', which "
                               f"states the rules of its variant alone (not refuted under {self.request.domain.label})")
        elif outcome.status is SolveStatus.LIMIT and self.gave_up and not spec_rules(self.request.domain):
            # under rules of its own (a variant that confines robots, say), the bound cannot say
            # that no plan exists: where the search stopped is said instead
            outcome.message = (f"the encoding '{self.program.encoding.name}' has no plan up to horizon {last}, where "
                               f"the search stops (the lower bound plus the floor's cells, the robots and twice the "
                               f"order lines): longer plans are not tried")
        return outcome

    def staged(self) -> bool:
        """Solve the first stage, if the request has one, and give its atoms to the program;
        whether the search goes on (a stage without an answer ends it, said in words)."""
        stage = self.request.stage
        if stage is None:
            return True
        from ..stage import solve_stage, stage_words

        answer = solve_stage(stage, self.program.facts, self.watch, self.request.horizon)
        self.program.warnings += [f"first stage: {warning}" for warning in answer.warnings]
        self.outcome.warnings = self.program.warnings
        self.outcome.stage = ", ".join(str(file) for file in stage.files)
        if answer.status is Status.SAT:
            self.program.staged, self.outcome.staged = answer.symbols, answer.facts
            return True
        self.outcome.message = stage_words(stage, answer)
        if answer.status is Status.UNSAT:
            self.outcome.status = SolveStatus.NONE
        else:
            self.outcome.status = SolveStatus.CANCELLED if self.watch.cancelled else SolveStatus.LIMIT
        return False

    def once(self) -> Outcome:
        """A program without a horizon: grounded and solved once, as it is."""
        outcome = self.outcome
        if self.stopped():
            return outcome
        started = time.perf_counter()
        solver = self.program.fresh(None)
        self.watch.phase("grounding", 0)
        solver.ground()
        self.program.heard(solver)
        result = self.program.solve(solver, 0)
        plan = self.program.plan(result) if result.status is Status.SAT else None
        self._tried(plan.horizon if plan is not None else 0, result, time.perf_counter() - started)
        if result.status is Status.UNSAT:
            outcome.message = "the encoding has no answer set on this instance (it sets its horizon itself)"
        if outcome.plan is not None:
            outcome.horizon = outcome.plan.horizon
            outcome.minimal = outcome.horizon <= self.request.lower_bound
        return outcome

    def unreachable(self) -> bool:
        """Whether the lower bound says that no plan exists (an upward search then ends at once)."""
        if self.request.lower_bound != INFINITE or self.request.horizon is not None:
            return False
        outcome = self.outcome
        outcome.status, outcome.minimal, outcome.message = SolveStatus.NONE, True, UNREACHABLE
        return True

    def last_horizon(self, first: int) -> int:
        """The horizon the search gives up after: the one asked for, the largest one asked
        for, or one no plan needs in practice."""
        request = self.request
        if request.horizon is not None:
            return request.horizon
        if request.max_horizon is not None:
            return request.max_horizon
        instance = request.instance
        lines = sum(len(order.lines) for order in instance.orders.values())
        return first + len(instance.cells) + len(instance.robots) + 2 * lines

    def searched_up(self) -> bool:
        """Whether the plan found ends an upward search in which every horizon below was
        refuted (the probe's tries aside)."""
        along = [attempt for attempt in self.outcome.horizons_tried if not attempt.note]
        return self.request.horizon is None and all(a.result == "unsat" for a in along[:-1])

    def upward(self, first: int, last: int) -> None:
        """Try the horizons ``first`` .. ``last`` until one has a plan."""
        if self.program.encoding.incremental:
            self._incremental(first, last)
        else:
            self._single_shot(first, last)

    def record(self, attempt: Attempt) -> None:
        """Keep and report one try (tried along the task assignment when the program follows one)."""
        attempt.along = self.program.assignment is not None or self.program.staged is not None or not self.sound
        self.outcome.horizons_tried.append(attempt)
        self.outcome.warnings = self.program.warnings
        self.watch.progress(attempt)

    def stopped(self) -> bool:
        """Whether the caller cancelled or the time is up (the outcome says which)."""
        if self.watch.cancelled:
            self.outcome.status = SolveStatus.CANCELLED
            return True
        if self.watch.expired:
            self.outcome.status = SolveStatus.LIMIT
            return True
        return False

    def _tried(self, horizon: int, result: Result, seconds: float) -> bool:
        """Record one horizon of the search; whether the search goes on."""
        outcome = self.outcome
        if result.status is Status.SAT:
            outcome.status, outcome.plan = SolveStatus.FOUND, self.program.plan(result)
            if self._shows_no_plan(result):
                outcome.status, outcome.plan, outcome.message = SolveStatus.INVALID, None, INTERFACE
            # the plan goes with its report: a search stopped from outside later still has it
            self.record(Attempt(horizon, result.status.value, seconds, plan=outcome.plan))
            return False
        self.record(Attempt(horizon, result.status.value, seconds))
        if result.status is Status.UNSAT:
            outcome.status = SolveStatus.NONE
            return True
        outcome.status = SolveStatus.CANCELLED if self.watch.cancelled else SolveStatus.LIMIT
        return False

    def _shows_no_plan(self, result: Result) -> bool:
        """Whether a user's encoding answered with a model that shows no plan although the
        instance asks for one (the lower bound is above 0)."""
        return self.program.encoding.own and self.request.lower_bound > 0 and \
            not any(symbol.match("occurs", 3) for symbol in result.symbols)

    def _single_shot(self, first: int, last: int) -> None:
        for horizon in range(first, last + 1):
            if self.stopped():
                return
            started = time.perf_counter()
            if not self._tried(horizon, self.program.solve_at(horizon), time.perf_counter() - started):
                return
        self._gave_up()

    def _incremental(self, first: int, last: int) -> None:
        """One solver for all horizons: ground one more step, move the query, solve again."""
        solver = self.program.fresh(None)
        started = time.perf_counter()
        self.watch.phase("grounding", first)
        solver.ground(incmode_parts(first)[:-1])  # as incmode: check(t) of every earlier step too
        for horizon in range(first, last + 1):
            if self.stopped():
                return
            if horizon > first:
                started = time.perf_counter()
                self.watch.phase("grounding", horizon)
                solver.ground([("step", [horizon])])
            self.program.heard(solver)
            if not self._incremental_step(solver, horizon, started):
                return
        self._gave_up()

    def _incremental_step(self, solver: Solver, horizon: int, started: float) -> bool:
        """Check and solve one more horizon of the incremental program; whether the search goes on."""
        solver.ground([("check", [horizon])])
        solver.assign_external(f"query({horizon})", True)
        going_on = self._tried(horizon, self.program.solve(solver, horizon), time.perf_counter() - started)
        solver.release_external(f"query({horizon})")
        return going_on

    def _gave_up(self) -> None:
        """Every horizon up to the last refuted: an upward search ran out of horizons."""
        if self.request.horizon is None:
            self.outcome.status = SolveStatus.LIMIT
            self.gave_up = True


def refutes_for(domain: Domain, encoding: Encoding) -> bool:
    """Whether a horizon ``encoding`` has no plan for has none under ``domain``'s rules.  So for
    a domain's own encodings and a user's (their claim), but for the model solution of a
    variant composed after others (``M+diagonal+sides`` runs ``sides``' solution, which knows
    four moves only) just where those others only restrict the rules: the domain before the
    last variant keeps its base's bound."""
    variants = domain.variants
    if len(variants) < 2 or encoding.own or encoding.name != variants[-1] or domain.bound is not None:
        return True
    name = domain.value.rsplit("+", 1)[0]  # registered when the variants were applied in turn
    before = next((known for known in domains() if known.value == name), None)
    return before is not None and before.bound is not None


class ExactSearch(Method):
    """The minimal makespan by a logic program over growing horizons (``--method asp``)."""

    name = "asp"
    words = "the exact search"
    encoded = True

    def check(self, request: SolveRequest) -> None:
        if request.stage is not None and request.assign:
            raise InputError("--stage and --assign each give the plan an assignment: give one of them")
        encoding = request.encoding
        if encoding is not None and encoding.fixed and request.horizon is not None:
            raise InputError(f"the encoding {encoding.name} has no horizon constant and no step(t) parts: "
                             "it is solved as it is, --horizon does not apply")

    def label(self, request: SolveRequest) -> str:
        return _encoding(request).name

    def run(self, request: SolveRequest, watch: Watch) -> Outcome:
        search = HorizonSearch(request, _encoding(request), watch)
        if not request.assign:
            return search.run()
        from .assigned import AssignedSearch
        return AssignedSearch(search).run()


def _encoding(request: SolveRequest) -> Encoding:
    return request.encoding if request.encoding is not None else default_encoding(request.domain)
