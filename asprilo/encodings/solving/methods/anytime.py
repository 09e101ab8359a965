"""The anytime method (``anytime``): a checked plan fast, then better ones
(:mod:`asprilo.encodings.anytime`); each plan it reports is an ``improved`` attempt."""

from __future__ import annotations

from asprilo.domain import Domain
from asprilo.errors import InputError

from ..method import Method, spec_rules
from ..outcome import Outcome
from ..request import SolveRequest
from ..status import SolveStatus
from ..watch import Watch


class Anytime(Method):
    """Plans of falling makespan until the time limit or the lower bound (``--method anytime``)."""

    name = "anytime"
    words = "the anytime planner"
    bounds_beside = True  # a first plan does not wait for the strong bound (minutes on 200x200)

    def honours(self, domain: Domain) -> bool:
        """The rules of SPEC.md (the planner moves robots in four directions, knows no rule more)."""
        return spec_rules(domain)

    def check(self, request: SolveRequest) -> None:
        if request.horizon is not None:
            raise InputError("the anytime method searches the makespan itself; leave out --horizon")
        self.refuse_other_rules(request, "the anytime planner")

    def time_limit(self, request: SolveRequest) -> float | None:
        """The request's, or the planner's default (it needs one to share out its time)."""
        from ...anytime import DEFAULT_SECONDS  # many modules: only when it runs

        return DEFAULT_SECONDS if request.time_limit is None else request.time_limit

    def run(self, request: SolveRequest, watch: Watch) -> Outcome:
        from ...anytime import plan_anytime

        outcome = Outcome(SolveStatus.LIMIT, request.domain, self.name, self.name)

        def heard(better) -> None:
            outcome.horizons_tried.append(better)
            watch.progress(better)

        result = plan_anytime(request.instance, request.domain, on_improvement=heard, watch=watch,
                              bounds=request.bounds, start=request.start)
        outcome.status = result.status
        outcome.plan, outcome.check, outcome.minimal = result.plan, result.check, result.minimal
        outcome.horizon = result.plan.horizon if result.plan is not None else None
        outcome.lower_bound = result.bound
        outcome.message = "; ".join(said for said in (result.message, *result.notes) if said)
        outcome.history = [better.figures() for better in result.history]
        outcome.stats = dict(result.stats)
        return outcome
