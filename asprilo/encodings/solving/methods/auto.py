"""The default method (``auto``): the exact horizon search and the anytime planner at the same
time, each in a child process of its own, within the one time limit (:class:`Auto`).

Both children start at once.  The exact search computes the lower bounds (once: this process
hands them to the anytime planner, which starts without them and takes them when they come)
and reports every horizon it tries, each plan with the horizon that has it (checked here as
it arrives); the anytime planner reports every better plan (checked in its process).  This
process keeps the best checked plan and the proven lower bound (the lower bound raised past
the horizons refuted for the problem -- not those refuted only along a task assignment), and
stops both as soon as the best plan meets that bound: the exact search found a plan at a
horizon all below which are refuted, or refuted every horizon below the anytime plan, or the
anytime plan met the lower bound.  Otherwise both run until the time limit (or the caller's
cancel), and the answer is the best plan with its bound and gap.  A plan once reported is
never lost, whatever stops a child later.

Where one method answers at once and exactly, ``auto`` is that method (:func:`resolve`): the
max-flow solver for M/Md with anonymous goals, the horizon search for a given horizon or an
encoding without one.  Where the anytime planner and max-flow do not honour the domain's
rules (a rule variant, a domain with a checker concern of its own: :meth:`Method.honours`),
``auto`` is the horizon search with the domain's own encoding (a variant's model solution),
and bad input where the domain has none.  The alternatives measured (benchmarks/RESULTS.md,
"A plan always"): the two in turns in one process, and the anytime plan's makespan as the
exact search's largest horizon.
"""

from __future__ import annotations

import contextlib
import threading
import time
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from asprilo.bounds import INFINITE
from asprilo.domain import Bound
from asprilo.errors import InputError

from ...registry import Encoding, default_encoding, no_encoding_words
from ..bounds import AwaitedBounds, LowerBounds
from ..method import Method, unserved_words
from ..outcome import Outcome, proven_bound
from ..request import SolveRequest
from ..status import IMPROVED, Attempt, Phase, SolveStatus, Totals
from ..watch import Watch
from .anytime import Anytime
from .exact import UNREACHABLE
from .flow import MaxFlow

if TYPE_CHECKING:
    from asprilo.isolation import Child, Isolated

#: the method's name, and the names of its two parts
AUTO, EXACT, ANYTIME = "auto", "asp", "anytime"
#: how much longer than its time limit a part may take before it is killed (seconds)
_PART_GRACE = 0.5
#: how often the parent looks at the caller's cancel (seconds)
_POLL = 0.05


def resolve(request: SolveRequest) -> SolveRequest:
    """``request`` with method ``auto`` where one method serves it alone: ``flow`` for M/Md
    with anonymous goals (exact and fast), ``asp`` for a horizon given or an encoding that
    sets its horizon itself.  Other requests (and other methods) are returned as they are."""
    if request.method != AUTO:
        return request
    encoding = request.encoding
    if request.horizon is not None or (encoding is not None and encoding.fixed):
        return replace(request, method=EXACT)
    own = encoding is not None and encoding.own
    plain = not request.instance.assignment and not request.assign and not own and request.stage is None
    if plain and MaxFlow().honours(request.domain):
        return replace(request, method="flow")
    if request.stage is not None or not Anytime().honours(request.domain):
        return replace(request, method=EXACT)
    return request


class Auto(Method):
    """The exact search and the anytime planner together (``--method auto``, the command's
    default)."""

    name = AUTO
    words = "the exact search beside the anytime planner"
    encoded = True
    isolates_itself = True

    def check(self, request: SolveRequest) -> None:
        """A domain none of whose methods serves without an encoding of its own (a variant
        without a model solution) is bad input: said naming the variant and what to do."""
        domain = request.domain
        if request.encoding is None and not domain.encodings and not MaxFlow().honours(domain) \
                and not Anytime().honours(domain):
            raise InputError(f"no method of solve serves {domain.label}: max-flow and the anytime planner know only "
                             f"SPEC.md's rules, not {unserved_words(domain)}, and {no_encoding_words(domain)}; "
                             "give your own encoding to solve under its rules: --encoding FILE")

    def label(self, request: SolveRequest) -> str:
        return _encoding(request).name

    def run(self, request: SolveRequest, watch: Watch) -> Outcome:
        return Portfolio(request, watch).run()


def _encoding(request: SolveRequest) -> Encoding:
    return request.encoding if request.encoding is not None else default_encoding(request.domain)


