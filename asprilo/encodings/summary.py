"""What ``asprilo solve`` says of a solve on stderr (:func:`summary`) and prints with
``--json`` (:func:`report`): the plan and how its makespan was proven minimal (for a domain
changed by rule variants: under which rules, from which bound, refuted by which encoding),
or the bound proven and the gap, or (a user's own encoding) the shortest plan the encoding
allows and the problem's minimum (:mod:`.solving.minimality`); the violations of a plan that
breaks the rules; why there is none; what was tried."""

from __future__ import annotations

import sys

from asprilo.model import Instance
from asprilo.reader import plan_misfits
from asprilo.writer import format_action

from .registry import Encoding
from .solving import Outcome
from .solving.minimality import no_plan_headline, problem_minimum, proof, refuted_words

#: the most violations the summary lists of a plan that breaks the rules, and of clingo's warnings
SHOWN_VIOLATIONS, SHOWN_WARNINGS = 20, 5


def summary(outcome: Outcome, encoding: Encoding | None = None, hint: bool = False,
            instance: Instance | None = None) -> None:
    """The summary on stderr (``hint``: a search forced to method asp that ran out of time
    points to the default; ``instance``: a plan of the user's own encoding that does not fit
    it is said so in one sentence before its violations)."""
    lines = [f"domain {outcome.domain.label}, method {outcome.method}, encoding {outcome.encoding}, "
             f"lower bound {outcome.lower_bound:g}"]
    if encoding is not None and encoding.own and outcome.method == "asp":
        lines.append(f"your encoding ({', '.join(str(file) for file in encoding.files)}): {encoding.summary}")
        lines += [f"  assumed: {note}" for note in encoding.assumed]
    if outcome.stage:
        atoms = outcome.staged
        said = "no answer" if atoms is None else (
            f"its first answer, {len(atoms)} atom{'s' * (len(atoms) != 1)}{': ' * bool(atoms)}{' '.join(atoms)}")
        lines.append(f"first stage ({outcome.stage}): {said}")
    if (encoding is not None and encoding.own and outcome.method == "asp") or outcome.stage:
        lines += [f"  clingo: {' '.join(warning.split())}" for warning in outcome.warnings[:SHOWN_WARNINGS]]
    if outcome.assignment is not None:
        assignment = outcome.assignment
        state = assignment.origin if assignment.origin != "optimised" else (
            f"{'optimal' if assignment.optimal else 'best found'}, cost {assignment.cost}")
        lines.append(f"assignment ({state}): " + " ".join(assignment.facts))
    lines += _misfit(outcome, encoding, instance) + verdict(outcome) + rules_words(outcome)
    if hint and outcome.status.value == "limit":
        lines.append("for a plan fast (not proven minimal), leave out --method asp: the default runs the "
                     "anytime planner beside the exact search")
    lines.append(_figures(outcome))
    print("\n".join(lines), file=sys.stderr)


def _misfit(outcome: Outcome, encoding: Encoding | None, instance: Instance | None) -> list[str]:
    """One sentence for an invalid plan of the user's own encoding made for another instance
    or domain (robots the instance lacks, actions no domain knows, actions of another domain)."""
    if outcome.found or outcome.plan is None or instance is None or encoding is None or not encoding.own:
        return []
    said = plan_misfits(outcome.plan, instance, outcome.domain)
    return [f"your encoding's plan does not fit the instance: {'; '.join(said)}"] if said else []


#: who found the plan the answer holds (method auto), in words
_FOUND_BY = {"asp": "the exact search", "anytime": "the anytime planner"}


