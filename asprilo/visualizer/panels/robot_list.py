"""The robots panel: position, carried shelf, the level of each resource of the domain (a
variant's energy), action now (at the step shown) and next, idle steps so far."""

from __future__ import annotations

from typing import Any

from PyQt5.QtCore import QModelIndex, Qt
from PyQt5.QtGui import QColor

from ..state.describe import actions_text, cell_text, gauge_text
from ..state.gauges import Gauge
from ..state.track import Track
from .tables import PROBLEM, StepModel

#: the columns every robot has; the domain's resources come after ``Carries``, one column each
COLUMNS = ("Robot", "Position", "Carries", "Action", "Next", "Idle")
_GAUGES_AT = 3


class RobotsModel(StepModel):
    """One row per robot at the step shown; robots off the floor are tinted red, and so is a
    resource's level below the least one (marked ``⚠`` at the step it falls there)."""

    columns: tuple[str, ...] = COLUMNS
    dynamic = (1,)
    widths = {3: 120, 4: 120}  # "move right", "deliver 2 × product 5 to order 1" (cut short)

    def build_rows(self, track: Track) -> list[int]:
        names = tuple(gauge.name for gauge in track.gauges)
        self.columns = COLUMNS[:_GAUGES_AT] + names + COLUMNS[_GAUGES_AT:]
        self.widths = {column + len(names): width for column, width in RobotsModel.widths.items()}
        return list(track.robot_ids)

    @property
    def shown(self) -> Track:
        """The track the rows are of (there are rows only while there is one)."""
        assert self.track is not None
        return self.track

    def gauge(self, column: int) -> Gauge | None:
        """The resource a column shows (``None``: a column of every robot)."""
        gauges = self.track.gauges if self.track is not None else ()
        return gauges[column - _GAUGES_AT] if 0 <= column - _GAUGES_AT < len(gauges) else None

    def value(self, robot: int, column: int) -> Any:
        track, step = self.shown, self.step
        index = track.robot_index[robot]
        gauge = self.gauge(column)
        if gauge is not None:
            return gauge.level(index, step)
        if column > _GAUGES_AT:
            column -= len(track.gauges)
        if column == 0:
            return robot
        if column == 1:
            x, y = track.robot_xy[step, index].tolist()
            return int(y) * 1_000_000 + int(x)  # sorts row by row, as read
        if column == 2:
            return track.state(step).carries.get(robot)
        if column == 3:
            return actions_text(track.actions(robot, step)) if step >= 1 else ""
        if column == 4:
            return actions_text(track.actions(robot, step + 1)) if step < track.horizon else ""
        return int(track.idle[step, index])

    def text(self, robot: int, column: int) -> str:
        track = self.shown
        gauge = self.gauge(column)
        if gauge is not None:
            return gauge_text(gauge, track.robot_index[robot], robot, self.step)
        if column == 1:
            x, y = track.robot_xy[self.step, track.robot_index[robot]].tolist()
            return cell_text((x, y))
        return super().text(robot, column)

    def tooltip(self, robot: int, column: int) -> str | None:
        gauge = self.gauge(column)
        if gauge is None:
            return None
        return gauge_text(gauge, self.shown.robot_index[robot], robot, self.step, long=True)

    def background(self, robot: int) -> QColor | None:
        track = self.shown
        return PROBLEM if track.off_floor[self.step, track.robot_index[robot]] else None

    def data(self, index: QModelIndex, role: int = Qt.ItemDataRole.DisplayRole) -> Any:
        gauge = self.gauge(index.column()) if index.isValid() else None
        if gauge is not None and role == Qt.ItemDataRole.BackgroundRole:
            robot = self.rows[index.row()]
            if gauge.below(self.shown.robot_index[robot], self.step):
                return PROBLEM
        return super().data(index, role)
