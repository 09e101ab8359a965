"""The plan panel: every action by step, the step shown highlighted; a click jumps there."""

from __future__ import annotations

from bisect import bisect_left
from typing import Any

from PyQt5.QtGui import QColor

from asprilo.model import Action
from asprilo.writer import format_action

from ..state.describe import action_text
from ..state.track import Track
from .tables import CURRENT, FADED, StepModel


class PlanModel(StepModel):
    """One row per action: its step, robot and what it does."""

    columns = ("Step", "Robot", "Action")
    dynamic = (0,)

    def build_rows(self, track: Track) -> list[Action]:
        rows = list(track.plan.actions)
        self._steps = [action.step for action in rows]
        return rows

    def first_row(self, step: int) -> int | None:
        """Index of the first action at ``step`` (or the next step that has one)."""
        index = bisect_left(self._steps, step)
        return index if index < len(self.rows) else None

    def value(self, row: Action, column: int) -> Any:
        return (row.step, row.robot, action_text(row))[column]

    def tooltip(self, row: Action, column: int) -> str:
        return format_action(row) + "."

    def background(self, row: Action) -> QColor | None:
        return CURRENT if row.step == self.step else None

    def foreground(self, row: Action) -> QColor | None:
        return FADED if row.step < self.step else None

    def bold(self, row: Action) -> bool:
        return row.step == self.step
