"""The warehouse picture of the viewer's state: the scene, its animation, the paths of the
selected robots, and what the mouse says about it (clicks select, hovering describes).

The stage follows the state: a new scenario builds a new scene; an edit of the instance
changes only the items it touched; any change computes the animation again and moves the
clock to the time the change asks for.
"""

from __future__ import annotations

import gc

from PyQt5.QtCore import QObject, QPointF, Qt

from asprilo.model import Destination, Instance, PickingStation, Robot, Shelf
from asprilo.simulate import Violation

from ..state.describe import tooltip
from ..state.document import Change
from ..state.edits import TABLES, Edit
from ..state.viewer import ViewerState
from . import style
from .animator import Animator
from .paths import PathMode, Trails
from .player import Player
from .view import WarehouseView
from .warehouse import WarehouseScene

_MAKERS = {"robot": Robot, "shelf": Shelf, "station": PickingStation, "destination": Destination}


class Stage(QObject):
    """Scene, animator and trails of the state's track, shown in ``view`` at ``player``'s time."""

    def __init__(self, state: ViewerState, view: WarehouseView, player: Player, parent: QObject | None = None):
        super().__init__(parent)
        self.state, self.view, self.player = state, view, player
        self.scene: WarehouseScene | None = None
        self.animator: Animator | None = None
        self.trails: Trails | None = None
        self.paths = PathMode.REMAINING
        self.show_paths = True
        self.show_goals = True
        self.show_labels = True
        state.shown.connect(self._show_new)
        state.track_changed.connect(self._show_change)
        state.step_changed.connect(self._show_step)
        state.selection.changed.connect(self._show_selection)
        player.time_changed.connect(self._show_time)
        view.zoom_changed.connect(self._zoomed)
        view.clicked.connect(self._clicked)
        view.describe = self._describe

    @property
    def time(self) -> float:
        """The time the scene shows."""
        return self.animator.time if self.animator is not None else 0.0

    # --- following the state ------------------------------------------------------------------

    def _show_new(self, keep_time: bool) -> None:
        time = self.player.time if keep_time else 0.0
        self.player.pause()
        gc.unfreeze()  # what the last scenario froze may now be collected
        old_scene, track = self.scene, self.state.track
        if track is None:
            self.animator = self.trails = None
            self.scene = WarehouseScene(Instance(), self)
            self.scene.addText("Open an instance (Ctrl+O) or drop files here.", style.font(16, bold=False))
            self.scene.setSceneRect(self.scene.picture_rect())
            self.view.setScene(self.scene)
        else:
            self.scene = WarehouseScene(track.instance, self)
            self._animate()
            self.view.setScene(self.scene)
            self.view.fit()
        if old_scene is not None:
            old_scene.deleteLater()
        self.player.set_horizon(track.horizon if track else 0, time)
        self._show_selection()
        # Exempt the scenario's many long-lived objects from the garbage collector's full
        # passes: over a big warehouse one takes ~0.1 s and would stall the animation.
        gc.freeze()

    def _show_change(self, change: Change) -> None:
        if self.scene is None or self.state.track is None:
            return
        if self.animator is not None:
            self.animator.detach()
        if self.trails is not None:
            self.trails.show([])
        if change.edit is not None:
            self._show_edit(change.edit)
        self._animate()
        self.player.set_horizon(self.state.track.horizon, self.player.time if change.time is None else change.time)
        self._show_selection()

    def _show_edit(self, edit: Edit) -> None:
        """Update the items the edit touched (the floor, objects added, moved or removed)."""
        scene, instance = self.scene, self.state.document.instance
        if {"nodes", "highways"} & edit.tables:
            scene.set_floor(instance.nodes.values(), instance.highways.values())
        for kind, table in TABLES.items():
            items = getattr(scene, table)
            for key in sorted({change.key for change in edit.changes if change.table == table}):
                if key in items:
                    scene.remove(kind, key)
                thing = getattr(instance, table).get(key)
                if thing is not None:
                    getattr(scene, f"add_{kind}")(_MAKERS[kind](thing.id, thing.at))

    def _animate(self) -> None:
        self.animator = Animator(self.scene, self.state.track)
        self.trails = Trails(self.scene, self.state.track)
        self.animator.goals.shown = self.show_goals

    def _show_time(self, time: float) -> None:
        if self.animator is not None:
            self.animator.show(time)

    def _show_step(self, _step: int) -> None:
        self._show_trails()

    def _zoomed(self, cell_px: float) -> None:
        if self.scene is not None:
            self.scene.show_labels(self.show_labels, cell_px)

    # --- what is shown on the map -------------------------------------------------------------

    def set_goals(self, shown: bool) -> None:
        """Mark the goals (those of the state shown) or not."""
        self.show_goals = shown
        if self.animator is not None:
            self.animator.show_goals(shown)

    def set_labels(self, shown: bool) -> None:
        """Show the ids of robots, shelves, stations, destinations (where they can be read)."""
        self.show_labels = shown
        self._zoomed(self.view.pixels_per_cell)

    # --- selection, paths, violations ---------------------------------------------------------

    def set_paths(self, shown: bool, mode: PathMode) -> None:
        """Show the paths of the selected robots (``mode``: what remains, or the whole path)."""
        self.show_paths, self.paths = shown, mode
        self._show_trails()

    def _show_selection(self) -> None:
        if self.scene is None or self.state.track is None:
            return
        selected = set(self.state.selection.robots)
        for ident, item in self.scene.robots.items():
            item.set_selected(ident in selected)
        self._show_trails()

    def _show_trails(self) -> None:
        if self.trails is not None:
            shown = self.state.selection.robots if self.show_paths else []
            self.trails.show(shown, self.state.step, self.paths)

    def show_violation(self, violation: Violation) -> None:
        """Jump to a violation's step, mark its objects and bring them into view."""
        self.state.seek(violation.step)
        if self.animator is None:
            return
        self.animator.highlight(violation)
        items = [self.scene.robots[r] for r in violation.robots if r in self.scene.robots]
        items += [self.scene.shelves[s] for s in violation.shelves if s in self.scene.shelves]
        if items:
            self.view.ensureVisible(items[0])
        elif violation.cells:
            self.view.ensureVisible(style.cell_rect(violation.cells[0]))
        self.state.selection.set(list(violation.robots) or self.state.selection.robots)

    def clear_highlight(self) -> None:
        if self.animator is not None:
            self.animator.highlight(None)

    # --- the mouse ----------------------------------------------------------------------------------

    def _clicked(self, objects: list[tuple[str, int]], modifiers) -> None:
        robots = [ident for kind, ident in objects if kind == "robot"]
        selection = self.state.selection
        if modifiers & (Qt.ControlModifier | Qt.ShiftModifier):
            chosen = list(selection.robots)
            for robot in robots[:1]:
                chosen.remove(robot) if robot in chosen else chosen.append(robot)
            selection.set(chosen)
        else:
            selection.set(robots[:1], objects[0] if objects else None)

    def _describe(self, point: QPointF, objects: list) -> str | None:
        track = self.state.track
        if track is None:
            return None
        cell, step = style.cell_at(point), self.state.step
        resting = [("shelf", shelf) for shelf, at in track.state(step).shelves.items()
                   if tuple(at) == cell and ("shelf", shelf) not in objects]  # drawn as one layer when tiny
        return tooltip(track, step, cell, objects + resting)
