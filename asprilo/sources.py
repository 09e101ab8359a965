"""Input sources: files, strings and stdin, turned into ground atoms by clingo.

A source is ASP text with a name for messages.  Text printed by clingo (``Answer: 1``
followed by a line of atoms, ``SATISFIABLE``, statistics) is recognised and reduced to
the facts of its last answer, keeping line numbers so that messages point into the
original text.  Everything read here follows the reading policy (:mod:`asprilo.policy`)
within the limits in force (:mod:`asprilo.limits`).
"""

from __future__ import annotations

import os
import re
import stat
import sys
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

import clingo
import clingo.ast

from . import clingo_logger
from .errors import InputError
from .facts import scan_facts
from .isolation import run_isolated
from .limits import Limits, current
from .policy import BOM, check_statements, decode, screen

clingo_logger.install()

STDIN = "-"
_SHORTEST_FACT = len("init(object(a,1),value(b,1)).")  # the fast scan reads no shorter fact


@dataclass(frozen=True)
class Source:
    """ASP text and the name it is reported under (a path, ``<stdin>`` or ``<string>``)."""

    name: str
    text: str

    @classmethod
    def from_path(cls, path: str | Path, limits: Limits | None = None) -> Source:
        """Read a file (UTF-8, at most ``file-mb`` megabytes); ``-`` reads standard input."""
        if str(path) == STDIN:
            return cls.from_stdin(limits)
        path = Path(path)
        if not path.exists():
            raise InputError("no such file", str(path))
        if path.is_dir():
            raise InputError("is a directory, not a file", str(path))
        try:
            with path.open("rb") as stream:
                return cls(str(path), decode(_read_at_most(stream, limits or current(), str(path)), str(path)))
        except OSError as error:
            raise InputError(error.strerror or "cannot be read", str(path)) from None

    @classmethod
    def from_stdin(cls, limits: Limits | None = None) -> Source:
        if sys.stdin is None or sys.stdin.isatty():
            raise InputError("nothing to read (standard input is a terminal)", "<stdin>")
        stream = getattr(sys.stdin, "buffer", None)
        if stream is None:  # a text stream put in place of stdin (tests)
            return cls("<stdin>", sys.stdin.read())
        return cls("<stdin>", decode(_read_at_most(stream, limits or current(), "<stdin>"), "<stdin>"))


def _read_at_most(stream, limits: Limits, name: str) -> bytes:
    """All bytes of a file or pipe, refused beyond the ``file-mb`` limit (pipes and devices
    are read piece by piece, so an endless one stops at the limit)."""
    most = limits.file_mb * 2**20
    status = os.fstat(stream.fileno())
    if stat.S_ISREG(status.st_mode) and status.st_size <= most:
        data = stream.read()
    else:
        pieces, size = [], 0
        while size <= most and (piece := stream.read(min(1 << 20, most + 1 - size))):
            pieces.append(piece)
            size += len(piece)
        data = b"".join(pieces)
    if len(data) > most:
        raise limits.exceeded("file_mb", f"more than {limits.file_mb:,} MB").at(name)
    return data


SourceLike = str | Path | Source


def as_sources(inputs: SourceLike | Iterable[SourceLike], limits: Limits | None = None) -> list[Source]:
    """Normalise one or several paths / ``-`` / :class:`Source` objects to sources."""
    if isinstance(inputs, (str, Path, Source)):
        inputs = [inputs]
    return [item if isinstance(item, Source) else Source.from_path(item, limits) for item in inputs]


# --- clingo's printed output -------------------------------------------------------------

# clingo prints atoms on lines of their own; every other line (version, "Reading from",
# "Solving...", status words, statistics) starts with an upper-case word or names a version.
_ATOM_LINE = re.compile(r"^(?![\w-]+ version )[a-z_&-]")


def is_clingo_output(text: str) -> bool:
    """Whether ``text`` looks like clingo's printed output rather than a program."""
    return any(
        line.startswith(("Answer:", "SATISFIABLE", "UNSATISFIABLE", "OPTIMUM FOUND", "clingo version"))
        for line in text.splitlines()
    )


