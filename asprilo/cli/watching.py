"""Re-running on save: the polling loop behind ``check --watch``.

A file counts as saved when its *stamp* changes: modification time, size, inode and device
(``os.stat``).  Editors save in several ways -- writing in place, or writing a new file
and renaming it over the old one (a new inode; for a moment the name may point at nothing)
-- and some write in two steps; a change is therefore acted on only once the stamps stood
still for one more poll (debounced), and a file that is missing is a stamp too (``None``),
so its coming back is a change.  Nothing busy: the loop sleeps ``POLL`` seconds between
looks (no inotify: that would be a dependency, and polling a few files costs nothing).

The loop takes its clock as arguments -- ``wait(seconds)`` and ``stop()`` -- so that tests
step it poll by poll, without timing anything.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path

#: seconds between two looks at the files
POLL = 0.3


@dataclass(frozen=True)
class Stamp:
    """What says that a file was saved: a new inode (renamed over), size or time."""

    mtime_ns: int
    size: int
    inode: int
    device: int


def stamp(path: Path) -> Stamp | None:
    """The file's stamp now (``None``: there is no file, or it cannot be looked at)."""
    try:
        status = os.stat(path)
    except (OSError, ValueError):  # missing, no permission, a name the system refuses
        return None
    return Stamp(status.st_mtime_ns, status.st_size, status.st_ino, status.st_dev)


class Stamps:
    """The stamps of the files followed, as last seen."""

    def __init__(self, paths: Iterable[Path] = ()):
        self.seen: dict[Path, Stamp | None] = {}
        self.follow(paths)

    def follow(self, paths: Iterable[Path]) -> None:
        """Follow ``paths`` from now on: those followed already keep the stamp last seen
        (a change not acted on yet stays a change), the others are stamped now."""
        self.seen = {path: self.seen[path] if path in self.seen else stamp(path) for path in dict.fromkeys(paths)}

    def changed(self) -> list[Path]:
        """The files whose stamp differs from the one last seen (which it becomes)."""
        changed = []
        for path, before in self.seen.items():
            now = stamp(path)
            if now != before:
                self.seen[path] = now
                changed.append(path)
        return changed


def watch(paths: Callable[[], Iterable[Path]], on_change: Callable[[list[Path]], None], *,
          wait: Callable[[float], object] = time.sleep, stop: Callable[[], bool] = lambda: False,
          poll: float = POLL) -> None:
    """Call ``on_change([])`` once, then ``on_change(changed)`` whenever files among
    ``paths()`` were saved, until ``stop()`` says so (or ``wait`` raises, e.g. on Ctrl-C).

    The files are stamped before the first call, so a save while ``on_change`` runs is seen
    at the next look; ``changed`` lists each file saved since the last call once, in the
    order first seen, and is handed over one quiet poll after the last save seen (an editor
    that writes in two steps makes one change).  ``paths()`` is asked again after every call:
    the files may change with the run (an encoding that ``#include``\\ s another file now).
    """
    stamps = Stamps(paths())
    on_change([])
    stamps.follow(paths())
    pending: list[Path] = []
    while not stop():
        wait(poll)
        changed = stamps.changed()
        if changed:
            pending += [path for path in changed if path not in pending]
            continue
        if pending:
            on_change(pending)
            pending = []
            stamps.follow(paths())
