"""Puts a :class:`Track` on a :class:`WarehouseScene` at any time, moving only what changed.

A frame costs one array interpolation and a ``setPos`` per moving item: the scene is
never rebuilt.  Pickups, putdowns and deliveries show as badges while they happen;
objects that take part in a rule violation (or robots off the floor) are marked red in
the states where that happens, so an impossible state is never drawn silently.  Goals are
framed, and the gauge of a resource (a variant's energy: the track's first) is filled, as
the state nearest to the time shown has them.
"""

from __future__ import annotations

import numpy as np

from asprilo.model import Action, Robot, Shelf
from asprilo.simulate import Violation

from ..state.track import Track
from . import style
from .goal_marks import GoalMarks
from .items import RobotItem, ShelfItem
from .marks import Badge, CellMark
from .style import CELL
from .warehouse import WarehouseScene


class Animator:
    """Shows the states of ``track`` on ``scene``."""

    def __init__(self, scene: WarehouseScene, track: Track):
        self.scene = scene
        self.track = track
        for robot in track.robot_ids:  # objects the simulator knows but the scene lacks
            if robot not in scene.robots:
                scene.add_robot(Robot(robot, tuple(int(v) for v in track.robot_xy[0, track.robot_index[robot]])))
        for shelf in track.shelf_ids:
            if shelf not in scene.shelves:
                scene.add_shelf(Shelf(shelf, tuple(int(v) for v in track.shelf_xy[0, track.shelf_index[shelf]])))
        scene.include_cells(track.bounds)
        self.robot_items: list[RobotItem] = [scene.robots[r] for r in track.robot_ids]
        self.shelf_items: list[ShelfItem] = [scene.shelves[s] for s in track.shelf_ids]
        self._robot_shown = _cells_of(self.robot_items)
        self._shelf_shown = _cells_of(self.shelf_items)
        # what the items show now: resting (-1) or carried by someone (-2: look again)
        self._carrier_shown = np.array([-2 if shelf.carried else -1 for shelf in self.shelf_items],
                                       dtype=np.int32)
        self._marked_step: int | None = None
        self._flagged: list = []  # items marked red now
        self._cell_marks: list[CellMark] = []
        self._badge_step: int | None = None
        self._badges: list[tuple[Badge, RobotItem]] = []
        self.highlighted: Violation | None = None
        self.goals = GoalMarks(scene, track)
        self._goal_step: int | None = None
        self._gauge_step: int | None = None
        self.time = 0.0
        self._nearest = 0  # the state nearest to the time shown

    def show(self, time: float) -> None:
        """Place everything as it is at ``time`` (fractions interpolate between two states)."""
        track = self.track
        step, fraction = track.split(time)
        self.time = step + fraction
        _move(self.robot_items, track.robot_positions(self.time), self._robot_shown)
        moved = _move(self.shelf_items, track.shelf_positions(self.time), self._shelf_shown)
        self._nearest = step + 1 if fraction >= 0.5 else step
        carriers = track.carrier[self._nearest]
        if self._show_carriers(carriers) or (carriers[moved] < 0).any():
            self.scene.refresh_shelf_layer()  # a shelf was picked up, put down or moved while resting
        self._show_marks(self._nearest)
        if self._nearest != self._goal_step:
            self._goal_step = self._nearest
            self.goals.show(self._nearest)
        if self._nearest != self._gauge_step:
            self._gauge_step = self._nearest
            self._show_gauges(self._nearest)
        self._show_badges(step if fraction > 0 else None, fraction)

    def show_goals(self, shown: bool) -> None:
        """Mark the goals of the state shown, or none."""
        self.goals.set_shown(shown, self._nearest)

    def highlight(self, violation: Violation | None) -> None:
        """Keep the objects of ``violation`` marked whatever the time (``None``: stop)."""
        self.highlighted = violation
        self._marked_step = None
        self._show_marks(self._nearest)

    def detach(self) -> None:
        """Take back the marks and badges this animator put on the scene (before another
        animator takes over the same scene)."""
        for item in self._flagged:
            item.set_flagged(False)
        for mark in self._cell_marks:
            self.scene.removeItem(mark)
        for badge, _robot in self._badges:
            self.scene.removeItem(badge)
        self._flagged, self._cell_marks, self._badges = [], [], []
        self.goals.detach()
        for robot in self.robot_items:
            robot.set_gauge(None)

    # --- the parts of a frame ------------------------------------------------------------

    def _show_carriers(self, carriers: np.ndarray) -> bool:
        """Restyle the shelves whose carrier changed; whether there were any."""
        changed = np.flatnonzero(carriers != self._carrier_shown).tolist()
        for index in changed:
            robot = int(carriers[index])
            self.shelf_items[index].set_carrier(None if robot < 0 else self.robot_items[robot].colour)
        self._carrier_shown = carriers.copy()
        return bool(changed)

    def _show_marks(self, step: int) -> None:
        if step == self._marked_step:
            return
        self._marked_step = step
        track = self.track
        violations = list(track.violations_at.get(step, []))
        if self.highlighted is not None:
            violations.append(self.highlighted)
        robots = {robot for v in violations for robot in v.robots}
        robots.update(track.robot_ids[i] for i in np.flatnonzero(track.off_floor[step]).tolist())
        shelves = {shelf for v in violations for shelf in v.shelves}
        cells = {cell for v in violations for cell in v.cells}
        flagged = set(self._flagged)
        self._flagged = [self.scene.robots[r] for r in robots if r in self.scene.robots]
        self._flagged += [self.scene.shelves[s] for s in shelves if s in self.scene.shelves]
        for item in flagged.difference(self._flagged):
            item.set_flagged(False)
        for item in self._flagged:
            item.set_flagged(True)
        for mark in self._cell_marks:
            self.scene.removeItem(mark)
        self._cell_marks = [CellMark(style.cell_rect(cell)) for cell in sorted(cells)]
        for mark in self._cell_marks:
            self.scene.addItem(mark)

    def _show_gauges(self, step: int) -> None:
        """Fill each robot's gauge with its level after ``step`` (the track's first resource)."""
        gauge = self.track.gauges[0] if self.track.gauges else None
        for index, robot in enumerate(self.robot_items):
            level = gauge.level(index, step) if gauge is not None else None
            if gauge is None or level is None:
                robot.set_gauge(None)
                continue
            start = gauge.level(index, 0) or 0
            robot.set_gauge(level / start if start > 0 else 0.0, gauge.below(index, step))

    def _show_badges(self, segment: int | None, fraction: float) -> None:
        """Badges for the actions of step ``segment + 1`` while moving towards it."""
        if segment is None or not self.scene.fine:
            segment = None
        if segment != self._badge_step:
            for badge, _robot in self._badges:
                self.scene.removeItem(badge)
            self._badges = []
            if segment is not None:
                self._badges = [(badge, self.scene.robots[action.robot])
                                for action in self.track.actions_at(segment + 1)
                                if (badge := _badge(action, self.scene)) is not None]
                for badge, _robot in self._badges:
                    self.scene.addItem(badge)
            self._badge_step = segment
        for badge, robot in self._badges:
            badge.show_progress(robot.pos(), fraction)


