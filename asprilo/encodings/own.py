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
clingcon 5 cannot read; options clingo refuses; syntax errors (clingo's message, located).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import clingo
import clingo.ast
from clingo.ast import ASTType

from asprilo.errors import InputError
from asprilo.syntax_hint import missing_period

from .registry import Encoding

#: the theory atoms clingo-dl reads; every other one is clingcon's
DL_ATOMS = {"diff"}
#: clingo 4's iclingo parts, and the parts of clingo 5's incmode they are read as
ICLINGO_PARTS = {"cumulative": "step", "volatile": "check"}
INCREMENTAL_PARTS = {"step", "check", *ICLINGO_PARTS}

#: strings and comments, which say nothing of a program's style
_QUOTED = re.compile(r'%\*.*?\*%|%[^\n]*|"(?:[^"\\\n]|\\.)*"', re.S)
_CSP = re.compile(r"#include\s*<csp>\s*\.")
_CSP3 = re.compile(r"\$(?:<=|>=|!=|<|>|=|\+|\*|-|\w)")
_INCMODE = re.compile(r"#include\s*<incmode>\s*\.")
_INCLUDES = re.compile(r'#include\s*(?:"[^"]*"|<[^>]*>)\s*\.')
_INCLUDED = re.compile(r'#include\s*"([^"]*)"\s*\.')


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
    and clingo ``options``; its style recognised (bad input: :class:`InputError`)."""
    files = [_existing(Path(path)) for path in paths]
    if not files:
        raise InputError("no encoding file given")
    program = _program_files(files)
    codes = {file: _code(_text(file)) for file in program}
    for file, code in codes.items():
        _refuse_clingcon3(file, code)
    constants = tuple((name, str(value)) for name, value in constants)
    check_options(options)
    features = _features(program)
    style = _style(features, any(_INCMODE.search(code) for code in codes.values()),
                   any(_CSP.search(code) for code in codes.values()))
    given = {name for name, _ in constants}
    if style.incremental and "horizon" in given:
        raise InputError("-c horizon=H is for single-shot encodings; an incremental one takes --horizon H")
    name = "+".join(file.stem for file in files)
    return Encoding(name, None, files[0], style.theory, style.incremental, style.describe(),
                    options=tuple(options), extra=tuple(files[1:]), additions=style.additions,
                    renamed=tuple(style.renamed.items()), constants=constants, own=True, fixed=style.fixed,
                    assumed=style.assumed, dropped=("csp",) if style.csp else ())


def _existing(path: Path) -> Path:
    if not path.exists():
        raise InputError("no such file", str(path))
    if not path.is_file():
        raise InputError("is not a file", str(path))
    return path


def _text(path: Path) -> str:
    try:
        return path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise InputError("not a UTF-8 text file", str(path)) from None


def _code(text: str) -> str:
    """``text`` without its strings and comments."""
    return _QUOTED.sub(" ", text)


def _uncommented(text: str) -> str:
    """``text`` without its comments (strings kept)."""
    return _QUOTED.sub(lambda match: match.group(0) if match.group(0).startswith('"') else " ", text)


def _refuse_clingcon3(path: Path, code: str) -> None:
    match = _CSP3.search(code)
    if match:
        line = code.count("\n", 0, match.start()) + 1
        raise InputError("written for clingcon 3 ('#include <csp>.' and $-constraints such as $<=), which "
                         "clingcon 5 cannot read: state the constraints with &sum{...} and &dom{...} "
                         "(docs/OWN_ENCODINGS.md)", str(path), line)


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


def _features(program: list[Path]) -> _Features:
    """Parse every file of the program (the given ones and those they include) and collect
    what they use; a syntax error is clingo's message, located in its file."""
    features = _Features()
    messages: list[str] = []
    for file in program:
        messages.clear()
        text = _INCLUDES.sub(lambda match: "\n" * match.group(0).count("\n"), file.read_text(encoding="utf-8"))
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
    return _program_files([Path(path) for path in paths], strict=False)


def _program_files(files: list[Path], strict: bool = True) -> list[Path]:
    """The files and, after each, those it includes (``#include "file".``, relative to it),
    each once (``strict``: a missing file is an error)."""
    seen: list[Path] = []
    stack: list[tuple[Path, Path | None]] = [(file, None) for file in reversed(files)]
    while stack:
        file, includer = stack.pop()
        file = file.resolve()
        if file in seen:
            continue
        seen.append(file)
        try:
            if not file.is_file():
                raise InputError(f"#include of a missing file {str(file)!r}", str(includer or file))
            text = _uncommented(_text(file))
        except (InputError, OSError):
            if strict:
                raise
            continue
        stack.extend((file.parent / name, file) for name in reversed(_INCLUDED.findall(text)))
    return seen


def _located(messages: list[str], file: Path, program: str) -> InputError:
    """clingo's first error message on ``file`` (its text ``program``) as bad input with its
    line, and the hint where a missing ``.`` on the line before is the likely cause."""
    text = next((m for m in messages if ": error:" in m), messages[0] if messages else "syntax error")
    match = re.match(r"^.*?:(\d+):(\d+)(?:-\d+(?::\d+)?)?: error: (.*)", text, re.S)
    if not match:
        return InputError(text.strip().splitlines()[0], str(file))
    line, column, what = match.groups()
    hint = missing_period(program, int(line), int(column)) or ""
    return InputError(f"column {column}: {' '.join(what.split())}{hint}", str(file), int(line))


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
