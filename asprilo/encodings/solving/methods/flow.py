"""The max-flow method (``flow``): the exact solver of M/Md (:mod:`asprilo.encodings.flow`)."""

from __future__ import annotations

from asprilo.domain import Domain, Job
from asprilo.errors import InputError
from asprilo.solver import Statistics

from ..method import Method, spec_rules
from ..outcome import Outcome
from ..request import SolveRequest
from ..status import SolveStatus
from ..watch import Watch

#: robots x cells up to which a max-flow run is quick (the paper's small M instance: 726; its
#: plan takes a few milliseconds, a child process about 15)
QUICK_ROBOT_CELLS = 2_000


class MaxFlow(Method):
    """The minimal makespan of anonymous robots as maximum flow over time (``--method flow``)."""

    name = "flow"
    words = "max-flow"

    def honours(self, domain: Domain) -> bool:
        """M and Md as SPEC.md has them: robots move in four directions to goal cells."""
        return domain.work is Job.GOALS and spec_rules(domain)

    def check(self, request: SolveRequest) -> None:
        if request.domain.work is not Job.GOALS:
            raise InputError(f"the flow method solves domains M and Md only, not {request.domain.label}")
        self.refuse_other_rules(request, "the flow method", "SPEC.md's rules of M and Md")
        if request.instance.assignment:
            raise InputError("the instance assigns goals to robots; the flow method solves anonymous "
                             "goals only (use --method asp)")

    def quick(self, request: SolveRequest) -> bool:
        return len(request.instance.robots) * len(request.instance.cells) <= QUICK_ROBOT_CELLS

    def run(self, request: SolveRequest, watch: Watch) -> Outcome:
        from ...flow import flow_plan  # numpy and the network: only when max-flow runs

        outcome = Outcome(SolveStatus.LIMIT, request.domain, self.name, self.name)
        search = flow_plan(request.instance, request.horizon, watch, watch.progress, request.lower_bound)
        watch.count(Statistics(solve_time=sum(attempt.seconds for attempt in search.attempts)))
        outcome.status, outcome.lower_bound = search.status, search.lower_bound
        outcome.horizons_tried = list(search.attempts)
        if search.plan is not None:
            outcome.plan, outcome.horizon, outcome.minimal = search.plan, search.plan.horizon, search.minimal
        return outcome
