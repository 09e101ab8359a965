"""The atoms pane: the instance's facts and the plan's ``occurs/3`` facts as text, following
the map, and the plan editable there.

Selecting an object (on the map, in a panel) marks its facts and its actions; the actions of
the step shown are marked as the plan plays.  Clicking a fact selects its object; clicking
an action goes to its step.  Edits of the plan's text are read back a moment after the last
keystroke: if the text is a plan of the instance's robots it replaces the plan shown (one
undoable step: Ctrl+Z takes it back), the animation and the violations follow; otherwise the
line at fault is marked and the plan shown stays.  What ``check`` would warn about (an atom
that is no plan atom, ``occur/3`` or ``occurs/2``; an action no domain knows, ``mvoe``) is
said below the text with its did-you-mean, the lines marked, and the plan read all the same.
What the reader warned about reading the files shown (a plan file with ``occur/3`` in it,
opened, reloaded or saved in an editor) is said there too, naming the file and its line, until
another file is read or the plan is edited here (the pane's own warnings then) or replaced.
"""

from __future__ import annotations

from html import escape

from PyQt5.QtCore import QEvent, QSize, Qt, QTimer
from PyQt5.QtGui import QColor, QFont, QKeySequence, QTextCursor, QTextFormat
from PyQt5.QtWidgets import QFrame, QLabel, QPlainTextEdit, QScrollArea, QSplitter, QTextEdit, QVBoxLayout, QWidget

from asprilo.errors import InputError
from asprilo.model import Plan
from asprilo.sources import Source

from ..state.atoms import AtomLine, Note, about, instance_lines, lines_about, plan_lines, read_plan_text
from ..state.document import Change
from ..state.viewer import ViewerState
from .screen import own_scroll_bar, room
from .tables import CURRENT, PROBLEM

#: milliseconds after the last keystroke before an edited plan is read
READ_DELAY_MS = 400
SUBJECT = QColor("#ffec99")  # the facts of the object selected
WARNED = QColor("#ffe8cc")  # lines the reader warned about
#: the lines of text the words below the plan show before they scroll (fewer where the
#: window would not fit its screen)
NOTE_LINES = 16


class _PlanText(QPlainTextEdit):
    """The plan's text: Ctrl+Z and Ctrl+Shift+Z go to the window's undo (the document's
    history), after what was typed so far has been read."""

    def __init__(self, pane: AtomsPane):
        super().__init__()
        self.pane = pane
        self.setUndoRedoEnabled(False)

    def event(self, event) -> bool:
        if event.type() == QEvent.ShortcutOverride and (event.matches(QKeySequence.Undo)
                                                        or event.matches(QKeySequence.Redo)):
            self.pane.read_now()
            event.ignore()  # not the text's own undo: the window's shortcut runs
            return True
        return super().event(event)


