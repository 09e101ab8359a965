"""What the window says of a solve: its progress, the plan it found, a plan that breaks the
rules, no plan, and a checker's ``err/3`` atom as a violation in words."""

from __future__ import annotations

import clingo

from asprilo.reader import value_of
from asprilo.simulate import Violation

from . import encoding_files
from .job import Job


def doing(phase) -> str:
    """What the progress line says while the search grounds or solves one horizon."""
    if phase.name == "bounding":
        return "computing the lower bound…"
    if phase.horizon == 0:
        return f"{phase.name}…"
    return f"horizon {phase.horizon}: {phase.name}…"


def tried(attempt) -> str:
    """What the progress line says of one horizon tried, or of a better plan (anytime)."""
    if attempt.result == "improved":
        return f"makespan {attempt.horizon}, {attempt.note} ({attempt.seconds:.1f} s)"
    return f"horizon {attempt.horizon}: {attempt.result} ({attempt.seconds:.1f} s)"


def found(outcome, job: Job, domain: str, own=None) -> str:
    """What the status bar says of the plan a solve found (``own``: with the user's encoding)."""
    minimal = "minimal " if outcome.minimal else ""
    if outcome.method == "auto":
        head = f"Solve stopped after {job.seconds:.1f} s, best plan" if job.cancel.is_set() else \
            f"plan found in {job.seconds:.1f} s"
        by = {"asp": "the exact search", "anytime": "the anytime planner"}.get(outcome.found_by, "")
        bound = outcome.proven_bound
        proof = "" if outcome.minimal or not bound else f" (no plan is shorter than {bound:g}: not proven minimal)"
        return (f"{head}: {minimal}makespan {outcome.horizon}{proof}, {len(outcome.plan)} actions "
                f"({domain}, {outcome.encoding} and anytime, found by {by})")
    if outcome.method != "anytime":
        from asprilo.encodings.solving.minimality import proof as proof_words

        said = "" if outcome.trusted or outcome.minimal else f" ({proof_words(outcome)})"  # an own encoding's
        return (f"plan found in {job.seconds:.1f} s: {minimal}makespan {outcome.horizon}{said}, "
                f"{len(outcome.plan)} actions ({domain}, {encoding_words(outcome, own)})")
    head = f"Solve stopped after {job.seconds:.1f} s, best plan" if job.cancel.is_set() else \
        f"plan found in {job.seconds:.1f} s"
    gap = outcome.history[-1]["gap"] if outcome.history else None
    above = f", {100 * gap:.1f}% above the lower bound {outcome.lower_bound:g}" if gap and not minimal else ""
    plans = len(outcome.history)
    return (f"{head}: {minimal}makespan {outcome.horizon}{above}, {len(outcome.plan)} actions, "
            f"{plans} plan{'s' if plans != 1 else ''} reported ({domain}, anytime)")


def encoding_words(outcome, own=None) -> str:
    """The encoding that solved: its name, and for a user's own its style in words."""
    return outcome.encoding if own is None else f"{outcome.encoding}: {own.summary}"


def broken(outcome, job: Job, domain: str, own=None) -> str:
    """What the status bar says of a plan that breaks the rules (its violations are listed)."""
    count = len(outcome.check.errors)
    return (f"the plan found in {job.seconds:.1f} s breaks {count} rule{'s' if count != 1 else ''}: makespan "
            f"{outcome.horizon}, {len(outcome.plan)} actions ({domain}, {encoding_words(outcome, own)}); "
            f"the checker's violations are in the Violations panel")


def no_plan(outcome, own) -> str:
    """What the error dialog says when the user's encoding gave no plan: why, in words."""
    from asprilo.encodings.solving.minimality import no_plan_headline, refuted_words

    names = encoding_files.entry_text([str(path) for path in own.files])
    why = {"none": no_plan_headline(outcome), "limit": "no plan within the time limit",
           "invalid": "no plan"}.get(outcome.status.value, outcome.status.value)
    text = f"{names}: {why}" + (f": {outcome.message}" if outcome.message else "")
    refuted = outcome.refuted
    if refuted and outcome.status.value == "limit":
        several = len(refuted) > 1
        horizons = f"{refuted[0]}–{refuted[-1]}" if refuted == list(range(refuted[0], refuted[-1] + 1)) and several \
            else ", ".join(map(str, refuted))
        text += f" ({refuted_words(outcome, horizons, several)})"
    return text


def explain(timeline, atom: str) -> Violation:
    """An ``err(Module,Check,Params)`` atom as the replay words it (with what to highlight)."""
    term = clingo.parse_term(atom)
    module, check, params = term.arguments
    values = value_of(params)
    values = values if isinstance(values, tuple) else (values,)
    try:
        return timeline.explain(module.name, check.name, values)
    except (KeyError, IndexError, TypeError, ValueError):
        step = values[-1] if values and isinstance(values[-1], int) else 0
        return Violation(module.name, check.name, values, step, f"{module.name} rule '{check.name}' is broken ({atom})")
