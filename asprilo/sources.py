"""Input sources: files, strings and stdin, read into facts by :mod:`asprilo.parse`.

A source is ASP text with a name for messages.  Text printed by clingo (``Answer: 1``
followed by a line of atoms, ``SATISFIABLE``, statistics) is recognised and reduced to
the facts of its last answer, keeping line numbers so that messages point into the
original text.  Everything read here follows the reading policy (:mod:`asprilo.policy`)
within the limits in force (:mod:`asprilo.limits`): data is parsed, never handed to clingo
as text; only rules that ``--allow-rules`` lets in are, in a child process under limits.
"""

from __future__ import annotations

import os
import re
import stat
import sys
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import clingo

from . import clingo_logger
from .errors import InputError
from .facts import fact_atom, fact_text, scan_facts
from .limits import Limits, StepCounter, current
from .parse import NotData, Reader, check_program_tokens, find_constants, line_at, resolve_constants, shown, to_symbol
from .policy import BOM, decode

clingo_logger.install()

STDIN = "-"


@dataclass(frozen=True)
class Source:
    """ASP text and the name it is reported under (a path, ``<stdin>`` or ``<string>``)."""

    name: str
    text: str

    @classmethod
    def from_path(cls, path: str | Path, limits: Limits | None = None) -> Source:
        """Read a file (UTF-8, at most ``file-mb`` megabytes); ``-`` reads standard input.
        Only regular files are read: a FIFO, a device or a socket is refused (a FIFO would
        wait for a writer for ever; pipe data in through ``-``)."""
        if str(path) == STDIN:
            return cls.from_stdin(limits)
        path = Path(path)
        try:
            descriptor = os.open(path, os.O_RDONLY | os.O_NONBLOCK)  # opening a FIFO does not wait
        except FileNotFoundError:
            raise InputError("no such file", str(path)) from None
        except IsADirectoryError:
            raise InputError("is a directory, not a file", str(path)) from None
        except OSError as error:
            raise InputError(error.strerror or "cannot be read", str(path)) from None
        try:
            mode = os.fstat(descriptor).st_mode
            if stat.S_ISDIR(mode):
                raise InputError("is a directory, not a file", str(path))
            if not stat.S_ISREG(mode):
                raise InputError(f"is {_file_kind(mode)}, not a regular file (give data on standard input as -)",
                                 str(path))
            os.set_blocking(descriptor, True)
            with os.fdopen(descriptor, "rb") as stream:
                descriptor = -1
                return cls(str(path), decode(_read_at_most(stream, limits or current(), str(path)), str(path)))
        except OSError as error:
            raise InputError(error.strerror or "cannot be read", str(path)) from None
        finally:
            if descriptor >= 0:
                os.close(descriptor)

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