class _Note(QScrollArea):
    """The words below the plan (the verdict, the reader's warnings), wrapped, as tall as all
    their lines (at most ``NOTE_LINES``) where the window can grow that much on its screen
    (the dock takes the room from the panels above it), else as tall as it can and scrolled
    (a QLabel that wraps asks for too little height in a layout: the last warnings were cut,
    and a fixed height would make the window taller than a small screen)."""

    def __init__(self, parent: QWidget):
        super().__init__(parent)
        self.label = QLabel(self)
        self.label.setWordWrap(True)
        self.label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)  # a warning can be copied
        self.setWidget(self.label)
        self.setWidgetResizable(True)
        self.setFrameShape(QFrame.NoFrame)
        self.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        self.bar = own_scroll_bar(self)
        self._wanted = 0  # the height of all its lines, at most NOTE_LINES
        self.setFixedHeight(0)  # no words yet
        self._settling = QTimer(self)  # the least height is found once the layouts settled
        self._settling.setSingleShot(True)
        self._settling.setInterval(0)
        self._settling.timeout.connect(self._settle)

    def text(self) -> str:
        return self.label.text()

    def setText(self, text: str) -> None:  # noqa: N802 - as QLabel's
        self.label.setText(text)
        self._fit()

    def sizeHint(self) -> QSize:  # noqa: N802 - Qt's name
        return QSize(super().sizeHint().width(), self._wanted)

    def minimumSizeHint(self) -> QSize:  # noqa: N802 - Qt's name
        return QSize(0, 0)  # its least height is set (_settle)

    def resizeEvent(self, event) -> None:  # noqa: N802 - Qt's name
        super().resizeEvent(event)
        self._fit()

    def _fit(self) -> None:
        width = self.width() - (self.bar.width() if self.bar.isVisible() else 0)
        needed = self.label.heightForWidth(max(1, width)) if self.label.text() else 0
        wanted = min(max(needed, 0), self.label.fontMetrics().lineSpacing() * NOTE_LINES)
        if wanted != self._wanted:
            self._wanted = wanted
            self.setMinimumHeight(min(self.minimumHeight(), wanted))
            self.setMaximumHeight(wanted)
            self.updateGeometry()
            if not self._settling.isActive():
                self._settling.start()

    def _settle(self) -> None:
        """Ask for the height wanted, or what the window's screen leaves (the window's least
        height, its layouts settled, without this one's)."""
        least = self._wanted
        window = self.window()
        if window is not None and window is not self and least:
            self.setMinimumHeight(0)
            widget = self.parentWidget()
            while widget is not None:  # the least sizes up to the window, without this one's
                layout = widget.layout()
                if layout is not None:
                    layout.invalidate()
                widget = widget.parentWidget()
            least = max(0, min(least, room(self).height() - window.minimumSizeHint().height()))
        self.setMinimumHeight(least)


def _text_box(read_only: bool, editor: QPlainTextEdit | None = None) -> QPlainTextEdit:
    box = editor or QPlainTextEdit()
    own_scroll_bar(box)  # _scroll_to asks for it
    box.setReadOnly(read_only)
    box.setLineWrapMode(QPlainTextEdit.NoWrap)
    font = QFont("DejaVu Sans Mono")
    font.setStyleHint(QFont.Monospace)
    font.setPointSize(9)
    box.setFont(font)
    return box


