"""Write instances and plans as canonical fact files (SPEC.md §2-3), atomically."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterable
from pathlib import Path

from . import __version__
from .facts import fact_groups, format_action, format_value
from .model import Instance, Plan

#: format_action and format_value are the tools' way to write single terms and actions
__all__ = ["format_action", "format_instance", "format_plan", "format_value", "header_lines", "write_bytes",
           "write_instance", "write_plan", "write_text"]

_UMASK = os.umask(0)
os.umask(_UMASK)


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
    for title, facts in fact_groups(instance):
        out.extend([f"% {title}", *facts, ""])
    return "\n".join(out)


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
