"""The one resolver of the paths a user names: encoding files, the files they ``#include``,
output files and folders.

Whatever is at a path, a problem is one sentence naming it, never a traceback: a name that
is not UTF-8 (``enc_\\xff.lp``), a loop of symbolic links, a folder, a FIFO, a device or a
socket where a file to read is meant, a file that cannot be read.  Names are shown printable
(:func:`shown`: bytes that are not UTF-8 as ``\\xff``, control characters escaped).
:func:`real` is the canonical form of a path for comparisons; unlike ``Path.resolve`` it
never raises, a loop of links included.
"""

from __future__ import annotations

import errno
import os
import stat
from pathlib import Path

from .errors import InputError

#: what a path is, by the kind of file there (anything but a regular file is refused)
_KINDS = ((stat.S_ISDIR, "a folder"), (stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISCHR, "a character device"),
          (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK, "a socket"))
#: why a path cannot be looked at, by error number
_ERRORS = {errno.ENOENT: "no such file", errno.ELOOP: "is a loop of symbolic links",
           errno.ENOTDIR: "no such file (a part of its path is a file, not a folder)",
           errno.EACCES: "cannot be read (permission denied)", errno.ENAMETOOLONG: "has a name too long for the system"}


class PathError(InputError):
    """A path a user named that cannot be used as meant (see the module docstring)."""

    def __reduce__(self):  # pickled as itself: errors come back from child processes
        return PathError, (self.message, self.file, self.line)


def shown(path: str | Path) -> str:
    """``path`` for a one-line message: bytes that are not UTF-8 as ``\\xNN``, control
    characters escaped."""
    text = os.fsencode(path).decode("utf-8", "backslashreplace")
    if text.isprintable():
        return text
    return "".join(char if char.isprintable() else char.encode("unicode_escape").decode("ascii") for char in text)


def real(path: str | Path) -> Path:
    """The canonical absolute form of ``path`` (links followed as far as they lead); never
    raises, not even on a loop of symbolic links."""
    return Path(os.path.realpath(path))


def problem(path: str | Path) -> str | None:
    """Why ``path`` is no file to read, in words (``is a folder, not a file``...), or ``None``
    when it is a readable regular file with a UTF-8 name."""
    try:
        os.fsencode(path).decode("utf-8")
    except UnicodeDecodeError:
        return "has a name that is not UTF-8 (rename the file)"
    try:
        mode = os.stat(path).st_mode
    except OSError as error:
        return _ERRORS.get(error.errno or 0, f"cannot be read ({error.strerror or error})")
    except ValueError:  # a NUL in the name
        return "has a name with a NUL character"
    if stat.S_ISDIR(mode):
        return "is a folder, not a file"
    if not stat.S_ISREG(mode):
        return f"is {_kind(mode)}, not a regular file"
    if not os.access(path, os.R_OK):
        return "cannot be read (permission denied)"
    return None


def input_file(path: str | Path) -> Path:
    """``path`` as a :class:`Path` when it names a readable regular file; else
    :class:`PathError` naming it and the problem."""
    why = problem(path)
    if why is not None:
        raise PathError(why, shown(path))
    return Path(path)


def included_file(name: str, includer: Path, line: int | None = None) -> Path:
    """The file that ``#include "name".`` in ``includer`` (at ``line``) names, next to the
    including file; else :class:`InputError` at the directive."""
    path = includer.parent / name
    why = problem(path)
    if why is None:
        return path
    if why == "no such file":
        raise InputError(f"#include of a missing file {shown(name)!r}", shown(includer), line)
    raise InputError(f"#include of {shown(name)!r}, which {why}", shown(includer), line)


def output_folder(folder: str | Path, flag: str) -> None:
    """Refuse (:class:`PathError`) an output ``folder`` (given with ``flag``) that is there
    but no folder: a file, a loop of links, a special file; or whose name is not UTF-8."""
    name = shown(folder)
    try:
        os.fsencode(folder).decode("utf-8")
    except UnicodeDecodeError:
        raise PathError(f"has a name that is not UTF-8; choose another output folder ({flag})", name) from None
    try:
        mode = os.stat(folder).st_mode
    except NotADirectoryError:  # a file on its way: the caller says which
        return
    except FileNotFoundError:
        if os.path.islink(folder):
            raise PathError(f"is a dangling symbolic link, not a folder ({flag} names the output folder)",
                            name) from None
        return
    except OSError as error:
        why = _ERRORS.get(error.errno or 0, f"cannot be used ({error.strerror or error})")
        raise PathError(f"{why} ({flag} names the output folder)", name) from None
    if not stat.S_ISDIR(mode):
        raise PathError(f"is {_kind(mode)}, not a folder ({flag} names the output folder)", name)


def _kind(mode: int) -> str:
    if stat.S_ISREG(mode):
        return "a file"
    return next((words for test, words in _KINDS if test(mode)), "a special file")
