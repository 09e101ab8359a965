"""What ``check --watch`` runs on every save (:mod:`asprilo.cli.check` makes one when
``--watch`` is given, :func:`asprilo.cli.watching.watch` calls it): :class:`PlanCheck` checks the
plan again, :class:`EncodingSolve` solves again with the student's encoding (in a child process,
cancelled by the next save: :class:`SavedMeanwhile`) and checks the plan found.  Each run
prints a heading, the first violations and the verdict; bad input is one line and the watch
goes on.  A module of its own because a single ``check`` needs none of it.
"""

from __future__ import annotations

import sys
import threading
import time
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, TextIO

from asprilo.checker import Report, check
from asprilo.checker import cli as checker_cli
from asprilo.domain import Domain, detect_domain
from asprilo.errors import InputError, InputWarning
from asprilo.model import Instance, Plan
from asprilo.reader import read_instance, read_instance_and_plan
from asprilo.writer import format_plan, write_text

from .watching import POLL, Stamps

if TYPE_CHECKING:  # the solver is imported where --watch --encoding needs it: a re-check does without
    from asprilo.encodings import Attempt, Encoding, Outcome, Phase

#: clingo's warnings on an encoding shown per run
SHOWN_WARNINGS = 3


def _warned(caught: list[warnings.WarningMessage]) -> list[str]:
    """The reader's warnings of a run, as the command line prints them."""
    return [f"warning: {warning.message}" for warning in caught if issubclass(warning.category, InputWarning)]


class Rerun:
    """What a watch does on every save: ``paths()`` to watch, called with the files changed
    (none: the first run); ``out`` gets its lines."""

    def __init__(self, instance: Path, domain: Domain | None, shown: int, out: TextIO | None = None):
        self.instance, self.domain, self.shown = instance, domain, shown
        self.out = out if out is not None else sys.stdout
        self.variants: list = []  # the --variant files (loaded), applied on every run

    def domain_for(self, instance: Instance, plan: Plan | None = None) -> Domain | None:
        """The domain of a run: ``--domain`` or the one detected, changed by the variants
        (``None``, to be detected by the check, when neither is given)."""
        if not self.variants:
            return self.domain
        from asprilo.domain.variants import with_variants
        return with_variants(self.domain or detect_domain(instance, plan), self.variants)

    def paths(self) -> list[Path]:
        raise NotImplementedError

    def __call__(self, changed: list[Path]) -> None:
        raise NotImplementedError

    def say(self, lines: Sequence[str]) -> None:
        self.out.write("".join(f"{line}\n" for line in lines))
        self.out.flush()

    def heading(self, changed: list[Path], doing: str) -> str:
        """``--- 14:02:31 plan.lp changed: checking ---``."""
        now = time.strftime("%H:%M:%S")
        if not changed:
            what = f"watching {', '.join(map(_shown, self.paths()))} (Ctrl-C ends)"
        else:
            what = f"{', '.join(map(_shown, changed))} changed"
        return f"--- {now} {what}: {doing} ---"

    def report_lines(self, report: Report) -> list[str]:
        """The first violations and the verdict."""
        errors = report.errors
        lines = [error.message for error in errors[:self.shown]]
        if len(errors) > self.shown:
            lines.append(f"... and {len(errors) - self.shown} more (check without --watch lists them all)")
        return lines + [checker_cli.verdict(report, detected=self.domain is None)]


class PlanCheck(Rerun):
    """``check INSTANCE PLAN --watch``: the plan checked again on every save."""

    def __init__(self, instance: Path, plan: Path, domain: Domain | None, shown: int, out: TextIO | None = None):
        super().__init__(instance, domain, shown, out)
        self.plan = plan

    def paths(self) -> list[Path]:
        return list(dict.fromkeys([self.instance, self.plan]))

    def __call__(self, changed: list[Path]) -> None:
        heading = self.heading(changed, "checking")
        with warnings.catch_warnings(record=True) as caught:  # said below the heading, in order
            warnings.simplefilter("always", InputWarning)
            try:
                instance, plan = read_instance_and_plan(str(self.instance), str(self.plan), domain=self.domain)
                report = check(instance, plan, self.domain_for(instance, plan))
            except InputError as error:
                self.say([heading, *_warned(caught), f"error: {error}"])
                return
            except Exception as error:  # noqa: BLE001 - whatever broke, the student's loop goes on
                self.say([heading, *_warned(caught), _unexpected(error)])
                return
        self.say([heading, *_warned(caught), *self.report_lines(report)])


