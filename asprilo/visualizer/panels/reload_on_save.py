"""File > Reload on save: the instance and plan files shown are watched, and read again when
one is saved -- as File > Reload reads them (the step shown kept).

A save is a new stamp (modification time, size, inode: editors that write a new file and
rename it over the old one too) whose text differs from the text shown, looked at a moment
after the last event (an editor may write in two steps); the viewer's own Save changes
nothing.  Unsaved edits are never dropped silently: while there are any (or a job or an
online session drives the warehouse), a banner says which file changed on disk and offers
Reload, which asks as File > Reload does.  A file saved that cannot be read (a syntax error
half-way through an edit) is said in the banner too, and the warehouse shown stays until a
later save reads.  The setting (on by default) lives in Qt's settings.
"""

from __future__ import annotations

import os
from html import escape
from pathlib import Path

from PyQt5.QtCore import QFileSystemWatcher, QObject, QSettings, QTimer
from PyQt5.QtWidgets import QAction, QFrame, QHBoxLayout, QLabel, QPushButton, QWidget

from ..state import loading
from ..state.viewer import WARNINGS_SAID_MS, ViewerState
from .files import FileActions, read_problem

#: the setting, and how long (milliseconds) the files must stand still before they are read
SETTING = "files/reload_on_save"
SETTLE_MS = 300

_STYLE = "QFrame#disk_banner { background: #fff3bf; border-bottom: 1px solid #f59f00; }"

Stamp = tuple[int, int, int, int]


def stamp(path: str) -> Stamp | None:
    """What says that a file was saved (``None``: no file there now)."""
    try:
        status = os.stat(path)
    except (OSError, ValueError):
        return None
    return status.st_mtime_ns, status.st_size, status.st_ino, status.st_dev


def disk_text(path: str) -> str | None:
    """The file's text now (``None``: it cannot be read as UTF-8 text)."""
    try:
        if not Path(path).is_file():  # a FIFO would wait for a writer
            return None
        return Path(path).read_bytes().decode("utf-8")
    except (OSError, ValueError):
        return None


class DiskBanner(QFrame):
    """Above the map: a file shown changed on disk (Reload, Dismiss), or cannot be read."""

    def __init__(self, parent: QWidget | None = None):
        super().__init__(parent)
        self.setObjectName("disk_banner")
        self.setStyleSheet(_STYLE)
        self.text = QLabel(self)
        self.text.setWordWrap(True)
        self.reload = QPushButton("Reload", self)
        self.dismiss = QPushButton("Dismiss", self)
        self.dismiss.clicked.connect(self.hide)
        layout = QHBoxLayout(self)
        layout.setContentsMargins(8, 4, 8, 4)
        layout.addWidget(self.text, 1)
        layout.addWidget(self.reload)
        layout.addWidget(self.dismiss)
        self.kind: str | None = None  # what it says while shown: "changed" or "unreadable"
        self.hide()

    def changed(self, names: list[str], why: str) -> None:
        """``names`` changed on disk; ``why`` they were not read at once."""
        self.text.setText(f"<b>{escape(_listed(names))} changed on disk</b> ({escape(why)}).")
        self.kind = "changed"
        self.reload.show()
        self.show()

    def unreadable(self, problem: str) -> None:
        """A file saved cannot be read: the warehouse shown is from before."""
        self.text.setText(f"<b>Saved, but cannot be read:</b> {escape(problem)} — the warehouse shown is from "
                          "before; the next save is read again.")
        self.kind = "unreadable"
        self.reload.hide()
        self.show()


