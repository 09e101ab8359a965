"""What ``check`` returns: the verdict, the diagnostics in plain words, and the plan's metrics."""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, field
from typing import Any

import clingo
import numpy as np

from asprilo.bounds import Floor, makespan_bound, mapf_bounds
from asprilo.domain import Bound, Domain, Goal
from asprilo.facts import value_of
from asprilo.model import Instance, Plan, Term
from asprilo.simulate import Timeline, Violation, simulate, sort_violations


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


def metrics(instance: Instance, plan: Plan, domain: Domain, errors: list[Violation],
            known: Known = (None, None)) -> dict[str, Any]:
    """Horizon, actions by name, sum of costs, idle steps, what the plan fulfils, lower
    bounds (those in ``known`` are not computed again) and the ratios plan/bound (``None``
    where a bound is 0 or infinite)."""
    robots = list(instance.robots)
    row: dict[Term, int] = {robot: i for i, robot in enumerate(robots)}
    rows = np.array([row.get(a.robot, -1) if a.kind == "robot" else -1 for a in plan.actions], dtype=np.int64)
    steps = np.array([a.step for a in plan.actions], dtype=np.int64)
    horizon = max(int(steps.max()), 0) if len(steps) else 0
    acting = (rows >= 0) & (steps >= 1)
    last_step = np.zeros(len(robots), dtype=np.int64)
    np.maximum.at(last_step, rows[acting], steps[acting])
    sum_of_costs = int(last_step.sum())
    busy = len(np.unique(rows[acting] * (horizon + 1) + steps[acting]))
    result: dict[str, Any] = {
        "horizon": horizon,
        "actions": dict(sorted(Counter(a.name for a in plan.actions).items())),
        "sum_of_costs": sum_of_costs,
        "idle_steps": len(robots) * horizon - busy,
    }
    if domain.goal is Goal.DESTINATIONS:
        missed = {e.params[0] for e in errors if e.check == "unoccupiedDestination"}
        result["destinations"] = len(instance.destinations)
        result["destinations_reached"] = len(instance.destinations) - len(missed)
    else:
        missed = {e.params[0] for e in errors if e.check == "unfilledOrder"}
        result["orders"] = len(instance.orders)
        result["orders_fulfilled"] = len(set(instance.orders) - missed)
    makespan, total = _bounds(instance, domain, known)
    result["makespan_bound"] = _number(makespan)
    if domain.bound is not Bound.DELIVERY:
        result["sum_of_costs_bound"] = _number(total)
        result["sum_of_costs_ratio"] = _ratio(sum_of_costs, total)
    result["makespan_ratio"] = _ratio(horizon, result["makespan_bound"])
    return result


def _bounds(instance: Instance, domain: Domain, known: Known) -> tuple[float, float | None]:
    """The makespan bound and (M/Md) the sum-of-costs bound: as known, or computed."""
    makespan, total = known
    if domain.bound is Bound.DELIVERY:
        return (makespan_bound(instance, domain, Floor(instance.cells)) if makespan is None else makespan), None
    if makespan is None or total is None:
        return mapf_bounds(instance, Floor(instance.cells))
    return makespan, total


def _number(value: float | None) -> int | None:
    """A bound as JSON shows it: an integer, or ``None`` when no plan can reach the goal."""
    return int(value) if value is not None and math.isfinite(value) else None


def _ratio(value: float, bound: float | None) -> float | None:
    if bound is None or not math.isfinite(bound) or bound <= 0:
        return None
    return round(value / bound, 3)


def build_report(instance: Instance, plan: Plan, domain: Domain, atoms: list[clingo.Symbol],
                 statistics: dict[str, float | int], known: Known = (None, None)) -> Report:
    """The report for a plan whose checker derived ``atoms`` (``known``: lower bounds the
    caller knows already)."""
    errors = diagnostics(atoms, simulate(instance, plan, domain)) if atoms else []
    measured = metrics(instance, plan, domain, errors, known)
    return Report(domain, measured["horizon"], errors, measured, statistics)
