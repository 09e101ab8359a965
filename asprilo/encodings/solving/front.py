"""The front end of every method: :func:`solve` makes the request, finds its method, computes
the lower bounds once, runs the method under one :class:`.Watch` (here or in a child process)
and checks the plan it returns.

clingo cannot be interrupted while it grounds, so a request with ``isolate`` runs in a child
process that is killed at the time limit: the limit then holds in every phase, and the
horizons refuted so far still prove a bound.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from asprilo.checker import Report, check
from asprilo.checker.report import bound_metrics
from asprilo.domain import Domain, detect_domain
from asprilo.errors import InputError
from asprilo.model import Instance
from asprilo.reader import read_instance
from asprilo.solver import Statistics

from ..registry import Encoding, default_encoding, find_encoding
from .bounds import LowerBounds, lower_bounds, prompt_bounds
from .method import Method
from .methods import method_for, resolve
from .minimality import settle
from .outcome import Outcome
from .request import SolveOptions, SolveRequest, given_assignment, given_start
from .status import Attempt, Note, Phase, PhaseListener, Progress, SolveStatus, Totals
from .watch import Listeners, Watch

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from asprilo.isolation import Isolated

#: how much longer than its time limit a child process may take before it is killed (seconds)
_CHILD_GRACE = 0.5


def solve(instance: SolveRequest | Instance | str | Path, domain: Domain | str | None = None, *,
          on_progress: Progress | None = None, on_phase: PhaseListener | None = None,
          cancel: threading.Event | None = None, **options: Unpack[SolveOptions]) -> Outcome:
    """Find a plan: for a :class:`SolveRequest`, or for ``instance`` (an :class:`Instance` or
    a path) with the request's fields as keywords (:func:`request_for`).

    ``domain``: a|b|c|m|md or a :class:`Domain` (default: detected).  ``method``: ``asp``
    (default: the ``encoding``, by default ``plain``, or the domain's own where it has no
    ``plain``: a variant's model solution, over growing horizons), ``flow`` (the
    exact max-flow solver of M/Md), ``anytime`` (a checked plan fast, then better ones until
    ``time_limit``, default 60 s, or the lower bound) or ``auto`` (the command's default: the
    horizon search and the anytime planner at once, each in a child process, the best plan
    with its proven bound; M/Md with anonymous goals: ``flow``).  The other keywords are the
    fields of :class:`SolveRequest`.  ``on_progress`` is called after every horizon (anytime:
    every better plan), ``on_phase`` when grounding, solving or assigning starts (and again
    with the conflicts so far while a horizon is solved); setting ``cancel`` stops the search
    from another thread.
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
    _refuse_releases(instance)
    domain = detect_domain(instance) if domain is None else Domain.parse(domain)
    fields: dict[str, Any] = dict(options)  # the request's other fields, as given
    encoding = fields.pop("encoding", None)
    facts = fields.pop("assignment", None)
    assign = fields.pop("assign", False) or facts is not None
    stage = fields.pop("stage", None)
    start = fields.pop("start", None)
    if stage is not None and not isinstance(stage, Encoding):
        from ..choice import stage_encoding
        stage = stage_encoding(stage, encoding.constants if isinstance(encoding, Encoding) else ())
    given = encoding if isinstance(encoding, Encoding) else None  # a method's check may look at it
    request = SolveRequest(instance, domain, assign=assign, stage=stage, encoding=given, **fields)
    method = method_for(request)
    if facts is not None:
        request = replace(request, assignment=given_assignment(instance, domain, facts))
    if start is not None:
        request = replace(request, start=given_start(instance, domain, start))
    if method.encoded and given is None:
        request = replace(request, encoding=default_encoding(domain) if encoding is None
                          else find_encoding(domain, encoding))
    return request


def _refuse_releases(instance: Instance) -> None:
    """An online scenario (orders released over time) is no offline problem: the searches
    know no release steps, and their plans would deliver orders before they exist."""
    released = sorted((order.release, order.id) for order in instance.orders.values() if order.release is not None)
    if released:
        step, order = released[0]
        raise InputError(f"the instance releases orders over time (order {order} at step {step}): run it with "
                         "'asprilo online', or leave out its release facts to solve it offline")


