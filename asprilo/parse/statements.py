"""The reader of statements: facts, ``#const`` and ``#program base.``, one by one from an
offset; plain facts read from their tokens found at once, anything else token by token;
anything beyond data refused with what it is."""

from __future__ import annotations

import re
from typing import Any

from ..errors import InputError
from ..limits import Limits
from .constants import ConstantReader, find_constants, resolve_constants
from .evaluate import Constant
from .refusals import DATA_ONLY, NotData
from .terms import Fn, Str
from .tokens import _ESCAPE, _LINE_END, _UNESCAPED, _token_name, line_at

# Plain facts, their tokens found at once (Reader._plain): blanks and comments (block
# comments without a '%' inside) before each token; a function's name with its '(', a name
# or variable, a string, a number of up to nine digits (with a '-' right before it: read
# only where an operand belongs, as a negative number), any other character.
_PLAIN_GAP = r"(?:[ \t\r\n]++|%(?!\*)[^\r\n]*+|%\*[^%]*?\*%)*+"
_PLAIN_STRING = r'"(?:[^"\\\r\n]++|\\["\\n])*+"'
_GAP = re.compile(_PLAIN_GAP)
_PLAIN_TOKEN = re.compile(_PLAIN_GAP + r"""(
     [_']*+[a-z][A-Za-z0-9_']*+[ \t\r\n]*+\(
    |[_']*+[A-Za-z][A-Za-z0-9_']*+
    |""" + _PLAIN_STRING + r"""
    |-?(?:0|[1-9][0-9]{0,8})(?![0-9])
    |.)""", re.X | re.S)
#: a statement up to its period, over strings and comments (None: read token by token)
_STATEMENT = re.compile(rf'(?:[^."%]++|{_PLAIN_STRING}|%(?!\*)[^\r\n]*+|%\*[^%]*?\*%)*+\.')
_IDENTIFIER = re.compile(r"[_']*+[a-z][A-Za-z0-9_']*+")
_NUMBER_START, _DIGIT = frozenset("-0123456789"), frozenset("0123456789")
_LEAVES = 10_000  # names a reader keeps made


