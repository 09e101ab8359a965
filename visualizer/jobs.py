"""Generate, Solve and Check from the window (the Run menu), each a job in a worker thread.

The window never freezes: a job runs in a :class:`Job` (a QThread); the status bar shows
what it does (the horizons the solver tries) with a Cancel button.  Editing is locked
while a job runs, so its result always fits the instance shown.  Cancelling a solve
interrupts clingo at once; the generator cannot be interrupted, so a cancelled generation
is left to finish in the background (at most its time limit) and its result is dropped.
"""

from __future__ import annotations

import copy
import threading
import time
from collections.abc import Callable
from typing import Any

import clingo
from PyQt5.QtCore import QObject, QSettings, QThread, pyqtSignal
from PyQt5.QtWidgets import QActionGroup, QHBoxLayout, QLabel, QMainWindow, QMenu, QProgressBar, QToolButton, QWidget

from asprilo.errors import InputError
from asprilo.reader import value_of
from asprilo.simulate import Violation

from . import edits
from .commands import Table, make_actions
from .dialogs import GenerateDialog
from .player import Player
from .state import ViewerState

#: seconds the solver and the generator may take from the window
SOLVE_SECONDS, GENERATE_SECONDS = 300.0, 120.0

JOB_ACTIONS: Table = {
    "generate": ("&Generate (fill this layout)…", ("Ctrl+Shift+G",)),
    "solve": ("&Solve", ("F9",)),
    "check": ("&Check with the ASP checker", ("F7",)),
    "cancel": ("C&ancel", ("Ctrl+.",)),
}


class Job(QThread):
    """Runs ``work(job)`` in a worker thread and reports its result or failure."""

    progress = pyqtSignal(str)
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


class JobBar(QWidget):
    """What a running job does, with a busy bar and a Cancel button (in the status bar)."""

    def __init__(self, parent: QWidget | None = None):
        super().__init__(parent)
        layout = QHBoxLayout(self)
        layout.setContentsMargins(16, 0, 4, 0)  # apart from the status message on its left
        self.label = QLabel(self)
        self.bar = QProgressBar(self)
        self.bar.setRange(0, 0)  # busy: how long a search takes is not known in advance
        self.bar.setMaximumWidth(120)
        self.bar.setMaximumHeight(14)
        self.cancel = QToolButton(self)
        self.cancel.setText("Cancel")
        for widget in (self.label, self.bar, self.cancel):
            layout.addWidget(widget)
        self.hide()


