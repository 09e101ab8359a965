"""Write instances and plans as canonical fact files (SPEC.md §2-3), atomically.

Every command writes its files through :func:`write_bytes` (README: "Where outputs go"):
only regular files, never an input, all or nothing."""

from __future__ import annotations

import errno
import os
import stat
import sys
import tempfile
from collections.abc import Iterable
from pathlib import Path

from . import __version__
from .errors import InputError
from .facts import fact_groups, format_action, format_value
from .model import Instance, Plan
from .paths import real

#: format_action and format_value are the tools' way to write single terms and actions
__all__ = ["check_output", "format_action", "format_instance", "format_plan", "format_value", "header_lines",
           "write_bytes", "write_instance", "write_output", "write_plan", "write_text"]

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


#: what an output is, by the kind of file at its path (anything but a regular file is refused)
_KINDS = ((stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
          (stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISSOCK, "a socket"))


def check_output(path: str | Path | None, inputs: Iterable[str | Path | None] = (),
                 standard_output: str | None = None) -> None:
    """Refuse an output path that is not meant to be written, before any work.

    Outputs go only to regular files: a new one, or an existing one that is replaced
    (atomically, by :func:`write_bytes`).  Refused: a directory, a device, a FIFO, a socket,
    a symbolic link (to a file too: replacing the link would break it, writing through it
    would write elsewhere; name the file itself), a file that cannot be written, and any
    output that is also one of ``inputs`` (the same path, or the same file by device and
    inode: through a hard or symbolic link too).  ``-`` and ``None`` (standard output,
    nothing) pass.  ``standard_output`` says how the command writes to standard output
    instead (e.g. ``"-o -"``), for the refusal of a device.
    """
    if path is None or str(path) == "-":
        return
    target = Path(path)
    name = _shown(target)
    for given in inputs:
        if given is not None and str(given) != "-" and _same_file(target, Path(given)):
            raise InputError(f"is also an input ({_shown(Path(given))}); choose another output file", name)
    try:
        mode = os.lstat(target).st_mode
    except FileNotFoundError:
        return
    except OSError as error:
        raise InputError(f"cannot be written ({error.strerror or error})", name) from None
    if stat.S_ISLNK(mode):
        link = "a symbolic link" if target.exists() else \
            "a loop of symbolic links" if _loops(target) else "a dangling symbolic link"
        raise InputError(f"is {link} (to {_shown(Path(os.readlink(target)))}): outputs go only to regular files, "
                         "not through links; name the file itself", name)
    if stat.S_ISDIR(mode):
        raise InputError("is a directory, not a file to write", name)
    if not stat.S_ISREG(mode):
        kind = next((words for test, words in _KINDS if test(mode)), "a special file")
        hint = f" ({standard_output} writes to standard output, which you may redirect)" if standard_output else ""
        raise InputError(f"is {kind}, not a regular file: outputs go only to regular files{hint}", name)
    if not os.access(target, os.W_OK):
        raise InputError(f"cannot be written ({os.strerror(errno.EACCES)})", name)



def _loops(link: Path) -> bool:
    """Whether following ``link`` comes back to a link already followed."""
    try:
        link.resolve(strict=True)
    except RuntimeError:  # Python's word for a loop of links
        return True
    except OSError as error:
        return error.errno == errno.ELOOP
    return False

def _same_file(target: Path, source: Path) -> bool:
    """Whether two paths name one file: by device and inode when both exist, else by path."""
    try:
        return os.path.samefile(target, source)
    except OSError:
        return target.absolute() == source.absolute() or real(target) == real(source)


def _shown(path: Path) -> str:
    """A path for a one-line message: control characters escaped."""
    text = str(path)
    if text.isprintable():
        return text
    return "".join(char if char.isprintable() else char.encode("unicode_escape").decode("ascii") for char in text)


def write_bytes(path: str | Path, data: bytes, inputs: Iterable[str | Path | None] = ()) -> None:
    """Write ``data`` to ``path`` atomically: readers see the old file or the whole new one.

    The one way asprilo writes a file.  The path must pass :func:`check_output` (a new or
    existing regular file, none of ``inputs``); the data goes to a temporary file in the same
    folder, is synced to disk and renamed over the path, so a write that fails (a full disk,
    a file size limit, no permission, a read-only file system) leaves no half-written file,
    only an :class:`InputError` naming the file and the problem.  A file replaced keeps its
    permissions; a new one gets the usual ones (0666 less the umask).
    """
    if str(path) == "-":  # not a file named '-' by mistake: standard output is write_output's
        raise InputError("is standard output, not a file to write", "-")
    check_output(path, inputs)
    path = Path(path)
    name = _shown(path)
    try:
        mode = path.stat().st_mode & 0o777 if path.exists() else 0o666 & ~_UMASK
        path.parent.mkdir(parents=True, exist_ok=True)
        handle, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    except OSError as error:
        raise InputError(f"cannot be written ({error.strerror or error})", name) from None
    try:
        with os.fdopen(handle, "wb") as stream:
            stream.write(data)
            stream.flush()
            os.fsync(stream.fileno())
        os.chmod(temporary, mode)
        check_output(path)  # again: the path may have become a link or a device meanwhile
        os.replace(temporary, path)
    except OSError as error:
        Path(temporary).unlink(missing_ok=True)
        raise InputError(f"cannot be written ({error.strerror or error})", name) from None
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def write_text(path: str | Path, text: str, inputs: Iterable[str | Path | None] = ()) -> None:
    """Write ``text`` (UTF-8) to ``path`` atomically (:func:`write_bytes`)."""
    write_bytes(path, text.encode("utf-8"), inputs)


def write_output(target: str | Path, text: str, inputs: Iterable[str | Path | None] = ()) -> None:
    """Write ``text`` to the file ``target`` (:func:`write_text`), or to standard output for ``-``."""
    if str(target) == "-":
        sys.stdout.write(text)
        sys.stdout.flush()
    else:
        write_text(target, text, inputs)


def write_instance(path: str | Path, instance: Instance, header: Iterable[str] | None = None) -> None:
    write_text(path, format_instance(instance, header))


def write_plan(path: str | Path, plan: Plan) -> None:
    write_text(path, format_plan(plan))