def split_atoms(line: str) -> list[str]:
    """Split a line of atoms as clingo prints them (space separated, strings quoted)."""
    atoms, depth, quoted, start = [], 0, False, 0
    for index, char in enumerate(line):
        if quoted:
            quoted = char != '"' or line[index - 1] == "\\"
        elif char == '"':
            quoted = True
        elif char in "([":
            depth += 1
        elif char in ")]":
            depth -= 1
        elif char.isspace() and depth == 0:
            if index > start:
                atoms.append(line[start:index])
            start = index + 1
    if line[start:].strip():
        atoms.append(line[start:].strip())
    return atoms


def answer_facts(text: str, name: str) -> str:
    """Reduce clingo output to the facts of its last answer, one output line per text line."""
    lines = text.splitlines()
    answers = [i for i, line in enumerate(lines) if line.startswith("Answer:")]
    if answers:
        keep = {answers[-1] + 1}
    else:
        keep = {i for i, line in enumerate(lines) if _ATOM_LINE.match(line)}
        if not keep:
            status = next((line.strip() for line in lines if line.strip() in
                           ("UNSATISFIABLE", "UNKNOWN", "INTERRUPTED")), None)
            reason = f" (clingo reported {status})" if status else ""
            raise InputError(f"the clingo output holds no answer{reason}", name)
    out = []
    for i, line in enumerate(lines):
        if i not in keep:
            out.append("")
            continue
        atoms = split_atoms(line.strip())
        out.append(" ".join(atom if atom.endswith(".") else atom + "." for atom in atoms))
    return "\n".join(out)


# --- facts ------------------------------------------------------------------------------

#: a fact as scanned: ``(name, arguments, (source, offset))`` (see :func:`asprilo.facts.scan_facts`)
ScannedFact = tuple[str, tuple, tuple[Source, int]]


def load_facts(sources: Sequence[Source], limits: Limits | None = None
               ) -> tuple[list[ScannedFact] | None, list[clingo.Symbol]]:
    """The sources' facts, scanned directly when they are plain facts (fast), else grounded.

    Returns ``(facts, [])`` with ``facts`` as ``(name, arguments, (source, offset))`` when
    scanning worked, or ``(None, atoms)`` with the ground atoms of the program.
    """
    limits = limits or current()
    scanned: list[ScannedFact] = []
    for source in sources:
        text, room = _program_text(source), limits.facts - len(scanned)
        facts = scan_facts(text, None if len(text) <= _SHORTEST_FACT * room else room)
        if facts is None:
            return None, ground_atoms(sources, limits)
        scanned += [(name, args, (source, offset)) for name, args, offset in facts]
        if len(scanned) > limits.facts:
            raise limits.exceeded("facts", f"more than {limits.facts:,} facts").at(source.name)
    if not scanned:
        return None, ground_atoms(sources, limits)
    return scanned, []


def line_of(source: Source, offset: int) -> tuple[str, int]:
    """``(file, line)`` of a character offset in a source's program text."""
    return source.name, _program_text(source).count("\n", 0, offset) + 1


# --- grounding ---------------------------------------------------------------------------

_LOCATION = re.compile(r"^<block>:(\d+):\d+(?:-\d+(?::\d+)?)?: (?:error|info|warning): (.*)", re.S)


def _program_text(source: Source) -> str:
    text = source.text.removeprefix(BOM)
    return answer_facts(text, source.name) if is_clingo_output(text) else text


def ground_atoms(sources: Sequence[Source], limits: Limits | None = None) -> list[clingo.Symbol]:
    """Ground the ``base`` part of all sources together and return the atoms of its answer.

    Sources hold facts, comments, ``#const`` and ``#program base.``; rules too where the
    limits allow them: they are then grounded in a child process under the limits' time
    and memory, and a program whose rules leave choices open contributes its first answer
    set.  See :mod:`asprilo.policy`.
    """
    limits = limits or current()
    programs = [Source(source.name, _program_text(source)) for source in sources]
    for program in programs:
        screen(program.text, program.name, limits)
        if not limits.allow_rules:
            check_statements(program.text, program.name)
    if limits.allow_rules:
        derived = Source(", ".join(p.name for p in programs), _ground_rules(programs, limits))
        screen(derived.text, derived.name, limits)
        programs = [derived]
    atoms = _ground(programs)
    if len(atoms) > limits.facts:
        raise limits.exceeded("facts", f"{len(atoms):,} atoms").at(programs[0].name if len(programs) == 1 else None)
    return atoms


