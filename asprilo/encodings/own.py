"""A user's own encoding: program files in any style people run with clingo, recognised and
made ready for the horizon search.

An encoding is code (DESIGN.md: "Encodings are code, data is data"): it may ``#include``
other files (found next to the including file), use ``#script``, theories and every clingo
option.  What is recognised, and said in the summary of a solve:

- **single-shot**: a ``horizon`` constant; the search grounds it for each horizon from the
  lower bound up (or for ``--horizon H`` / ``-c horizon=H`` only);
- **incremental**: ``#include <incmode>`` or ``#program step(t)`` / ``check(t)`` parts with a
  ``query(t)`` external, solved multi-shot as clingo's incmode does; the parts of clingo 4's
  iclingo (``cumulative(t)``, ``volatile(t)``) are read as ``step(t)`` and ``check(t)``, and
  a ``query(t)`` used without ``#external query(t).`` is declared as clingo 4 did;
- **fixed**: neither: solved once as it is;
- a **theory** from the atoms it uses: ``&diff`` only: clingo-dl; ``&sum``, ``&dom``,
  ``&distinct``...: clingcon 5.

Refused in words: programs for clingcon 3 (``#include <csp>.``, ``$``-constraints), which
clingcon 5 cannot read; options clingo refuses; syntax errors (clingo's message, located);
files that are not there or no files (:mod:`asprilo.paths`).

An encoding is read in a child process under :data:`READ_SECONDS` and :data:`READ_MB`
(:func:`asprilo.isolation.run_isolated`): clingo's parser recurses, and a term nested deep
enough (``p(- - - ... 1)``) crashes the process that parses it; whatever the program, the
command that reads it answers in one sentence.  :func:`program_files` (what ``check --watch``
watches) reads in the calling process with :mod:`.program_scan`, linear and bounded.
"""

from __future__ import annotations

import re
import signal
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import clingo
import clingo.ast
from clingo.ast import ASTType

from asprilo.errors import InputError
from asprilo.paths import included_file, input_file, real, shown
from asprilo.syntax_hint import missing_period

from .program_scan import Scan, scan
from .registry import Encoding

#: the theory atoms clingo-dl reads; every other one is clingcon's
DL_ATOMS = {"diff"}
#: clingo 4's iclingo parts, and the parts of clingo 5's incmode they are read as
ICLINGO_PARTS = {"cumulative": "step", "volatile": "check"}
INCREMENTAL_PARTS = {"step", "check", *ICLINGO_PARTS}

#: the limits of the child process that reads an encoding (its style, its syntax; the memory
#: never above the default limit of a user's encoding, :func:`asprilo.memory.default_memory_mb`)
READ_SECONDS = 60.0
READ_MB = 2048


@dataclass
class _Features:
    """What the statements of a program use."""

    parts: set[tuple[str, int]] = field(default_factory=set)   # (name, number of parameters)
    theory_atoms: set[str] = field(default_factory=set)
    names: set[str] = field(default_factory=set)               # function and constant names in terms
    externals: set[str] = field(default_factory=set)           # predicate names declared #external
    constants: set[str] = field(default_factory=set)           # names given a #const


@dataclass(frozen=True)
class Style:
    """How a program runs: ``incremental``, single-shot with a ``horizon`` constant, or
    ``fixed`` (solved once); its ``theory``; the parts renamed and the text added to run it
    as its author meant, with what was assumed in words."""

    incremental: bool
    horizon: bool
    theory: str | None
    renamed: Mapping[str, str] = field(default_factory=dict)
    additions: str = ""
    assumed: tuple[str, ...] = ()
    csp: bool = False  # it includes <csp> (clingcon 4): left out, clingcon 5 needs no include

    @property
    def fixed(self) -> bool:
        return not self.incremental and not self.horizon

    def describe(self) -> str:
        """The style in words, e.g. ``incremental (step/check/query), clingcon``."""
        if self.incremental:
            words = "incremental (step(t)/check(t), query(t))"
        elif self.horizon:
            words = "single-shot with a horizon constant"
        else:
            words = "fixed (no horizon constant: solved once)"
        theory = {"clingcon": ", clingcon 5", "dl": ", clingo-dl"}.get(self.theory or "", "")
        return words + theory


