"""The layout editor inside the viewer's window: edit tools, the right-click menu, undo and
redo, new instances, resizing, saving.

Edits always change the instance's initial state (the window shows step 0 after each);
a loaded plan stays and is replayed on the edited instance, so its violations update at
once.  Edits that would break a rule of SPEC.md §1 are refused with the reason in the
status bar and a tooltip; problems of a loaded instance are marked red like violations.
The mouse's part (clicks, drags, strokes) is in ``edit_mouse.py``.
"""

from __future__ import annotations

from collections.abc import Callable
from contextlib import AbstractContextManager
from pathlib import Path

from PyQt5.QtCore import QObject, QSettings, Qt
from PyQt5.QtWidgets import QDockWidget, QFileDialog, QMainWindow, QMenu

from asprilo.errors import InputError
from asprilo.model import Cell, Instance, Robot

from ..panels.commands import Table, make_actions, submenu
from ..panels.dialogs import SizeDialog, StockDialog, confirm_discard
from ..panels.docks import Panels
from ..panels.files import remember_folder, start_folder
from ..scene.stage import Stage
from ..state import edits, order_edits
from ..state.document import INSTANCE, PLAN, Change
from ..state.drafts import DraftOrders
from ..state.edits import NAMES, Edit, EditRefused
from ..state.loading import Scenario
from ..state.viewer import ViewerState
from .edit_mouse import MouseEditing
from .order_editor import OrderEditor
from .palette import OBJECT_TOOLS, EditPalette

INSTANCE_FILTER = "ASP facts (*.lp);;All files (*)"
PLAN_FILTER = "ASP facts (*.lp);;All files (*)"
DEFAULT_SIZE = (10, 6)

EDIT_ACTIONS: Table = {
    "new": ("&New instance…", ("Ctrl+N",)),
    "save": ("&Save instance", ("Ctrl+S",)),
    "save_as": ("Save instance &as…", ("Ctrl+Shift+S",)),
    "save_template": ("Save as &template (for gen -T)…", ()),
    "save_plan": ("Save &plan as…", ("Ctrl+Alt+S",)),
    "resize": ("&Resize grid…", ("Ctrl+Shift+R",)),
    "undo": ("&Undo", ("Ctrl+Z",)),
    "redo": ("&Redo", ("Ctrl+Shift+Z", "Ctrl+Y")),
}
_SCENARIO_COMMANDS = ("save", "save_as", "save_template", "save_plan")


