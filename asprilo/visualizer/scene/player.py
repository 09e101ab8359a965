"""The animation clock: play, pause, step, seek, loop and speed over the states 0..horizon.

Time is a float: ``3.0`` is the state after step 3, ``3.25`` a quarter of the way to
the state after step 4.  ``step`` is the state shown in the panels: the last whole step
reached (``floor(time)``).
"""

from __future__ import annotations

import math

from PyQt5.QtCore import QElapsedTimer, QObject, QTimer, pyqtSignal

#: Speeds offered, in steps per second.
SPEEDS = (0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0)
#: Steps per second at least when gliding one step forward or back.
GLIDE_SPEED = 4.0
FRAME_MS = 15


class Player(QObject):
    """Drives the time shown; emits ``time_changed`` every frame, ``step_changed`` per step."""

    time_changed = pyqtSignal(float)
    step_changed = pyqtSignal(int)
    playing_changed = pyqtSignal(bool)
    speed_changed = pyqtSignal(float)

    def __init__(self, parent: QObject | None = None):
        super().__init__(parent)
        self.horizon = 0
        self.time = 0.0
        self.speed = 2.0
        self.loop = False
        self._target: float | None = None  # where a step forward/back glides to
        self._timer = QTimer(self)
        self._timer.setInterval(FRAME_MS)
        self._timer.timeout.connect(self._tick)
        self._clock = QElapsedTimer()

    @property
    def step(self) -> int:
        """The state shown: the last whole step reached."""
        return int(math.floor(self.time + 1e-9))

    @property
    def playing(self) -> bool:
        return self._timer.isActive() and self._target is None

    @property
    def moving(self) -> bool:
        """Playing or gliding between two states."""
        return self._timer.isActive()

    def set_horizon(self, horizon: int, time: float | None = None) -> None:
        """New states to play: stop, and show ``time`` (default: the time shown, if still there)."""
        self.pause()
        self.horizon = max(0, horizon)
        self._set_time(min(self.time if time is None else max(time, 0.0), float(self.horizon)), force=True)

    # --- commands ------------------------------------------------------------------------

    def seek(self, time: float) -> None:
        """Show the state at ``time`` (a step number, or between two steps)."""
        self._stop_glide()
        self._set_time(min(max(float(time), 0.0), float(self.horizon)))

    def play(self) -> None:
        if self.horizon == 0:
            return
        self._target = None
        if self.time >= self.horizon:
            self._set_time(0.0)
        self._start()
        self.playing_changed.emit(True)

    def pause(self) -> None:
        was_playing = self.playing
        self._timer.stop()
        self._target = None
        if was_playing:
            self.playing_changed.emit(False)

    def toggle(self) -> None:
        self.pause() if self.playing else self.play()

    def step_forward(self) -> None:
        """Glide to the next state (from between two states: to the later one); during a glide
        one state further than where it goes, so that every key press counts."""
        base = self._target if self._target is not None else math.floor(self.time + 1e-9)
        self._glide(min(base + 1, self.horizon))

    def step_back(self) -> None:
        """Glide to the previous state (from between two states: to the earlier one); during a
        glide one state before where it goes."""
        base = self._target if self._target is not None else math.ceil(self.time - 1e-9)
        self._glide(max(base - 1, 0))

    def to_start(self) -> None:
        self.pause()
        self.seek(0)

    def to_end(self) -> None:
        self.pause()
        self.seek(self.horizon)

    def set_speed(self, speed: float) -> None:
        self.speed = max(0.01, float(speed))
        self.speed_changed.emit(self.speed)

    def faster(self) -> None:
        self.set_speed(next((s for s in SPEEDS if s > self.speed + 1e-9), SPEEDS[-1]))

    def slower(self) -> None:
        self.set_speed(next((s for s in reversed(SPEEDS) if s < self.speed - 1e-9), SPEEDS[0]))

    def set_loop(self, loop: bool) -> None:
        self.loop = bool(loop)

    # --- the clock -----------------------------------------------------------------------

    def _glide(self, target: float) -> None:
        was_playing = self.playing
        self._target = float(target)
        if was_playing:
            self.playing_changed.emit(False)
        if target == self.time:
            self._stop_glide()
            return
        self._start()

    def _stop_glide(self) -> None:
        if self._target is not None:
            self._target = None
            self._timer.stop()

    def _start(self) -> None:
        self._clock.start()
        if not self._timer.isActive():
            self._timer.start()

    def _tick(self) -> None:
        elapsed = self._clock.restart() / 1000.0
        if self._target is not None:
            # a glide over several states (keys pressed quickly) catches up: about a quarter of a
            # second whatever the distance
            distance = elapsed * max(self.speed, GLIDE_SPEED * max(1.0, abs(self._target - self.time)))
            if abs(self._target - self.time) <= distance:
                target, self._target = self._target, None
                self._timer.stop()
                self._set_time(target)
            else:
                self._set_time(self.time + math.copysign(distance, self._target - self.time))
            return
        time = self.time + elapsed * self.speed
        if time >= self.horizon:
            if self.loop:
                time = 0.0
            else:
                time = float(self.horizon)
                self.pause()
        self._set_time(time)

    def _set_time(self, time: float, force: bool = False) -> None:
        old_step = self.step
        self.time = time
        self.time_changed.emit(time)
        if force or self.step != old_step:
            self.step_changed.emit(self.step)