def own_encoding(paths: Sequence[str | Path], constants: Iterable[tuple[str, str]] = (),
                 options: Sequence[str] = ()) -> Encoding:
    """A user's encoding made of ``paths`` (loaded in this order), with ``-c`` ``constants``
    and clingo ``options``; its style recognised in a child process (see the module
    docstring).  Bad input: :class:`InputError` (a path that names no readable file:
    :class:`asprilo.paths.PathError`)."""
    files = [input_file(path) for path in paths]
    if not files:
        raise InputError("no encoding file given")
    constants = tuple((name, str(value)) for name, value in constants)
    check_options(options)
    from asprilo.isolation import run_isolated  # starting a child costs imports: only here
    from asprilo.memory import default_memory_mb

    memory = min(READ_MB, default_memory_mb())  # never above a limit this process has (ulimit -v)
    outcome = run_isolated(_read_encoding, (files, constants, tuple(options)), time_limit=READ_SECONDS,
                           memory_mb=memory)
    if outcome.done:
        return outcome.value
    reading = outcome.messages[-1] if outcome.messages else files[0]
    raise InputError(_failure(outcome.status, outcome.detail, memory), shown(reading))


def _failure(status: str, detail: str, memory: int) -> str:
    """Why the child that read an encoding (under ``memory`` MB) gave no answer, in words."""
    if status == "timeout":
        return f"clingo's parser took longer than {READ_SECONDS:g} s to read it"
    if status == "memout" and f"signal {signal.SIGSEGV.value}" not in detail:  # (a segfault is a crash)
        return f"clingo's parser needed more than {memory} MB to read it"
    return (f"clingo's parser crashed on it ({detail or 'no reason given'}); a term nested too deep, such as a "
            "long chain of operators, does that")


def _read_encoding(files: list[Path], constants: tuple[tuple[str, str], ...], options: tuple[str, ...],
                   report: Callable[[Path], None]) -> Encoding:
    """The side of the child process: the encoding read, its style recognised (``report``
    names each file before clingo's parser reads it)."""
    program = _program(files)
    for file, scanned in program:
        _refuse_clingcon3(file, scanned)
    system = {include.name for _file, scanned in program for include in scanned.includes if include.system}
    features = _features(program, report)
    style = _style(features, "incmode" in system, "csp" in system)
    given = {name for name, _ in constants}
    if style.incremental and "horizon" in given:
        raise InputError("-c horizon=H is for single-shot encodings; an incremental one takes --horizon H")
    name = "+".join(file.stem for file in files)
    return Encoding(name, None, files[0], style.theory, style.incremental, style.describe(),
                    options=tuple(options), extra=tuple(files[1:]), additions=style.additions,
                    renamed=tuple(style.renamed.items()), constants=constants, own=True, fixed=style.fixed,
                    assumed=style.assumed, dropped=("csp",) if style.csp else ())


def _refuse_clingcon3(path: Path, scanned: Scan) -> None:
    if scanned.csp3_line is not None:
        raise InputError("written for clingcon 3 ('#include <csp>.' and $-constraints such as $<=), which "
                         "clingcon 5 cannot read: state the constraints with &sum{...} and &dom{...} "
                         "(docs/OWN_ENCODINGS.md)", shown(path), scanned.csp3_line)


def check_options(options: Sequence[str]) -> None:
    """Refuse (InputError) clingo options that clingo does not take, in clingo's words."""
    if not options:
        return
    try:
        clingo.Control(list(options))
    except RuntimeError as error:
        message = str(error).replace("In context '<libclingo>': ", "")
        raise InputError(f"clingo refuses the option{'s' * (len(options) > 1)} {' '.join(options)}: "
                         f"{message}") from None


def _features(program: list[tuple[Path, Scan]], report: Callable[[Path], None]) -> _Features:
    """Parse every file of the program (its text without comments and includes) and collect
    what they use; a syntax error is clingo's message, located in its file."""
    features = _Features()
    messages: list[str] = []
    for file, scanned in program:
        messages.clear()
        text = scanned.code or ""
        report(file)
        try:
            clingo.ast.parse_string(text, lambda statement: _collect(statement, features),
                                    logger=lambda _code, message: messages.append(message))
        except RuntimeError:
            raise _located(messages, file, text) from None
    return features


def program_files(paths: Sequence[str | Path]) -> list[Path]:
    """The files of an encoding made of ``paths`` and those they ``#include``, as far as
    they can be read now: a missing file or one that cannot be read is listed, not followed
    (what ``check --watch --encoding`` watches; never an error)."""
    return [file for file, _scanned in _program([Path(path) for path in paths], strict=False)]