def _ground_rules(programs: list[Source], limits: Limits) -> str:
    """Ground programs with rules in a child process, stopped after ``rule-seconds`` and
    limited to ``rule-mb``: clingo cannot be stopped while it grounds (``p(X+1) :- p(X).``
    grounds for ever).  The atoms of the first answer come back as fact text."""
    names = ", ".join(program.name for program in programs) or None
    outcome = run_isolated(_atoms_text, ([(p.name, p.text) for p in programs],), time_limit=limits.rule_seconds,
                           memory_mb=limits.rule_mb)
    if outcome.status == "timeout":
        raise limits.exceeded("rule_seconds", "grounding the rules takes longer").at(names)
    if outcome.status == "memout":
        raise limits.exceeded("rule_mb", "grounding the rules needs more memory").at(names)
    if not outcome.done:
        raise InputError(f"grounding the rules failed ({outcome.detail})", names)
    return outcome.value


def _atoms_text(programs: list[tuple[str, str]], report=None) -> str:
    """In the child: the atoms of the first answer of ``programs``, one fact a line."""
    return "".join(f"{atom}.\n" for atom in _ground([Source(name, text) for name, text in programs]))


def _ground(sources: Sequence[Source]) -> list[clingo.Symbol]:
    """Ground and solve in this process (for screened facts, and in a child for rules).

    A Control of its own, not the driver's (:mod:`asprilo.solver` says why): untrusted text
    gets nothing but the ``base`` part and the first answer set."""
    messages: list[str] = []
    control = clingo.Control(["--warn=none"], logger=lambda _code, message: messages.append(message))
    for source in sources:
        messages.clear()
        try:
            control.add("base", [], _program_text(source))
        except RuntimeError:
            raise _clingo_error(messages, source.name) from None
    messages.clear()
    try:
        control.ground([("base", [])])
    except RuntimeError:
        raise _clingo_error(messages, sources[0].name if len(sources) == 1 else None) from None
    with control.solve(yield_=True) as handle:
        for model in handle:
            return list(model.symbols(atoms=True))
    names = ", ".join(source.name for source in sources)
    raise InputError("the program has no answer set (its rules contradict each other)", names)


def _clingo_error(messages: list[str], name: str | None) -> InputError:
    text = clingo_logger.first_error(messages) or "clingo rejected the input"
    match = _LOCATION.match(text)
    if match:
        detail = match.group(2).splitlines()[0]
        return InputError(detail, name, int(match.group(1)))
    return InputError(text.splitlines()[0], name)


# --- finding a fact again ----------------------------------------------------------------

def locate(sources: Sequence[Source], atom: clingo.Symbol | str) -> tuple[str | None, int | None]:
    """Return ``(file, line)`` of the first fact ``atom`` in the sources (for messages)."""
    wanted = str(atom).replace(" ", "")
    for source in sources:
        line = _fact_line(source, wanted)
        if line is not None:
            return source.name, line
    return (sources[0].name if len(sources) == 1 else None), None


def _fact_line(source: Source, wanted: str) -> int | None:
    """The line of the first fact of ``source`` whose text (without spaces) is ``wanted``."""
    found: list[int] = []

    def visit(statement: clingo.ast.AST) -> None:
        if found or statement.ast_type != clingo.ast.ASTType.Rule or statement.body:
            return
        head = statement.head
        if head.ast_type == clingo.ast.ASTType.Literal and str(head).replace(" ", "") == wanted:
            found.append(statement.location.begin.line)

    try:
        clingo.ast.parse_string(_program_text(source), visit, logger=lambda _c, _m: None)
    except (RuntimeError, InputError):
        return None
    return found[0] if found else None
