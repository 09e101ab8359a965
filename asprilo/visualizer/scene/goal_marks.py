"""Goal frames on the map, step by step: the goals of ``state/goals.py`` put on the items of the
shelves and destinations they mark (in the colour of the robot whose labelled goal it is)."""

from __future__ import annotations

from PyQt5.QtGui import QColor

from ..state.goals import Goal, goals_at
from ..state.track import Track
from . import style
from .marks import GoalLook
from .warehouse import WarehouseScene


def look_of(goal: Goal, scene: WarehouseScene) -> GoalLook:
    """The frame and tag of a goal: who reached it, who serves it, or where it must go."""
    robot = scene.robots.get(goal.robot) if goal.robot is not None else None
    colour = style.DELIVERY if goal.reached else robot.colour if robot is not None else style.GOAL
    if goal.stations:
        tag = f"\u2713 PS{goal.at}" if goal.reached else "\u2192" + ",".join(f"PS{s}" for s in goal.stations)
    elif goal.reached:
        tag = f"\u2713 R{goal.by}" if goal.by is not None else "\u2713"  # (served earlier: a variant's goal)
    else:
        tag = f"R{goal.robot}" if goal.robot is not None else ""
    return GoalLook(QColor(colour), goal.reached, tag)


class GoalMarks:
    """Marks the goals of ``track``'s state shown; only the marks that change are redrawn."""

    def __init__(self, scene: WarehouseScene, track: Track):
        self.scene, self.track = scene, track
        self.shown = True
        self.goals: dict[tuple[str, int], Goal] = {}

    def show(self, step: int) -> None:
        goals = {(goal.kind, goal.ident): goal for goal in goals_at(self.track, step)} if self.shown else {}
        for key in self.goals.keys() - goals.keys():
            self._mark(key, None)
        for key, goal in goals.items():
            if self.goals.get(key) != goal:
                self._mark(key, goal)
        self.goals = goals

    def set_shown(self, shown: bool, step: int) -> None:
        self.shown = shown
        self.show(step)

    def detach(self) -> None:
        """Take the marks off the scene (before another track is shown on it)."""
        for key in self.goals:
            self._mark(key, None)
        self.goals = {}

    def _mark(self, key: tuple[str, int], goal: Goal | None) -> None:
        item = self.scene.table(key[0]).get(key[1])
        if item is not None:
            item.set_goal(None if goal is None else look_of(goal, self.scene))
