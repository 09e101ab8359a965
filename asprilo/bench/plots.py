"""The plots of benchmark results (PNG, PDF, SVG; drawn without a display): a cactus plot
(one panel per domain, all encodings on one log time axis), average time by number of robots
(one panel per instance set), and per-instance scatter plots of one encoding against
another.  Runs are counted as the tables of :mod:`asprilo.bench.report` count them."""

from __future__ import annotations

import io
import math
from collections import defaultdict
from collections.abc import Iterable
from pathlib import Path
from statistics import mean
from typing import Any

from .report import LABELS, _ordered, _rows, _time, _timed, encodings_of
from .results import SOLVED

#: the plot formats ``plot`` may write
FORMATS = ("png", "pdf", "svg")

#: the shortest time a log axis shows (a run that took no measurable time)
FLOOR = 0.01


def _figure(panels: int, columns: int = 3, **share: Any):
    """A figure (no display: it is never shown, only saved) with a grid of ``panels`` axes;
    the grid's spare axes are hidden.  The figure and its visible axes."""
    from matplotlib.figure import Figure

    columns = max(1, min(columns, panels))
    rows = max(1, math.ceil(panels / columns))
    figure = Figure(figsize=(4.4 * columns, 3.6 * rows), layout="constrained")
    grid = figure.subplots(rows, columns, squeeze=False, **share)
    axes = [axis for row in grid for axis in row]
    for spare in axes[panels:]:
        spare.set_visible(False)
    return figure, axes[:panels]


def _limit_line(axis, records: list[dict], horizontal: bool = True) -> None:
    limits = {r["time_limit"] for r in records}
    if len(limits) == 1:
        limit = limits.pop()
        (axis.axhline if horizontal else axis.axvline)(limit, color="grey", linestyle=":", linewidth=1)


def cactus_figure(records: list[dict]):
    """Solved runs over time: one panel per domain (label), one line per encoding, every panel
    on one shared log time axis; runs of the anytime planner are left out (their time is the
    time to a first plan)."""
    import matplotlib.ticker

    runs = [r for r in records if r.get("method") != "anytime"]
    labels = _ordered({r["label"] for r in runs}, LABELS)
    figure, axes = _figure(max(1, len(labels)), sharey=True)
    for axis, label in zip(axes, labels, strict=False):
        for _l, encoding in [row for row in _rows(runs) if row[0] == label]:
            times = sorted(max(r["time"], FLOOR) for r in runs
                           if r["label"] == label and r["encoding"] == encoding and r["status"] == SOLVED)
            axis.plot(range(1, len(times) + 1), times, marker="o", markersize=3, label=encoding)
        _limit_line(axis, [r for r in runs if r["label"] == label])
        axis.set(title=label, xlabel="solved runs", ylabel="time (s)", yscale="log")
        axis.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
        axis.grid(alpha=0.3, which="both")
        axis.legend(fontsize="small")
    return figure


def robots_figure(records: list[dict], set_order: list[str] | None = None):
    """Average time (runs out of limits at the limit, failed runs left out) by number of
    robots: one panel per instance set, one line per domain and encoding, the robot counts as
    ticks."""
    sets = _ordered({r["set"] for r in records}, set_order or [])
    figure, axes = _figure(max(1, len(sets)), sharey=True)
    for axis, name in zip(axes, sets, strict=False):
        runs = [r for r in records if r["set"] == name and _timed(r)]
        for label, encoding in _rows(runs):
            points = defaultdict(list)
            for r in runs:
                if (r["label"], r["encoding"]) == (label, encoding):
                    points[r["robots"]].append(max(_time(r), FLOOR))
            robots = sorted(points)
            axis.plot(robots, [mean(points[n]) for n in robots], marker="o", label=f"{label} {encoding}")
        axis.set_xticks(sorted({r["robots"] for r in runs}))
        axis.set(title=name, xlabel="robots", ylabel="average time (s)", yscale="log")
        axis.grid(alpha=0.3, which="both")
        axis.legend(fontsize="x-small")
    return figure


def scatter_pairs(records: list[dict]) -> list[tuple[str, str]]:
    """The scatter plots made by default: the first encoding (``plain`` if it ran) against every other."""
    names = encodings_of(records)
    return [(names[0], other) for other in names[1:]]


