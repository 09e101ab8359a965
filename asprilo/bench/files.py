"""The files a suite's ``files:`` patterns name (paths relative to the suite's folder): a
pattern walks folders (``**``, or a wildcard in a folder's name) only below the suite's
folder, and ``**`` follows no symbolic link; elsewhere only its file name may hold
wildcards."""

from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from asprilo.errors import InputError
from asprilo.yamlfile import printable, shown

if TYPE_CHECKING:
    from .suite import InstanceSet, Suite

#: what makes a part of a ``files`` pattern a wildcard (as in :mod:`glob`)
_WILDCARD = re.compile(r"[*?[]")


def pattern_start(folder: Path, pattern: str) -> tuple[Path, str]:
    """Where a ``files`` pattern of a suite in ``folder`` starts (its parts before the first
    wildcard, relative to ``folder``) and the rest of it (``""``: a file named as it is).  A
    pattern that would walk folders outside ``folder`` (``/**/*.lp``, ``../*/*.lp``) or go up
    after a wildcard is an :class:`InputError`: only below the suite's folder may a pattern
    walk folders; elsewhere only a file name may hold wildcards."""
    parts = Path(pattern).parts
    fixed = next((number for number, part in enumerate(parts) if _WILDCARD.search(part)), len(parts))
    start, rest = folder.joinpath(*parts[:fixed]), parts[fixed:]
    if not rest:
        return start, ""
    if ".." in rest:
        raise InputError(f"{shown(pattern)}: '..' after a wildcard (a pattern walks only below the suite's folder)")
    walks = len(rest) > 1 or rest[0] == "**"
    if walks and not _below(start, folder):
        raise InputError(f"{shown(pattern)} walks folders outside the suite's folder: only below it may a pattern "
                         f"walk folders (** or a wildcard in a folder's name); elsewhere only a file name may hold "
                         f"wildcards")
    return start, "/".join(rest)


def _below(path: Path, folder: Path) -> bool:
    """Whether ``path`` is ``folder`` or lies below it (links followed)."""
    try:
        path.resolve().relative_to(folder.resolve())
    except (ValueError, OSError, RuntimeError):  # outside; or a link loop
        return False
    return True


def existing_files(suite: Suite, instance_set: InstanceSet) -> list[Path]:
    """The files a ``files:`` set names (:func:`matching_files`)."""
    return matching_files(suite.path, instance_set.files, f"instances.{printable(instance_set.name)}")


def matching_files(suite: Path, patterns: Sequence[str], where: str) -> list[Path]:
    """The files ``patterns`` of the suite file ``suite`` name (``where``: the key that lists
    them, for messages), sorted; a pattern that matches no regular file is an error.  Patterns
    walk folders only below the suite's folder (:func:`pattern_start`), and ``**`` follows no
    symbolic link (as :meth:`pathlib.Path.glob` has it: :func:`glob.glob` follows links back
    up for ever)."""
    found: list[Path] = []
    for pattern in patterns:
        try:
            start, rest = pattern_start(suite.parent, pattern)
        except InputError as error:
            raise InputError(f"{where}.files: {error.message}", str(suite)) from None
        if not rest:
            matches = [start] if start.exists() else []
        else:
            hidden = rest.startswith(".") or "/." in rest  # the pattern names hidden files or folders
            matches = sorted((path for path in start.glob(rest) if path.is_file()
                              and (hidden or not any(part.startswith(".") for part in path.relative_to(start).parts))),
                             key=str)
        if not matches:
            raise InputError(f"{where}: no file matches {shown(pattern)}", str(suite))
        found += matches
    return found