def _file_kind(mode: int) -> str:
    for test, words in ((stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISCHR, "a character device"),
                        (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return words
    return "no regular file"


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
_OUTPUT_WORDS = ("Answer:", "SATISFIABLE", "OPTIMUM FOUND", "clingo version")  # (UNSATISFIABLE too)
_OUTPUT_START = re.compile("|".join(_OUTPUT_WORDS).replace("SATISFIABLE", "(?:UN)?SATISFIABLE"))
_OUTPUT_LINE = re.compile(f"[\r\n](?:{_OUTPUT_START.pattern})")
_LINES = re.compile(r"\r\n|\r|\n")
#: what matters in a line of atoms: strings (escapes skipped), brackets, blanks
_ATOM_PIECE = re.compile(r'"(?:[^"\\]++|\\.)*+"?|[()\[\]]|\s++')


def is_clingo_output(text: str) -> bool:
    """Whether ``text`` looks like clingo's printed output rather than a program."""
    if not any(word in text for word in _OUTPUT_WORDS):  # (fast: most data holds none of them)
        return False
    return _OUTPUT_START.match(text) is not None or _OUTPUT_LINE.search(text) is not None


def split_atoms(line: str) -> list[str]:
    """Split a line of atoms as clingo prints them (space separated, strings quoted)."""
    atoms, depth, start = [], 0, 0
    for piece in _ATOM_PIECE.finditer(line):
        text = piece.group()
        if text in ("(", "["):
            depth += 1
        elif text in (")", "]"):
            depth -= 1
        elif text[0].isspace() and depth == 0:
            if piece.start() > start:
                atoms.append(line[start:piece.start()])
            start = piece.end()
    if line[start:].strip():
        atoms.append(line[start:].strip())
    return atoms


def answer_facts(text: str, name: str) -> str:
    """Reduce clingo output to the facts of its last answer, one output line per text line."""
    lines = _LINES.split(text)
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

#: a fact as read: ``(kind, arguments, (source, offset))`` (see :func:`asprilo.facts.scan_facts`)
ScannedFact = tuple[str, Any, tuple[Source, int]]


def load_facts(sources: Sequence[Source], limits: Limits | None = None,
               names: set[str] | None = None, steps: StepCounter | None = None) -> list[ScannedFact]:
    """The facts of the sources, read together (a ``#const`` of one applies to all):
    ``(kind, arguments, (source, offset))`` as :func:`asprilo.facts.scan_facts` gives them,
    atoms of other names than ``names`` (when given) left out; ``steps`` counts the actions
    against ``robot-steps`` as they are read.

    Sources hold facts, comments, ``#const`` and ``#program base.``; rules too where the
    limits allow them (``--allow-rules``): they are then grounded in a child process under
    the limits' time and memory, and a program whose rules leave choices open contributes
    its first answer set.
    """
    limits = limits or current()
    programs = [Source(source.name, _program_text(source)) for source in sources]
    try:
        constants = resolve_constants([definition for program in programs
                                       for definition in find_constants(Reader(program.text, program.name, limits))])
        facts: list[ScannedFact] = []
        for source, program in zip(sources, programs, strict=True):
            found = scan_facts(program.text, source.name, limits, constants, names, limits.facts - len(facts),
                               steps=steps)
            scanned: list[Any] = found  # given their origin in place: a plan may hold a million
            for index, (kind, args, offset) in enumerate(found):
                scanned[index] = (kind, args, (source, offset))
            facts += scanned
        return facts
    except NotData:
        if not limits.allow_rules:
            raise
    derived = Source(", ".join(p.name for p in programs), _ground_rules(programs, limits))
    found = scan_facts(derived.text, derived.name, limits, None, names, steps=steps)
    return [(kind, args, (derived, offset)) for kind, args, offset in found]


def line_of(source: Source, offset: int) -> tuple[str, int]:
    """``(file, line)`` of a character offset in a source's program text."""
    return source.name, line_at(_program_text(source), offset)


def _program_text(source: Source) -> str:
    text = source.text.removeprefix(BOM)
    return answer_facts(text, source.name) if is_clingo_output(text) else text


def ground_atoms(sources: Sequence[Source], limits: Limits | None = None) -> list[clingo.Symbol]:
    """The atoms of the sources as clingo symbols (each once), read as :func:`load_facts`
    reads them (no clingo but for rules that ``--allow-rules`` lets in)."""
    symbols = (to_symbol(fact_atom(kind, args)) for kind, args, _origin in load_facts(sources, limits))
    return list(dict.fromkeys(symbols))


# --- rules, on purpose (--allow-rules) -----------------------------------------------------------

_LOCATION = re.compile(r"^<block>:(\d+):\d+(?:-\d+(?::\d+)?)?: (?:error|info|warning): (.*)", re.S)


def _ground_rules(programs: list[Source], limits: Limits) -> str:
    """Ground programs with rules in a child process, stopped after ``rule-seconds`` and
    limited to ``rule-mb``: clingo cannot be stopped while it grounds (``p(X+1) :- p(X).``
    grounds for ever).  Their text is checked first (:func:`asprilo.parse.check_program_tokens`:
    every token as clingo reads it, never ``#include`` or ``#script``).  The atoms of the
    first answer come back as fact text, which is parsed like any data."""
    from .isolation import run_isolated  # multiprocessing: only for rules (reading facts never needs it)

    checked = [(p.name, check_program_tokens(p.text, p.name, limits)) for p in programs]
    names = ", ".join(program.name for program in programs) or None
    outcome = run_isolated(_atoms_text, (checked,), time_limit=limits.rule_seconds, memory_mb=limits.rule_mb)
    if outcome.status == "timeout":
        raise limits.exceeded("rule_seconds", "grounding the rules takes longer").at(names)
    if outcome.status == "memout":
        raise limits.exceeded("rule_mb", "grounding the rules needs more memory").at(names)
    if not outcome.done:
        raise InputError(f"grounding the rules failed ({outcome.detail})", names)
    return outcome.value


def _atoms_text(programs: list[tuple[str, str]], report=None) -> str:
    """In the child: the atoms of the first answer of ``programs``, one fact a line."""
    return "".join(f"{atom}.\n" for atom in _ground(programs))


def _ground(programs: list[tuple[str, str]]) -> list[clingo.Symbol]:
    """Ground and solve checked program text, in the child process of :func:`_ground_rules`.

    A Control of its own, not the driver's (:mod:`asprilo.solver` says why): rules from
    data get nothing but the ``base`` part and the first answer set."""
    messages: list[str] = []
    control = clingo.Control(["--warn=none"], logger=lambda _code, message: messages.append(message))
    for name, text in programs:
        messages.clear()
        try:
            control.add("base", [], text)
        except RuntimeError:
            raise _clingo_error(messages, name) from None
    messages.clear()
    try:
        control.ground([("base", [])])
    except RuntimeError:
        raise _clingo_error(messages, programs[0][0] if len(programs) == 1 else None) from None
    with control.solve(yield_=True) as handle:
        for model in handle:
            return list(model.symbols(atoms=True))
    names = ", ".join(name for name, _text in programs)
    raise InputError("the program has no answer set (its rules contradict each other)", names)


def _clingo_error(messages: list[str], name: str | None) -> InputError:
    text = clingo_logger.first_error(messages) or "clingo rejected the input"
    match = _LOCATION.match(text)
    if match:
        detail = match.group(2).splitlines()[0]
        return InputError(shown(detail, 200), name, int(match.group(1)))
    return InputError(shown(text.splitlines()[0], 200), name)


# --- finding a fact again ----------------------------------------------------------------

def locate(sources: Sequence[Source], atom: clingo.Symbol | str) -> tuple[str | None, int | None]:
    """Return ``(file, line)`` of the first fact ``atom`` in the sources (for messages)."""
    wanted = str(atom).replace(" ", "")
    try:
        facts = load_facts(sources)
    except InputError:
        facts = []
    for kind, args, (source, offset) in facts:
        if fact_text(kind, args) == wanted:
            return line_of(source, offset)
    return (sources[0].name if len(sources) == 1 else None), None
