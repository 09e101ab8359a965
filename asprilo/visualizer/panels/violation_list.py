"""The violations panel: every rule the plan breaks, by step; a click jumps there."""

from __future__ import annotations

from typing import Any

from PyQt5.QtGui import QColor

from asprilo.simulate import Violation

from ..state.track import Track
from .tables import CURRENT, StepModel, wrapped_tip


def sentence(violation: Violation) -> str:
    """What is wrong, in words, without the step the panel shows in a column of its own
    (``step 23: robot 1 …`` → ``robot 1 …``; a goal at the horizon says so)."""
    message = violation.message
    for prefix, instead in ((f"step {violation.step} (the horizon): ", "at the horizon: "),
                            (f"step {violation.step}: ", ""), ("instance: ", "")):
        if message.startswith(prefix):
            return instead + message[len(prefix):]
    return message


class ViolationsModel(StepModel):
    """One row per violation, as the simulator reports it: the sentence in full in its
    tooltip, the checker's ``err/3`` atom in the rule's."""

    columns = ("Step", "Rule", "What is wrong")
    dynamic = (0,)
    rich_tooltips = True  # wrapped, escaped where needed

    def build_rows(self, track: Track) -> list[Violation]:
        return list(track.violations)

    def set_rows(self, violations: list[Violation]) -> None:
        """Show these violations (e.g. the ASP checker's) instead of the replay's."""
        self.beginResetModel()
        self.rows = list(violations)
        self.endResetModel()

    def value(self, row: Violation, column: int) -> Any:
        return (row.step, f"{row.module}/{row.check}", sentence(row))[column]

    def tooltip(self, row: Violation, column: int) -> str:
        if column == 2:
            return wrapped_tip(sentence(row))
        return wrapped_tip(row.atom) if column == 1 else str(row.step)

    def background(self, row: Violation) -> QColor | None:
        return CURRENT if row.step == self.step else None
