"""What ``check`` returns: the verdict, the diagnostics in plain words, and the plan's metrics.

The metrics' lower bounds come last and never hold up the verdict: by default the cheap ones
(:func:`asprilo.bounds.cheap_bounds`, milliseconds), the strongest on request
(:func:`asprilo.bounds.strong_bounds`, up to seconds on A/B/C), or those a caller has
computed already (a solve hands over its own); ``metrics["bounds"]`` says which.
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal

import clingo

from asprilo.bounds.floor import Floor
from asprilo.bounds.makespan import cheap_bounds, strong_bounds
from asprilo.domain import Bound, Domain, Goal
from asprilo.facts import value_of
from asprilo.model import Instance, Plan, Term

if TYPE_CHECKING:  # the simulator explains violations: a valid plan is checked without it
    from asprilo.simulate import Timeline, Violation


@dataclass
class Report:
    """The checker's verdict on a plan.

    ``errors`` are :class:`~asprilo.simulate.Violation` objects built from the checker's
    ``err/3`` atoms (``.atom`` is the exact atom), sorted by step, module, check, params.
    """

    domain: Domain
    horizon: int
    errors: list[Violation]
    metrics: dict[str, Any] = field(default_factory=dict)
    statistics: dict[str, float | int] = field(default_factory=dict)  # clingo's, for benchmarks

    @property
    def valid(self) -> bool:
        return not self.errors

    def as_json(self) -> dict[str, Any]:
        """The object ``check --json`` prints."""
        return {
            "valid": self.valid,
            "domain": self.domain.value,
            "horizon": self.horizon,
            "errors": [{"atom": e.atom, "module": e.module, "check": e.check, "params": _json(e.params),
                        "step": e.step, "message": e.message} for e in self.errors],
            "metrics": self.metrics,
        }


def _json(value: Any) -> Any:
    return [_json(v) for v in value] if isinstance(value, tuple) else value


def diagnostics(atoms: list[clingo.Symbol], timeline: Timeline) -> list[Violation]:
    """``err(Module,Check,Params)`` atoms as violations in plain words (``timeline``, the
    replay of the same plan, supplies the words: positions, quantities, names)."""
    from asprilo.simulate import sort_violations
    replayed = {violation.atom: violation for violation in timeline.violations}
    errors = []
    for atom in atoms:
        error = replayed.get(str(atom))
        if error is None:  # the replay does not report it: say it all the same
            module, check, params = (value_of(argument) for argument in atom.arguments)
            error = timeline.explain(module, check, params if isinstance(params, tuple) else (params,))
        errors.append(error)
    return sort_violations(errors)


# --- metrics -----------------------------------------------------------------------------

#: lower bounds a caller already knows: (makespan, sum of costs), ``None`` where not known
Known = tuple[float | None, float | None]
#: which bounds the metrics show when the caller knows none: ``cheap`` (milliseconds) or
#: ``strong`` (the strongest asprilo has: what ``solve`` starts from)
Strength = Literal["cheap", "strong"]
STRENGTHS: tuple[Strength, ...] = ("cheap", "strong")


def metrics(instance: Instance, plan: Plan, domain: Domain, errors: list[Violation],
            known: Known = (None, None), bound: Strength | None = "cheap") -> dict[str, Any]:
    """Horizon, actions by name, sum of costs, idle steps, what the plan fulfils, then the
    lower bounds (:func:`bound_metrics`; with ``bound=None`` and none ``known``: left out)."""
    row: dict[Term, int] = {robot: i for i, robot in enumerate(instance.robots)}
    horizon = max(max((a.step for a in plan.actions), default=0), 0)
    last_step = [0] * len(row)
    busy: set[tuple[int, int]] = set()
    for action in plan.actions:
        robot = row.get(action.robot, -1) if action.kind == "robot" else -1
        if robot >= 0 and action.step >= 1:
            last_step[robot] = max(last_step[robot], action.step)
            busy.add((robot, action.step))
    result: dict[str, Any] = {
        "horizon": horizon,
        "actions": dict(sorted(Counter(a.name for a in plan.actions).items())),
        "sum_of_costs": sum(last_step),
        "idle_steps": len(row) * horizon - len(busy),
    }
    if domain.goal is Goal.DESTINATIONS:
        missed = {e.params[0] for e in errors if e.check == "unoccupiedDestination"}
        result["destinations"] = len(instance.destinations)
        result["destinations_reached"] = len(instance.destinations) - len(missed)
    else:
        missed = {e.params[0] for e in errors if e.check == "unfilledOrder" or _names_order(domain, e)}
        result["orders"] = len(instance.orders)
        result["orders_fulfilled"] = len(set(instance.orders) - missed)
    if domain.bound is None:  # a variant that may allow shorter plans than the base's bounds say
        result["bounds"] = "none"
    elif bound is not None or known[0] is not None:
        result.update(bound_metrics(instance, domain, result, known, bound or "cheap"))
    return result


def _names_order(domain: Domain, error: Any) -> bool:
    """Whether a variant's check says an order is not served: its words name an order first."""
    words = domain.messages.get((error.module, error.check)) if domain.variants else None
    params: tuple[tuple[str, str], ...] = getattr(words, "params", ())
    return bool(params) and params[0][1] == "order"


