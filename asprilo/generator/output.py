"""Where generated instances go: file names, directories, skipping existing ones, progress."""

from __future__ import annotations

import os
import sys
import threading
import time
from collections.abc import Iterable
from pathlib import Path
from typing import TextIO

from asprilo.errors import InputError
from asprilo.paths import output_folder
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
         replace: bool = False, inputs: Iterable[str | Path | None] = ()) -> Path:
    """Write an instance atomically; returns its path.  A file of the same name is replaced
    only with ``replace`` (else an :class:`InputError` says how to go on); never one of
    ``inputs`` (templates, the batch file), nor anything but a regular file."""
    path = instance_path(directory, item, prefix, instance_dir)
    if path.exists() and not replace:
        raise InputError("exists already; give --force to replace it or --skip-existing to keep it", str(path))
    try:
        write_text(path, format_instance(item.instance, item.header), inputs)
    except OSError as error:
        raise InputError(f"cannot write the instance: {error.strerror}", str(path)) from None
    return path


def check_output_folder(folder: str | Path, flag: str) -> None:
    """Refuse an output folder (given with ``flag``) that cannot be made or written to, before any work."""
    output_folder(folder, flag)  # a file, a loop of links, a special file, a name that is not UTF-8
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise InputError(f"is a file, not a folder ({flag} names the output folder)", str(folder))
    existing = next(p for p in (folder, *folder.absolute().parents) if p.exists())
    if not existing.is_dir():
        raise InputError(f"cannot make the output folder ({flag}): {existing} is a file", str(folder))
    if not os.access(existing, os.W_OK | os.X_OK):
        raise InputError(f"cannot write to the output folder ({flag}): permission denied", str(folder))


#: the generator's stages in the heartbeat's words
STAGE_WORDS = {"stations": "picking stations", "stock": "products on shelves", "units": "units on shelves",
               "lines": "order lines", "quantities": "order quantities", "one-shot": "one-shot solve"}


class WriteProgress:
    """A progress bar on stderr: redrawn in place on a terminal, a line per tenth otherwise.

    On a terminal, an instance that takes a while to make is said every second as well (a
    heartbeat: ``making N003 (products on shelves)... 4 s``); :meth:`working` names the
    instance being made, :meth:`stage` the generator's stage, :meth:`close` ends the
    heartbeat."""

    WIDTH = 30
    #: seconds between two heartbeats, and how long an instance is made before the first
    BEAT = 1.0

    def __init__(self, total: int, stream: TextIO | None = None, beats: bool = True):
        self.total = total
        self.done = 0
        self.stream = stream or sys.stderr
        self.live = self.stream.isatty()
        self.beats = beats and self.live
        self._shown_tenths = 0
        self._lock = threading.Lock()
        self._current: str | None = None  # the instance being made, and since when
        self._since = 0.0
        self._stage: str | None = None     # the stage it is in
        self._beating = False              # a heartbeat line is shown
        self._stopped = threading.Event()
        self._ticker: threading.Thread | None = None

    def working(self, label: str) -> None:
        """``label`` is being made now (on a terminal the heartbeat starts)."""
        with self._lock:
            self._current, self._since, self._stage = label, time.perf_counter(), None
        if self.beats and self._ticker is None:
            self._ticker = threading.Thread(target=self._beat_on, daemon=True)
            self._ticker.start()

    def stage(self, name: str) -> None:
        """The instance being made is in the generator's stage ``name`` now (pipeline.STAGES)."""
        with self._lock:
            self._stage = STAGE_WORDS.get(name, name)

    def advance(self, label: str = "") -> None:
        with self._lock:
            self.done += 1
            self._current = None
            if self.total < 2:
                self._clear()
                return
            if self.live:
                filled = self.WIDTH * self.done // self.total
                bar = "#" * filled + "-" * (self.WIDTH - filled)
                end = "\n" if self.done == self.total else ""
                self.stream.write(f"\r\033[K[{bar}] {self.done}/{self.total} {label[-60:]:<60}{end}")
                self._beating = False
            elif self.done * 10 // self.total > self._shown_tenths or self.done == self.total:
                self._shown_tenths = self.done * 10 // self.total
                self.stream.write(f"[{self.done}/{self.total}] {label}\n")
            self.stream.flush()

    def beat(self) -> None:
        """Say the instance being made and for how long (on a terminal, once it took a while)."""
        with self._lock:
            seconds = time.perf_counter() - self._since
            if not self.beats or self._current is None or seconds < self.BEAT:
                return
            done = f"{self.done}/{self.total} " if self.total >= 2 else ""
            stage = f" ({self._stage})" if self._stage else ""
            self.stream.write(f"\r\033[K{done}making {self._current}{stage}... {seconds:.0f} s")
            self.stream.flush()
            self._beating = True

    def interrupt(self) -> None:
        """End the bar's line before a message is printed."""
        with self._lock:
            if self._beating and (self.total < 2 or self.done in (0, self.total)):
                self._clear()
            elif self.live and 0 < self.done < self.total:
                self.stream.write("\n")
                self._beating = False

    def close(self) -> None:
        """No more heartbeats (a heartbeat line shown goes)."""
        self._stopped.set()
        with self._lock:
            self._current = None
            self._clear()

    def _clear(self) -> None:
        if self._beating:
            self.stream.write("\r\033[K")
            self.stream.flush()
            self._beating = False

    def _beat_on(self) -> None:
        while not self._stopped.wait(self.BEAT):
            self.beat()
