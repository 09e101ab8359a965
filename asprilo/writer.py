"""Write instances and plans as canonical fact files (SPEC.md §2-3), atomically."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterable
from pathlib import Path

from . import __version__
from .errors import InputError
from .facts import fact_groups, format_action, format_value
from .model import Instance, Plan

#: format_action and format_value are the tools' way to write single terms and actions
__all__ = ["format_action", "format_instance", "format_plan", "format_value", "header_lines", "refuse_overwriting",
           "write_bytes", "write_instance", "write_plan", "write_text"]

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
    """Write ``data`` to ``path`` atomically: readers see the old file or the whole new one.

    A file replaced keeps its permissions; a new one gets the usual ones (0666 less the
    umask).  A path that cannot be written is bad input (:class:`InputError`).
    """
    path = Path(path)
    if path.is_dir():
        raise InputError("is a directory, not a file to write", str(path))
    try:
        mode = path.stat().st_mode & 0o777 if path.exists() else 0o666 & ~_UMASK
        path.parent.mkdir(parents=True, exist_ok=True)
        handle, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    except OSError as error:
        raise InputError(f"cannot be written ({error.strerror or error})", str(path)) from None
    try:
        with os.fdopen(handle, "wb") as stream:
            stream.write(data)
        os.chmod(temporary, mode)
        os.replace(temporary, path)
    except OSError as error:
        Path(temporary).unlink(missing_ok=True)
        raise InputError(f"cannot be written ({error.strerror or error})", str(path)) from None
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def refuse_overwriting(output: str | Path | None, inputs: Iterable[str | Path | None]) -> None:
    """Refuse an output file that is one of the inputs (or a folder): writing it would
    destroy what is read.  ``-`` and ``None`` (standard streams, nothing) pass."""
    if output is None or str(output) == "-":
        return
    target = Path(output)
    if target.is_dir():
        raise InputError("is a directory, not a file to write", str(target))
    for given in inputs:
        if given is None or str(given) == "-":
            continue
        source = Path(given)
        same = target.exists() and source.exists() and os.path.samefile(target, source)
        if same or target.resolve() == source.resolve():
            raise InputError(f"is also an input ({given}); choose another output file", str(target))


def write_text(path: str | Path, text: str) -> None:
    """Write ``text`` (UTF-8) to ``path`` atomically."""
    write_bytes(path, text.encode("utf-8"))


def write_instance(path: str | Path, instance: Instance, header: Iterable[str] | None = None) -> None:
    write_text(path, format_instance(instance, header))


def write_plan(path: str | Path, plan: Plan) -> None:
    write_text(path, format_plan(plan))
