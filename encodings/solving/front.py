"""The front end of every method: :func:`solve` makes the request, finds its method, computes
the lower bounds once, runs the method under one :class:`.Watch` (here or in a child process)
and checks the plan it returns.

clingo cannot be interrupted while it grounds, so a request with ``isolate`` runs in a child
process that is killed at the time limit: the limit then holds in every phase, and the
horizons refuted so far still prove a bound.
"""

from __future__ import annotations

import threading
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

from asprilo.checker import check
from asprilo.domain import Domain, detect_domain
from asprilo.isolation import Isolated, run_isolated
from asprilo.model import Instance
from asprilo.reader import read_instance
from asprilo.solver import Statistics

from ..registry import Encoding, find_encoding
from .bounds import LowerBounds, lower_bounds
from .method import Method
from .methods import method_for
from .outcome import Outcome
from .request import SolveOptions, SolveRequest, given_assignment
from .status import Attempt, Phase, PhaseListener, Progress, SolveStatus
from .watch import Listeners, Watch

if TYPE_CHECKING:
    from typing_extensions import Unpack

#: how much longer than its time limit a child process may take before it is killed (seconds)
_CHILD_GRACE = 0.5


def solve(instance: SolveRequest | Instance | str | Path, domain: Domain | str | None = None, *,
          on_progress: Progress | None = None, on_phase: PhaseListener | None = None,
          cancel: threading.Event | None = None, **options: Unpack[SolveOptions]) -> Outcome:
    """Find a plan: for a :class:`SolveRequest`, or for ``instance`` (an :class:`Instance` or
    a path) with the request's fields as keywords (:func:`request_for`).

    ``domain``: a|b|c|m|md or a :class:`Domain` (default: detected).  ``method``: ``asp``
    (default: the ``encoding``, by default ``plain``, over growing horizons), ``flow`` (the
    exact max-flow solver of M/Md) or ``anytime`` (a checked plan fast, then better ones until
    ``time_limit``, default 60 s, or the lower bound).  The other keywords are the fields of
    :class:`SolveRequest`.  ``on_progress`` is called after every horizon (anytime: every
    better plan), ``on_phase`` when grounding, solving or assigning starts; setting ``cancel``
    stops the search from another thread.
    """
    if isinstance(instance, SolveRequest):
        if domain is not None or options:
            raise TypeError("solve() takes a SolveRequest alone (with listeners and cancel)")
        request = instance
    else:
        request = request_for(instance, domain, **options)
    return solve_request(request, Listeners(on_progress, on_phase), cancel)


def request_for(instance: Instance | str | Path, domain: Domain | str | None = None,
                **options: Unpack[SolveOptions]) -> SolveRequest:
    """The request for ``instance``, checked (bad input: :class:`~asprilo.errors.InputError`):
    the instance read, the domain detected, the encoding found by name, the given assignment
    checked."""
    if not isinstance(instance, Instance):
        instance = read_instance(instance)
    domain = detect_domain(instance) if domain is None else Domain.parse(domain)
    encoding = options.pop("encoding", "plain")
    facts = options.pop("assignment", None)
    assign = options.pop("assign", False) or facts is not None
    request = SolveRequest(instance, domain, assign=assign, **options)
    method = method_for(request)
    if facts is not None:
        request = replace(request, assignment=given_assignment(instance, domain, facts))
    if method.encoded:
        request = replace(request, encoding=encoding if isinstance(encoding, Encoding)
                          else find_encoding(domain, encoding))
    return request


def solve_request(request: SolveRequest, listeners: Listeners | None = None,
                  cancel: threading.Event | None = None) -> Outcome:
    """Run ``request`` with its method, here or (``isolate``) in a child process."""
    method = method_for(request)
    listeners = listeners or Listeners()
    if request.isolate:
        return _solve_isolated(request, method, listeners, cancel)
    return _solve_here(request, method, listeners, cancel)


