"""The violations panel: every rule the plan breaks, by step; a click jumps there."""

from __future__ import annotations

from typing import Any

from PyQt5.QtGui import QColor

from asprilo.simulate import Violation

from ..state.track import Track
from .tables import CURRENT, StepModel


class ViolationsModel(StepModel):
    """One row per violation, as the simulator reports it (the checker's ``err/3`` in the tooltip)."""

    columns = ("Step", "Rule", "What is wrong")
    dynamic = (0,)

    def build_rows(self, track: Track) -> list[Violation]:
        return list(track.violations)

    def set_rows(self, violations: list[Violation]) -> None:
        """Show these violations (e.g. the ASP checker's) instead of the replay's."""
        self.beginResetModel()
        self.rows = list(violations)
        self.endResetModel()

    def value(self, row: Violation, column: int) -> Any:
        return (row.step, f"{row.module}/{row.check}", row.message)[column]

    def tooltip(self, row: Violation, column: int) -> str:
        return row.atom

    def background(self, row: Violation) -> QColor | None:
        return CURRENT if row.step == self.step else None