class EncodingSolve(Rerun):
    """``check INSTANCE [PLAN] --watch --encoding FILE...``: solved again (in a child process
    under the time limit) on every save of the instance or the encoding; a solve still
    running when the next save comes is cancelled.

    The solve runs in the watch's own thread, which looks at the files while it waits for the
    child (:class:`SavedMeanwhile`): no other thread, so the child is forked (no start-up)
    and a Ctrl-C meets the watch, which kills the child on its way out."""

    def __init__(self, instance: Path, plan: Path | None, domain: Domain | None, shown: int,
                 encoding: Sequence[str], const: Sequence[str], options: Sequence[str], horizon: int | None,
                 time_limit: float, out: TextIO | None = None, err: TextIO | None = None):
        super().__init__(instance, domain, shown, out)
        self.plan, self.encoding, self.const, self.options = plan, list(encoding), list(const), list(options)
        self.horizon, self.time_limit = horizon, time_limit
        self.err = err if err is not None else sys.stderr

    def paths(self) -> list[Path]:
        from asprilo.encodings.choice import is_encoding_file
        from asprilo.encodings.own import program_files
        return [self.instance, *program_files([value for value in self.encoding if is_encoding_file(value)])]

    def validate(self) -> None:
        """Refuse what no save can mend (clingo's options, -c, a reference name), when the
        instance can be read now (otherwise the first run says what is wrong with it)."""
        try:
            with warnings.catch_warnings():  # the first run says them
                warnings.simplefilter("ignore", InputWarning)
                instance = read_instance(str(self.instance))
            self.choose(self.domain_for(instance) or detect_domain(instance))
        except InputError as error:
            if error.file is None:
                raise

    def choose(self, domain: Domain) -> tuple[Encoding, int | None]:
        from asprilo.encodings.choice import choose_encoding
        return choose_encoding(self.encoding, self.const, self.options, domain, self.horizon)

    def __call__(self, changed: list[Path]) -> None:
        self.say([self.heading(changed, "solving")])
        cancel = SavedMeanwhile(self.paths())
        try:
            lines = self._lines(cancel)
        except InputError as error:
            lines = [f"error: {error}"]
        except Exception as error:  # noqa: BLE001 - whatever broke, the student's loop goes on
            lines = [_unexpected(error)]
        if threading.Event.is_set(cancel):  # set while the solve ran (not looked at now)
            lines = [f"(cancelled: {', '.join(map(_shown, cancel.changed))} changed)"]
        self.say(lines)

    def _lines(self, cancel: threading.Event) -> list[str]:
        from asprilo.encodings import solve
        instance = read_instance(str(self.instance))
        domain = self.domain_for(instance) or detect_domain(instance)
        encoding, horizon = self.choose(domain)
        progress = Progress(self.err)
        try:
            outcome = solve(instance, domain, encoding=encoding, horizon=horizon, time_limit=self.time_limit,
                            isolate=True, cancel=cancel, on_progress=progress.attempt, on_phase=progress.phase)
        finally:
            progress.close()
        from asprilo.encodings.solving.minimality import learn_minimum

        learn_minimum(outcome, instance)  # your encoding's plan above the bound: the problem's minimum, where cheap
        lines = []
        if encoding.own:
            lines.append(f"your encoding: {encoding.summary}")
            lines += [f"  assumed: {note}" for note in encoding.assumed]
            lines += [f"  clingo: {' '.join(warning.split())}" for warning in outcome.warnings[:SHOWN_WARNINGS]]
        return lines + self._outcome_lines(outcome)

    def _outcome_lines(self, outcome: Outcome) -> list[str]:
        if outcome.plan is None or outcome.check is None:
            return _no_plan(outcome, self.time_limit)
        plan = outcome.plan
        from asprilo.encodings.solving.minimality import proof

        said = f" ({proof(outcome)})" if outcome.found else ""
        line = f"plan: horizon {plan.horizon}{said}, {len(plan)} actions"
        if self.plan is not None:
            write_text(self.plan, format_plan(plan), self.paths())
            line += f", written to {self.plan}"
        return [line, *self.report_lines(outcome.check)]