def solve_request(request: SolveRequest, listeners: Listeners | None = None,
                  cancel: threading.Event | None = None) -> Outcome:
    """Run ``request`` with its method, here or (``isolate``) in a child process (a method
    that runs its own child processes, ``auto``, and a quick run always run here); then say
    what its plan is minimal for (:func:`.minimality.settle`)."""
    request = resolve(request)
    if request.start is not None and request.method == "asp":
        raise InputError("--start goes with the anytime planner (--method auto or anytime): the exact search "
                         "starts from no plan")
    if request.isolate and request.memory_limit is None and _runs_users_program(request):
        from asprilo.memory import default_memory_mb  # a user's program is limited by default (README)
        request = replace(request, memory_limit=default_memory_mb())
    method = method_for(request)
    listeners = listeners or Listeners()
    quick = request.memory_limit is None and method.quick(request)
    if request.isolate and not method.isolates_itself and not quick:
        outcome = _solve_isolated(request, method, listeners, cancel)
    else:
        outcome = solve_here(request, method, listeners, cancel)
    settle(request, outcome)  # minimal for the problem, or for a user's own encoding only
    return outcome


def _runs_users_program(request: SolveRequest) -> bool:
    """Whether the request runs a program of the user's own (an encoding or a first stage)."""
    return any(encoding is not None and encoding.own for encoding in (request.encoding, request.stage))


def solve_here(request: SolveRequest, method: Method, listeners: Listeners,
               cancel: threading.Event | None) -> Outcome:
    """Run ``request`` with ``method`` in this process: the bounds (unless the request has
    them, or the method has its child processes compute them), one watch, the method, the
    check of its plan."""
    with Watch(method.time_limit(request), cancel, listeners) as watch:
        if request.bounds is None and not method.isolates_itself and not method.bounds_beside:
            watch.phase("bounding", 0)
            request = replace(request, bounds=lower_bounds(request.instance, request.domain))
        if request.bounds is not None:
            watch.lower_bounds(request.bounds)
        outcome = method.run(request, watch)
    outcome.stats = outcome.stats or watch.totals()
    if outcome.plan is not None and outcome.check is None:
        check_plan(request, outcome)
    return outcome


def check_plan(request: SolveRequest, outcome: Outcome) -> None:
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
    from asprilo.isolation import run_isolated  # only here: starting child processes costs imports

    time_limit = request.time_limit
    child = run_isolated(solve_in_child, (request,),
                         time_limit=None if time_limit is None else time_limit + _CHILD_GRACE,
                         memory_mb=request.memory_limit, on_message=forwarder(listeners), cancel=cancel)
    if child.done:
        return child.value
    return _stopped_from_outside(request, method, child, cancel)


def forwarder(listeners: Listeners) -> Callable[[object], None]:
    """What hands each message of a child process to the listener that hears its kind."""
    def forward(message: object) -> None:
        if isinstance(message, Attempt) and listeners.progress is not None:
            listeners.progress(message)
        elif isinstance(message, Phase) and listeners.phase is not None:
            listeners.phase(message)
        elif isinstance(message, LowerBounds) and listeners.bounds is not None:
            listeners.bounds(message)
        elif isinstance(message, Totals) and listeners.totals is not None:
            listeners.totals(message)
        elif isinstance(message, Note) and listeners.notes is not None:
            listeners.notes(message)

    return forward


def solve_in_child(request: SolveRequest, report: Callable[[object], None]) -> Outcome:
    """The side of a child process: the request solved, everything heard reported at once."""
    return solve_here(request, method_for(request), Listeners(report, report, report, report, report), None)


def _stopped_from_outside(request: SolveRequest, method: Method, child: Isolated,
                          cancel: threading.Event | None) -> Outcome:
    """The outcome of a child process killed at a limit or on cancel, from what it reported:
    the horizons tried, the statistics so far and the best plan reported (checked here)."""
    cancelled = cancel is not None and cancel.is_set()
    outcome = Outcome(SolveStatus.CANCELLED if cancelled else SolveStatus.LIMIT, request.domain, request.method,
                      method.label(request))
    outcome.horizons_tried = [m for m in child.messages if isinstance(m, Attempt)]
    request = replace(request, bounds=_bounds_heard(request, child))
    outcome.lower_bound = request.lower_bound
    totals = [message.figures for message in child.messages if isinstance(message, Totals)]
    outcome.stats = totals[-1] if totals else {key: value for key, value in Statistics().as_dict().items()
                                               if key != "models"}
    stopped = why_stopped(request, child.status, child.detail, cancelled)
    if child.status == "timeout":
        stopped += _doing(child.messages)
    stopped = "; ".join([stopped, *(message.text for message in child.messages if isinstance(message, Note))])
    best = [attempt for attempt in outcome.horizons_tried if attempt.plan is not None]
    if best and best_plan(request, outcome, best):
        outcome.message = f"{stopped}; the answer is the best plan found before"
        return outcome
    outcome.message = stopped
    return outcome