class Editor(QObject):
    """Edits the state's document; refuses edits the rules forbid, saying why."""

    def __init__(self, state: ViewerState, stage: Stage, window: QMainWindow, settings: QSettings):
        super().__init__(window)
        self.state, self.stage, self.window, self.settings = state, stage, window, settings
        self.document = state.document
        self.view = stage.view
        self.last_message: str | None = None  # the last refusal (tests and status bar)
        self.palette = EditPalette(window)
        self.palette.tool_changed.connect(self._tool_changed)
        self.document_orders = _DocumentOrders(self)
        self.drafts: DraftOrders | None = None  # orders written during an online session
        self.orders = OrderEditor(self.document_orders)
        self.orders.send_clicked.connect(self.send_drafts)
        self.orders.discard_clicked.connect(self.discard_drafts)
        self.commands = make_actions(window, EDIT_ACTIONS, {
            "new": self.ask_new, "save": self.save, "save_as": self.ask_save_as,
            "save_template": self.ask_save_template, "save_plan": self.ask_save_plan, "resize": self.ask_resize,
            "undo": self.document.history.undo, "redo": self.document.history.redo})
        self.mouse = MouseEditing(self, self)
        self.document.history.changed.connect(self._show_locks)
        state.shown.connect(lambda _keep: self._follow())
        state.track_changed.connect(self._changed)
        state.locks_changed.connect(self._show_locks)
        self._follow()

    def install(self, menus: dict[str, QMenu], panels: Panels) -> QDockWidget:
        """Fill the Edit menu, put the palette on the left and the order editor beside the inventory."""
        edit = menus["edit"]
        edit.addAction(self.commands["undo"])
        edit.addAction(self.commands["redo"])
        edit.addSeparator()
        tools = submenu(edit, "Edit &tool")
        for action in self.palette.group.actions():
            tools.addAction(action)
        edit.addAction(self.commands["resize"])
        self.window.addToolBar(Qt.LeftToolBarArea, self.palette)
        dock = panels.add_dock("order_editor", "Order editor", self.orders, panels.docks["inventory"])
        edit.addAction(dock.toggleViewAction())
        return dock

    # --- following the state ------------------------------------------------------------------

    def _follow(self) -> None:
        """Another scenario is shown (or none): edit its instance from now on."""
        for name in _SCENARIO_COMMANDS:
            self.commands[name].setEnabled(self.document.scenario is not None)
        self._show_locks()
        self._refresh_orders()

    def _changed(self, change: Change) -> None:
        if self.drafts is not None:
            self.drafts.sync()  # the session's world grew
        self._refresh_orders()
        if change.edit is not None:
            self.state.say(change.edit.text, 4000)

    def _show_locks(self) -> None:
        """Enable what may be edited now."""
        history = self.document.history
        editable = self.state.layout_lock() is None and self.document.scenario is not None
        live = self._follow_session()
        self.palette.setEnabled(editable)
        self.commands["resize"].setEnabled(editable)
        self.orders.setEnabled(editable or (live and self.state.order_lock() is None))
        self.commands["undo"].setEnabled(editable and history.can_undo)
        self.commands["redo"].setEnabled(editable and history.can_redo)
        self.commands["undo"].setStatusTip(f"Undo {history.undo_text}" if history.can_undo else "")
        self.commands["redo"].setStatusTip(f"Redo {history.redo_text}" if history.can_redo else "")

    def _refresh_orders(self) -> None:
        track = self.state.track
        self.orders.refresh(track.violations if track is not None and self.drafts is None else [])

    # --- orders during an online session -----------------------------------------------------------

    def _follow_session(self) -> bool:
        """Orders written during a session are drafts until sent; whether one runs."""
        live = self.state.session.running and self.document.scenario is not None
        if live and (self.drafts is None or self.drafts.world is not self.document.instance):
            self.drafts = DraftOrders(self.document.instance, self.refuse)
            self.drafts.changed.connect(self.orders.refresh)
            self.orders.set_book(self.drafts, live=True)
        elif not live and self.drafts is not None:
            self.drafts = None
            self.orders.set_book(self.document_orders, live=False)
            self._refresh_orders()
        return live

    def send_drafts(self) -> bool:
        """Send the orders written during the session to the solver."""
        if self.drafts is None:
            return False
        problems = self.drafts.problems()
        if not self.drafts.drafts or problems:
            self.refuse(problems[0] if problems else "no orders to send: add one first")
            return False
        count = len(self.drafts.drafts)
        self.state.session.send(self.drafts.take())
        self.state.say(f"sent {count} order{'s' if count != 1 else ''} to the solver", 8000)
        return True

    def discard_drafts(self) -> None:
        if self.drafts is not None:
            self.drafts.discard()

    def _tool_changed(self, tool: str) -> None:
        self.mouse.tool_changed(tool)
        self.state.say(self.palette.group.checkedAction().statusTip(), 4000)

    # --- edits -------------------------------------------------------------------------------

    def perform(self, make: Callable[[], Edit]) -> bool:
        """Make an edit of the instance and put it in the history, or say why not."""
        if self.document.scenario is None:
            return False
        locked = self.state.layout_lock()
        if locked is not None:
            self.refuse(locked)
            return False
        try:
            edit = make()
        except EditRefused as refusal:
            self.refuse(str(refusal))
            return False
        self.last_message = None
        return self.document.perform(edit)

    def refuse(self, reason: str) -> None:
        """Say why an edit was not made (the status bar; a tooltip at the mouse for mouse edits)."""
        self.last_message = reason
        self.state.say(f"Not done: {reason}", 8000)

    def add(self, kind: str, cell: Cell) -> bool:
        return self.perform(lambda: edits.add_object(self.document.instance, kind, cell))

    def remove(self, kind: str, ident: int) -> bool:
        return self.perform(lambda: edits.remove_object(self.document.instance, kind, ident))

    def move(self, kind: str, ident: int, cell: Cell) -> bool:
        return self.perform(lambda: edits.move_object(self.document.instance, kind, ident, cell))

    def set_floor(self, cell: Cell, kind: str) -> bool:
        return self.perform(lambda: edits.set_floor(self.document.instance, cell, kind))

    def set_carries(self, robot: int, shelf: int | None) -> bool:
        return self.perform(lambda: edits.set_carries(self.document.instance, robot, shelf))

    def set_stock(self, shelf: int, stock: dict[int, int | None]) -> bool:
        return self.perform(lambda: order_edits.set_stock(self.document.instance, shelf, stock))

    def resize(self, width: int, height: int) -> bool:
        done = self.perform(lambda: edits.resize(self.document.instance, width, height))
        if done:
            self.view.fit()
        return done

    def replace(self, instance: Instance, text: str) -> bool:
        """Replace the whole instance (e.g. by the generator's result) as one undoable edit."""
        return self.perform(lambda: edits.replace_all(self.document.instance, instance, text))

    def new_instance(self, width: int, height: int) -> None:
        """Start a new instance: a full grid of storage nodes, nothing on it."""
        self.document.open(Scenario(edits.grid(width, height)))

    # --- the right-click menu -------------------------------------------------------------------------

    def context_menu(self, cell: Cell) -> QMenu:
        """What can be done on ``cell``: add objects, change the floor, edit what stands there."""
        instance = self.document.instance
        menu = QMenu(self.view)
        menu.setAttribute(Qt.WA_DeleteOnClose)
        floor = edits.floor_kind(instance, cell)
        menu.addAction(f"Cell {edits.cell_text(cell)}: {_FLOOR_WORDS[floor]}").setEnabled(False)
        here = edits.objects_at(instance, cell)
        for kind, ident in here:
            menu.addSeparator()
            if kind == "robot":
                self._robot_entries(menu, instance.robots[ident], here)
            if kind == "shelf":
                menu.addAction(f"Products on shelf {ident}…", lambda i=ident: self.ask_stock(i))
            menu.addAction(f"Remove {NAMES[kind]} {ident}", lambda k=kind, i=ident: self.remove(k, i))
        menu.addSeparator()
        for kind in OBJECT_TOOLS:
            menu.addAction(f"Add {NAMES[kind]} here", lambda k=kind: self.add(k, cell))
        menu.addSeparator()
        for kind, text in (("storage", "Make storage node"), ("highway", "Make highway"),
                           ("missing", "Remove node (wall)")):
            if kind != floor:
                label = "Restore node" if floor == "missing" and kind == "storage" else text
                menu.addAction(label, lambda k=kind: self.set_floor(cell, k))
        return menu

    def _robot_entries(self, menu: QMenu, robot: Robot, here: list[tuple[str, int]]) -> None:
        if robot.carries is not None:
            menu.addAction(f"Robot {robot.id} puts shelf {robot.carries} down",
                           lambda: self.set_carries(robot.id, None))
        for kind, shelf in here:
            if kind == "shelf" and shelf != robot.carries:
                menu.addAction(f"Robot {robot.id} starts carrying shelf {shelf}",
                               lambda s=shelf: self.set_carries(robot.id, s))

    # --- dialogs and files -------------------------------------------------------------------------

    def ask_new(self) -> None:
        if not confirm_discard(self.window, self.document):
            return
        width, height = self.document.instance.size if self.document.scenario else DEFAULT_SIZE
        dialog = SizeDialog("New instance", width or DEFAULT_SIZE[0], height or DEFAULT_SIZE[1], parent=self.window)
        if dialog.exec_():
            self.new_instance(*dialog.values())

    def ask_resize(self) -> None:
        width, height = self.document.instance.size
        dialog = SizeDialog("Resize grid", width, height,
                            "New cells become storage nodes; what lies beyond a smaller grid is removed "
                            "(undo brings it back).", self.window)
        if dialog.exec_():
            self.resize(*dialog.values())

    def ask_stock(self, shelf: int) -> None:
        dialog = StockDialog(shelf, self.document.instance.shelf_stock().get(shelf, {}), self.window)
        if dialog.exec_():
            self.set_stock(shelf, dialog.stock())

    def save(self) -> bool:
        if self.document.path is None:
            return self.ask_save_as()
        return self.save_as(self.document.path)

    def ask_save_as(self) -> bool:
        path = self._ask_path("Save instance", self.document.instance.file_name(1), INSTANCE_FILTER)
        return bool(path) and self.save_as(path)

    def ask_save_template(self) -> bool:
        path = self._ask_path("Save as template for gen -T", "template.lp", INSTANCE_FILTER)
        return bool(path) and self.save_template(path)

    def ask_save_plan(self) -> bool:
        path = self._ask_path("Save plan", "plan.lp", PLAN_FILTER)
        return bool(path) and self.save_plan(path)

    def save_unsaved(self) -> bool:
        """Save the parts with unsaved edits as File > Save instance and File > Save plan as…
        do; whether all of them were saved (not when a file dialog was cancelled)."""
        if self.document.unsaved(INSTANCE) and not self.save():
            return False
        return not self.document.unsaved(PLAN) or self.ask_save_plan()

    def _ask_path(self, title: str, name: str, filters: str) -> str:
        folder = Path(start_folder(self.settings))
        path, _ = QFileDialog.getSaveFileName(self.window, title, str(folder / name), filters)
        if path:
            remember_folder(self.settings, path)
        return path

    def save_as(self, path: str | Path) -> bool:
        """Save the instance's initial state in the canonical format; the window now shows that file."""
        return self._write(lambda: self.document.save(path), path, "the instance", f"saved {path}")

    def save_template(self, path: str | Path) -> bool:
        return self._write(lambda: self.document.save_template(path), path, "the template",
                           f"saved template {path} (for gen -T)")

    def save_plan(self, path: str | Path) -> bool:
        """Save the plan shown (one ``occurs/3`` fact per line)."""
        return self._write(lambda: self.document.save_plan(path), path, "the plan", f"saved plan {path}")

    def _write(self, write: Callable[[], None], path: str | Path, what: str, done: str) -> bool:
        try:
            write()
        except InputError as error:  # not a regular file, also an input, a failed write
            self.state.report_error(str(error))
            return False
        except OSError as error:
            self.state.report_error(f"{path}: cannot write {what} ({error.strerror or error})")
            return False
        self.state.say(done)
        return True


class _DocumentOrders:
    """The document's orders for the order editor: edits go through the editor (locks,
    refusals) into the history."""

    def __init__(self, editor: Editor):
        self.editor = editor

    @property
    def instance(self) -> Instance:
        return self.editor.document.instance

    def perform(self, make: Callable[[], Edit]) -> bool:
        return self.editor.perform(make)

    def group(self, text: str) -> AbstractContextManager:
        return self.editor.document.history.group(text)

    def shows(self, order: int) -> bool:
        return True


_FLOOR_WORDS = {"storage": "storage node", "highway": "highway", "missing": "no node (wall)"}
