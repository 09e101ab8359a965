"""Where generated instances go: file names, directories, skipping existing ones, progress."""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import TextIO

from asprilo.errors import InputError
from asprilo.writer import format_instance, write_text

from .api import Generated


def instance_path(directory: str | Path, item: Generated, prefix: str = "", instance_dir: bool = False) -> Path:
    """``DIR/[PREFIX]x.._N001.lp``, or ``DIR/[PREFIX]x.._N001/[PREFIX]x.._N001.lp`` with instance_dir."""
    name = item.file_name(prefix)
    directory = Path(directory)
    return directory / name[:-3] / name if instance_dir else directory / name


def exists(directory: str | Path, number: int, prefix: str = "", instance_dir: bool = False) -> bool:
    """Whether instance ``number`` was written to ``directory`` before (for --skip-existing).

    The full name depends on counts the generator decides (e.g. units when -u is not given),
    so any file ending in ``_N<number>.lp`` counts.
    """
    pattern = f"{prefix}x*_N{number:03d}"
    pattern = f"{pattern}/{pattern}.lp" if instance_dir else f"{pattern}.lp"
    return any(Path(directory).glob(pattern))


def save(item: Generated, directory: str | Path, prefix: str = "", instance_dir: bool = False,
         replace: bool = False) -> Path:
    """Write an instance atomically; returns its path.  A file of the same name is replaced
    only with ``replace`` (else an :class:`InputError` says how to go on)."""
    path = instance_path(directory, item, prefix, instance_dir)
    if path.exists() and not replace:
        raise InputError("exists already; give --force to replace it or --skip-existing to keep it", str(path))
    try:
        write_text(path, format_instance(item.instance, item.header))
    except OSError as error:
        raise InputError(f"cannot write the instance: {error.strerror}", str(path)) from None
    return path


def check_output_folder(folder: str | Path, flag: str) -> None:
    """Refuse an output folder (given with ``flag``) that cannot be made or written to, before any work."""
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise InputError(f"is a file, not a folder ({flag} names the output folder)", str(folder))
    existing = next(p for p in (folder, *folder.absolute().parents) if p.exists())
    if not existing.is_dir():
        raise InputError(f"cannot make the output folder ({flag}): {existing} is a file", str(folder))
    if not os.access(existing, os.W_OK | os.X_OK):
        raise InputError(f"cannot write to the output folder ({flag}): permission denied", str(folder))


class WriteProgress:
    """A progress bar on stderr: redrawn in place on a terminal, a line per tenth otherwise."""

    WIDTH = 30

    def __init__(self, total: int, stream: TextIO | None = None):
        self.total = total
        self.done = 0
        self.stream = stream or sys.stderr
        self.live = self.stream.isatty()
        self._shown_tenths = 0

    def advance(self, label: str = "") -> None:
        self.done += 1
        if self.total < 2:
            return
        if self.live:
            filled = self.WIDTH * self.done // self.total
            bar = "#" * filled + "-" * (self.WIDTH - filled)
            end = "\n" if self.done == self.total else ""
            self.stream.write(f"\r[{bar}] {self.done}/{self.total} {label[-60:]:<60}{end}")
        elif self.done * 10 // self.total > self._shown_tenths or self.done == self.total:
            self._shown_tenths = self.done * 10 // self.total
            self.stream.write(f"[{self.done}/{self.total}] {label}\n")
        self.stream.flush()

    def interrupt(self) -> None:
        """End the bar's line before a message is printed."""
        if self.live and 0 < self.done < self.total:
            self.stream.write("\n")
