"""The undo history of the viewer's document, without Qt.

Each entry is a :class:`Step`: something that can be done and taken back (``redo`` /
``undo``) and says what it is called.  Steps pushed inside :meth:`History.group` form one
entry: a stroke of the highway tool, several order lines removed at once.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Protocol

from .observe import Signal


class Step(Protocol):
    text: str

    def redo(self) -> None: ...

    def undo(self) -> None: ...


@dataclass
class Group:
    """Several steps done and undone as one."""

    text: str
    steps: list[Step] = field(default_factory=list)

    def redo(self) -> None:
        for step in self.steps:
            step.redo()

    def undo(self) -> None:
        for step in reversed(self.steps):
            step.undo()


class History:
    """Done steps (undo takes back the last) and undone ones (redo does them again)."""

    def __init__(self) -> None:
        self.entries: list[Step] = []
        self.index = 0  # entries[:index] are done
        self._group: Group | None = None
        self._depth = 0  # groups begun and not ended
        self._marks: dict[str, int | None] = {}  # name -> position (None: no longer reachable)
        self.changed = Signal()  # after every push, undo, redo or clear

    @property
    def count(self) -> int:
        return len(self.entries)

    @property
    def can_undo(self) -> bool:
        return self.index > 0 and self._group is None

    @property
    def can_redo(self) -> bool:
        return self.index < len(self.entries) and self._group is None

    @property
    def undo_text(self) -> str:
        return self.entries[self.index - 1].text if self.index else ""

    @property
    def redo_text(self) -> str:
        return self.entries[self.index].text if self.index < len(self.entries) else ""

    def push(self, step: Step) -> None:
        """Do ``step`` and make it the last done one (what was undone is forgotten)."""
        step.redo()
        if self._group is not None:
            self._group.steps.append(step)
            return
        self._append(step)

    def begin_group(self, text: str) -> None:
        """Steps pushed from now until :meth:`end_group` become one entry called ``text``
        (none when nothing was pushed; a group begun inside another joins it)."""
        if self._group is None:
            self._group = Group(text)
            self._depth = 0
        self._depth += 1

    def end_group(self) -> None:
        self._depth -= 1
        if self._depth == 0:
            group, self._group = self._group, None
            if group.steps:
                self._append(group)

    @contextmanager
    def group(self, text: str) -> Iterator[None]:
        """The steps pushed inside the ``with`` block as one entry (see :meth:`begin_group`)."""
        self.begin_group(text)
        try:
            yield
        finally:
            self.end_group()

    def _append(self, step: Step) -> None:
        del self.entries[self.index:]
        self._marks = {name: (None if at is None or at > self.index else at) for name, at in self._marks.items()}
        self.entries.append(step)
        self.index += 1
        self.changed.emit()

    def undo(self) -> None:
        if self.can_undo:
            self.index -= 1
            self.entries[self.index].undo()
            self.changed.emit()

    def redo(self) -> None:
        if self.can_redo:
            self.entries[self.index].redo()
            self.index += 1
            self.changed.emit()

    def clear(self) -> None:
        self.entries, self.index = [], 0
        self._marks = dict.fromkeys(self._marks, 0)
        self.changed.emit()

    def mark(self, name: str) -> None:
        """Remember the position now under ``name`` (e.g. where the instance was saved)."""
        self._marks[name] = self.index

    def since(self, name: str) -> list[Step] | None:
        """The entries done or undone since the mark ``name``; ``None`` when the history
        went another way meanwhile (that position cannot come back)."""
        at = self._marks.get(name, 0)
        if at is None:
            return None
        low, high = sorted((at, self.index))
        return self.entries[low:high]