class ReloadOnSave(QObject):
    """Watches the files shown and reloads them when they are saved (see the module)."""

    def __init__(self, state: ViewerState, files: FileActions, settings: QSettings, parent: QWidget):
        super().__init__(parent)
        self.state, self.files, self.settings = state, files, settings
        self.watcher: QFileSystemWatcher | None = None  # made when there is a file to watch
        self.stamps: dict[str, Stamp | None] = {}
        self.texts: dict[str, str] = {}
        self.timer = QTimer(self)
        self.timer.setSingleShot(True)
        self.timer.setInterval(SETTLE_MS)
        self.timer.timeout.connect(self.look)
        self.banner = DiskBanner(parent)
        self.banner.reload.clicked.connect(self._reload)
        self.action = QAction("Reload on &save", parent)
        self.action.setCheckable(True)
        self.action.setChecked(settings.value(SETTING, True, type=bool))
        self.action.setToolTip("Read the instance and plan files again when they are saved (the step shown kept)")
        self.action.toggled.connect(self.set_enabled)
        state.document.opened.connect(lambda _keep: self.follow(fresh=True))
        state.document.saved.connect(self.follow)

    @property
    def enabled(self) -> bool:
        return self.action.isChecked()

    def set_enabled(self, enabled: bool) -> None:
        self.settings.setValue(SETTING, enabled)
        self.follow(fresh=True)
        if enabled:  # what was saved meanwhile is read now
            self.stamps = dict.fromkeys(self.stamps)
            self.look()

    # --- following the files shown -----------------------------------------------------------------

    def follow(self, fresh: bool = False) -> None:
        """Watch the files of the scenario shown; ``fresh``: a new scenario (its stamps taken
        now, the banner gone), otherwise those followed already keep theirs (a save not acted
        on stays one: the viewer's own Save only changed the text they are compared with)."""
        scenario = self.state.document.scenario
        paths: list[str] = []
        self.texts = {}
        if scenario is not None:
            instances, plans = scenario.files
            paths = list(dict.fromkeys(instances + plans))
            self.texts = {source.name: source.text for source in scenario.instance_sources + scenario.plan_sources}
        if fresh:
            self.banner.hide()
            self.stamps = {}
        self.stamps = {path: self.stamps[path] if path in self.stamps else stamp(path) for path in paths}
        self._watch()

    def _watch(self) -> None:
        """Give the watcher the files and their folders (a file renamed over is dropped from
        the watch: added again; a folder tells when a missing file comes back)."""
        wanted = set()
        if self.enabled:
            for path in self.stamps:
                wanted.add(path)
                wanted.add(str(Path(path).parent))
        if self.watcher is None:
            if not wanted:
                return
            self.watcher = QFileSystemWatcher(self)
            self.watcher.fileChanged.connect(self._touched)
            self.watcher.directoryChanged.connect(self._touched)
        watched = set(self.watcher.files()) | set(self.watcher.directories())
        if watched - wanted:
            self.watcher.removePaths(sorted(watched - wanted))
        missing = sorted(path for path in wanted - watched if os.path.exists(path))
        if missing:
            self.watcher.addPaths(missing)

    def _touched(self, _path: str) -> None:
        if self.enabled:
            self.timer.start()  # again: the files must stand still for a moment

    # --- a save ---------------------------------------------------------------------------------------

    def look(self) -> None:
        """Read the files again if one was saved with a text other than the one shown."""
        if not self.enabled or self.state.document.scenario is None:
            return
        self._watch()
        changed = []
        for path, before in self.stamps.items():
            now = stamp(path)
            if now != before:
                self.stamps[path] = now
                changed.append(path)
        saved = [path for path in changed if disk_text(path) != self.texts.get(path)]
        if saved:
            self._saved(saved)
        elif changed and self.banner.kind == "unreadable":  # saved back as it is shown
            self.banner.hide()

    def _saved(self, paths: list[str]) -> None:
        names = [Path(path).name for path in paths]
        why = self._held()
        if why is not None:
            self.banner.changed(names, why)
            return
        scenario = self.state.document.scenario
        if scenario is None:
            return
        try:
            fresh = loading.reload(scenario)
        except Exception as error:  # noqa: BLE001 - whatever breaks, the window stays
            self.banner.unreadable(read_problem(error, names))
            return
        self.state.document.open(fresh, keep_time=True)
        self.files.remember(fresh)
        said = loading.warnings_said(fresh)  # (said on opening too: this says both)
        self.state.say(f"{_listed(names)} saved: read again" + (f"; {said}" if said else ""),
                       WARNINGS_SAID_MS if said else 5000)

    def _reload(self) -> None:
        """The banner's Reload: File > Reload (which asks before unsaved edits go)."""
        self.files.reload()

    def _held(self) -> str | None:
        """Why the files saved are not read at once (``None``: they are)."""
        if self.state.document.modified:
            return "the edits shown are not saved: Reload drops them, after asking"
        if self.state.job is not None:
            return f"{self.state.job.lower()} is running"
        if self.state.session.running:
            return "an online session is running"
        return None


def _listed(names: list[str]) -> str:
    return ", ".join(dict.fromkeys(names))
