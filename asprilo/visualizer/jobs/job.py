"""A job of the Run menu in a worker thread (:class:`Job`), and what the status bar shows of
it while it runs (:class:`JobBar`).

A job's thread belongs to no window: closing the window while a job still runs never
destroys a running thread (Qt would abort the process); the application waits for such
jobs when its window has gone (:func:`wait_for_jobs`).
"""

from __future__ import annotations

import contextlib
import threading
import time
from collections.abc import Callable
from typing import Any

from PyQt5.QtCore import QObject, QThread, QTimer, pyqtSignal
from PyQt5.QtWidgets import QHBoxLayout, QLabel, QProgressBar, QToolButton, QWidget

from asprilo.errors import InputError

from ..panels.status import ElidedLabel

#: the least and the most pixels a running job's progress takes in the status bar (more ends in …)
JOB_TEXT_PX = (160, 360)


class Job(QThread):
    """Runs ``work(job)`` in a worker thread and reports its result or failure (and, from
    an anytime search, each better result so far through ``better``)."""

    progress = pyqtSignal(str)
    better = pyqtSignal(object)
    succeeded = pyqtSignal(object)
    failed = pyqtSignal(str)

    def __init__(self, title: str, work: Callable[[Job], Any], parent: QObject | None = None):
        super().__init__(parent)
        self.title = title
        self.work = work
        self.cancel = threading.Event()
        self.seconds = 0.0

    def run(self) -> None:
        started = time.perf_counter()
        try:
            result = self.work(self)
        except InputError as error:
            self.failed.emit(str(error))
        except Exception as error:  # a bug must not take the window down: say what happened
            self.failed.emit(f"{self.title} failed: {type(error).__name__}: {error}")
        else:
            self.seconds = time.perf_counter() - started
            self.succeeded.emit(result)


#: the jobs started, until their threads are seen finished (see the module's docstring)
_STARTED: list[Job] = []


def keep(job: Job) -> None:
    """Hold on to ``job`` until its thread has finished (dropping the finished ones)."""
    _STARTED[:] = [started for started in _STARTED if started.isRunning()]
    _STARTED.append(job)


def silence(job: Job) -> None:
    """Disconnect everything ``job`` reports to: its result is no longer wanted."""
    for signal in (job.progress, job.better, job.succeeded, job.failed):
        with contextlib.suppress(TypeError):  # TypeError: nothing connected
            signal.disconnect()


def wait_for_jobs() -> None:
    """Cancel the jobs still running and let them end (a solve stops at once); for the
    application's last moments, before Qt destroys every object it still has."""
    for job in _STARTED:
        job.cancel.set()
        job.wait()


class JobBar(QWidget):
    """What a running job does, with a busy bar and a Cancel button (in the status bar)."""

    def __init__(self, parent: QWidget | None = None):
        super().__init__(parent)
        layout = QHBoxLayout(self)
        layout.setContentsMargins(16, 0, 4, 0)  # apart from the status message on its left
        self.label = ElidedLabel(self, *JOB_TEXT_PX)  # ends in … first: the verdict beside it never does
        self.bar = QProgressBar(self)
        self.bar.setRange(0, 0)  # busy: how long a search takes is not known in advance
        self.bar.setMaximumWidth(120)
        self.bar.setMaximumHeight(14)
        self.cancel = QToolButton(self)
        self.cancel.setText("Cancel")
        self.clock = QLabel(self)  # a solve's best plan so far, seconds elapsed and left
        for widget in (self.label, self.clock, self.bar, self.cancel):
            layout.addWidget(widget)
        self.started = 0.0
        self.time_limit: float | None = None
        self.best: int | None = None
        self.ticker = QTimer(self)
        self.ticker.setInterval(1000)
        self.ticker.timeout.connect(self.tick)
        self.hide()

    def begin(self, time_limit: float | None) -> None:
        """A job starts: the clock from 0, counting down to ``time_limit`` (when it has one)."""
        self.started, self.time_limit, self.best = time.perf_counter(), time_limit, None
        self.tick()
        self.ticker.start()

    def end(self) -> None:
        self.ticker.stop()
        self.clock.clear()

    def tick(self) -> None:
        """Redraw the clock: ``best makespan 30 · 12 s, 288 s left``."""
        elapsed = time.perf_counter() - self.started
        text = f"{elapsed:.0f} s" + ("" if self.time_limit is None else
                                     f", {max(0.0, self.time_limit - elapsed):.0f} s left")
        self.clock.setText(text if self.best is None else f"best makespan {self.best} · {text}")
