"""The reading policy for data: what an instance, a plan or an online message may hold,
checked before clingo sees it (README: "Reading data").

- Bytes: UTF-8, a byte-order mark is dropped; other encodings and NUL bytes are refused.
- Text: outside strings and comments only printable ASCII; numbers within clingo's
  32-bit range; terms nested at most ``depth`` deep; never ``#include`` or ``#script``.
- Statements: facts, ``#const`` and ``#program base.``; rules, intervals (``1..N``) and
  pools only with ``allow_rules`` (they are grounded in a child process, under limits).
"""

from __future__ import annotations

import re

import clingo
import clingo.ast

from .errors import InputError
from .limits import Limits

BOM = "\ufeff"
_INT_MAX = 2**31 - 1
_DIRECTIVES = 1000  # statements beyond the facts a file may hold (#const, #program base.)


def decode(data: bytes, name: str) -> str:
    """The text of a file or message: UTF-8 (a leading byte-order mark dropped), no NUL."""
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        line = data.count(b"\n", 0, error.start) + 1
        raise InputError(f"not a UTF-8 text file (byte 0x{data[error.start]:02x} cannot be read)",
                         name, line) from None
    text = text.removeprefix(BOM)
    nul = text.find("\x00")
    if nul >= 0:
        raise InputError("not a text file (it holds a NUL byte)", name, text.count("\n", 0, nul) + 1)
    return text


# --- text --------------------------------------------------------------------------------

#: strings and comments, whose characters clingo reads as they are
_QUOTED = re.compile(r'%\*.*?\*%|%[^\n]*|"(?:[^"\\\n]|\\.)*"', re.S)
_FORBIDDEN = re.compile(r"[^\t\n\r\x20-\x7e]")
_DIRECTIVE = re.compile(r"#\s*(include|script)\b")
_LONG_NUMBER = re.compile(r"\b\d{10,}\b")
_BRACKET = re.compile(r"[()\[\]{}]")
_BRACKETS = {ord(c): None for c in map(chr, range(128)) if c not in "()[]{}"}
#: texts longer than this are measured with numpy (a vectorised running sum)
_VECTORISE = 200_000


def screen(text: str, name: str, limits: Limits) -> None:
    """Refuse text that clingo must not see (see the module docstring)."""
    code = _QUOTED.sub(lambda match: re.sub(r"[^\n]", " ", match.group(0)), text)

    def fail(message: str, offset: int) -> InputError:
        return InputError(message, name, code.count("\n", 0, offset) + 1)

    nul = text.find("\x00")
    if nul >= 0:
        raise fail("not a text file (it holds a NUL byte)", nul)
    if code.count(".") > limits.facts + _DIRECTIVES:
        raise limits.exceeded("facts", f"more than {limits.facts:,} facts").at(name)

    bad = _FORBIDDEN.search(code)
    if bad:
        char = bad.group(0)
        shown = f"'{char}' " if char.isprintable() else ""
        raise fail(f"character {shown}(U+{ord(char):04X}) outside a string or comment", bad.start())
    directive = _DIRECTIVE.search(code)
    if directive:
        raise fail(f"#{directive.group(1)} is not followed in data (give every file on the command line)",
                   directive.start())
    for number in _LONG_NUMBER.finditer(code):
        digits = number.group(0).lstrip("0")
        if len(digits) > 10 or int(digits or "0") > _INT_MAX:
            raise fail(f"the number {_shortened(number.group(0))} is out of range (at most {_INT_MAX})",
                       number.start())
    _check_depth(code, limits, fail)


def _shortened(digits: str) -> str:
    return digits if len(digits) <= 20 else f"{digits[:10]}...{digits[-5:]} ({len(digits)} digits)"


def _check_depth(code: str, limits: Limits, fail) -> None:
    """Refuse brackets nested deeper than the limit (clingo recurses into terms)."""
    offset = _too_deep(code, limits.depth)
    if offset is not None:
        raise fail(limits.exceeded("depth", "terms nested more deeply").message, offset)


