"""Generate, Solve and Check from the window (the Run menu), each a job in a worker thread.

The window never freezes: a job runs in a :class:`Job` (a QThread); the status bar shows
what it does (the horizons the solver tries) with a Cancel button.  Editing is locked
while a job runs, so its result always fits the instance shown.  Cancelling a solve
interrupts clingo at once; the generator cannot be interrupted, so a cancelled generation
is left to finish in the background (at most its time limit) and its result is dropped.
A job's thread belongs to no window: closing the window while a job still runs never
destroys a running thread (Qt would abort the process); the application waits for such
jobs when its window has gone (:func:`wait_for_jobs`).

Solve has three methods (Run > Solve method, kept in the settings like the encoding): by
default the exact search and the anytime planner together (``auto``: a plan fast, proven
minimal when the exact search gets there), a plan of minimal makespan with a reference
encoding alone, or the anytime planner alone.  With ``auto`` and the anytime planner the
better plans are shown as they come (a draft, outside the undo history) and the job answers
with its best plan when cancelled.  While a solve runs, the status bar says what it does, and
beside it the best plan so far, the seconds elapsed and the seconds left to the time limit.

Solve with encoding file… runs a user's own encoding (``asprilo.encodings.own``) the way the
references run, its style recognised and said while it runs, in a child process (a program
may ground for ever: cancel kills it).  Its plan is checked: a plan that breaks the rules is
shown all the same, with the checker's violations, because that is what its author needs to
see; a file that cannot be used is reported in the error dialog (``FILE:LINE: …``).
"""

from __future__ import annotations

import copy
import functools
from collections.abc import Callable, Sequence
from typing import Any

from PyQt5.QtCore import QObject, QSettings
from PyQt5.QtWidgets import (
    QAction,
    QActionGroup,
    QMainWindow,
    QMenu,
)

from asprilo.domain import Domain

from ..panels.commands import Table, make_actions, menu_entry, submenu
from ..panels.dialogs import GenerateDialog
from ..scene.player import Player
from ..state import edits
from ..state.viewer import ViewerState
from . import encoding_files
from .job import Job, JobBar, keep, silence
from .job_words import broken, doing, explain, found, no_plan, tried

#: seconds the solver and the generator may take from the window
SOLVE_SECONDS, GENERATE_SECONDS = 300.0, 120.0
#: the Solve methods: setting -> menu entry (``asp``: minimal makespan with the encoding chosen;
#: ``auto``, the default: the exact search with that encoding and the anytime planner together)
SOLVE_METHODS = {"auto": "&Best plan fast, proven minimal when possible (exact search and anytime together)",
                 "asp": "&Minimal makespan only (the encoding chosen, alone)",
                 "anytime": "&Anytime only: a plan fast, then better ones"}
#: the Solve method until another is chosen
DEFAULT_METHOD = "auto"
#: what Run > Solve with encoding says while the Solve method is the anytime planner alone
NO_ENCODING = "(Solve method Anytime only runs no encoding)"