def _cells_of(items: list) -> np.ndarray:
    """The cells items stand on now, shape (len(items), 2)."""
    points = [(item.x(), item.y()) for item in items]
    return np.array(points, dtype=np.float64).reshape(len(items), 2) / CELL + 0.5


def _move(items: list, cells: np.ndarray, shown: np.ndarray) -> np.ndarray:
    """Move the items whose cell differs from the one they show; returns their indices."""
    changed = np.flatnonzero(np.any(cells != shown, axis=1))
    if not len(changed):
        return changed
    points = ((cells[changed] - 0.5) * CELL).tolist()
    for index, (x, y) in zip(changed.tolist(), points, strict=True):
        items[index].setPos(x, y)
    shown[changed] = cells[changed]
    return changed


def _badge(action: Action, scene: WarehouseScene) -> Badge | None:
    robot = scene.robots.get(action.robot) if action.kind == "robot" else None
    if robot is None or action.name == "move":
        return None
    if action.name == "pickup":
        return Badge("\u2191 pick up", robot.colour.darker(130))
    if action.name == "putdown":
        return Badge("\u2193 put down", robot.colour.darker(130))
    if action.name == "deliver" and isinstance(action.args, tuple) and len(action.args) >= 2:
        order, product, *units = action.args
        amount = f"+{units[0]}" if units else "\u2713"
        return Badge(f"{amount} \u00d7 product {product}", style.DELIVERY)
    return Badge(action.name, style.VIOLATION)