def scatter_figure(records: list[dict], first: str, second: str):
    """Per instance the time of ``first`` (x) against ``second`` (y), one panel per domain
    (label) where both ran: log axes, the diagonal, runs out of limits at the time limit with
    a mark of their own; an instance where either failed is left out (the panel says how
    many).  ``None`` if no instance has runs of both."""
    pairs = _scatter_pairs(records, first, second)
    labels = _ordered({label for label, _s, _i in pairs}, LABELS)
    if not labels:
        return None
    figure, axes = _figure(len(labels))
    for axis, label in zip(axes, labels, strict=True):
        _scatter_panel(axis, label, [pair for (row, _s, _i), pair in pairs.items() if row == label], first, second)
    return figure


def _scatter_pairs(records: list[dict], first: str, second: str) -> dict[tuple, tuple[dict, dict]]:
    """(label, set, instance) -> the runs of ``first`` and ``second`` there (where both ran)."""
    by: dict[tuple, dict[str, dict]] = defaultdict(dict)
    for r in records:
        if r.get("method") != "anytime" and r["encoding"] in (first, second):
            by[(r["label"], r["set"], r["instance"])][r["encoding"]] = r
    return {key: (pair[first], pair[second]) for key, pair in by.items() if first in pair and second in pair}


def _scatter_panel(axis, label: str, mine: list[tuple[dict, dict]], first: str, second: str) -> None:
    """One domain's panel of :func:`scatter_figure`."""
    shown = [(a, b) for a, b in mine if _timed(a) and _timed(b)]
    points: dict[str, list[tuple[float, float]]] = {kind: [] for kind in ("both", "out")}
    for a, b in shown:
        kind = "both" if a["status"] == SOLVED and b["status"] == SOLVED else "out"
        points[kind].append((max(_time(a), FLOOR), max(_time(b), FLOOR)))
    limit = max([r["time_limit"] for pair in mine for r in pair], default=1.0)
    low = min([FLOOR * 10, *(t for point in points["both"] + points["out"] for t in point)]) / 2
    axis.plot([low, limit * 1.5], [low, limit * 1.5], color="grey", linewidth=1, label="_diagonal")
    axis.axvline(limit, color="grey", linestyle=":", linewidth=1)
    axis.axhline(limit, color="grey", linestyle=":", linewidth=1)
    if points["both"]:
        axis.scatter(*zip(*points["both"], strict=True), s=14, label="both solved")
    if points["out"]:
        axis.scatter(*zip(*points["out"], strict=True), s=22, marker="^", color="tab:red",
                     label="out of limits (at the limit)")
    left_out = len(mine) - len(shown)
    axis.set(xscale="log", yscale="log", xlim=(low, limit * 1.5), ylim=(low, limit * 1.5),
             xlabel=f"{first}: time (s)", ylabel=f"{second}: time (s)",
             title=label + (f" ({left_out} with a failed run left out)" if left_out else ""))
    axis.set_aspect("equal")
    axis.grid(alpha=0.3, which="both")
    if shown:
        axis.legend(fontsize="x-small", loc="upper left")


def plot(records: list[dict], folder: Path, set_order: list[str] | None = None,
         formats: Iterable[str] = ("png",), pairs: list[tuple[str, str]] | None = None) -> list[Path]:
    """Write the cactus plot, the plot by robots and the scatter plots (of ``pairs``, by
    default :func:`scatter_pairs`) in every one of ``formats``; the files written."""
    formats = list(formats)
    figures = [("cactus", cactus_figure(records)), ("time-by-robots", robots_figure(records, set_order))]
    for first, second in scatter_pairs(records) if pairs is None else pairs:
        figure = scatter_figure(records, first, second)
        if figure is not None:
            figures.append((f"scatter-{first}-{second}", figure))
    return [save(figure, folder / f"{name}.{kind}") for name, figure in figures for kind in formats]


#: no dates in the files: the same results give the same files
_METADATA = {"pdf": {"CreationDate": None}, "svg": {"Date": None}}


def save(figure, path: Path) -> Path:
    """Save a figure atomically (render to memory, then replace the file) in the format of
    its suffix."""
    from asprilo.writer import write_bytes
    kind = path.suffix[1:]
    buffer = io.BytesIO()
    figure.savefig(buffer, format=kind, dpi=110, metadata=_METADATA.get(kind))
    write_bytes(path, buffer.getvalue())
    return path
