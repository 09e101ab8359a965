"""Lower bounds on the makespan (and, for M/Md, the sum of costs) of every plan, and the
floor's distances they are made of.

Modules, each importing only those below it (an import-linter contract):

- ``makespan``: :func:`makespan_bound`, the one bound that ``check``, ``solve`` and the
  benchmark reports use, picked by the domain's descriptor (``domain.bound``); in two
  strengths with the sum of costs beside it: :func:`strong_bounds` (what ``solve`` computes
  once) and :func:`cheap_bounds` (what ``check`` shows by default: milliseconds, no numpy);
- ``trip`` (+ ``trip.lp``): A/B/C when shelves serve several order lines;
- ``delivery`` (+ ``delivery.lp``): what the A/B/C bounds share (lines, releases), the
  stations' bound and the scheduling relaxation; ``mapf``: M/Md by robot-to-goal matching;
- ``floor``: :class:`Floor`, the one engine for walking distances in asprilo, and
  :data:`INFINITE`, which stands for "unreachable" and "no plan at all".

Distances are 4-connected shortest paths over the floor's nodes; whatever they ignore (other
robots, shelves that could move away) only makes them smaller, so every bound is admissible.
"""

from __future__ import annotations

from importlib import import_module
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from .delivery import assigned_bound, delivery_schedule
    from .floor import INFINITE, Floor
    from .makespan import cheap_bounds, delivery_bound, makespan_bound, strong_bounds
    from .mapf import bottleneck_assignment, goal_cells, mapf_bounds, min_cost_assignment, nearest_goal_bounds

#: where each name of the package lives
_HOMES = {
    "assigned_bound": "delivery", "delivery_schedule": "delivery",
    "INFINITE": "floor", "Floor": "floor",
    "cheap_bounds": "makespan", "delivery_bound": "makespan", "makespan_bound": "makespan", "strong_bounds": "makespan",
    "bottleneck_assignment": "mapf", "goal_cells": "mapf", "mapf_bounds": "mapf", "min_cost_assignment": "mapf",
    "nearest_goal_bounds": "mapf",
}

__all__ = ["INFINITE", "Floor", "assigned_bound", "bottleneck_assignment", "cheap_bounds", "delivery_bound",
           "delivery_schedule", "goal_cells", "makespan_bound", "mapf_bounds", "min_cost_assignment",
           "nearest_goal_bounds", "strong_bounds"]


def __getattr__(name: str) -> Any:
    """A name of the package, its module imported when first asked for: ``check`` shows the
    cheap bound of one domain, which needs two or three of the five modules (a check of an A
    plan loads neither the trip relaxation nor the M/Md matching)."""
    if name in _HOMES:
        value = getattr(import_module(f".{_HOMES[name]}", __name__), name)
        globals()[name] = value  # asked once
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
