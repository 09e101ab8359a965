"""Trails: the paths of selected robots, drawn in their colours."""

from __future__ import annotations

from enum import Enum

from PyQt5.QtCore import QPointF

from ..state.track import Track
from . import style
from .marks import TrailItem
from .warehouse import WarehouseScene


class PathMode(str, Enum):
    REMAINING = "remaining"   # from the state shown to the end
    WHOLE = "whole"           # the whole path, the part behind drawn faint


class Trails:
    """One trail item per selected robot, redrawn when the step or the selection changes."""

    def __init__(self, scene: WarehouseScene, track: Track):
        self.scene = scene
        self.track = track
        self.mode = PathMode.REMAINING
        self.robots: list[int] = []
        self._items: dict[int, TrailItem] = {}
        self._step = 0

    def show(self, robots: list[int] | set[int], step: int | None = None,
             mode: PathMode | None = None) -> None:
        """Show the trails of ``robots`` as seen from state ``step`` (default: the last one asked)."""
        self.robots = sorted(r for r in robots if r in self.track.robot_index)
        self._step = self._step if step is None else step
        self.mode = self.mode if mode is None else PathMode(mode)
        for robot in list(self._items):
            if robot not in self.robots:
                self.scene.removeItem(self._items.pop(robot))
        for robot in self.robots:
            item = self._items.get(robot)
            if item is None:
                item = self._items[robot] = TrailItem(self.scene.robots[robot].colour)
                self.scene.addItem(item)
            ahead = _away_from_robot(self._points(robot, self._step, None), 0)
            behind = self._points(robot, 0, self._step) if self.mode is PathMode.WHOLE else []
            item.set_points(ahead, _away_from_robot(behind, -1))

    def _points(self, robot: int, start: int, end: int | None) -> list[QPointF]:
        """Centres of the cells ``robot`` visits in states start..end, waits left out."""
        cells = self.track.robot_xy[start:None if end is None else end + 1, self.track.robot_index[robot]]
        points: list[QPointF] = []
        last = None
        for x, y in cells.tolist():
            if (x, y) != last:
                points.append(style.centre((x, y)))
                last = (x, y)
        return points


def _away_from_robot(points: list[QPointF], end: int) -> list[QPointF]:
    """Start (``end=0``) or stop (``end=-1``) the line at the rim of the robot standing there,
    so that it never covers the robot's id."""
    if len(points) < 2:
        return points
    points = list(points)
    here, next_ = (points[0], points[1]) if end == 0 else (points[-1], points[-2])
    shift = style.ROBOT_SIZE / 2 * style.CELL
    length = max(abs(next_.x() - here.x()) + abs(next_.y() - here.y()), 1e-9)
    points[end] = here + (next_ - here) * (shift / length)
    return points