def verdict(outcome: Outcome) -> list[str]:
    """What was found: the plan (proven minimal, or with the bound proven and the gap), the
    violations of a plan that breaks the rules, or why there is none; and what was tried
    and proven on the way, where that is not said by "proven minimal"."""
    plan = outcome.plan
    if outcome.found and plan is not None:
        by = f"; found by {_FOUND_BY[outcome.found_by]}" if outcome.found_by in _FOUND_BY else ""
        line = f"plan: horizon {outcome.horizon} ({proof(outcome)}), {len(plan)} actions, checked: valid{by}"
        ended = [f"the search ended: {outcome.message}"] if outcome.message and not outcome.minimal else []
        return [line] + ([] if outcome.minimal else _tried(outcome)) + ended
    if outcome.check is not None and not outcome.check.valid and plan is not None:
        errors = outcome.check.errors
        lines = [error.message for error in errors[:SHOWN_VIOLATIONS]]
        if len(errors) > SHOWN_VIOLATIONS:
            lines.append(f"... and {len(errors) - SHOWN_VIOLATIONS} more (asprilo check lists them all)")
        return lines + [f"no valid plan: the plan of makespan {plan.horizon} breaks the rules "
                        f"({len(errors)} violation{'s' * (len(errors) != 1)})"]
    headline = {"none": no_plan_headline(outcome), "limit": "no plan within the limits", "cancelled": "cancelled",
                "invalid": "no valid plan"}[outcome.status.value]
    if outcome.status.value == "none" and (outcome.stage or (outcome.refuted_along and not outcome.refuted)):
        headline = "no plan"  # none along a stage's answer, or for an encoding of part of the rules: not none at all
    lines = [headline + (f": {outcome.message}" if outcome.message else "")]
    if outcome.status.value in ("limit", "cancelled"):
        lines += _tried(outcome)
    return lines


def _tried(outcome: Outcome) -> list[str]:
    """What was tried and proven: the horizons refuted (for the problem, and those refuted only
    along the task assignment), the horizons left undecided, the anytime planner's plans."""
    lines = []
    if outcome.refuted:
        lines.append(refuted_words(outcome, _spans(outcome.refuted), len(outcome.refuted) > 1 or outcome.trusted))
    along = [horizon for horizon in outcome.refuted_along if horizon not in outcome.refuted]
    if along:
        horizons = f"horizon{'s' * (len(along) > 1)} {_spans(along)}"
        variants = outcome.domain.variants
        if outcome.stage:
            lines.append(f"no plan along the first stage's answer at {horizons} (refuted along that answer only, "
                         "not for the problem)")
        elif outcome.assignment is None and len(variants) > 1 and outcome.encoding == variants[-1]:
            lines.append(f"no plan for the encoding '{outcome.encoding}' at {horizons} (it states the rules of its "
                         f"variant alone: not refuted under {outcome.domain.label})")
        else:
            lines.append(f"no plan along the task assignment at {horizons} (refuted along the assignment only, not "
                         "for the problem)")
    undecided = sorted({a.horizon for a in outcome.horizons_tried if a.result == "unknown"} - set(outcome.refuted))
    if undecided:
        lines.append(f"undecided: horizon{'s' * (len(undecided) > 1)} {_spans(undecided)}")
    plans = [a.horizon for a in outcome.horizons_tried if a.result == "improved"]
    if plans and outcome.method == "auto":
        shown = str(plans[0]) if len(plans) == 1 else f"{plans[0]} -> {min(plans)}"
        lines.append(f"anytime planner: {len(plans)} plan{'s' * (len(plans) > 1)}, makespan {shown}")
    return lines


def _figures(outcome: Outcome) -> str:
    """The method's statistics in one line."""
    stats = outcome.stats
    if outcome.method == "flow":
        return f"max-flow {stats['solve_time']:.2f} s"
    if outcome.method == "anytime":
        plans = len(outcome.history)
        if not plans:
            return "the anytime planner: no plan reported"
        given = f"; {stats['start']}" if stats.get("start") else ""  # a plan to start from (--start)
        return (f"first plan {stats.get('first_plan_seconds', 0):.2f} s, {plans} plan{'s' * (plans > 1)} reported, "
                f"{stats.get('neighbourhoods', 0)} neighbourhoods tried{given}")
    figures = (f"ground {stats.get('ground_time', 0):.2f} s, solve {stats.get('solve_time', 0):.2f} s, "
               f"rules {stats.get('rules', 0)}, atoms {stats.get('atoms', 0)}, choices {stats.get('choices', 0)}, "
               f"conflicts {stats.get('conflicts', 0)}")
    return f"exact search: {figures}" if outcome.method == "auto" else figures


