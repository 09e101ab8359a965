"""The run record of ``asprilo online --record``: what ran (steps, why it ended, release
steps, planner calls, waiting steps) and its figures, as JSON; read back by the viewer
(``viz SCENARIO PLAN --record RUN.json``), checked as data."""

from __future__ import annotations

import json
from pathlib import Path

from asprilo.errors import InputError
from asprilo.limits import current

from .ceiling import Ceiling
from .metrics import Metrics
from .run import OnlineRun

#: the version of the record's format
VERSION = 1


def figures(metrics: Metrics, bound: Ceiling | None) -> dict:
    """The figures as JSON values."""
    latency = metrics.latency
    return {"steps": metrics.steps, "lines": metrics.lines, "lines_done": metrics.lines_done,
            "units_done": metrics.units_done, "orders_open": metrics.orders_open,
            "lines_per_100": metrics.lines_per_100, "units_per_100": metrics.units_per_100,
            "ceiling_lines": None if bound is None else bound.lines,
            "ceiling_lines_per_100": None if bound is None else bound.lines_per_100,
            "latency": {"orders": latency.orders, "mean": latency.mean, "p95": latency.p95, "max": latency.most},
            "planner": {"calls": metrics.calls, "mean_seconds": metrics.planner_mean,
                        "max_seconds": metrics.planner_max},
            "waiting_steps": metrics.waiting_steps,
            "windows": [{"first": w.first, "last": w.last, "lines": w.lines, "units": w.units}
                        for w in metrics.windows]}


def record(outcome: OnlineRun, metrics: Metrics, bound: Ceiling | None) -> dict:
    """The run record: what ran, and its figures."""
    return {"version": VERSION, "steps": outcome.steps, "ended": outcome.ended,
            "releases": {str(order): step for order, step in sorted(outcome.releases.items())},
            "calls": [{"step": call.step, "seconds": call.seconds, "found": call.found} for call in outcome.calls],
            "waiting": outcome.waiting, "figures": figures(metrics, bound)}


def read_record(path: str) -> dict:
    """The run record in ``path``, its planner calls and waiting steps checked (bad input:
    :class:`InputError` naming the file)."""
    limit = current().file_mb
    try:
        if Path(path).stat().st_size > limit * 2**20:
            raise InputError(f"{path}: a run record of more than {limit} MB (the limit file-mb)")
        value = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError, RecursionError) as error:
        raise InputError(f"{path}: not a run record of asprilo online ({type(error).__name__}: {error})") from None
    if not isinstance(value, dict) or value.get("version") != VERSION:
        raise InputError(f"{path}: not a run record of asprilo online (no \"version\": {VERSION})")
    calls, waiting = value.get("calls"), value.get("waiting")
    if not isinstance(calls, list) or not all(_is_call(call) for call in calls) \
            or not isinstance(waiting, list) or not all(type(step) is int for step in waiting):
        raise InputError(f"{path}: a run record needs \"calls\" ({{step, seconds, found}} each) and \"waiting\" "
                         "(steps)")
    return value


def _is_call(call: object) -> bool:
    return isinstance(call, dict) and type(call.get("step")) is int \
        and type(call.get("seconds")) in (int, float) and type(call.get("found")) is bool