JOB_ACTIONS: Table = {
    "generate": ("&Generate (fill this layout)…", ("Ctrl+Shift+G",)),
    "solve": ("&Solve", ("F9",)),
    "solve_file": ("Solve with encoding &file…", ("Shift+F9",)),
    "check": ("&Check with the ASP checker", ("F7",)),
    "cancel": ("C&ancel", ("Ctrl+.",)),
}


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
                                                           "solve_file": self.ask_solve_file,
                                                           "check": self.check, "cancel": self.cancel})
        self.encodings = QActionGroup(self)
        self.encoding_menu: QMenu | None = None
        self.recent_menu: QMenu | None = None
        self.methods = QActionGroup(self)
        for method, text in SOLVE_METHODS.items():
            action = QAction(text, self)
            self.methods.addAction(action)
            action.setCheckable(True)
            action.setData(method)
            action.triggered.connect(lambda _checked=False, m=method: self.settings.setValue("tools/method", m))
        state.shown.connect(lambda _keep: self.update_actions())
        state.locks_changed.connect(self.update_actions)
        self.update_actions()

    def install(self, menu: QMenu) -> None:
        menu.addAction(self.commands["generate"])
        menu.addSeparator()
        menu.addAction(self.commands["solve"])
        methods = submenu(menu, "Solve &method")
        methods.addActions(self.methods.actions())
        methods.aboutToShow.connect(self._show_method)
        self.encoding_menu = submenu(menu, "Solve &with encoding")
        self.encoding_menu.aboutToShow.connect(self._fill_encodings)
        menu.addAction(self.commands["solve_file"])
        recent = QMenu("&Recent encoding files", menu)
        recent.aboutToShow.connect(self.fill_recent_encodings)
        menu.addMenu(recent)
        self.recent_menu = recent
        menu.addAction(self.commands["check"])
        menu.addSeparator()
        menu.addAction(self.commands["cancel"])

    def update_actions(self) -> None:
        idle = self.job is None
        shown = self.state.document.scenario is not None and not self.state.session.running
        for name in ("generate", "solve", "solve_file", "check"):
            self.commands[name].setEnabled(idle and shown)
        self.commands["cancel"].setEnabled(not idle)

    def _fill_encodings(self) -> None:
        from asprilo.encodings import encoding_names
        self.encoding_menu.clear()
        chosen = str(self.settings.value("tools/encoding", "plain"))
        names = encoding_names(self.state.document.domain) if self.state.document.scenario is not None else ["plain"]
        unused = self.method == "anytime"  # the anytime planner runs no encoding: none is offered
        if unused and self.encoding_menu is not None:
            note = menu_entry(self.encoding_menu, NO_ENCODING)
            note.setEnabled(False)
        for name in names:
            action = menu_entry(self.encoding_menu, name)
            action.setCheckable(True)
            action.setChecked(name == chosen)
            action.setEnabled(not unused)
            self.encodings.addAction(action)
            action.triggered.connect(lambda _checked=False, n=name: self.settings.setValue("tools/encoding", n))

    def fill_recent_encodings(self) -> None:
        """Run > Recent encoding files: the sets used lately, newest first; a set whose files
        are gone is listed disabled, marked missing."""
        menu = self.recent_menu
        if menu is None:
            return
        menu.clear()
        usable = self.commands["solve_file"].isEnabled()
        for entry in encoding_files.recent_encodings(self.settings):
            gone = encoding_files.missing(entry)
            action = QAction(encoding_files.entry_text(entry) + ("  (missing)" if gone else ""), menu)
            action.setToolTip("\n".join(entry) + ("\nmissing: " + ", ".join(gone) if gone else ""))
            action.setEnabled(usable and not gone)
            action.triggered.connect(lambda _checked=False, files=entry: self._solve_again(files))
            menu.addAction(action)
        if not menu.actions():
            none = QAction("(none yet)", menu)
            none.setEnabled(False)
            menu.addAction(none)

    def _solve_again(self, files: list[str]) -> None:
        self.solve_files(files)

    @property
    def method(self) -> str:
        """The Solve method chosen (``auto``, ``asp`` or ``anytime``)."""
        method = str(self.settings.value("tools/method", DEFAULT_METHOD))
        return method if method in SOLVE_METHODS else DEFAULT_METHOD

    def _show_method(self) -> None:
        for action in self.methods.actions():
            action.setChecked(action.data() == self.method)

    # --- running jobs ----------------------------------------------------------------------------

    def start(self, title: str, work: Callable[[Job], Any], done: Callable[[Job, Any], None],
              better: Callable[[Any], None] | None = None, time_limit: float | None = None) -> Job | None:
        """Run ``work`` in the background; ``done(job, result)`` in the window's thread afterwards.

        ``better(value)``, in the window's thread, hears of each better result so far; such
        a job still answers when cancelled (with its best result).  ``time_limit``: the
        seconds the job may take (the clock beside its progress counts down to it)."""
        if self.job is not None or self.state.document.scenario is None:
            return None
        job = Job(title, work)
        keep(job)
        job.progress.connect(lambda text: self.bar.label.setText(f"{title}: {text}"))
        if better is not None:
            job.better.connect(better)
        job.succeeded.connect(lambda result: self._finished(job, better is not None) and done(job, result))
        job.failed.connect(lambda message: self._finished(job) and self.state.report_error(message))
        self.job = job
        self.bar.label.setText(f"{title}…")
        self.bar.begin(time_limit)
        self.bar.show()
        self.player.pause()
        self.state.begin_job(title)
        job.start()
        return job

    def _finished(self, job: Job, answers: bool = False) -> bool:
        """Tidy up after ``job``; whether its result is still wanted (not cancelled, or
        ``answers``: its result is the best so far also when cancelled).  A draft plan it
        showed goes when its result is not wanted."""
        job.wait()
        if self.job is job:
            self._idle()
        if not answers:
            self.state.document.drop_draft()
        if job.cancel.is_set() and not answers:
            self.state.say(f"{job.title} cancelled")
            return False
        return True

    def _idle(self) -> None:
        self.job = None
        self.bar.end()
        self.bar.hide()
        self.state.end_job()

    def cancel(self) -> None:
        """Stop the running job (the solver at once; a generation's result is dropped)."""
        job = self.job
        if job is None:
            return
        job.cancel.set()
        if job.title == "Generate":  # the generator cannot be interrupted: let it run out unheard
            self._abandon(job)
            self.state.say("Generate cancelled")

    def close(self) -> None:
        """The window closes: stop the running job and hear nothing more from it."""
        if self.job is not None:
            self.job.cancel.set()
            self._abandon(self.job)

    def _abandon(self, job: Job) -> None:
        silence(job)
        self._idle()

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

        return self.start("Generate", work, done, time_limit=GENERATE_SECONDS)

    # --- solve ----------------------------------------------------------------------------------

    def solve(self, encoding: str | None = None, time_limit: float | None = None,
              method: str | None = None) -> Job | None:
        """Find a plan for the instance shown and play it: by default (``method`` ``auto``)
        the exact search with the encoding chosen and the anytime planner together, the best
        plan proven minimal when the search gets there; of minimal makespan with the encoding
        alone (``asp``); or with the anytime planner alone (``anytime``).  With ``auto`` and
        ``anytime`` each better plan is shown as it comes, and Cancel keeps the best.  Default:
        the method and encoding chosen in the Run menu, the time limit :data:`SOLVE_SECONDS`
        (anytime: the planner's own default)."""
        from asprilo.encodings.anytime import DEFAULT_SECONDS as ANYTIME_SECONDS

        document = self.state.document
        if document.scenario is None:
            return None
        scenario, instance, domain = document.scenario, copy.deepcopy(document.instance), document.domain
        base = document.base_domain  # the plan found is shown under the rules it is solved for
        method = method or self.method
        drafts = method in ("auto", "anytime")
        encoding = encoding or str(self.settings.value("tools/encoding", "plain"))
        if time_limit is None:
            time_limit = ANYTIME_SECONDS if method == "anytime" else SOLVE_SECONDS

        def work(job: Job):
            from asprilo.encodings import solve

            def heard(attempt) -> None:
                if method != "auto" or attempt.result != "improved":  # auto: the label follows the exact search
                    job.progress.emit(tried(attempt))
                if attempt.plan is not None:
                    job.better.emit(attempt)

            return solve(instance, domain, encoding=encoding, method=method, time_limit=time_limit,
                         cancel=job.cancel, on_progress=heard,
                         on_phase=lambda phase: job.progress.emit(doing(phase)))

        def done(job: Job, outcome) -> None:
            self._solved(job, outcome, scenario, domain.label, solved_in=base)

        better = functools.partial(self._show_better, scenario, base) if drafts else None
        return self.start("Solve", work, done, better, time_limit)

    def _show_better(self, scenario, solved_in: Domain, attempt) -> None:
        """A better plan of a solve for ``scenario`` in the domain ``solved_in``: drafted (while
        that scenario is shown) and its makespan beside the job's clock."""
        if self.bar.best is not None and attempt.horizon > self.bar.best:
            return  # (the anytime planner's next plan of the same makespan has a smaller sum of costs)
        self.bar.best = attempt.horizon
        self.bar.tick()
        document = self.state.document
        if document.scenario is scenario:
            document.draft_plan(attempt.plan, solved_in)

    def ask_solve_file(self) -> None:
        """Run > Solve with encoding file…: choose the files of an encoding and solve with them."""
        if self.job is not None or self.state.document.scenario is None:
            return
        paths = encoding_files.ask_encoding_files(self.window, self.settings)
        if paths:
            self.solve_files(paths)

    def solve_files(self, paths: Sequence[str], time_limit: float | None = None) -> Job | None:
        """Find a plan of minimal makespan for the instance shown with a user's own encoding made
        of ``paths`` (loaded in this order; remembered among the recent encodings) and show it:
        a valid plan plays, a plan that breaks the rules is shown with the checker's violations.
        Time limit: :data:`SOLVE_SECONDS`."""
        document = self.state.document
        if self.job is not None or document.scenario is None:
            return None
        paths = [str(path) for path in paths]
        encoding_files.remember_encoding(self.settings, paths)
        scenario, instance, domain = document.scenario, copy.deepcopy(document.instance), document.domain
        base = document.base_domain  # the plan found is shown under the rules it is solved for
        time_limit = SOLVE_SECONDS if time_limit is None else time_limit
        names = encoding_files.entry_text(paths)

        def work(job: Job):
            from asprilo.encodings import solve
            from asprilo.encodings.own import own_encoding

            encoding = own_encoding(paths)  # bad files: InputError, said in the error dialog
            said = f"{names}, {encoding.summary}"
            assumed = "".join(f"; assumed: {note}" for note in encoding.assumed)
            job.progress.emit(f"{said}{assumed}…")
            outcome = solve(instance, domain, encoding=encoding, time_limit=time_limit, isolate=True,
                            cancel=job.cancel,
                            on_progress=lambda attempt: job.progress.emit(f"{said} — {tried(attempt)}"),
                            on_phase=lambda phase: job.progress.emit(f"{said} — {doing(phase)}"))
            from asprilo.encodings.solving.minimality import learn_minimum
            learn_minimum(outcome, instance)  # a plan above the bound: the problem's minimum, where cheap
            return encoding, outcome

        def done(job: Job, result) -> None:
            encoding, outcome = result
            self._solved(job, outcome, scenario, domain.label, encoding, solved_in=base)

        return self.start("Solve", work, done, time_limit=time_limit)

    def _solved(self, job: Job, outcome, scenario, domain: str, own=None, solved_in: Domain | None = None) -> None:
        """Load and play the plan found in ``scenario`` (if still shown), show a plan that breaks
        the rules with the checker's violations, or say why there is none.  ``own``: the user's
        own encoding that solved (an :class:`~asprilo.encodings.Encoding`); ``solved_in``: the
        domain it was solved for (before the variants), which the plan is then shown under, so
        that the checker's verdict, the replay, the panels and the status bar judge it alike."""
        document = self.state.document
        self.last_outcome = outcome
        if document.scenario is not scenario:
            self.state.say("Solve: another instance is open now; the plan found is dropped", 10000)
            return
        invalid = outcome.status.value == "invalid" and outcome.plan is not None and outcome.check is not None
        if not outcome.found and not invalid:
            document.drop_draft()
            if outcome.status.value == "cancelled":
                self.state.say("Solve cancelled")
                return
            if own is not None:
                self.state.report_error(no_plan(outcome, own))
                return
            why = f" ({outcome.message})" if outcome.message else ""
            hint = (" For a plan fast (not proven minimal), choose Run > Solve method > Best plan fast."
                    if outcome.status.value == "limit" and outcome.method == "asp" and self.method == "asp" else "")
            self.state.report_error(f"No plan: {outcome.status.value}{why}.{hint}")
            return
        verdict = "" if outcome.found else ", invalid"
        document.replace_plan(outcome.plan, f"solve ({outcome.encoding}, makespan {outcome.horizon}{verdict})",
                              time=0.0, sources=[], solved_in=solved_in)
        if invalid:  # the checker's violations, the first one's step shown
            violations = list(outcome.check.errors)
            self.state.show_checker_report(violations)
            self.state.say(broken(outcome, job, domain, own), 20000)
            self.state.seek(min((violation.step for violation in violations), default=0))
            return
        self.state.say(found(outcome, job, domain, own), 10000)
        self.player.play()

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
        assert track is not None  # (a check needs a scenario shown)
        violations = [explain(track.timeline, error.atom) for error in report.errors]
        self.state.show_checker_report(violations)
        shown = track.checker_violations if track.checked else track.timeline.violations  # the goal too, always
        agree = "agrees with" if {v.atom for v in shown} == {v.atom for v in violations} else "differs from"
        verdict = "valid plan" if report.valid else f"{len(violations)} violation{'s' if len(violations) != 1 else ''}"
        seen = f"the verdict shown ({track.domain.label})" if track.checked else "the viewer's replay"
        self.state.say(f"ASP checker: {verdict}; it {agree} {seen}", 10000)
