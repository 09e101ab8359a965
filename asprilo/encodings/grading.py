"""Grade an encoding on a ladder (``asprilo grade``): every instance solved in a child process
under a time limit, its plan checked, and the makespan compared with the stored minimum.

    from asprilo.encodings.grading import grade_ladder
    from asprilo.encodings.ladder import bundled_ladder
    for graded in grade_ladder(encoding, bundled_ladder(Domain.M), time_limit=20):
        graded.result, graded.valid, graded.minimal, graded.makespan, graded.reason

A wrong answer is a grade, never an error: a plan that breaks the rules (its first
violation in words), no plan (no answer set, no occurs/3, occurs/3 atoms that are no plan,
clingo refusing the encoding, a crash of the child process, the memory limit) or the time
limit (and where the search was then) each give one :class:`Graded`, with clingo's warnings
on the encoding.  Against a model solution (``reference``: :class:`.reference.Reference`)
each instance's minimum is what the reference's search proves first.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from asprilo.errors import InputError
from asprilo.facts import OCCURS_SHAPE
from asprilo.model import Instance, Plan
from asprilo.reader import read_instance
from asprilo.simulate import Violation

from .ladder import Ladder, Rung
from .registry import Encoding
from .solving import Outcome, Phase, SolveStatus, solve
from .summary import SHOWN_WARNINGS

if TYPE_CHECKING:
    from .reference import Reference

#: the results of one instance
VALID, INVALID, NO_PLAN, TIME_OUT = "valid", "invalid", "no-plan", "time-out"
#: the results as the grader's lines say them
VERDICTS = {VALID: "valid", INVALID: "INVALID", NO_PLAN: "no plan", TIME_OUT: "time-out"}
#: the version of the ``--json`` shape (docs/GRADING.md); raised when a key changes meaning or goes
JSON_VERSION = 1


@dataclass
class Graded:
    """How an encoding did on one instance of a ladder.

    ``result``: ``valid`` (a plan the checker accepts), ``invalid`` (a plan that breaks the
    rules: ``violation`` is the first, ``violations`` how many), ``no-plan`` or ``time-out``
    (``reason`` says why in words).  ``makespan``: of the plan, valid or not; ``refuted``:
    the horizons the encoding proved to have no plan; ``encoding_minimal``: a valid plan and
    the encoding allows none shorter (minimal for the problem or not: :attr:`minimal`);
    ``seconds``: the whole solve, the child process and the check included.
    """

    step: int
    rung: Rung
    instance: Instance
    result: str
    seconds: float
    makespan: int | None = None
    violation: Violation | None = None
    violations: int = 0
    reason: str = ""
    refuted: list[int] = field(default_factory=list)
    encoding_minimal: bool = False
    plan: Plan | None = field(default=None, repr=False)
    warnings: list[str] = field(default_factory=list)  # clingo's warnings and hints on the encoding

    @property
    def valid(self) -> bool:
        return self.result == VALID

    @property
    def minimal(self) -> bool:
        """A valid plan of the minimal makespan (never claimed where the minimum is unknown)."""
        return self.valid and self.rung.minimum is not None and self.makespan == self.rung.minimum

    @property
    def too_strong(self) -> list[int]:
        """The refuted horizons at which a plan exists (from the minimum, or where it is
        unknown from the reference's plan, on)."""
        least = self.rung.plans_from
        return [] if least is None else [horizon for horizon in self.refuted if horizon >= least]

    @property
    def size(self) -> str:
        """The floor and the robots in words, e.g. ``11x6, 3 robots``."""
        x, y = self.instance.size
        robots = len(self.instance.robots)
        return f"{x}x{y}, {robots} robot{'s' * (robots != 1)}"

    def as_json(self) -> dict[str, Any]:
        """One entry of ``instances`` in ``asprilo grade --json`` (docs/GRADING.md)."""
        violation = self.violation
        x, y = self.instance.size
        return {
            "step": self.step,
            "name": self.rung.name,
            "file": self.rung.file.name,
            "size": f"{x}x{y}",
            "robots": len(self.instance.robots),
            "minimum": self.rung.minimum,
            "result": self.result,
            "valid": self.valid,
            "minimal": self.minimal,
            "encoding_minimal": self.encoding_minimal,
            "makespan": self.makespan,
            "seconds": round(self.seconds, 3),
            "violation": None if violation is None else {
                "atom": violation.atom, "module": violation.module, "check": violation.check,
                "step": violation.step, "message": violation.message},
            "violations": self.violations,
            "reason": self.reason or None,
            "refuted": self.refuted,
            "warnings": self.warnings,
        }


@dataclass
class Summary:
    """The counts of a graded ladder."""

    instances: int = 0
    valid: int = 0
    minimal: int = 0
    invalid: int = 0
    no_plan: int = 0
    time_outs: int = 0
    seconds: float = 0.0
    unknown: int = 0  # instances whose minimum the reference did not prove

    @classmethod
    def of(cls, graded: list[Graded], seconds: float) -> Summary:
        results = [g.result for g in graded]
        unknown = sum(g.rung.reference is not None and g.rung.minimum is None for g in graded)
        return cls(len(graded), results.count(VALID), sum(g.minimal for g in graded), results.count(INVALID),
                   results.count(NO_PLAN), results.count(TIME_OUT), seconds, unknown)

    def line(self) -> str:
        """E.g. ``7/8 valid, 5/8 minimal, 1 time-out; 12.3 s``."""
        n = self.instances
        parts = [f"{self.valid}/{n} valid", f"{self.minimal}/{n} minimal"] + [self.failures()] * bool(self.failures())
        if self.unknown:
            parts.append(f"minimum unknown on {self.unknown}")
        return f"{', '.join(parts)}; {self.seconds:.1f} s"

    def failures(self) -> str:
        """``2 invalid, 1 without a plan, 1 time-out`` (``""``: every plan valid)."""
        parts = [f"{self.invalid} invalid"] * bool(self.invalid)
        parts += [f"{self.no_plan} without a plan"] * bool(self.no_plan)
        parts += [f"{self.time_outs} time-out{'s' * (self.time_outs != 1)}"] * bool(self.time_outs)
        return ", ".join(parts)

    def as_json(self) -> dict[str, Any]:
        return {"instances": self.instances, "valid": self.valid, "minimal": self.minimal, "invalid": self.invalid,
                "no_plan": self.no_plan, "time_outs": self.time_outs, "seconds": round(self.seconds, 3)}


def grade_ladder(encoding: Encoding, ladder: Ladder, *, time_limit: float, horizon: int | None = None,
                 stage: Encoding | None = None, memory_limit: int | None = None, first: int | None = None,
                 reference: Reference | None = None,
                 on_start: Callable[[int, int, Rung], None] | None = None,
                 on_phase: Callable[[Phase], None] | None = None,
                 on_reference_phase: Callable[[Phase], None] | None = None) -> Iterator[Graded]:
    """Grade ``encoding`` on the (``first``) instances of ``ladder``, one after the other,
    each under ``time_limit`` seconds (and ``memory_limit`` MB); ``horizon``: solve at this
    makespan only (``-c horizon=H``); ``stage``: a first stage solved once per instance, whose
    first answer's atoms the encoding reads (``--stage``).  With a ``reference``, each instance's minimum is what
    the reference's search proves first (``None`` where it proves none).
    ``on_start(step, steps, rung)`` is called before an instance, ``on_reference_phase``
    while the reference solves it, ``on_phase`` while the encoding does.

    Bad input is :class:`InputError` before the first grade: an instance of the ladder that
    cannot be read, or a reference that clingo refuses on the first instance.  Whatever the
    encoding does is a grade: clingo refusing it (unsafe variables, found when grounding), a
    model whose occurs/3 atoms are no plan, a crash of the child process, a limit."""
    rungs = ladder.rungs[:first] if first is not None else ladder.rungs
    instances = [read_instance(rung.file) for rung in rungs]
    for step, (rung, instance) in enumerate(zip(rungs, instances, strict=True), 1):
        if on_start is not None:
            on_start(step, len(rungs), rung)
        if reference is not None:
            rung = reference.rung(rung, instance, on_reference_phase)
        started = time.perf_counter()
        try:
            graded = grade_rung(step, rung, instance, ladder, encoding, time_limit=time_limit, horizon=horizon,
                                stage=stage, memory_limit=memory_limit, on_phase=on_phase)
        except InputError as error:
            graded = Graded(step, rung, instance, NO_PLAN, time.perf_counter() - started, reason=refusal_words(error))
        yield graded


def refused(ladder: Ladder, reason: str, first: int | None = None) -> Iterator[Graded]:
    """The grades of an encoding refused outright (a syntax error: :func:`refusal_words`):
    no plan on every (``first``) instance of ``ladder``, for the ``reason`` in words."""
    rungs = ladder.rungs[:first] if first is not None else ladder.rungs
    for step, rung in enumerate(rungs, 1):
        yield Graded(step, rung, read_instance(rung.file), NO_PLAN, 0.0, reason=reason)


def refusal_words(error: InputError) -> str:
    """Why an encoding got no grade from the solver, in words: its model's ``occurs/3`` atoms
    are no plan, clingo refused it (located in its files), or its model broke a limit."""
    shape = no_plan_shape(error)
    if shape:
        return shape
    if error.file is not None:
        return f"clingo refused the encoding: {_words(str(error))}"
    return f"its model is no plan: {_words(str(error))}"


def no_plan_shape(error: InputError) -> str:
    """Why a model's ``occurs/3`` atoms are no plan, when ``error`` (raised while a plan
    was read from them) says so; else ``""``."""
    message = error.message
    if message.startswith((f"expected {OCCURS_SHAPE}", "the time step of occurs(")):
        return f"its model's occurs/3 atoms are no plan: {_words(message)}"
    return ""


def grade_rung(step: int, rung: Rung, instance: Instance, ladder: Ladder, encoding: Encoding, *,
               time_limit: float, horizon: int | None = None, stage: Encoding | None = None,
               memory_limit: int | None = None,
               on_phase: Callable[[Phase], None] | None = None) -> Graded:
    """Grade ``encoding`` on one instance of ``ladder`` (``instance``: the rung's file, read);
    an encoding that clingo refuses is :class:`InputError`."""
    started = time.perf_counter()
    try:
        outcome = solve(instance, ladder.domain, encoding=encoding, horizon=horizon, time_limit=time_limit,
                        memory_limit=memory_limit, isolate=True, on_phase=on_phase, stage=stage)
    except InputError:
        raise
    except Exception as error:  # whatever the encoding does, it is graded, never a crash of the grader
        return Graded(step, rung, instance, NO_PLAN, time.perf_counter() - started,
                      reason=f"the solve failed: {_words(str(error)) or type(error).__name__}")
    return _graded(step, rung, instance, outcome, time.perf_counter() - started, time_limit)


def _words(text: str) -> str:
    return " ".join(text.split())


def _graded(step: int, rung: Rung, instance: Instance, outcome: Outcome, seconds: float,
            time_limit: float) -> Graded:
    graded = Graded(step, rung, instance, NO_PLAN, seconds, refuted=outcome.refuted, plan=outcome.plan,
                    warnings=_warnings(outcome))
    if outcome.status is SolveStatus.FOUND:
        graded.result, graded.makespan, graded.encoding_minimal = VALID, outcome.horizon, outcome.encoding_minimal
    elif outcome.check is not None and not outcome.check.valid:
        errors = outcome.check.errors
        graded.result, graded.violation, graded.violations = INVALID, errors[0], len(errors)
        graded.makespan = outcome.plan.horizon if outcome.plan is not None else None
    elif timed_out(outcome):
        graded.result = TIME_OUT
        graded.reason = f"time limit ({time_limit:g} s){stopped_while(outcome)}" + _refuted(graded)
    else:
        graded.reason = _no_plan(outcome, graded)
    return graded


#: clingo's words for a predicate without atoms: at a horizon too short for any move, moves have none
_EMPTY_SIGNATURE = "no atoms over signature occur in program"


def _warnings(outcome: Outcome) -> list[str]:
    """clingo's warnings on the encoding, each in one line; with a plan, not those on
    predicates without atoms (said for the short horizons tried before it)."""
    said = [_words(warning) for warning in outcome.warnings]
    return [warning for warning in said if outcome.plan is None or _EMPTY_SIGNATURE not in warning]


def warning_lines(graded: Graded, said: list[str]) -> list[str]:
    """clingo's warnings on the encoding not ``said`` before (at most :data:`SHOWN_WARNINGS`
    in all, then how many more there are), under an instance's line as solve shows them."""
    lines = []
    for warning in graded.warnings:
        if warning in said:
            continue
        said.append(warning)
        if len(said) <= SHOWN_WARNINGS:
            lines.append(f"  clingo: {warning}")
        elif len(said) == SHOWN_WARNINGS + 1:
            lines.append("  clingo: more warnings (--json lists them all)")
    return lines


def timed_out(outcome: Outcome) -> bool:
    """Whether the time limit stopped the solve (rather than the memory limit, a crash, or
    an upward search that refuted every horizon it may try)."""
    if outcome.status is not SolveStatus.LIMIT:
        return False
    if outcome.message:
        return "time limit" in outcome.message
    tried = outcome.horizons_tried
    return not tried or tried[-1].result != "unsat"


def stopped_while(outcome: Outcome) -> str:
    """Where a search stopped by its time limit was: `` while grounding horizon 7`` (as the
    child process last said), `` while solving horizon 7`` (a horizon left undecided), or ``""``."""
    said = outcome.message.partition(" while ")[2].partition(";")[0]
    if said:
        return f" while {said}"
    tried = outcome.horizons_tried
    if tried and tried[-1].result == "unknown":
        return f" while solving horizon {tried[-1].horizon}"
    return ""


def _no_plan(outcome: Outcome, graded: Graded) -> str:
    """Why there is no plan, in words."""
    if outcome.status is SolveStatus.LIMIT and not outcome.message and graded.refuted:
        return f"no answer set up to horizon {max(graded.refuted)}" + _refuted(graded)
    if outcome.status is SolveStatus.NONE and not outcome.message:
        return "no answer set" + _refuted(graded)
    return (outcome.message or outcome.status.value) + _refuted(graded)


def _refuted(graded: Graded) -> str:
    """The horizons refuted, and whether plans exist at some of them."""
    if not graded.refuted:
        return ""
    return f"; {horizons(graded.refuted)} refuted" + too_strong(graded)


def too_strong(graded: Graded) -> str:
    """Words on the refuted horizons at which a plan exists (none: ``""``)."""
    if not graded.too_strong:
        return ""
    return f", yet plans exist from makespan {graded.rung.plans_from} on: a constraint is too strong"


def horizons(numbers: list[int]) -> str:
    """``horizon 7`` or ``horizons 3-5, 8``."""
    return f"horizon{'s' * (len(numbers) > 1)} {spans(numbers)}"


def spans(horizons: list[int]) -> str:
    """``[3, 4, 5, 8]`` -> ``"3-5, 8"``."""
    runs: list[list[int]] = []
    for horizon in horizons:
        if runs and horizon == runs[-1][1] + 1:
            runs[-1][1] = horizon
        else:
            runs.append([horizon, horizon])
    return ", ".join(str(a) if a == b else f"{a}-{b}" for a, b in runs)
