"""The robots panel: position, carried shelf, action now (at the step shown) and next, idle
steps so far."""

from __future__ import annotations

from typing import Any

from PyQt5.QtGui import QColor

from ..state.describe import actions_text, cell_text
from ..state.track import Track
from .tables import PROBLEM, StepModel


class RobotsModel(StepModel):
    """One row per robot at the step shown; robots off the floor are tinted red."""

    columns = ("Robot", "Position", "Carries", "Action", "Next", "Idle")
    dynamic = (1,)
    widths = {3: 120, 4: 120}  # "move right", "deliver 2 × product 5 to order 1" (cut short)

    def build_rows(self, track: Track) -> list[int]:
        return list(track.robot_ids)

    def value(self, robot: int, column: int) -> Any:
        track, step = self.track, self.step
        if column == 0:
            return robot
        if column == 1:
            x, y = track.robot_xy[step, track.robot_index[robot]].tolist()
            return int(y) * 1_000_000 + int(x)  # sorts row by row, as read
        if column == 2:
            return track.state(step).carries.get(robot)
        if column == 3:
            return actions_text(track.actions(robot, step)) if step >= 1 else ""
        if column == 4:
            return actions_text(track.actions(robot, step + 1)) if step < track.horizon else ""
        return int(track.idle[step, track.robot_index[robot]])

    def text(self, robot: int, column: int) -> str:
        if column == 1:
            return cell_text(self.track.robot_xy[self.step, self.track.robot_index[robot]])
        return super().text(robot, column)

    def background(self, robot: int) -> QColor | None:
        return PROBLEM if self.track.off_floor[self.step, self.track.robot_index[robot]] else None
