"""Write instances and plans as canonical fact files (SPEC.md §2-3), atomically."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from . import __version__
from .model import Action, Instance, Plan

_UMASK = os.umask(0)
os.umask(_UMASK)


def format_value(value: Any) -> str:
    """A Python value (as produced by :func:`asprilo.reader.value_of`) as an ASP term."""
    if isinstance(value, tuple):
        inner = ",".join(format_value(item) for item in value)
        return f"({inner},)" if len(value) == 1 else f"({inner})"
    return str(value)


def _init(kind: str, ident: int, attribute: str, value: Any) -> str:
    return f"init(object({kind},{ident}),value({attribute},{format_value(value)}))."


def header_lines(instance: Instance, command: str | None = None, seed: int | None = None,
                 tool: str = "asprilo") -> list[str]:
    """The comment header of an instance file: tool, command line, seed and counts."""
    counts = instance.counts()
    lines = [f"{tool} {__version__}"]
    if command is not None:
        lines.append(f"command: {command}")
    if seed is not None:
        lines.append(f"seed: {seed}")
    figures = [("Grid Size X", counts["x"]), ("Grid Size Y", counts["y"]),
               ("Number of Nodes", counts["nodes"]), ("Number of Highway Nodes", counts["highways"]),
               ("Number of Robots", counts["robots"]), ("Number of Shelves", counts["shelves"]),
               ("Number of Picking Stations", counts["stations"]),
               ("Number of Products", counts["products"]),
               ("Number of Product Units in Total", counts["units"]),
               ("Number of Orders", counts["orders"])]
    if counts["destinations"]:
        figures.append(("Number of Destinations", counts["destinations"]))
    lines += [f"{label + ':':<35}{value}" for label, value in figures]
    return lines


def format_instance(instance: Instance, header: Iterable[str] | None = None) -> str:
    """The canonical text of an instance: ``%`` header, ``#program base.``, facts by type."""
    if header is None:
        header = header_lines(instance)
    out = ["%" * 60, *(f"% {line}" if line else "%" for line in header), "%" * 60, "",
           "#program base.", ""]

    def group(title: str, facts: list[str]) -> None:
        if facts:
            out.extend([f"% {title}", *facts, ""])

    group("nodes", [_init("node", i, "at", cell) for i, cell in sorted(instance.nodes.items())])
    group("highways", [_init("highway", i, "at", cell) for i, cell in sorted(instance.highways.items())])
    group("picking stations", [_init("pickingStation", i, "at", s.at)
                               for i, s in sorted(instance.stations.items())])
    robots = []
    for i, robot in sorted(instance.robots.items()):
        robots.append(_init("robot", i, "at", robot.at))
        if robot.carries is not None:
            robots.append(_init("robot", i, "carries", robot.carries))
    group("robots", robots)
    group("shelves", [_init("shelf", i, "at", s.at) for i, s in sorted(instance.shelves.items())])
    group("products on shelves", [
        _init("product", i, "on", shelf if units is None else (shelf, units))
        for i, product in sorted(instance.products.items())
        for shelf, units in sorted(product.stock.items())])
    orders = []
    for i, order in sorted(instance.orders.items()):
        orders += [_init("order", i, "line", product if units is None else (product, units))
                   for product, units in sorted(order.lines.items())]
        if order.station is not None:
            orders.append(_init("order", i, "pickingStation", order.station))
    group("orders", orders)
    group("destinations", [_init("destination", i, "at", d.at)
                           for i, d in sorted(instance.destinations.items())])
    group("labelled goals: robot -> goal", [f"assign(robot({robot}),{kind}({goal}))."
                                            for robot, (kind, goal) in sorted(instance.assignment.items())])
    return "\n".join(out)


def format_action(action: Action) -> str:
    """The ``occurs/3`` atom of an action (without the final period)."""
    return (f"occurs(object({action.kind},{action.robot}),"
            f"action({action.name},{format_value(action.args)}),{action.step})")


def format_plan(plan: Plan) -> str:
    """One ``occurs/3`` fact per line, ordered by time step and robot."""
    return "".join(f"{format_action(action)}.\n" for action in plan.actions)


def write_bytes(path: str | Path, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically: readers see the old file or the whole new one."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(handle, "wb") as stream:
            stream.write(data)
        os.chmod(temporary, 0o666 & ~_UMASK)
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def write_text(path: str | Path, text: str) -> None:
    """Write ``text`` (UTF-8) to ``path`` atomically."""
    write_bytes(path, text.encode("utf-8"))


def write_instance(path: str | Path, instance: Instance, header: Iterable[str] | None = None) -> None:
    write_text(path, format_instance(instance, header))


def write_plan(path: str | Path, plan: Plan) -> None:
    write_text(path, format_plan(plan))