class Portfolio:
    """One run of :class:`Auto`: its two parts, what they reported, the best plan so far."""

    def __init__(self, request: SolveRequest, watch: Watch):
        self.request, self.watch = request, watch
        self.outcome = Outcome(SolveStatus.LIMIT, request.domain, AUTO, _encoding(request).name)
        self.bounds: LowerBounds | None = request.bounds
        self.lock = threading.Lock()
        self.stop = threading.Event()       # ends both children (the one cancel they share)
        self.best: Attempt | None = None    # the best checked plan so far
        self.ended: dict[str, Isolated] = {}
        self.totals: dict[str, Any] = {}    # the exact search's statistics so far
        self.error: BaseException | None = None
        self.outbox: Any = None             # where the bounds go to the anytime planner

    # --- running the parts -------------------------------------------------------------------

    def run(self) -> Outcome:
        outcome = self.outcome
        if self.bounds is not None and self.bounds.makespan == INFINITE:
            outcome.lower_bound = INFINITE
            outcome.status, outcome.minimal, outcome.message = SolveStatus.NONE, True, UNREACHABLE
            return outcome
        threads = [threading.Thread(target=self._part, args=(name, child, limit), daemon=True, name=f"auto-{name}")
                   for name, (child, limit) in self._start().items()]
        for thread in threads:
            thread.start()
        try:
            while any(thread.is_alive() for thread in threads):
                if self.watch.cancelled:
                    self.stop.set()
                for thread in threads:
                    thread.join(_POLL / len(threads))
        except BaseException:  # an interrupt: both children are killed before it goes on (issue 46)
            self.stop.set()
            for thread in threads:
                thread.join()
            raise
        if self.outbox is not None:
            self.outbox.close()
        if self.error is not None:
            raise self.error
        return self._answer()

    def _start(self) -> dict[str, tuple[Child, float | None]]:
        """Start both children (before the threads that wait for them: a process that ran no
        other thread then forks both instead of starting fresh interpreters), with their
        time limits."""
        import multiprocessing  # here, not at the top: a quick method (flow) starts faster without it

        from asprilo.isolation import start_isolated

        request, inbox = self.request, None
        if self.bounds is None:
            inbox, self.outbox = multiprocessing.Pipe(duplex=False)
        parts = {EXACT: (replace(request, method=EXACT, isolate=False), None),
                 ANYTIME: (replace(request, method=ANYTIME, isolate=False, assign=False, assignment=None,
                                   max_horizon=None), inbox)}
        children: dict[str, tuple[Child, float | None]] = {}
        try:
            for name, (part, box) in parts.items():
                limit = self._limit(name)
                deadline = None if limit is None else time.time() + limit
                children[name] = start_isolated(_part_in_child, (part, deadline, box), request.memory_limit), limit
        except BaseException:
            self.stop.set()
            for child, _ in children.values():
                child.wait(cancel=self.stop)
            raise
        finally:
            if inbox is not None:
                inbox.close()  # the children have their own ends
        return children

    def _limit(self, name: str) -> float | None:
        """The seconds a part has: the solve's time left (the anytime planner needs a limit
        to share its time out: its own default when the solve has none)."""
        limit = self.watch.remaining()
        if name == ANYTIME and limit is None:
            from ...anytime import DEFAULT_SECONDS
            limit = DEFAULT_SECONDS
        return limit

    def _part(self, name: str, child: Child, limit: float | None) -> None:
        """Wait for one part's child process (in a thread of this process); the child's time
        ends when this solve's does, and it is killed a moment later."""
        try:
            ended = child.wait(time_limit=None if limit is None else limit + _PART_GRACE,
                               on_message=lambda message: self._heard(name, message), cancel=self.stop)
        except BaseException as error:  # noqa: BLE001 - raised again in the caller's thread
            self.error = error
            self.stop.set()
            return
        with self.lock:
            self.ended[name] = ended
            if ended.done:
                self._part_done(name, ended.value)
            if len(self.ended) == 2 or self._settled() or (ended.done and ended.value.status is SolveStatus.NONE):
                self.stop.set()

    def _part_done(self, name: str, outcome: Outcome) -> None:
        """A part that ended on its own: what its outcome says (its plans were reported
        already, but for a plan of a search that sets its horizon itself)."""
        if name == EXACT:
            self.totals = outcome.stats or self.totals
            self.outcome.assignment = outcome.assignment
            self.outcome.minimal_along_assignment = outcome.minimal_along_assignment
            self.outcome.warnings = outcome.warnings
        if (outcome.found and outcome.plan is not None and outcome.horizon is not None
                and (self.best is None or outcome.horizon < self.best.horizon)):
            self._offer(name, Attempt(outcome.horizon, IMPROVED if name == ANYTIME else "sat", 0.0,
                                      plan=outcome.plan), checked=True)

    # --- what the parts report -------------------------------------------------------------------

    def _heard(self, name: str, message: object) -> None:
        """One message of a part's child (in the thread that waits for that child)."""
        listeners = self.watch.listeners
        with self.lock:
            if isinstance(message, Attempt):
                self.outcome.horizons_tried.append(message)
                if message.plan is not None:
                    self._offer(name, message, checked=name == ANYTIME)
                if listeners.progress is not None:
                    listeners.progress(message)
                if self._settled():
                    self.stop.set()
            elif isinstance(message, Phase) and listeners.phase is not None:
                listeners.phase(message)
            elif isinstance(message, Totals) and name == EXACT:
                self.totals = message.figures
            elif isinstance(message, LowerBounds) and name == EXACT and self.bounds is None:
                self._bounds_known(message)

    def _bounds_known(self, bounds: LowerBounds) -> None:
        """The exact search computed the bounds: hand them to the anytime planner (and to
        whoever listens)."""
        self.bounds = bounds
        if self.outbox is not None:
            with contextlib.suppress(OSError):  # the anytime planner may have ended
                self.outbox.send(bounds)
        if self.watch.listeners.bounds is not None:
            self.watch.listeners.bounds(bounds)
        if self._settled():  # the anytime planner's plan meets the bound
            self.stop.set()

    def _offer(self, name: str, attempt: Attempt, checked: bool) -> None:
        """A plan reported: the best one so far if it is shorter (and, unless ``checked`` in
        its child, passes the check here)."""
        # (the anytime planner's later plan of the same makespan has a smaller sum of costs)
        same = name == ANYTIME and self.outcome.found_by == ANYTIME
        if self.best is not None and (attempt.horizon > self.best.horizon or
                                      (attempt.horizon == self.best.horizon and not same)):
            return
        report = None
        if not checked:
            trial = self._checked(attempt)
            if not trial.found:
                self.outcome.message = trial.message
                return
            report = trial.check
        self.best, self.outcome.found_by, self.outcome.check = attempt, name, report
        self.outcome.history.append({"seconds": round(self.watch.elapsed(), 3), "makespan": attempt.horizon,
                                     "by": name})

    def _checked(self, attempt: Attempt) -> Outcome:
        """The ASP checker's verdict on a plan (with the bounds known, or the admissible 0)."""
        from ..front import check_plan  # the front end imports the method table

        trial = Outcome(SolveStatus.FOUND, self.request.domain, AUTO, self.outcome.encoding, plan=attempt.plan,
                        horizon=attempt.horizon)
        check_plan(replace(self.request, bounds=self.bounds or LowerBounds(0.0)), trial)
        return trial

    def _lower(self) -> float:
        return 0.0 if self.bounds is None else self.bounds.makespan

    def _settled(self) -> bool:
        """Whether the best plan is proven minimal: nothing is left to search."""
        return self.best is not None and self.best.horizon <= proven_bound(self._lower(), self.outcome.refuted)

    # --- the answer --------------------------------------------------------------------------------

    def _answer(self) -> Outcome:
        outcome, best = self.outcome, self.best
        outcome.lower_bound = self._lower()
        outcome.stats = dict(self.totals)
        if best is not None:
            outcome.status, outcome.plan, outcome.horizon = SolveStatus.FOUND, best.plan, best.horizon
            if outcome.check is None:  # the anytime planner's plan: checked there, with the bounds known now
                from ..front import checked_verdict  # the front end imports the method table

                outcome.check = checked_verdict(best, self.request.instance, LowerBounds(self._lower())) or \
                    self._checked(best).check
            outcome.minimal = best.horizon <= outcome.proven_bound
            outcome.message = "" if outcome.minimal else self._why()
            if self.bounds is None:
                outcome.message += "; the lower bound was not computed by then"
            return outcome
        outcome.found_by = ""
        ended = {name: child.value for name, child in self.ended.items() if child.done}
        if self.watch.cancelled:
            outcome.status, outcome.message = SolveStatus.CANCELLED, self._why()
        elif any(part.status is SolveStatus.NONE for part in ended.values()):
            none = next(part for part in ended.values() if part.status is SolveStatus.NONE)
            outcome.status, outcome.minimal, outcome.message = SolveStatus.NONE, True, none.message
        else:
            outcome.status = SolveStatus.LIMIT
            outcome.message = outcome.message or self._why()
        return outcome

    def _why(self) -> str:
        """Why the search ended before a plan was proven minimal: the caller's cancel, what
        the parts said, or the time limit."""
        from ..front import why_stopped

        if self.watch.cancelled:
            return "cancelled"
        said = [child.value.message for child in self.ended.values() if child.done and child.value.message]
        stopped = [child for child in self.ended.values() if not child.done and child.status != "timeout"]
        if stopped:
            said.append(why_stopped(self.request, stopped[0].status, stopped[0].detail, False))
        if not said and self.request.time_limit is not None:
            said.append(f"stopped at the time limit ({self.request.time_limit:g} s)")
        return "; ".join(dict.fromkeys(said))


def _part_in_child(request: SolveRequest, deadline: float | None, inbox: Any,
                   report: Callable[[object], None]) -> Outcome:
    """A part's child process: its request, with the time left until ``deadline`` (wall-clock
    seconds since the epoch: starting the child took some of it), and for the anytime planner
    the bounds to come on ``inbox`` (M/Md wait for them: their goal assignment needs them)."""
    from ..front import solve_in_child  # the front end imports the method table

    if deadline is not None:
        request = replace(request, time_limit=max(0.01, deadline - time.time()))
    if inbox is not None and request.bounds is None:
        if request.domain.bound is Bound.MAPF:
            with contextlib.suppress(EOFError, OSError):  # the exact search ended before: computed here
                request = replace(request, bounds=inbox.recv())
        else:
            request = replace(request, bounds=AwaitedBounds(inbox=inbox))

        def passed_on(message: object) -> None:  # the parent has the bounds already
            if not isinstance(message, LowerBounds):
                report(message)

        return solve_in_child(request, passed_on)
    return solve_in_child(request, report)