def best_plan(request: SolveRequest, outcome: Outcome, found: list[Attempt]) -> bool:
    """The outcome found with the shortest of the plans ``found`` that passes the check (of
    two as short, the later: the anytime method's later plan has the smaller sum of costs);
    whether one passed.  Minimal when no plan is shorter than the bound the horizons refuted
    prove.  A plan checked where it was found (:func:`checked_verdict`) is not checked again:
    the time is up."""
    ranked = sorted(range(len(found)), key=lambda i: (found[i].horizon, -i))
    for index in ranked:
        attempt = found[index]
        verdict = checked_verdict(attempt, request.instance, request.bounds)
        outcome.status, outcome.plan, outcome.horizon, outcome.check = (
            SolveStatus.FOUND, attempt.plan, attempt.horizon, verdict)
        if outcome.check is None:
            check_plan(request, outcome)
        if outcome.found:
            outcome.message = ""
            outcome.minimal = outcome.horizon <= outcome.proven_bound
            outcome.history = [{"seconds": a.seconds, "makespan": a.horizon} for a in found]
            return True
    return False


def checked_verdict(attempt: Attempt, instance: Instance, bounds: LowerBounds | None) -> Report | None:
    """The checker's verdict that came with a plan (the anytime planner checks every plan it
    reports), if it passed, with the metrics of ``bounds`` (those known now: the planner may
    have checked it before the strong ones came)."""
    verdict = getattr(attempt, "verdict", None)
    if not isinstance(verdict, Report) or not verdict.valid:
        return None
    if bounds is None:
        return verdict
    known = bound_metrics(instance, verdict.domain, verdict.metrics, (bounds.makespan, bounds.sum_of_costs))
    return replace(verdict, metrics={**verdict.metrics, **known})


def _bounds_heard(request: SolveRequest, child: Isolated) -> LowerBounds:
    """The last lower bounds the child reported (the anytime planner says the cheap ones,
    then the strong ones when they come), else the request's or those found here at once: the
    time is up, and the strong bound of a large floor takes minutes (:func:`prompt_bounds`)."""
    heard = [message for message in child.messages if isinstance(message, LowerBounds)]
    if heard:
        return heard[-1]
    return request.bounds or prompt_bounds(request.instance, request.domain)


def why_stopped(request: SolveRequest, status: str, detail: str, cancelled: bool) -> str:
    """Why a child process ended without an answer, in words."""
    if cancelled:
        return "cancelled"
    time_limit = request.time_limit
    return {"timeout": f"stopped at the time limit ({time_limit:g} s)" if time_limit else "stopped",
            "memout": f"stopped at the memory limit ({request.memory_limit} MB)" if request.memory_limit
            else out_of_memory_words(),
            "crashed": f"the solver process died ({detail})"}[status]


def out_of_memory_words() -> str:
    """A process that ran out of memory without ``--memory-limit``: the limit it had, if any
    (``ulimit -v``)."""
    import resource

    soft, _hard = resource.getrlimit(resource.RLIMIT_AS)
    if soft == resource.RLIM_INFINITY:
        return "the solver process ran out of memory"
    return f"the solver process ran out of memory (its address space is limited to {soft // 2**20} MB: ulimit -v)"


def _doing(messages: list[object]) -> str:
    """What a child stopped from outside was doing then: the last phase it began, unless an
    attempt ended it."""
    for message in reversed(messages):
        if isinstance(message, Attempt):
            return ""
        if isinstance(message, Phase):
            return " while " + phase_words(message)
    return ""


def phase_words(phase: Phase) -> str:
    """``solving horizon 25 (12,345 conflicts so far)``, ``computing the task assignment``."""
    if phase.name == "assigning":
        return "computing the task assignment"
    if phase.name == "bounding":
        return "computing the lower bound"
    conflicts = f" ({phase.conflicts:,} conflicts so far)" if phase.conflicts else ""
    return f"{phase.name} horizon {phase.horizon}{conflicts}"