class Reader(ConstantReader):
    """Reads one text: statements one by one from an offset (:meth:`statement`), within the
    limits and with the constants given."""

    def __init__(self, text: str, name: str, limits: Limits, constants: dict[str, Constant] | None = None,
                 quick: bool = True):
        super().__init__(text, name, limits, constants)
        self.quick = quick  # plain statements through :meth:`_plain` (a test turns it off)
        self._leaves: dict[str, Any] = {}  # the terms of plain tokens, each made once

    # statements ----------------------------------------------------------------------------------

    def statement(self, pos: int) -> tuple[str, Fn | None, int, int] | None:
        """The statement from ``pos`` (blanks and comments first): ``(kind, atom, start, end)``
        with kind ``fact`` (and its atom), ``const`` or ``program``; ``None`` at the end."""
        if self.quick:
            plain = self._plain(pos)
            if plain is not None:
                return plain
        kind, text, start, end = self.token(pos)
        if kind == "e":
            return None
        if kind == "h":
            return self._hash(text, start, end)
        self._start = start
        negative, name_start = False, start
        if kind == "p" and text == "-":
            negative = True
            kind, text, name_start, end = self.token(end)
        if kind != "i" or text == "not":
            raise self._beyond(start, kind, text, name_start)
        name = text
        kind2, text2, start2, end2 = self.token(end)
        if kind2 == "p" and text2 == ".":
            return self._fact(Fn(name, (), negative), start, end2, 0)
        if kind2 == "p" and text2 == "(":
            args, after, extra = self._arguments(end2, start2)
            kind3, text3, start3, end3 = self.token(after)
            if kind3 == "p" and text3 == ".":
                return self._fact(Fn(name, args, negative), start, end3, extra)
            raise self._missing_period(after, kind3, text3, start3) or self._beyond(start, kind3, text3, start3)
        raise self._missing_period(end, kind2, text2, start2) or self._beyond(start, kind2, text2, start2)

    def _missing_period(self, end: int, kind: str, text: str, at: int) -> InputError | None:
        """The error for an atom ending at ``end`` that is followed by the start of the next
        statement (a name, ``-``, a directive) on a later line, or by the end of the text:
        the line where the atom ends lacks its ``.`` (clingo's parser says so only where the
        next statement starts)."""
        starts = kind in ("i", "h", "e") or (kind == "p" and text == "-")
        if not starts or (kind != "e" and _LINE_END.search(self.text, end, at) is None):
            return None
        found = "EOF" if kind == "e" else f"{_token_name(kind, text)} on line {line_at(self.text, at)}"
        return self.error(f"a '.' is missing at the end of this line? (syntax error, unexpected {found})", end)

    def _plain(self, pos: int) -> tuple[str, Fn, int, int] | None:
        """A fact of plain terms only (names, strings, numbers of up to nine digits,
        functions, tuples of two or more; comments between them), read from its tokens
        found at once; ``None`` for anything else (operators, constants, ``#sup``, nested
        comments, ...), which the token-by-token reading reads (:mod:`tests.test_parse`
        checks that both read the same)."""
        text = self.text
        start = _GAP.match(text, pos).end()  # type: ignore[union-attr]
        found = _STATEMENT.match(text, start, min(self.end, start + self.limits.fact_chars))
        if found is None or text.startswith(".", found.end()):
            return None
        end = found.end()
        # up to and with the period: findall then yields every token in a row (a comment
        # right before the period would otherwise end the tokens early and findall go on
        # inside the comment)
        tokens = _PLAIN_TOKEN.findall(text, start, end)
        if not tokens or tokens.pop() != ".":
            return None
        negative = tokens[0] == "-" if tokens else False
        first = tokens[negative] if len(tokens) > negative else "("
        if first[-1] == "(":
            name = first[:-1].rstrip()
            if not _IDENTIFIER.fullmatch(name) or name == "not":
                return None
            args = _plain_arguments(self, tokens, negative + 1)
            return None if args is None else ("fact", Fn(name, args, negative), start, end)
        if len(tokens) == negative + 1 and _IDENTIFIER.fullmatch(first) and first != "not":
            return "fact", Fn(first, (), negative), start, end
        return None

    def _leaf(self, token: str) -> Any:
        """The term of a plain token, or ``None`` when it is not plain (a variable, ``not``,
        a constant, a punctuation mark)."""
        leaf = self._leaves.get(token)
        if leaf is not None:
            return leaf
        if token[0] in _NUMBER_START and token[-1] in _DIGIT:
            return int(token)
        if token[0] == '"':
            if len(token) - 2 > self.limits.string_chars:
                return None
            body = token[1:-1]
            return Str(_ESCAPE.sub(lambda m: _UNESCAPED[m.group(1)], body) if "\\" in body else body)
        if not _IDENTIFIER.fullmatch(token) or token == "not" or token in self.constants:
            return None
        leaf = Fn(token)
        if len(self._leaves) < _LEAVES:  # names repeat (node, at, robot): each made once, up to a bound
            self._leaves[token] = leaf
        return leaf

    def _hash(self, word: str, start: int, end: int) -> tuple[str, None, int, int]:
        """A statement that starts with a directive."""
        if word == "#const":
            return "const", None, start, self.constant_at(start)[-1]
        if word == "#program":
            return "program", None, start, self._program(start, end)
        raise self._directive(word, start)

    def _fact(self, atom: Fn, start: int, end: int, extra: int) -> tuple[str, Fn, int, int]:
        if end - start + extra > self.limits.fact_chars:
            raise self._too_long(start, end - start + extra)
        return "fact", atom, start, end

    def _program(self, start: int, pos: int) -> int:
        kind, name, at, pos = self.token(pos)
        if kind != "i" or name == "not":
            raise self._unexpected(kind, name, at)
        kind, text, at, pos = self.token(pos)
        parameters = False
        if kind == "p" and text == "(":
            kind, text, at, pos = self.token(pos)
            parameters = not (kind == "p" and text == ")")
            if not parameters:
                kind, text, at, pos = self.token(pos)
        if name == "base" and not parameters and kind == "p" and text == ".":
            return pos
        if name != "base" or parameters:
            end = self._statement_end(start)
            what = "has parameters" if name == "base" else "starts a program part other than base"
            raise NotData(f"'{self._excerpt(start, end)}' {what}; {DATA_ONLY}", self.name, line_at(self.text, start))
        raise self._unexpected(kind, text, at)


def _plain_arguments(reader: Reader, tokens: list[str], first: int) -> tuple | None:
    """The arguments of a plain fact from its tokens after ``name(`` (see :meth:`Reader._plain`):
    the frames of open brackets on a stack, ``None`` at the first token that is not plain
    (or where the depth limit is reached: the token-by-token reading says so)."""
    stack: list[tuple[str | None, list]] = []
    name: str | None = ""  # the atom's arguments; a function's name; None for a bracket
    args: list = []
    expect = True
    most, last = reader.limits.depth - 1, len(tokens) - 1
    for index in range(first, last + 1):
        token = tokens[index]
        if expect and token[-1] == "(":
            if len(stack) >= most:
                return None
            stack.append((name, args))
            name, args = (token[:-1].rstrip() if len(token) > 1 else None), []
            if name == "not":  # a keyword, not a name: the token-by-token reading says so
                return None
        elif expect:
            leaf = reader._leaf(token)
            if leaf is None:
                return None
            args.append(leaf)
            expect = False
        elif token == ",":
            expect = True
        elif token != ")" or (name is None and len(args) < 2):
            return None  # (t) and (t,) are read token by token
        elif not stack:
            return tuple(args) if index == last else None
        else:
            term = Fn(name or "", tuple(args))
            name, args = stack.pop()
            args.append(term)
    return None


def parse_terms(text: str, name: str, limits: Limits) -> list[tuple[Fn, int]]:
    """All atoms of a text of facts (with its own constants): ``(atom, offset)``; a helper
    for tests and small texts (the reader goes through :func:`asprilo.facts.scan_facts`)."""
    reader = Reader(text, name, limits)
    reader.constants = resolve_constants(find_constants(reader))
    atoms: list[tuple[Fn, int]] = []
    pos = 0
    while (statement := reader.statement(pos)) is not None:
        _kind, atom, start, pos = statement
        if atom is not None:
            atoms.append((atom, start))
    return atoms