def _solve_here(request: SolveRequest, method: Method, listeners: Listeners,
                cancel: threading.Event | None) -> Outcome:
    with Watch(method.time_limit(request), cancel, listeners) as watch:
        if request.bounds is None:
            request = replace(request, bounds=lower_bounds(request.instance, request.domain))
        watch.lower_bounds(request.bounds)
        outcome = method.run(request, watch)
    outcome.stats = outcome.stats or watch.totals()
    if outcome.plan is not None and outcome.check is None:
        _check_plan(request, outcome)
    return outcome


def _check_plan(request: SolveRequest, outcome: Outcome) -> None:
    """Check the plan with the ASP checker (which gets the bounds known already)."""
    bounds = request.bounds
    outcome.check = check(request.instance, outcome.plan, request.domain,
                          makespan_bound=bounds.makespan, sum_of_costs_bound=bounds.sum_of_costs)
    if not outcome.check.valid:
        outcome.status = SolveStatus.INVALID
        outcome.message = "the plan failed the check: " + "; ".join(
            error.message for error in outcome.check.errors[:3])


def _solve_isolated(request: SolveRequest, method: Method, listeners: Listeners,
                    cancel: threading.Event | None) -> Outcome:
    def forward(message: Attempt | Phase | LowerBounds) -> None:
        if isinstance(message, Attempt) and listeners.progress is not None:
            listeners.progress(message)
        elif isinstance(message, Phase) and listeners.phase is not None:
            listeners.phase(message)
        elif isinstance(message, LowerBounds) and listeners.bounds is not None:
            listeners.bounds(message)

    time_limit = request.time_limit
    child = run_isolated(_solve_in_child, (request,),
                         time_limit=None if time_limit is None else time_limit + _CHILD_GRACE,
                         memory_mb=request.memory_limit, on_message=forward, cancel=cancel)
    if child.done:
        return child.value
    return _stopped_from_outside(request, method, child, cancel)


def _solve_in_child(request: SolveRequest, report) -> Outcome:
    return _solve_here(request, method_for(request), Listeners(report, report, report), None)


def _stopped_from_outside(request: SolveRequest, method: Method, child: Isolated,
                          cancel: threading.Event | None) -> Outcome:
    """The outcome of a child process killed at a limit or on cancel, from what it reported:
    the horizons tried and, from the anytime method, its last plan (checked)."""
    cancelled = cancel is not None and cancel.is_set()
    outcome = Outcome(SolveStatus.CANCELLED if cancelled else SolveStatus.LIMIT, request.domain, request.method,
                      method.label(request))
    outcome.horizons_tried = [m for m in child.messages if isinstance(m, Attempt)]
    request = replace(request, bounds=_bounds_heard(request, child))
    outcome.lower_bound = request.lower_bound
    best = [attempt for attempt in outcome.horizons_tried if attempt.plan is not None]
    if best:  # the anytime method stopped from outside: its last plan reported (checked) is the answer
        _last_plan(request, outcome, best)
        return outcome
    outcome.stats = {key: value for key, value in Statistics().as_dict().items() if key != "models"}
    outcome.message = _why_stopped(request, child, cancelled)
    return outcome


def _last_plan(request: SolveRequest, outcome: Outcome, best: list[Attempt]) -> None:
    """The outcome found: the last of the plans reported by a method stopped from outside."""
    outcome.status, outcome.plan, outcome.horizon = SolveStatus.FOUND, best[-1].plan, best[-1].horizon
    _check_plan(request, outcome)
    outcome.minimal = outcome.horizon <= outcome.lower_bound
    outcome.history = [{"seconds": a.seconds, "makespan": a.horizon} for a in best]


def _bounds_heard(request: SolveRequest, child: Isolated) -> LowerBounds:
    """The lower bounds the child reported (computed here if it was stopped before it could)."""
    heard = [message for message in child.messages if isinstance(message, LowerBounds)]
    if heard:
        return heard[0]
    return request.bounds or lower_bounds(request.instance, request.domain)


def _why_stopped(request: SolveRequest, child: Isolated, cancelled: bool) -> str:
    if cancelled:
        return "cancelled"
    time_limit = request.time_limit
    return {"timeout": f"stopped at the time limit ({time_limit:g} s)" if time_limit else "stopped",
            "memout": f"stopped at the memory limit ({request.memory_limit} MB)",
            "crashed": f"the solver process died ({child.detail})"}[child.status]
