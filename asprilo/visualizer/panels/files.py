"""Opening files in the viewer: File > Open, Open plan, Reload, Recent files, dropped files.

A file is read completely before anything shown changes: a file that cannot be read
(missing, not UTF-8, a syntax error, a fact of the wrong shape, ...) is reported in a
dialog, and the warehouse shown stays, unsaved edits included.  Unsaved edits are given
up only when the user agrees, after the new files were read.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable
from pathlib import Path

from PyQt5.QtCore import QObject, QSettings, Qt
from PyQt5.QtWidgets import QApplication, QFileDialog, QMenu, QWidget

from asprilo.errors import InputError

from ..state import loading
from ..state.loading import Scenario
from ..state.viewer import ViewerState
from .commands import menu_entry
from .dialogs import confirm_discard

RECENT_LIMIT = 10
FILE_FILTER = "ASP facts and clingo output (*.lp *.txt *.plan *.out);;All files (*)"


def start_folder(settings: QSettings) -> str:
    """The folder file dialogs open in: the last one used."""
    return str(settings.value("last_folder", str(Path.cwd())))


def remember_folder(settings: QSettings, path: str) -> None:
    settings.setValue("last_folder", str(Path(path).parent))


def read_problem(error: Exception, names: list[str]) -> str:
    """What to say when reading failed: the reader's ``FILE:LINE: …``, or what broke."""
    if isinstance(error, InputError):
        return str(error)
    return f"{', '.join(names)}: cannot be read ({type(error).__name__}: {error})"


def _names(inputs: Iterable) -> list[str]:
    return [getattr(item, "name", None) or str(item) for item in inputs]


class FileActions(QObject):
    """Reads scenarios from files and hands them to the state's document."""

    def __init__(self, state: ViewerState, settings: QSettings, parent: QWidget):
        super().__init__(parent)
        self.state, self.settings, self.parent_widget = state, settings, parent
        self.recent_menu: QMenu | None = None

    # --- opening ----------------------------------------------------------------------------

    def open_files(self, instance: Iterable, plans: Iterable = ()) -> bool:
        """Show an instance (files, ``-`` or sources) and its plan."""
        instance, plans = list(instance), list(plans)
        variants = self.state.document.variants  # the window's rule variants: they must fit its domain
        return self._load(lambda: loading.load_scenario(instance, plans, variants=variants), _names(instance + plans))

    def open_plan_files(self, plans: Iterable) -> bool:
        """Show a plan on the instance already open."""
        scenario = self.state.document.scenario
        if scenario is None:
            self.state.report_error("Open an instance first: a plan needs its warehouse.")
            return False
        plans = list(plans)
        return self._load(lambda: loading.add_plan(scenario, plans), _names(plans))

    def open_dropped(self, paths: list[str]) -> bool:
        """Files dropped on the window: instances (and plans) or plans for the open instance."""
        try:
            instances, plans = loading.sort_files(paths)
        except Exception as error:  # whatever breaks, the window stays
            self.state.report_error(read_problem(error, paths))
            return False
        if instances:
            return self.open_files(instances, plans)
        return self.open_plan_files(plans)

    def reload(self) -> bool:
        scenario = self.state.document.scenario
        if scenario is None:
            return False
        instances, plans = scenario.files
        return self._load(lambda: loading.reload(scenario), instances + plans, keep_time=True)

    def _load(self, read: Callable[[], Scenario], names: list[str], keep_time: bool = False) -> bool:
        QApplication.setOverrideCursor(Qt.WaitCursor)
        try:
            scenario = read()
        except Exception as error:  # whatever breaks, the window stays
            self.state.report_error(read_problem(error, names))
            return False
        finally:
            QApplication.restoreOverrideCursor()
        if not confirm_discard(self.parent_widget, self.state.document):
            return False
        self.state.document.open(scenario, keep_time)
        self.remember(scenario)
        return True

    # --- dialogs --------------------------------------------------------------------------------

    def ask_open(self) -> None:
        paths, _ = QFileDialog.getOpenFileNames(self.parent_widget, "Open instance (and plan) files",
                                                start_folder(self.settings), FILE_FILTER)
        if paths:
            remember_folder(self.settings, paths[0])
            self.open_dropped(paths)

    def ask_open_plan(self) -> None:
        paths, _ = QFileDialog.getOpenFileNames(self.parent_widget, "Open plan files", start_folder(self.settings),
                                                FILE_FILTER)
        if paths:
            remember_folder(self.settings, paths[0])
            self.open_plan_files(paths)

    # --- recent files ---------------------------------------------------------------------------

    def recent(self) -> list[dict]:
        """Recently opened files, newest first: ``{"instance": [paths], "plans": [paths]}``."""
        try:
            entries = json.loads(str(self.settings.value("recent", "[]")))
        except ValueError:
            return []
        if not isinstance(entries, list):
            return []
        return [e for e in entries if isinstance(e, dict) and {"instance", "plans"} <= set(e)]

    def remember(self, scenario: Scenario) -> None:
        """Put the scenario's files first in the recent files (standard input is not kept)."""
        instances, plans = scenario.files
        if not instances:
            return
        entry = {"instance": [str(Path(p).resolve()) for p in instances],
                 "plans": [str(Path(p).resolve()) for p in plans]}
        entries = [entry] + [e for e in self.recent() if e != entry]
        self.settings.setValue("recent", json.dumps(entries[:RECENT_LIMIT]))

    def install_recent(self, menu: QMenu) -> None:
        self.recent_menu = menu
        menu.aboutToShow.connect(self.fill_recent)

    def fill_recent(self) -> None:
        menu = self.recent_menu
        menu.clear()
        for entry in self.recent():
            names = [Path(p).name for p in entry["instance"] + entry["plans"]]
            action = menu_entry(menu, " + ".join(names))
            action.setToolTip("\n".join(entry["instance"] + entry["plans"]))
            action.triggered.connect(lambda _c=False, e=entry: self.open_files(e["instance"], e["plans"]))
        if not menu.actions():
            menu_entry(menu, "(none yet)").setEnabled(False)