def report(outcome: Outcome) -> dict:
    """The outcome as plain data (``--json``)."""
    finite = outcome.proven_bound != float("inf")
    return {
        "status": outcome.status.value,
        "domain": outcome.domain.value,
        "method": outcome.method,
        "encoding": outcome.encoding,
        "horizon": outcome.horizon,
        "minimal": outcome.minimal,
        "encoding_minimal": outcome.encoding_minimal,
        "minimum": outcome.minimum,
        "minimum_by": outcome.minimum_by or None,
        "lower_bound": outcome.lower_bound if outcome.lower_bound != float("inf") else None,
        "horizons_tried": [attempt.as_json() for attempt in outcome.horizons_tried],
        "refuted": outcome.refuted,
        "refuted_along_assignment": outcome.refuted_along,
        "proven_bound": outcome.proven_bound if finite else None,
        "gap": outcome.gap if finite else None,
        "stats": outcome.stats,
        "assignment": outcome.assignment.facts if outcome.assignment is not None else None,
        "plan": [format_action(action) for action in outcome.plan.actions]
        if outcome.found and outcome.plan is not None else None,
        "message": outcome.message,
        "variants": list(outcome.domain.variants),
        **({"stage": outcome.staged} if outcome.stage else {}),
        **({"found_by": outcome.found_by} if outcome.method == "auto" else {}),
        **({"history": outcome.history} if outcome.method in ("anytime", "auto") else {}),
    }


def rules_words(outcome: Outcome) -> list[str]:
    """For a domain whose rules are not SPEC.md's (a rule variant, a domain registered with
    concerns of its own): which lower bound holds under them, and how the plan was proven
    minimal under them -- by the bound, or by the horizons the encoding refuted."""
    from .solving.method import spec_rules

    domain = outcome.domain
    if spec_rules(domain):
        return []
    lines = []
    if domain.variants:
        from asprilo.domain import Domain
        from asprilo.domain.variants import base_of

        base = Domain.parse(base_of(domain)).label
        names = ", ".join(f"'{name}'" for name in domain.variants)
        several = "s" * (len(domain.variants) > 1)
        if domain.bound is None:
            lines.append(f"no lower bound under {domain.label}: variant{several} {names} may allow shorter plans "
                         f"than {base}'s rules, so the search starts at horizon 0")
        elif outcome.lower_bound != float("inf"):
            lines.append(f"lower bound {outcome.lower_bound:g}: {base}'s, which holds under {domain.label} (variant"
                         f"{several} {names} only restrict{'s' * (not several)} its rules)")
    if outcome.found and outcome.minimal and outcome.horizon is not None:
        if outcome.horizon <= outcome.lower_bound:
            how = "the plan meets the lower bound"
        elif not outcome.trusted:
            how = problem_minimum(outcome.minimum, outcome.proven_bound, outcome.minimum_by)
        else:
            refuted = [horizon for horizon in outcome.refuted if horizon < outcome.horizon]
            how = (f"{_encoding_words(outcome)} has no plan at horizon{'s' * (len(refuted) > 1)} "
                   f"{_spans(refuted)}")
        lines.append(f"proven minimal under {domain.label}'s rules: {how}")
    return lines


def _encoding_words(outcome: Outcome) -> str:
    """The encoding that refuted the horizons, in words."""
    if outcome.encoding in outcome.domain.variants:
        return f"the encoding '{outcome.encoding}' (the model solution of variant '{outcome.encoding}')"
    return f"the encoding '{outcome.encoding}'"


def _spans(horizons: list[int]) -> str:
    """``[3, 4, 5, 8]`` -> ``"3-5, 8"``."""
    spans: list[list[int]] = []
    for horizon in horizons:
        if spans and horizon == spans[-1][1] + 1:
            spans[-1][1] = horizon
        else:
            spans.append([horizon, horizon])
    return ", ".join(str(a) if a == b else f"{a}-{b}" for a, b in spans)
