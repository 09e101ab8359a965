"""The presentation mode (View > Presentation mode, F11): the map fills the screen, the
panels, menus and bars are hidden, and a bar under the map tells the step shown in one
sentence, the plan's verdict and the checker rules behind the step's violations, in
letters a projector shows to the back row.

Every key of the window keeps working (Right and Left step, Space plays); F11 or Esc
brings the window back as it was.
"""

from __future__ import annotations

from PyQt5.QtCore import QByteArray, QObject, QRect, Qt, pyqtSignal
from PyQt5.QtGui import QFont
from PyQt5.QtWidgets import (
    QDockWidget,
    QFrame,
    QLabel,
    QMainWindow,
    QSizePolicy,
    QToolBar,
    QVBoxLayout,
    QWidget,
)

from asprilo.checker.rules import rule_line

from ..scene.view import WarehouseView
from ..state.narrate import narrate, verdict
from ..state.viewer import ViewerState

#: pixel sizes of the bar's letters: the sentence, the verdict, the rules
SENTENCE_PX, VERDICT_PX, RULE_PX = 26, 22, 17
#: the most checker rules the bar shows for one step
RULES_SHOWN = 2
_GOOD, _BAD, _NEUTRAL = "#2b8a3e", "#e03131", "#495057"


def _font(pixels: int, bold: bool = False, fixed: bool = False) -> QFont:
    font = QFont("DejaVu Sans Mono" if fixed else "DejaVu Sans")
    if fixed:
        font.setStyleHint(QFont.Monospace)
    font.setPixelSize(pixels)
    font.setBold(bold)
    return font


class NarrationBar(QFrame):
    """Under the map: the plan's verdict, the step in one sentence
    (:func:`~..state.narrate.narrate`), and the checker rule behind each kind of violation
    at that step."""

    def __init__(self, state: ViewerState, parent: QWidget | None = None):
        super().__init__(parent)
        self.state = state
        self.setObjectName("narration")
        self.setStyleSheet("#narration { background: white; border-top: 1px solid #ced4da; }")
        self.verdict = self._label(_font(VERDICT_PX, bold=True), wrap=True)
        self.sentence = self._label(_font(SENTENCE_PX), wrap=True)
        self.rules = self._label(_font(RULE_PX, fixed=True), wrap=True)
        self.rules.setStyleSheet(f"color: {_NEUTRAL};")
        layout = QVBoxLayout(self)
        layout.setContentsMargins(16, 6, 16, 10)
        layout.setSpacing(4)
        for label in (self.verdict, self.sentence, self.rules):
            layout.addWidget(label)
        self.setSizePolicy(QSizePolicy.Preferred, QSizePolicy.Maximum)
        self.hide()
        state.step_changed.connect(self._show_step)
        state.shown.connect(lambda _keep: self.refresh())
        state.track_changed.connect(lambda _change: self.refresh())

    def _label(self, font: QFont, wrap: bool) -> QLabel:
        label = QLabel(self)
        label.setFont(font)
        label.setTextFormat(Qt.TextFormat.PlainText)
        label.setWordWrap(wrap)
        return label

    def refresh(self) -> None:
        """Say the step shown now (only while the bar is shown: playing costs nothing else)."""
        self._show_step(self.state.step)

    def _show_step(self, step: int) -> None:
        if not self.isVisible():
            return
        track, scenario = self.state.track, self.state.document.scenario
        if track is None or scenario is None:
            self.sentence.setText("No instance open: Ctrl+O opens one.")
            self.verdict.setText("")
            self.rules.hide()
            return
        sentence = narrate(track, step)
        self.sentence.setText(sentence[:1].upper() + sentence[1:] + ".")
        words = verdict(track, scenario.unfinished)
        colour = _BAD if track.violations else _GOOD if len(track.plan) else _NEUTRAL
        self.verdict.setText(words + (" \u2713" if colour == _GOOD else ""))
        self.verdict.setStyleSheet(f"color: {colour};")
        kinds = list(dict.fromkeys((v.module, v.check) for v in track.violations_at.get(step, [])))
        lines = [line for line in (rule_line(track.domain, *kind) for kind in kinds[:RULES_SHOWN]) if line]
        if len(kinds) > RULES_SHOWN:
            lines.append(f"… and {len(kinds) - RULES_SHOWN} more rules")
        self.rules.setText("\n".join(lines))
        self.rules.setVisible(bool(lines))


class Presentation(QObject):
    """Enters and leaves the presentation mode of ``window``: hides its docks, tool bars,
    menu bar and status bar, shows ``bar`` and goes full screen, with ``view`` fitting the
    warehouse; leaving restores the window's layout and screen state as they were."""

    toggled = pyqtSignal(bool)

    def __init__(self, window: QMainWindow, view: WarehouseView, bar: NarrationBar):
        super().__init__(window)
        self.window, self.view, self.bar = window, view, bar
        self._layout: QByteArray | None = None
        self._geometry = QRect()
        self._screen = Qt.WindowState.WindowNoState

    @property
    def active(self) -> bool:
        return self._layout is not None

    def toggle(self) -> None:
        self.leave() if self.active else self.enter()

    def enter(self) -> None:
        if self.active:
            return
        window = self.window
        self._layout, self._screen, self._geometry = window.saveState(), window.windowState(), window.geometry()
        for part in (*window.findChildren(QDockWidget), *window.findChildren(QToolBar)):
            if part.parent() is window:
                part.hide()
        for bar in _bars(window):
            bar.hide()
        self.bar.show()
        self.bar.refresh()
        screen = window.screen()
        if screen is not None:  # where no window manager honours "full screen", cover the screen all the same
            window.setGeometry(screen.geometry())
        window.setWindowState(self._screen | Qt.WindowState.WindowFullScreen)
        self.view.fit()
        self.toggled.emit(True)

    def leave(self) -> None:
        if self._layout is None:
            return
        window, layout = self.window, self._layout
        self._layout = None
        self.bar.hide()
        window.setWindowState(self._screen)
        if not self._screen & (Qt.WindowState.WindowMaximized | Qt.WindowState.WindowFullScreen):
            window.setGeometry(self._geometry)
        for bar in _bars(window):
            bar.show()
        window.restoreState(layout)
        self.view.fit()
        self.toggled.emit(False)


def _bars(window: QMainWindow) -> list[QWidget]:
    """The window's menu bar and status bar."""
    return [bar for bar in (window.menuBar(), window.statusBar()) if bar is not None]
