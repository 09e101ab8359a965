"""The status bar's words: what is shown (title, domain, size, plan) and the verdict at the
step shown (valid plan, or how many rules it breaks)."""

from __future__ import annotations

from PyQt5.QtCore import QEvent, QSize, Qt, QTimer
from PyQt5.QtWidgets import QLabel, QSizePolicy, QStatusBar, QWidget

from ..state.viewer import ViewerState

#: the share of the status bar's width the summary keeps while a job's progress is shown beside it
SUMMARY_SHARE = 0.4


class ElidedLabel(QLabel):
    """One line of plain text that ends in ``…`` where its room is too small (the whole text
    in the tooltip then).  It asks for its whole text, at most ``longest`` pixels, and
    shrinks to ``shortest`` pixels (its whole text if shorter), or to the share ``keep`` of
    its parent's width (not below its whole text), so that what lies beside it gives way
    first."""

    def __init__(self, parent: QWidget | None = None, shortest: int = 40, longest: int | None = None,
                 keep: float = 0.0):
        super().__init__(parent)
        self.setTextFormat(Qt.TextFormat.PlainText)
        self.setSizePolicy(QSizePolicy.Preferred, QSizePolicy.Preferred)
        self.shortest, self.longest, self.keep = shortest, longest, keep
        self._whole = ""
        if keep and parent is not None:
            parent.installEventFilter(self)  # its share follows the parent's width

    def eventFilter(self, watched, event) -> bool:
        if event.type() == QEvent.Type.Resize and watched is self.parentWidget():
            self.updateGeometry()
        return False

    def setText(self, text: str | None) -> None:
        self._whole = text or ""
        self._elide()
        self.updateGeometry()

    def text(self) -> str:
        """The whole text, also where only its start is shown."""
        return self._whole

    def shown(self) -> str:
        """What the label shows: the text, or its start and ``…``."""
        return super().text()

    def sizeHint(self) -> QSize:
        margins = self.contentsMargins()
        width = (self.fontMetrics().horizontalAdvance(self._whole) + margins.left() + margins.right()
                 + 2 * self.margin() + 4)
        if self.longest is not None:
            width = min(width, self.longest)
        return QSize(width, super().sizeHint().height())

    def minimumSizeHint(self) -> QSize:
        width = min(self.shortest, self.sizeHint().width())  # a short text needs no more
        parent = self.parentWidget()
        if self.keep and parent is not None:
            width = max(width, min(self.sizeHint().width(), int(self.keep * parent.width())))
        return QSize(width, super().minimumSizeHint().height())

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)
        self._elide()

    def _elide(self) -> None:
        room = max(0, self.contentsRect().width())
        shown = self.fontMetrics().elidedText(self._whole, Qt.TextElideMode.ElideRight, room)
        if shown != super().text():
            super().setText(shown)
        self.setToolTip(self._whole if shown != self._whole else "")


class StatusLine:
    """A summary on the left, the verdict on the right, passing messages in between.

    The verdict never shrinks: what lies beside it ends in ``…`` first (its whole text in its
    tooltip), a running job's progress before the summary's first ``SUMMARY_SHARE``.
    """

    def __init__(self, state: ViewerState, bar: QStatusBar):
        self.state, self.bar = state, bar
        self.summary = ElidedLabel(bar, shortest=0, keep=SUMMARY_SHARE)
        self.verdict = QLabel(bar)
        self.verdict.setSizePolicy(QSizePolicy.Fixed, QSizePolicy.Preferred)  # as wide as its words, always
        bar.addWidget(self.summary, 1)
        bar.addPermanentWidget(self.verdict)
        state.shown.connect(lambda _keep: self._show_track())
        state.track_changed.connect(lambda _change: self._show_track())
        state.step_changed.connect(self._show_verdict)
        state.said.connect(self._say)
        self._again = ("", 0)
        self._again_timer = QTimer(bar)  # (the bar's: it goes with the window)
        self._again_timer.setSingleShot(True)
        self._again_timer.setInterval(0)
        self._again_timer.timeout.connect(self._say_again)

    def _say(self, text: str, milliseconds: int) -> None:
        """A passing message; one said before the window shows (the files of the command line
        read with warnings) is said again when it shows: Qt hides the summary under a message
        only while it is visible (else both would be drawn on top of each other)."""
        self.bar.showMessage(text, milliseconds)
        if not self.bar.isVisible():  # said again once the window shows, if still said
            self._again = (text, milliseconds)
            self._again_timer.start()

    def _say_again(self) -> None:
        text, milliseconds = self._again
        if text and self.bar.currentMessage() == text:
            self.bar.clearMessage()  # (Qt does nothing for the message it says already)
            self.bar.showMessage(text, milliseconds)

    def _show_track(self) -> None:
        self._show_summary()
        self._show_verdict(self.state.step)

    def _show_summary(self) -> None:
        scenario, track = self.state.document.scenario, self.state.track
        if scenario is None:
            self.summary.setText("No instance open.")
            return
        counts = scenario.instance.counts()
        actions = len(scenario.plan)
        plan = f"plan: {actions} action{'s' * (actions != 1)}, horizon {track.horizon}" if actions else "no plan"
        self.summary.setText(
            f"{scenario.title}   ·   domain {track.domain.label}   ·   {counts['x']}×{counts['y']}, "
            f"{counts['robots']} robots, {counts['shelves']} shelves, {counts['orders']} orders   ·   {plan}")

    def _show_verdict(self, step: int) -> None:
        scenario, track = self.state.document.scenario, self.state.track
        self.verdict.setToolTip(f"the ASP checker's verdict: domain {track.domain.label} has rules the viewer's "
                                "simulator does not know" if track is not None and track.checked else "")
        if track is None or not len(scenario.plan):
            self.verdict.setText("")
            return
        total = len(track.violations)
        here = len(track.violations_at.get(step, []))
        if not total:
            verdict = "no rule broken so far" if scenario.unfinished else "valid plan"
            self.verdict.setText(f"<span style='color:#2b8a3e'>{verdict} \u2713</span>")
            return
        text = f"\u26a0 {total} rule violation{'s' if total > 1 else ''}"
        if here:
            text += f", {here} at step {step}"
        self.verdict.setText(f"<span style='color:#e03131'><b>{text}</b></span>")