def _too_deep(code: str, limit: int) -> int | None:
    """The offset where brackets first nest deeper than ``limit`` (``None``: never)."""
    if len(code) > _VECTORISE:
        import numpy as np
        characters = np.frombuffer(code.encode("ascii"), dtype=np.uint8)
        opens = np.isin(characters, np.frombuffer(b"([{", dtype=np.uint8))
        closes = np.isin(characters, np.frombuffer(b")]}", dtype=np.uint8))
        deep = np.cumsum(opens.astype(np.int64) - closes) > limit
        return int(np.argmax(deep)) if deep.any() else None
    if len(code.translate(_BRACKETS)) <= limit:
        return None  # not even that many brackets in all
    depth = 0
    for bracket in _BRACKET.finditer(code):
        if bracket.group(0) in "([{":
            depth += 1
            if depth > limit:
                return bracket.start()
        else:
            depth -= 1
    return None


# --- statements --------------------------------------------------------------------------

#: text that only rules, intervals, pools and directives other than the allowed ones have
_BEYOND_FACTS = re.compile(r":|\.\.|;|\{|\||#(?!const\b|program\s+base\s*\.)")
_ALLOWED_TERMS = {clingo.ast.ASTType.SymbolicTerm, clingo.ast.ASTType.Function, clingo.ast.ASTType.Variable,
                  clingo.ast.ASTType.UnaryOperation, clingo.ast.ASTType.BinaryOperation}


def check_statements(text: str, name: str) -> None:
    """Refuse anything but facts, ``#const`` and ``#program base.`` (text already screened)."""
    code = _QUOTED.sub('""', text)
    if not _BEYOND_FACTS.search(code):
        return
    refused: list[InputError] = []

    def visit(statement: clingo.ast.AST) -> None:
        if not refused:
            problem = _problem(statement)
            if problem:
                refused.append(InputError(f"{problem}; data holds only facts, #const and '#program base.' "
                                          "(rules need --allow-rules)", name, statement.location.begin.line))

    try:
        clingo.ast.parse_string(text, visit, logger=lambda _code, _message: None)
    except RuntimeError:
        return  # a syntax error: clingo says where when it reads the text
    if refused:
        raise refused[0]


def _problem(statement: clingo.ast.AST) -> str | None:
    """What makes a statement more than a fact, ``#const`` or ``#program base.``"""
    kind = statement.ast_type
    if kind == clingo.ast.ASTType.Program:
        return None if statement.name == "base" and not statement.parameters else f"'#program {statement.name}'"
    if kind == clingo.ast.ASTType.Definition:
        return _term_problem(statement.value)
    head = statement.head if kind == clingo.ast.ASTType.Rule else None
    if head is None or statement.body or head.ast_type != clingo.ast.ASTType.Literal \
            or head.sign != clingo.ast.Sign.NoSign or head.atom.ast_type != clingo.ast.ASTType.SymbolicAtom:
        return f"'{_first_line(statement)}' is a rule"
    return _term_problem(statement.head.atom.symbol)


def _term_problem(term: clingo.ast.AST) -> str | None:
    if term.ast_type == clingo.ast.ASTType.Interval:
        return f"the interval '{term}' stands for many facts"
    if term.ast_type == clingo.ast.ASTType.Pool:
        return f"the pool '{_first_line(term)}' stands for several facts"
    if term.ast_type not in _ALLOWED_TERMS:
        return f"'{_first_line(term)}' is not a plain term"
    for key in term.child_keys:
        children = getattr(term, key)
        for child in [children] if isinstance(children, clingo.ast.AST) else children:
            problem = _term_problem(child)
            if problem:
                return problem
    return None


def _first_line(node: clingo.ast.AST) -> str:
    text = str(node).splitlines()[0] if str(node) else ""
    return text if len(text) <= 60 else text[:57] + "..."