class SavedMeanwhile(threading.Event):
    """The cancel of a solve: set once one of ``paths`` is saved.  The solve asks whether it
    is set about ten times a second while it waits for its child; the files are looked at
    then, at most every ``POLL`` seconds."""

    def __init__(self, paths: Sequence[Path]):
        super().__init__()
        self.stamps = Stamps(paths)
        self.changed: list[Path] = []
        self.looked = time.monotonic()

    def is_set(self) -> bool:
        if not super().is_set() and time.monotonic() - self.looked >= POLL:
            self.looked = time.monotonic()
            self.changed = self.stamps.changed()
            if self.changed:
                self.set()
        return super().is_set()

    def wait(self, timeout: float | None = None) -> bool:
        deadline = None if timeout is None else time.monotonic() + timeout
        while not self.is_set():
            left = POLL if deadline is None else min(POLL, deadline - time.monotonic())
            if left <= 0:
                return False
            super().wait(left)
        return True


class Progress:
    """What the search does, on standard error: a line per horizon tried, and the phase under
    way -- on a terminal on one line redrawn in place, otherwise a line per phase.  (No
    clock redrawn: that would take a thread, and the child is forked only from a process
    that runs none.)"""

    def __init__(self, stream: TextIO):
        self.stream, self.live = stream, stream.isatty()

    def phase(self, phase: Phase) -> None:
        if phase.name in ("grounding", "solving", "assigning"):
            what = "task assignment" if phase.name == "assigning" else f"horizon {phase.horizon}: {phase.name}"
            self._write(f"{what}…" if self.live else what, final=not self.live)

    def attempt(self, attempt: Attempt) -> None:
        note = f" {attempt.note}" if attempt.note else ""
        self._write(f"horizon {attempt.horizon}{note}: {attempt.result} ({attempt.seconds:.2f} s)", final=True)

    def close(self) -> None:
        if self.live:
            self.stream.write("\r\033[K")
            self.stream.flush()

    def _write(self, text: str, final: bool) -> None:
        prefix = "\r\033[K" if self.live else ""
        self.stream.write(prefix + text + ("\n" if final else ""))
        self.stream.flush()


def _no_plan(outcome: Outcome, time_limit: float) -> list[str]:
    """Why there is no plan, in a line (and the horizons refuted)."""
    from asprilo.encodings import SolveStatus
    from asprilo.encodings.solving.minimality import no_plan_headline, refuted_words

    words = {SolveStatus.NONE: no_plan_headline(outcome),
             SolveStatus.LIMIT: f"no plan within the limits ({time_limit:g} s)",
             SolveStatus.CANCELLED: "cancelled", SolveStatus.INVALID: "no valid plan"}.get(outcome.status,
                                                                                       outcome.status.value)
    lines = [words + (f": {outcome.message}" if outcome.message else "")]
    refuted = outcome.refuted
    if refuted and (outcome.trusted or outcome.status is not SolveStatus.NONE):  # (else said by the headline)
        lines.append(refuted_words(outcome, ", ".join(map(str, refuted)), len(refuted) > 1))
    return lines


def _shown(path: Path) -> str:
    """A path for the heading: relative to the working folder when it is in it."""
    if path.is_absolute():
        try:
            return str(path.relative_to(Path.cwd()))
        except ValueError:
            pass
    return str(path)


def _unexpected(error: Exception) -> str:
    return f"error: {type(error).__name__}: {' '.join(str(error).split())}"