def bound_metrics(instance: Instance, domain: Domain, measured: dict[str, Any], known: Known = (None, None),
                  bound: Strength = "cheap") -> dict[str, Any]:
    """The lower bounds (:func:`lower_bounds`: those in ``known`` are not computed again, the
    others at strength ``bound``), which bounds they are (``"bounds"``: ``given``, ``cheap``
    or ``strong``) and the ratios plan/bound of the plan ``measured`` (``None`` where a
    bound is 0 or infinite)."""
    (makespan, total), strength = lower_bounds(instance, domain, known, bound)
    result: dict[str, Any] = {"bounds": strength, "makespan_bound": _number(makespan)}
    if domain.bound is not Bound.DELIVERY:
        result["sum_of_costs_bound"] = _number(total)
        result["sum_of_costs_ratio"] = _ratio(measured["sum_of_costs"], total)
    result["makespan_ratio"] = _ratio(measured["horizon"], result["makespan_bound"])
    return result


def add_bounds(report: Report, instance: Instance, bound: Strength = "strong") -> None:
    """Put the lower bounds of strength ``bound`` into the metrics of ``report`` (checked on
    ``instance``), in place of those there: the verdict first, the bounds when they come."""
    if report.domain.bound is None:
        return
    for key in ("bounds", "makespan_bound", "sum_of_costs_bound", "sum_of_costs_ratio", "makespan_ratio"):
        report.metrics.pop(key, None)
    report.metrics.update(bound_metrics(instance, report.domain, report.metrics, (None, None), bound))


def lower_bounds(instance: Instance, domain: Domain, known: Known = (None, None),
                 bound: Strength = "cheap") -> tuple[tuple[float, float | None], str]:
    """The makespan bound and (M/Md) the sum-of-costs bound, and which they are: as known
    (``given``; a sum of costs missing beside a known makespan is the cheap one), else
    computed, once, at strength ``bound``."""
    if bound not in STRENGTHS:
        raise ValueError(f"bound must be one of {', '.join(STRENGTHS)}, not {bound!r}")
    makespan, total = known
    needs_total = domain.bound is not Bound.DELIVERY
    if makespan is not None and (total is not None or not needs_total):
        return (makespan, total if needs_total else None), "given"
    if makespan is not None:  # M/Md without the sum of costs: the cheap one beside it
        return (makespan, cheap_bounds(instance, domain, Floor(instance.cells))[1]), "given"
    compute = strong_bounds if bound == "strong" else cheap_bounds
    computed = compute(instance, domain, Floor(instance.cells))
    return (computed[0], total if total is not None else computed[1]), bound


def _number(value: float | None) -> int | None:
    """A bound as JSON shows it: an integer, or ``None`` when no plan can reach the goal."""
    return int(value) if value is not None and math.isfinite(value) else None


def _ratio(value: float, bound: float | None) -> float | None:
    if bound is None or not math.isfinite(bound) or bound <= 0:
        return None
    return round(value / bound, 3)


def build_report(instance: Instance, plan: Plan, domain: Domain, atoms: list[clingo.Symbol],
                 statistics: dict[str, float | int], known: Known = (None, None),
                 bound: Strength | None = "cheap") -> Report:
    """The report for a plan whose checker derived ``atoms`` (``known``: lower bounds the
    caller knows already; ``bound``: the strength of those it does not know, ``None``: none
    of them, for :func:`add_bounds` to put in later)."""
    errors = []
    if atoms:
        from asprilo.simulate import simulate
        errors = diagnostics(atoms, simulate(instance, plan, domain))
    measured = metrics(instance, plan, domain, errors, known, bound)
    return Report(domain, measured["horizon"], errors, measured, statistics)
