"""The minima of ``asprilo grade --reference``: a teacher's model solution searched from the
domain's lower bound up, one horizon at a time, on every instance of an exercise.

    reference = Reference(own_encoding(["teacher.lp"]), with_variants(Domain.M, ["visit-anytime"]),
                          time_limit=20)
    found = reference.minimum(path, instance)   # a ReferenceMinimum; computed once per instance
    found.minimum, found.makespan, found.at_least, found.reason

A minimum is known only where the search proved it: a plan at a horizon after every horizon
below was refuted (or at the lower bound itself), its plan accepted by the checker under the
domain's rules (a varied domain's too).  Otherwise it is unknown (``None``) and the reason
says why in words: the time limit, no answer set, a plan that fails the check.  The minima
are kept in memory for the run only; nothing is written.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.model import Instance

from .grading import timed_out
from .ladder import ReferenceMinimum, Rung
from .registry import Encoding
from .solving import Outcome, Phase, SolveStatus, solve
from .solving.outcome import proven_bound


class Reference:
    """A teacher's encoding on one domain (a varied one checks its plans under the variant's
    rules), each instance solved under ``time_limit`` seconds (and ``memory_limit`` MB) in a
    child process.  The minima found are kept for the life of the object (one run)."""

    def __init__(self, encoding: Encoding, domain: Domain, *, time_limit: float, memory_limit: int | None = None):
        self.encoding, self.domain = encoding, domain
        self.time_limit, self.memory_limit = time_limit, memory_limit
        self._minima: dict[Path, ReferenceMinimum] = {}
        self._accepted = False  # clingo grounded the encoding on some instance

    def minimum(self, file: Path, instance: Instance,
                on_phase: Callable[[Phase], None] | None = None) -> ReferenceMinimum:
        """What the reference finds on ``instance`` (read from ``file``), searched once per
        file.  An encoding clingo refuses on the first instance searched is
        :class:`InputError` (bad input of the teacher's); refused later, that instance's
        minimum is unknown."""
        key = file.resolve()
        if key not in self._minima:
            self._minima[key] = self._search(instance, on_phase)
        return self._minima[key]

    def rung(self, rung: Rung, instance: Instance, on_phase: Callable[[Phase], None] | None = None) -> Rung:
        """``rung`` with the minimum the reference found (``None`` where unknown)."""
        found = self.minimum(rung.file, instance, on_phase)
        return replace(rung, minimum=found.minimum, reference=found)

    def _search(self, instance: Instance, on_phase: Callable[[Phase], None] | None) -> ReferenceMinimum:
        started = time.perf_counter()
        try:
            outcome = solve(instance, self.domain, method="asp", encoding=self.encoding, time_limit=self.time_limit,
                            memory_limit=self.memory_limit, isolate=True, on_phase=on_phase)
        except InputError as error:
            if not self._accepted:  # bad input of the teacher's: said as such
                raise error if error.file else InputError(f"the reference encoding: {error.message}") from None
            return ReferenceMinimum(None, None, 0, time.perf_counter() - started,
                                    f"clingo refused the reference encoding on this instance: {_words(str(error))}")
        except Exception as error:  # the teacher's encoding crashed the solve: this minimum is unknown
            return ReferenceMinimum(None, None, 0, time.perf_counter() - started,
                                    f"the reference's solve failed: {_words(str(error)) or type(error).__name__}")
        self._accepted = True
        return found(outcome, time.perf_counter() - started, self.time_limit)


def found(outcome: Outcome, seconds: float, time_limit: float) -> ReferenceMinimum:
    """What an outcome of the reference's search says of the minimum.  The teacher's encoding
    is trusted: the horizons it refutes, and its shortest plan, hold for the problem."""
    bound = proven_bound(outcome.lower_bound, outcome.refuted)
    at_least = int(bound) if math.isfinite(bound) else None
    if outcome.status is SolveStatus.FOUND and outcome.horizon is not None:
        makespan = outcome.horizon
        if outcome.encoding_minimal:
            return ReferenceMinimum(makespan, makespan, makespan, seconds)
        return ReferenceMinimum(None, makespan, at_least, seconds,
                                f"the reference found makespan {makespan} but did not prove it minimal")
    if outcome.check is not None and not outcome.check.valid:
        error = outcome.check.errors[0]
        return ReferenceMinimum(None, None, at_least, seconds,
                                f"the reference's plan fails the check: {error.message}")
    if at_least is None:
        return ReferenceMinimum(None, None, None, seconds, f"no plan exists: {outcome.message}")
    if timed_out(outcome):
        return ReferenceMinimum(None, None, at_least, seconds,
                                f"the reference's search did not end within {time_limit:g} s")
    if not outcome.message and outcome.refuted:
        why = f"no answer set up to horizon {max(outcome.refuted)}"
    else:
        why = outcome.message or "no answer set"
    return ReferenceMinimum(None, None, at_least, seconds, f"the reference found no plan ({why})")


def _words(text: str) -> str:
    return " ".join(text.split())
