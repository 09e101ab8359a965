"""The clingo driver: one wrapper around ``clingo.Control`` for the tools' programs.

It loads programs and facts, registers the clingcon or clingo-dl theory when a program
needs one, grounds and solves program parts step by step (multi-shot), stops a solve call
after a wall-clock limit or a number of conflicts, takes assumptions, and reports
statistics.  Models come back as symbols.  The generator, the checker, the reference
encodings and their search (``asprilo solve``, and through it the online planner and the
benchmark runs), the task assignment, the bounds' scheduling relaxations
(:mod:`asprilo.bounds.delivery`, :mod:`asprilo.bounds.trip`) and the anytime planner's
task assignment go through it.

Two places build a ``clingo.Control`` of their own, on purpose:

- :mod:`asprilo.sources` grounds *untrusted* input (instances and plans as read): its
  control has its own narrow contract (the ``base`` part of screened text, the first answer
  set, messages located in the reader's terms, in a child process under limits when rules
  are allowed) and none of the driver's features (``#include`` resolved from files,
  theories, constants), which must not reach data;
- the anytime planner's router (``asprilo/encodings/anytime/router.py``) grounds and solves a tiny
  program per routing call, hundreds of them per plan: the driver's bookkeeping (a solve in
  a thread of its own to keep the time limit, statistics, the ``#include`` check of the
  program file) adds about 0.8 ms to a call of about 20 ms, measured on the paper's
  19x9 instances; the router needs none of it.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path
from typing import TYPE_CHECKING, cast

import clingo

from . import clingo_logger
from .errors import InputError
from .paths import included_file, input_file, real

if TYPE_CHECKING:
    import tempfile

    import clingo.ast  # imported where a program is rewritten (a theory, renamed parts): a check needs none

clingo_logger.install()

Part = tuple[str, Sequence[clingo.Symbol | int | str]]

#: Options each theory needs here (see DESIGN.md: clingcon answered UNSAT on satisfiable
#: A/B/C programs unless translation of pseudo-Boolean constraints is switched off).
_THEORY_OPTIONS = {"clingcon": {"translate-pb": "0"}, "dl": {}}


class Status(str, Enum):
    SAT = "sat"
    UNSAT = "unsat"
    UNKNOWN = "unknown"  # stopped by the time limit before an answer was found


@dataclass
class Statistics:
    """Accumulated over all ground and solve calls of a :class:`Solver`."""

    ground_time: float = 0.0
    solve_time: float = 0.0
    rules: int = 0
    atoms: int = 0
    choices: int = 0
    conflicts: int = 0
    models: int = 0

    def as_dict(self) -> dict[str, float | int]:
        return dict(self.__dict__)


@dataclass
class Result:
    """The outcome of one solve call."""

    status: Status
    symbols: list[clingo.Symbol] = field(default_factory=list)
    assignment: dict[str, int] = field(default_factory=dict)  # theory variables (clingcon / dl)
    cost: list[int] = field(default_factory=list)
    optimal: bool = False  # the optimisation was proven (for programs with #minimize)
    timed_out: bool = False
    exhausted: bool = False  # the search space was exhausted (every model seen, or the optimum proven)

    @property
    def satisfiable(self) -> bool:
        return self.status is Status.SAT


def _theory(name: str | None):
    if name is None:
        return None
    if name == "clingcon":
        from clingcon import ClingconTheory
        return ClingconTheory()
    if name == "dl":
        from clingodl import ClingoDLTheory
        return ClingoDLTheory()
    raise ValueError(f"unknown theory {name!r} (use 'clingcon' or 'dl')")


def _symbol(value: clingo.Symbol | int | str) -> clingo.Symbol:
    if isinstance(value, clingo.Symbol):
        return value
    return clingo.Number(value) if isinstance(value, int) else clingo.parse_term(str(value))


_LOCATION = re.compile(r"^(.*?):(\d+):\d+(?:-\d+(?::\d+)?)?: (?:error|info|warning): (.*)", re.S)


#: an ``#include "file".`` directive, wherever it stands (several on a line, after code); one in
#: a comment is rewritten too (harmlessly), and one whose file cannot be used is left to clingo
_INCLUDE = re.compile(r'#include[ \t]*"([^"\n]+)"[ \t]*\.')


def _hint(message: str, name: str) -> str:
    """The hint for a syntax error in the file ``name`` that a missing ``.`` on the line
    before causes (:func:`asprilo.syntax_hint.missing_period`), or nothing."""
    where = re.match(r"^.*?:(\d+):(\d+)(?:-\d+(?::\d+)?)?: error: syntax error", message)
    if where is None or not Path(name).is_file():
        return ""
    from .syntax_hint import missing_period
    try:
        text = Path(name).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return ""
    return missing_period(text, int(where.group(1)), int(where.group(2))) or ""


def _one_line(message: str) -> str:
    """clingo's message on one line: an unsafe rule's lines, and which variable is unsafe,
    joined (at most 300 characters)."""
    parts = [line.strip() for line in message.splitlines() if line.strip()]
    parts = [re.sub(r"^\S*:\d+:\d+(?:-\d+(?::\d+)?)?: note: ", "", part) for part in parts]
    text = " ".join(parts)
    return text if len(text) <= 300 else text[:297] + "..."


class Solver:
    """A clingo ``Control`` with a theory (``"clingcon"``, ``"dl"`` or none) and statistics.

    ``options`` are clingo command-line options (e.g. ``["--seed=3"]``); ``constants``
    become ``-c name=value``.
    """

    def __init__(self, theory: str | None = None, options: Iterable[str] = (),
                 constants: Mapping[str, int | str] | None = None):
        self.messages: list[str] = []
        arguments = [*options, *(f"-c{name}={value}" for name, value in (constants or {}).items())]
        self.control = clingo.Control(arguments, logger=self._log)
        self.theory = _theory(theory)
        if theory is not None:  # _theory made one (or refused the name)
            self.theory.register(self.control)
            for key, value in _THEORY_OPTIONS[theory].items():
                self.theory.configure(key, value)
        self.stats = Statistics()
        self._prepared = False
        self._copies: tempfile.TemporaryDirectory | None = None
        self._originals: dict[str, str] = {}  # a copy of a program file (see _loadable) -> the file

    def _log(self, _code: clingo.MessageCode, message: str) -> None:
        for copy, original in self._originals.items():
            message = message.replace(copy, original)
        self.messages.append(message)

    def _error(self, default_name: str) -> InputError:
        text = clingo_logger.first_error(self.messages) or "clingo rejected the program"
        self.messages.clear()
        match = _LOCATION.match(text)
        if not match:
            return InputError(text.splitlines()[0], default_name)
        name = default_name if match.group(1) in ("<string>", "<block>") else match.group(1)
        return InputError(_one_line(match.group(3)) + _hint(text, name), name, int(match.group(2)))

    # --- programs ------------------------------------------------------------------------

    def load(self, path: str | Path, renamed: Mapping[str, str] | None = None, dropped: Sequence[str] = ()) -> None:
        """Load a program file (all of its ``#program`` parts; ``renamed`` parts, old name ->
        new name, under their new names; ``#include <name>.`` of the ``dropped`` names left out).

        ``#include "file".`` is resolved here, next to the including file: clingo itself
        looks in the working directory first, where a user's own ``core.lp`` would win.
        """
        path = input_file(path)
        loaded = self._loadable(path, {}, tuple(dropped))
        self.messages.clear()
        try:
            if self.theory is None and not renamed:
                self.control.load(str(loaded))
            else:
                from clingo.ast import ProgramBuilder, parse_files
                with ProgramBuilder(self.control) as builder:
                    parse_files([str(loaded)], self._adder(builder, renamed), logger=self._log)
        except RuntimeError:
            raise self._error(str(path)) from None

    def _loadable(self, path: Path, done: dict[Path, Path], dropped: tuple[str, ...] = ()) -> Path:
        """``path`` itself, or -- when it includes files -- a copy whose ``#include "file".``
        directives name the files by absolute path, next to the including file (clingo would
        look in the working directory first), so that clingo still reads every file and names
        it in its messages; a copy is made for every included file that includes others (or
        one of the ``dropped`` system includes)."""
        path = real(path)
        if path in done:
            return done[path]
        original = path.read_text(encoding="utf-8")
        text = original
        if dropped:
            text = re.sub(r"#include\s*<(?:" + "|".join(map(re.escape, dropped)) + r")>\s*\.", "", original)
        if text == original and not _INCLUDE.search(text):
            done[path] = path
            return path
        if self._copies is None:
            import tempfile  # here: only a program that includes files is copied
            self._copies = tempfile.TemporaryDirectory(prefix="asprilo-program-")
        copy = Path(self._copies.name) / f"{len(self._originals)}-{path.name}"
        done[path] = copy
        self._originals[str(copy)] = str(path)

        def absolute(match: re.Match) -> str:
            try:
                target = real(included_file(match.group(1), path))
            except InputError:  # in a comment, or said by the reading of the encoding already
                return match.group(0)
            return f'#include "{self._loadable(target, done, dropped)}".'

        copy.write_text(_INCLUDE.sub(absolute, text), encoding="utf-8")
        return copy

    def _adder(self, builder: clingo.ast.ProgramBuilder,
               renamed: Mapping[str, str] | None) -> Callable[[clingo.ast.AST], None]:
        """What adds a parsed statement: renamed (its part), rewritten for the theory."""
        add = builder.add if self.theory is None else (lambda s: self.theory.rewrite_ast(s, builder.add))
        if not renamed:
            return add

        def rename(statement: clingo.ast.AST) -> None:
            if statement.ast_type == clingo.ast.ASTType.Program and statement.name in renamed:
                statement = statement.update(name=renamed[statement.name])
            add(statement)

        return rename

    def add(self, text: str, part: str = "base", parameters: Sequence[str] = (),
            name: str = "<string>", renamed: Mapping[str, str] | None = None) -> None:
        """Add program text to ``part`` (the text may switch parts with ``#program``;
        ``renamed`` as in :meth:`load`)."""
        self.messages.clear()
        try:
            if self.theory is None and not renamed:
                self.control.add(part, list(parameters), text)
            else:
                from clingo.ast import ProgramBuilder, parse_string
                header = f"#program {part}({','.join(parameters)}).\n" if parameters else f"#program {part}.\n"
                with ProgramBuilder(self.control) as builder:
                    parse_string(header + text, self._adder(builder, renamed), logger=self._log)
        except RuntimeError:
            raise self._error(name) from None

    def add_facts(self, facts: Iterable[clingo.Symbol | str], part: str = "base") -> None:
        """Add ground facts (symbols or their text) to ``part``."""
        self.add("".join(f"{fact}.\n" for fact in facts), part)

    def ground(self, parts: Iterable[Part] = (("base", ()),), context: object | None = None) -> None:
        """Ground program parts, e.g. ``[("step", [3])]``."""
        symbols = [(name, [_symbol(value) for value in values]) for name, values in parts]
        self.messages.clear()
        started = time.perf_counter()
        try:
            self.control.ground(symbols, context=context)
        except RuntimeError:
            raise self._error("<program>") from None
        self.stats.ground_time += time.perf_counter() - started
        self._prepared = False

    def assign_external(self, atom: clingo.Symbol | str, value: bool | None) -> None:
        """Set an ``#external`` atom to true, false, or free (``None``)."""
        self.control.assign_external(_symbol(atom), value)

    def release_external(self, atom: clingo.Symbol | str) -> None:
        self.control.release_external(_symbol(atom))

    # --- solving -------------------------------------------------------------------------

    def solve(self, time_limit: float | None = None,
              assumptions: Sequence[tuple[clingo.Symbol, bool]] = (),
              on_model: Callable[[clingo.Model], None] | None = None,
              shown: bool = True, conflicts: int | None = None,
              stop_waiting: Callable[[], bool] | None = None) -> Result:
        """Solve the grounded program; stop after ``time_limit`` seconds of wall-clock time
        or ``conflicts`` conflicts (a budget that is the same on every machine).  With
        ``stop_waiting``, a search that has found no model by ``time_limit`` goes on until it
        finds one or ``stop_waiting()`` is true (asked every 0.2 s).

        The result holds the last model found (the best one when optimising), its shown
        atoms (all atoms with ``shown=False``) and the theory assignment.
        """
        if self.theory is not None and not self._prepared:
            self.theory.prepare(self.control)
            self._prepared = True
        result = Result(Status.UNKNOWN)
        solve_options = cast(clingo.Configuration, self.control.configuration.solve)  # a group, not a value
        solve_options.solve_limit = "umax" if conflicts is None else str(conflicts)

        def record(model: clingo.Model) -> None:
            if self.theory is not None:
                self.theory.on_model(model)
                result.assignment = {str(name): value for name, value
                                     in self.theory.assignment(model.thread_id)}
            result.symbols = list(model.symbols(shown=True) if shown else model.symbols(atoms=True))
            result.cost = list(model.cost)
            result.status = Status.SAT
            self.stats.models += 1
            if on_model is not None:
                on_model(model)

        on_statistics = self.theory.on_statistics if self.theory is not None else None
        started = time.perf_counter()
        with self.control.solve(assumptions=list(assumptions), on_model=record,
                                on_statistics=on_statistics, async_=True) as handle:
            finished = handle.wait(time_limit) if time_limit is not None else handle.wait()
            while not finished and stop_waiting is not None and result.status is not Status.SAT \
                    and not stop_waiting():
                finished = handle.wait(0.2)
            if not finished:
                handle.cancel()
                result.timed_out = True
            outcome = handle.get()
        self.stats.solve_time += time.perf_counter() - started
        if outcome.unsatisfiable and not result.timed_out:
            result.status = Status.UNSAT
        result.exhausted = outcome.exhausted and not result.timed_out
        result.optimal = bool(result.cost) and result.exhausted
        self._collect_statistics()
        return result

    def _collect_statistics(self) -> None:
        stats = self.control.statistics
        if not stats or "problem" not in stats:
            return
        program = stats["problem"].get("lp", {})
        self.stats.rules = int(program.get("rules", 0))
        self.stats.atoms = int(program.get("atoms", 0))
        solvers = stats["solving"]["solvers"]  # this call's figures; the program's are cumulative
        self.stats.choices += int(solvers.get("choices", 0))
        self.stats.conflicts += int(solvers.get("conflicts", 0))
