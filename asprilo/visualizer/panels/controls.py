"""The transport bar: media buttons, a time slider with violations marked, go-to-step,
speed and loop, and a time display that says which state is shown."""

from __future__ import annotations

import math

from PyQt5.QtCore import QPoint, Qt
from PyQt5.QtGui import QPainter, QPen
from PyQt5.QtWidgets import (
    QAction,
    QComboBox,
    QHBoxLayout,
    QLabel,
    QSlider,
    QSpinBox,
    QStyle,
    QStyleOptionSlider,
    QToolButton,
    QWidget,
)

from ..scene import style
from ..scene.player import SPEEDS, Player


def time_text(time: float, horizon: int) -> str:
    """``initial state (step 0 of 29)``, ``state after step 12 of 29``, ``step 12 → 13 of 29``."""
    step = int(math.floor(time + 1e-9))
    if time - step > 1e-9:
        return f"step {step} \u2192 {step + 1} of {horizon}"
    if step == 0:
        return f"initial state (step 0 of {horizon})"
    return f"state after step {step} of {horizon}"


def speed_text(speed: float) -> str:
    return f"{speed:g} steps/s"


class TimeSlider(QSlider):
    """A slider over the steps 0..horizon with a red tick at each step that breaks a rule."""

    def __init__(self, parent=None):
        super().__init__(Qt.Horizontal, parent)
        self.setRange(0, 0)
        self.setPageStep(1)
        self.marks: list[int] = []

    def set_marks(self, steps: list[int]) -> None:
        self.marks = sorted(set(steps))
        self.setToolTip("red ticks: steps that break a rule" if self.marks else "")
        self.update()

    def mark_x(self, step: int) -> int:
        """Horizontal pixel position of ``step`` on the groove."""
        option = QStyleOptionSlider()
        self.initStyleOption(option)
        groove = self.style().subControlRect(QStyle.CC_Slider, option, QStyle.SC_SliderGroove, self)
        handle = self.style().subControlRect(QStyle.CC_Slider, option, QStyle.SC_SliderHandle, self)
        span = groove.width() - handle.width()
        offset = QStyle.sliderPositionFromValue(self.minimum(), self.maximum(), step, span)
        return groove.left() + handle.width() // 2 + offset

    def paintEvent(self, event) -> None:
        super().paintEvent(event)
        if not self.marks or self.maximum() == 0:
            return
        painter = QPainter(self)
        painter.setPen(QPen(style.VIOLATION, 2))
        bottom = self.height() - 1
        for step in self.marks:
            x = self.mark_x(step)
            painter.drawLine(QPoint(x, bottom - 6), QPoint(x, bottom))
            painter.drawLine(QPoint(x, 0), QPoint(x, 5))
        painter.end()


class TransportBar(QWidget):
    """Media controls bound to a :class:`Player` and to the window's actions."""

    def __init__(self, player: Player, actions: dict[str, QAction], parent=None):
        super().__init__(parent)
        self.player = player
        layout = QHBoxLayout(self)
        layout.setContentsMargins(6, 2, 6, 2)
        for name in ("start", "back", "play", "forward", "end"):
            button = QToolButton(self)
            button.setDefaultAction(actions[name])
            button.setAutoRaise(True)
            layout.addWidget(button)
        self.slider = TimeSlider(self)
        self.slider.valueChanged.connect(self._slider_moved)
        layout.addWidget(self.slider, 1)
        self.label = QLabel(self)
        layout.addWidget(self.label)
        layout.addWidget(QLabel("go to", self))
        self.spin = QSpinBox(self)
        self.spin.setToolTip("go to step (Ctrl+G)")
        self.spin.setKeyboardTracking(False)
        self.spin.valueChanged.connect(lambda step: self.player.seek(step))
        layout.addWidget(self.spin)
        self.speed = QComboBox(self)
        self.speed.setToolTip("animation speed ([ slower, ] faster)")
        for value in SPEEDS:
            self.speed.addItem(speed_text(value), value)
        self.speed.activated.connect(lambda index: player.set_speed(self.speed.itemData(index)))
        layout.addWidget(self.speed)
        loop = QToolButton(self)
        loop.setDefaultAction(actions["loop"])
        loop.setAutoRaise(True)
        layout.addWidget(loop)
        player.time_changed.connect(self._show_time)
        player.step_changed.connect(self._show_step)
        player.speed_changed.connect(self._show_speed)
        self._show_speed(player.speed)
        self.set_horizon(0)

    def set_horizon(self, horizon: int) -> None:
        for widget in (self.slider, self.spin):
            widget.blockSignals(True)
            widget.setRange(0, horizon)
            widget.blockSignals(False)
        # a fixed width: the text changes every frame and must not shake the window's layout
        texts = (time_text(0, horizon), time_text(horizon, horizon), time_text(horizon - 0.5, horizon))
        self.label.setFixedWidth(max(self.label.fontMetrics().horizontalAdvance(t) for t in texts) + 8)
        self._show_time(self.player.time)
        self._show_step(self.player.step)

    def _slider_moved(self, step: int) -> None:
        if step != self.player.step or self.player.moving:
            self.player.seek(step)

    def _show_time(self, time: float) -> None:
        self.label.setText(time_text(time, self.player.horizon))

    def _show_step(self, step: int) -> None:
        for widget in (self.slider, self.spin):
            widget.blockSignals(True)
            widget.setValue(step)
            widget.blockSignals(False)

    def _show_speed(self, speed: float) -> None:
        index = self.speed.findData(speed)
        if index < 0:
            self.speed.addItem(speed_text(speed), speed)
            index = self.speed.count() - 1
        self.speed.setCurrentIndex(index)