def _program(files: list[Path], strict: bool = True) -> list[tuple[Path, Scan]]:
    """The files and, after each, those it includes (``#include "file".``, relative to it),
    each once, with what a scan found in each (``strict``: with the text for clingo's parser;
    an include that names no readable file is an error, else it is listed, not followed)."""
    seen: set[Path] = set()
    program: list[tuple[Path, Scan]] = []
    stack: list[tuple[Path, Path | None, int | None]] = [(file, None, None) for file in reversed(files)]
    while stack:
        file, includer, line = stack.pop()  # an included file: its name, and where it is included
        key = real(file if includer is None else includer.parent / file)
        if key in seen:
            continue
        seen.add(key)
        try:
            if includer is not None:
                included_file(str(file), includer, line)
            scanned = scan(key, keep_code=strict)
        except InputError:
            if strict:
                raise
            program.append((key, Scan()))
            continue
        program.append((key, scanned))
        stack.extend((Path(include.name), key, include.line)
                     for include in reversed(scanned.includes) if not include.system)
    return program


def _located(messages: list[str], file: Path, program: str) -> InputError:
    """clingo's first error message on ``file`` (its text ``program``) as bad input with its
    line, and the hint where a missing ``.`` on the line before is the likely cause."""
    text = next((m for m in messages if ": error:" in m), messages[0] if messages else "syntax error")
    match = re.match(r"^.*?:(\d+):(\d+)(?:-\d+(?::\d+)?)?: error: (.*)", text, re.S)
    if not match:
        return InputError(text.strip().splitlines()[0], shown(file))
    line, column, what = match.groups()
    hint = missing_period(program, int(line), int(column)) or ""
    return InputError(f"column {column}: {' '.join(what.split())}{hint}", shown(file), int(line))


def _collect(statement: clingo.ast.AST, features: _Features) -> None:
    kind = statement.ast_type
    if kind == ASTType.Program:
        features.parts.add((statement.name, len(statement.parameters)))
    elif kind == ASTType.External:
        features.externals.add(_predicate(statement.atom))
    elif kind == ASTType.Definition:
        features.constants.add(statement.name)
    _walk(statement, features)


def _predicate(atom: clingo.ast.AST) -> str:
    symbol = atom.symbol if atom.ast_type == ASTType.SymbolicAtom else atom
    return getattr(symbol, "name", str(symbol))


def _walk(node: clingo.ast.AST, features: _Features) -> None:
    """Collect the theory atoms and the names in terms of ``node`` (iteratively: programs
    may be deep)."""
    stack = [node]
    while stack:
        current = stack.pop()
        kind = current.ast_type
        if kind == ASTType.TheoryAtom:
            features.theory_atoms.add(getattr(current.term, "name", str(current.term)))
        elif kind == ASTType.Function:
            features.names.add(current.name)
        elif kind == ASTType.SymbolicTerm and current.symbol.type == clingo.SymbolType.Function:
            features.names.add(current.symbol.name)
        for key in current.child_keys:
            child = getattr(current, key)
            if isinstance(child, clingo.ast.AST):
                stack.append(child)
            elif child is not None:
                stack.extend(item for item in child if isinstance(item, clingo.ast.AST))


def _style(features: _Features, incmode: bool, csp: bool) -> Style:
    parts = {name for name, arity in features.parts if arity == 1 and name in INCREMENTAL_PARTS}
    incremental = incmode or bool(parts)
    renamed = {old: new for old, new in ICLINGO_PARTS.items() if old in parts}
    assumed = [f"#program {old}(t) read as {new}(t) (clingo 4's iclingo)" for old, new in renamed.items()]
    additions = ""
    if incremental and "query" in features.names and "query" not in features.externals:
        additions = "#program check(t).\n#external query(t).\n"
        assumed.append("query(t) declared #external in check(t), as clingo 4's incmode did")
    if incremental and "query" not in features.names:
        assumed.append("no query(t): nothing ties the goal to the horizon, so the first horizon solved is the answer")
    if csp:
        assumed.append("#include <csp>. left out: clingcon 5 reads &sum/&dom without it (clingcon 4's style)")
    return Style(incremental, not incremental and "horizon" in features.names | features.constants,
                 _theory(features.theory_atoms), renamed, additions, tuple(assumed), csp)


def _theory(atoms: set[str]) -> str | None:
    if not atoms:
        return None
    return "dl" if atoms <= DL_ATOMS else "clingcon"
