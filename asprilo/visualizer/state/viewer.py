"""What the viewer shows, without Qt: the document, the plan's states (a :class:`Track`),
the step shown, the selection, the online session, and the job that runs.

The window, the panels, the editor, the jobs (generate, solve, check) and the online link
observe it through its signals and change it through its methods; none of them calls
into another.  The clock that animates between steps is the window's (a Qt timer): it
reports each step it reaches through :meth:`ViewerState.show_step`, and whoever wants
another step asks for it with :meth:`ViewerState.seek`.
"""

from __future__ import annotations

from asprilo.simulate import Violation

from .document import Change, Document
from .edits import TABLES
from .loading import warnings_said
from .observe import Signal
from .track import Track

#: how long the status bar says that reading a file gave warnings (milliseconds)
WARNINGS_SAID_MS = 15000


class Selection:
    """The robots selected (rings, paths, rows) and the object in focus (its facts)."""

    def __init__(self) -> None:
        self.robots: list[int] = []
        self.focus: tuple[str, int] | None = None
        self.changed = Signal()

    def set(self, robots: list[int], focus: tuple[str, int] | None = None) -> None:
        robots = list(dict.fromkeys(robots))
        focus = focus if focus is not None or not robots else ("robot", robots[0])
        if (robots, focus) != (self.robots, self.focus):
            self.robots, self.focus = robots, focus
            self.changed.emit()


class Session:
    """The online session's state: whether one runs, what it is called, why the last one ended."""

    def __init__(self) -> None:
        self.name = ""
        self.running = False
        self.ended_because: str | None = None  # shown until dismissed
        self.last_reason: str | None = None
        self.changed = Signal()
        self.outgoing = Signal()  # (facts) for the solver: orders written during the session

    def start(self, name: str) -> None:
        self.name, self.running, self.ended_because = name, True, None
        self.changed.emit()

    def end(self, reason: str, note: str = "") -> None:
        """The session is over; ``reason`` (and ``note``) stay shown until dismissed."""
        self.running, self.last_reason = False, reason
        self.ended_because = reason + note
        self.changed.emit()

    def send(self, facts: str) -> None:
        """Send facts (new orders) to the solver with the next step."""
        if self.running:
            self.outgoing.emit(facts)

    def dismiss(self) -> None:
        if self.ended_because is not None:
            self.ended_because = None
            self.changed.emit()


class ViewerState:
    """The document and everything the viewer derives from it or adds to it."""

    def __init__(self) -> None:
        self.document = Document()
        self.selection = Selection()
        self.session = Session()
        self.track: Track | None = None
        self.step = 0
        self.job: str | None = None  # the title of the job that runs
        self.last_error: str | None = None
        self._warned = False  # the status bar says that reading the files shown gave warnings
        self.shown = Signal()           # (keep_time) a new scenario (track rebuilt, or None)
        self.track_changed = Signal()   # (Change) the same scenario, changed: the track is new
        self.step_changed = Signal()    # (step) the clock reached another step
        self.seek_requested = Signal()  # (step) someone wants that step shown
        self.locks_changed = Signal()   # a job or a session started or ended
        self.checked = Signal()         # (violations) the ASP checker's, to show instead of the replay's
        self.said = Signal()            # (text, milliseconds) a passing message
        self.error_reported = Signal()  # (text) something went wrong: a dialog
        self.document.opened.connect(self._opened)
        self.document.changed.connect(self._changed)
        self.session.changed.connect(self.locks_changed.emit)

    # --- the track ------------------------------------------------------------------------------

    def _track(self) -> Track | None:
        scenario = self.document.scenario
        if scenario is None:
            return None
        # without a plan (yet) the goal is no problem: only the instance's own are shown
        unfinished = scenario.unfinished or not len(scenario.plan)
        return Track(scenario.instance, scenario.plan, self.document.domain, unfinished)

    def _opened(self, keep_time: bool) -> None:
        self.track = self._track()
        self.shown.emit(keep_time)
        self._keep_selection()
        self.locks_changed.emit()
        said = warnings_said(self.document.scenario)
        if said is not None:  # the warnings themselves: in the atoms pane
            self.say(said, WARNINGS_SAID_MS)
        elif self._warned:  # those of the files shown before no longer hold
            self.say("", 0)
        self._warned = said is not None

    def _changed(self, change: Change) -> None:
        self.track = self._track()
        self.track_changed.emit(change)
        self._keep_selection()

    def _keep_selection(self) -> None:
        """Drop from the selection what the scenario no longer has."""
        track, focus = self.track, self.selection.focus
        robots = [r for r in self.selection.robots if track is not None and r in track.robot_index]
        if focus is not None and (track is None or focus[1] not in getattr(track.instance, TABLES[focus[0]])
                                  or (focus[0] == "robot" and focus[1] not in robots)):
            focus = None
        self.selection.set(robots, focus)

    # --- time ---------------------------------------------------------------------------------

    def show_step(self, step: int) -> None:
        """The clock shows the state after ``step`` now."""
        self.step = step
        self.step_changed.emit(step)

    def seek(self, step: int) -> None:
        """Ask for the state after ``step`` (playing stops)."""
        self.seek_requested.emit(step)

    # --- what may be edited ----------------------------------------------------------------------

    def begin_job(self, title: str) -> None:
        self.job = title
        self.locks_changed.emit()

    def end_job(self) -> None:
        self.job = None
        self.locks_changed.emit()

    def layout_lock(self) -> str | None:
        """Why the instance's layout cannot be edited now (``None``: it can)."""
        if self.job is not None:
            return f"{self.job.lower()} is running: wait or cancel it (Ctrl+.) to edit"
        if self.session.running:
            return "an online session owns the world: disconnect to edit (new orders go to the solver)"
        return None

    def order_lock(self) -> str | None:
        """Why orders cannot be edited now (during a session they can: they are sent live)."""
        return f"{self.job.lower()} is running: wait or cancel it (Ctrl+.) to edit" if self.job else None

    # --- words for the user ----------------------------------------------------------------------

    def say(self, text: str, milliseconds: int = 5000) -> None:
        self.said.emit(text, milliseconds)

    def report_error(self, text: str) -> None:
        self.last_error = text
        self.error_reported.emit(text)

    def show_checker_report(self, violations: list[Violation]) -> None:
        self.checked.emit(violations)