class JobRunner(QObject):
    """The Run menu: Generate…, Solve, Check, Cancel, each a job in the background."""

    def __init__(self, state: ViewerState, player: Player, window: QMainWindow, settings: QSettings):
        super().__init__(window)
        self.state, self.player, self.window, self.settings = state, player, window, settings
        self.job: Job | None = None
        self.last_outcome: Any = None  # the last solve's outcome, the last check's report
        self.bar = JobBar(window)
        self.bar.cancel.clicked.connect(self.cancel)
        window.statusBar().addPermanentWidget(self.bar)
        self.commands = make_actions(window, JOB_ACTIONS, {"generate": self.ask_generate, "solve": self.solve,
                                                           "check": self.check, "cancel": self.cancel})
        self.encodings = QActionGroup(self)
        self.encoding_menu: QMenu | None = None
        state.shown.connect(lambda _keep: self.update_actions())
        state.locks_changed.connect(self.update_actions)
        self.update_actions()

    def install(self, menu: QMenu) -> None:
        menu.addAction(self.commands["generate"])
        menu.addSeparator()
        menu.addAction(self.commands["solve"])
        self.encoding_menu = menu.addMenu("Solve &with encoding")
        self.encoding_menu.aboutToShow.connect(self._fill_encodings)
        menu.addAction(self.commands["check"])
        menu.addSeparator()
        menu.addAction(self.commands["cancel"])

    def update_actions(self) -> None:
        idle = self.job is None
        shown = self.state.document.scenario is not None and not self.state.session.running
        for name in ("generate", "solve", "check"):
            self.commands[name].setEnabled(idle and shown)
        self.commands["cancel"].setEnabled(not idle)

    def _fill_encodings(self) -> None:
        from asprilo.encodings import encoding_names
        self.encoding_menu.clear()
        chosen = str(self.settings.value("tools/encoding", "plain"))
        names = encoding_names(self.state.document.domain) if self.state.document.scenario is not None else ["plain"]
        for name in names:
            action = self.encoding_menu.addAction(name)
            action.setCheckable(True)
            action.setChecked(name == chosen)
            self.encodings.addAction(action)
            action.triggered.connect(lambda _checked=False, n=name: self.settings.setValue("tools/encoding", n))

    # --- running jobs ----------------------------------------------------------------------------

    def start(self, title: str, work: Callable[[Job], Any], done: Callable[[Job, Any], None]) -> Job | None:
        """Run ``work`` in the background; ``done(job, result)`` in the window's thread afterwards."""
        if self.job is not None or self.state.document.scenario is None:
            return None
        job = Job(title, work, self)
        job.progress.connect(lambda text: self.bar.label.setText(f"{title}: {text}"))
        job.succeeded.connect(lambda result: self._finished(job) and done(job, result))
        job.failed.connect(lambda message: self._finished(job) and self.state.report_error(message))
        self.job = job
        self.bar.label.setText(f"{title}…")
        self.bar.show()
        self.player.pause()
        self.state.begin_job(title)
        job.start()
        return job

    def _finished(self, job: Job) -> bool:
        """Tidy up after ``job``; whether its result is still wanted (not cancelled)."""
        job.wait()
        job.deleteLater()
        if self.job is job:
            self._idle()
        if job.cancel.is_set():
            self.state.say(f"{job.title} cancelled")
            return False
        return True

    def _idle(self) -> None:
        self.job = None
        self.bar.hide()
        self.state.end_job()

    def cancel(self) -> None:
        """Stop the running job (the solver at once; a generation's result is dropped)."""
        job = self.job
        if job is None:
            return
        job.cancel.set()
        if job.title == "Generate":  # the generator cannot be interrupted: let it run out unseen
            self._idle()
            self.state.say("Generate cancelled")

    # --- generate ----------------------------------------------------------------------------------

    def ask_generate(self) -> None:
        if self.state.document.scenario is None:
            return
        counts = self.state.document.instance.counts()
        dialog = GenerateDialog(counts, int(self.settings.value("tools/seed", 1)), self.window)
        if dialog.exec_():
            values = dialog.values()
            self.settings.setValue("tools/seed", values["seed"])
            self.generate(values["options"], values["seed"])

    def generate(self, options: dict, seed: int) -> Job | None:
        """Fill the instance shown with the generator (totals in ``options``), as one undoable edit."""
        document = self.state.document
        template = copy.deepcopy(document.instance)

        def work(job: Job):
            from asprilo.generator import populate
            return populate(template, seed=seed, time_limit=GENERATE_SECONDS, **options)

        def done(job: Job, generated) -> None:
            self.last_outcome = generated
            document.perform(edits.replace_all(document.instance, generated.instance, f"generate (seed {seed})"))
            counts = generated.instance.counts()
            self.state.say(f"generated in {job.seconds:.1f} s: {counts['robots']} robots, {counts['shelves']} "
                           f"shelves, {counts['orders']} orders (Undo takes it back)", 8000)

        return self.start("Generate", work, done)

    # --- solve ----------------------------------------------------------------------------------

    def solve(self, encoding: str | None = None, time_limit: float = SOLVE_SECONDS) -> Job | None:
        """Find a plan of minimal makespan for the instance shown; play it when found."""
        document = self.state.document
        if document.scenario is None:
            return None
        instance, domain = copy.deepcopy(document.instance), document.domain
        encoding = encoding or str(self.settings.value("tools/encoding", "plain"))

        def work(job: Job):
            from asprilo.encodings import solve
            return solve(instance, domain, encoding=encoding, time_limit=time_limit, cancel=job.cancel,
                         on_progress=lambda attempt: job.progress.emit(
                             f"horizon {attempt.horizon}: {attempt.result} ({attempt.seconds:.1f} s)"))

        def done(job: Job, outcome) -> None:
            self.last_outcome = outcome
            if not outcome.found:
                why = f" ({outcome.message})" if outcome.message else ""
                self.state.report_error(f"No plan: {outcome.status.value}{why}.")
                return
            document.replace_plan(outcome.plan, f"solve ({encoding}, makespan {outcome.horizon})", time=0.0,
                                  sources=[])
            minimal = "minimal " if outcome.minimal else ""
            self.state.say(f"plan found in {job.seconds:.1f} s: {minimal}makespan {outcome.horizon}, "
                           f"{len(outcome.plan)} actions ({domain.label}, {encoding})", 10000)
            self.player.play()

        return self.start("Solve", work, done)

    # --- check ----------------------------------------------------------------------------------

    def check(self) -> Job | None:
        """Run the ASP checker on instance and plan; its diagnostics go to the violations panel."""
        document = self.state.document
        if document.scenario is None:
            return None
        instance, plan, domain = copy.deepcopy(document.instance), document.plan, document.domain

        def work(job: Job):
            from asprilo.checker import check
            return check(instance, plan, domain)

        def done(job: Job, report) -> None:
            self.last_outcome = report
            self.show_report(report)

        return self.start("Check", work, done)

    def show_report(self, report) -> None:
        """The checker's ``err/3`` diagnostics in the violations panel, said as the viewer says them."""
        track = self.state.track
        violations = [explain(track.timeline, error.atom) for error in report.errors]
        self.state.show_checker_report(violations)
        replay = {v.atom for v in track.timeline.violations}  # the goal included, also without a plan
        agree = "agrees with" if replay == {v.atom for v in violations} else "differs from"
        verdict = "valid plan" if report.valid else f"{len(violations)} violation{'s' if len(violations) != 1 else ''}"
        self.state.say(f"ASP checker: {verdict}; it {agree} the viewer's replay", 10000)


def explain(timeline, atom: str) -> Violation:
    """An ``err(Module,Check,Params)`` atom as the replay words it (with what to highlight)."""
    term = clingo.parse_term(atom)
    module, check, params = term.arguments
    values = value_of(params)
    values = values if isinstance(values, tuple) else (values,)
    try:
        return timeline.explain(module.name, check.name, values)
    except (KeyError, IndexError, TypeError, ValueError):
        step = values[-1] if values and isinstance(values[-1], int) else 0
        return Violation(module.name, check.name, values, step, f"{module.name} rule '{check.name}' is broken ({atom})")