class AtomsPane(QWidget):
    """Instance facts above, plan facts below, each with a line saying what it shows."""

    def __init__(self, state: ViewerState, parent: QWidget | None = None):
        super().__init__(parent)
        self.state = state
        self.instance_box = _text_box(True)
        self.plan_box = _text_box(False, _PlanText(self))
        self.plan_note = _Note(self)
        self.lines: dict[str, list[AtomLine]] = {"instance": [], "plan": []}
        self._stale = {"instance": True, "plan": True}
        self.shown = False  # the pane can be seen (its dock is open and its tab chosen)
        self._by_step: dict[int, list[int]] = {}  # step -> numbers of the plan's lines
        self._own_edit = False  # the plan shown came from this pane's text
        self._problem_marks: list = []  # the line the reader refused, or those it warned about
        self._notes: list[Note] = []  # what the reader said of the plan text read last
        self._edited = False  # the plan's text was read here since it was last filled in
        self._file_notes: list[str] = []  # what the reader said of the files shown
        self._file_plan: Plan | None = None  # the plan those files hold: the notes go with it
        self._file_sources: list[Source] = []
        self._filling = False
        self._timer = QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(READ_DELAY_MS)
        self._timer.timeout.connect(self._read)
        self._layout()
        self.plan_box.textChanged.connect(self._typed)
        self.plan_box.cursorPositionChanged.connect(self._plan_clicked)
        self.instance_box.cursorPositionChanged.connect(self._instance_clicked)
        state.shown.connect(lambda _keep: self._stale_all())
        state.track_changed.connect(self._changed)
        state.step_changed.connect(lambda _step: self._mark())
        state.selection.changed.connect(self._follow_selection)
        state.locks_changed.connect(self._show_locks)
        state.document.saved.connect(self._saved)

    def _layout(self) -> None:
        splitter = QSplitter(Qt.Vertical, self)
        for title, box, note in (("Instance facts (read only)", self.instance_box, None),
                                 ("Plan: occurs/3 facts, edit them here", self.plan_box, self.plan_note)):
            part = QWidget(splitter)
            layout = QVBoxLayout(part)
            layout.setContentsMargins(2, 2, 2, 2)
            layout.setSpacing(2)
            layout.addWidget(QLabel(f"<b>{title}</b>", part))
            layout.addWidget(box)
            if note is not None:
                layout.addWidget(note)
            splitter.addWidget(part)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(splitter)

    # --- following the state ------------------------------------------------------------------

    def _stale_all(self) -> None:
        scenario = self.state.document.scenario
        self._file_notes = list(scenario.read_warnings) if scenario is not None else []
        self._file_plan = scenario.plan if scenario is not None else None
        self._file_sources = scenario.instance_sources + scenario.plan_sources if scenario is not None else []
        self._stale = {"instance": True, "plan": True}
        self._own_edit = False
        self._show_locks()
        self.refresh()

    def _changed(self, change: Change) -> None:
        if change.edit is not None:
            self._stale["instance"] = True
        if change.plan and not self._own_edit:
            self._stale["plan"] = True
        self._own_edit = False
        self.refresh()

    def set_shown(self, shown: bool) -> None:
        """The pane's dock was opened or closed, its tab chosen or left."""
        self.shown = shown
        self.refresh()

    def refresh(self) -> None:
        """Fill in what went out of date (only while the pane can be seen: big plans take a while)."""
        if not self.shown:
            return
        document = self.state.document
        if self._stale["instance"]:
            self._fill("instance", self.instance_box, instance_lines(document.instance))
        if self._stale["plan"]:
            self._timer.stop()
            self._fill("plan", self.plan_box, plan_lines(document.plan))
        self._show_note()
        self._follow_selection()

    def _fill(self, part: str, box: QPlainTextEdit, lines: list[AtomLine]) -> None:
        self._filling = True
        try:
            box.setPlainText("\n".join(line.text for line in lines))
        finally:
            self._filling = False
        self._stale[part] = False
        self._set_lines(part, lines)
        if part == "plan":
            self._problem_marks = []
            self._notes = []
            self._edited = False

    def _set_lines(self, part: str, lines: list[AtomLine]) -> None:
        self.lines[part] = lines
        if part == "plan":
            self._by_step = {}
            for number, line in enumerate(lines):
                if line.step is not None:
                    self._by_step.setdefault(line.step, []).append(number)

    def _show_locks(self) -> None:
        self.plan_box.setReadOnly(self.state.layout_lock() is not None or self.state.document.scenario is None)

    def _show_note(self, problem: str | None = None) -> None:
        track = self.state.track
        if problem is not None:
            self.plan_note.setText(f"<span style='color:#e03131'>{escape(problem)} (the plan shown stays)</span>")
        elif track is None:
            self.plan_note.setText("")
        else:
            count = len(track.violations)
            verdict = f"{count} violation{'s' if count != 1 else ''}" if count else "no violation"
            warned = "".join(f"<br><span style='color:#d9480f'>warning: {escape(text)}</span>"
                             for text in self.notes)
            actions = f"{len(track.plan)} action{'s' * (len(track.plan) != 1)}"
            self.plan_note.setText(f"{actions}, horizon {track.horizon}: {verdict}{warned}")

    @property
    def notes(self) -> list[str]:
        """The warnings said below the plan: the reader's on the text edited here, or, while the
        plan shown is the one read from the files, on those files (``FILE:LINE: ...``)."""
        if self._edited or self.state.document.plan is not self._file_plan:
            return [note.text for note in self._notes]
        return self._file_notes

    def _saved(self) -> None:
        """A file written: what was said of the text read from it before no longer holds."""
        scenario = self.state.document.scenario
        now = scenario.instance_sources + scenario.plan_sources if scenario is not None else []
        gone = [source.name for source in self._file_sources if not any(source is s for s in now)]
        self._file_notes = [text for text in self._file_notes if not any(text.startswith(f"{name}:")
                                                                         for name in gone)]
        if self.shown:
            self._show_note()

    # --- marks: the object selected, the step shown ----------------------------------------------

    def _follow_selection(self) -> None:
        focus = self.state.selection.focus
        numbers = lines_about(self.lines["instance"], focus) if focus is not None else []
        if numbers and self.shown and not self.instance_box.hasFocus():
            _scroll_to(self.instance_box, numbers[0])
        self._mark()

    def _mark(self) -> None:
        if not self.shown:
            return
        focus, step = self.state.selection.focus, self.state.step
        subject = lines_about(self.lines["instance"], focus) if focus else []
        self.instance_box.setExtraSelections(_marks(self.instance_box, subject, SUBJECT))
        plan = self.lines["plan"]
        now = self._by_step.get(step, [])
        mine = [n for n in lines_about(plan, focus) if plan[n].step != step] if focus else []
        self.plan_box.setExtraSelections(_marks(self.plan_box, now, CURRENT) + _marks(self.plan_box, mine, SUBJECT)
                                         + self._problem_marks)
        if now and not self.plan_box.hasFocus() and self.state.document.scenario is not None:
            _scroll_to(self.plan_box, now[0])

    # --- what the user does ----------------------------------------------------------------------

    def _typed(self) -> None:
        if not self._filling:
            self._timer.start()

    def read_now(self) -> None:
        """Read the edited plan now, if it was edited since it was last read."""
        if self._timer.isActive():
            self._timer.stop()
            self._read()

    def _read(self) -> None:
        """Show the plan the text holds, or say what is wrong with it."""
        text = self.plan_box.toPlainText()
        self._edited = True
        self._set_lines("plan", [about(line) for line in text.split("\n")])
        scenario = self.state.document.scenario
        try:
            plan, self._notes = read_plan_text(text, self.state.document.instance,
                                               scenario.domain if scenario is not None else None)
        except InputError as error:
            self._notes = []
            self._problem_marks = _marks(self.plan_box, [error.line - 1] if error.line else [], PROBLEM)
            self._show_note(str(error))
            self._mark()
            return
        self._problem_marks = _marks(self.plan_box, [note.line - 1 for note in self._notes if note.line], WARNED)
        self._own_edit = True
        if not self.state.document.replace_plan(plan, "edit the plan's atoms"):
            self._own_edit = False
            self._show_note()
            self._mark()

    def _plan_clicked(self) -> None:
        if self._filling or not self.plan_box.hasFocus():
            return
        line = about(self.plan_box.textCursor().block().text())
        if line.step is not None and line.step != self.state.step:
            self.state.seek(line.step)

    def _instance_clicked(self) -> None:
        if self._filling or not self.instance_box.hasFocus():
            return
        line = about(self.instance_box.textCursor().block().text())
        objects = sorted(subject for subject in line.subjects if subject[0] in ("robot", "shelf", "station",
                                                                                   "destination"))
        if objects:
            robots = [ident for kind, ident in objects if kind == "robot"]
            self.state.selection.set(robots, ("robot", robots[0]) if robots else objects[0])


def _marks(box: QPlainTextEdit, numbers: list[int], colour: QColor) -> list:
    """Whole-line marks on the lines ``numbers`` of ``box``."""
    marks = []
    document = box.document()
    for number in numbers:
        block = document.findBlockByNumber(number)
        if not block.isValid():
            continue
        mark = QTextEdit.ExtraSelection()
        mark.format.setBackground(colour)
        mark.format.setProperty(QTextFormat.FullWidthSelection, True)
        mark.cursor = QTextCursor(block)
        marks.append(mark)
    return marks


def _scroll_to(box: QPlainTextEdit, number: int) -> None:
    """Scroll so that line ``number`` shows near the top (the text cursor stays where it is)."""
    box.verticalScrollBar().setValue(max(0, number - 3))

