"""The one parser of data: the fact language SPEC.md §2-3 allows, read without clingo.

Instances, plans, solver answers and online messages are text from strangers.  They are
read here, token by token, into terms; clingo never sees their text (DESIGN.md: "Encodings
are code, data is data").  What is read:

- **Tokens** as clingo 5.8's lexer makes them: identifiers ``[_']*[a-z][A-Za-z0-9_']*``
  (``not`` is a keyword), variables ``[_']*[A-Z][A-Za-z0-9_']*`` and ``_`` (refused:
  data is ground), numbers (decimal ``0`` or ``[1-9][0-9]*``, ``0x…``, ``0o…``, ``0b…``),
  strings (``"…"`` with the escapes ``\\"``, ``\\\\`` and ``\\n`` only, on one line),
  ``#sup``/``#supremum``, ``#inf``/``#infimum``, the directives ``#const`` and
  ``#program``, punctuation and operators; comments ``%`` to the end of the line, ``#!``
  likewise, ``%* … *%`` (nested, and a ``%`` inside one comments out the rest of its
  line, as in clingo); blanks are space, tab and line ends: LF, CRLF and CR (clingo ends
  a line at LF only: a ``%`` comment in a file with CR line ends would run to the end of
  the file there, here it ends at the CR).
- **Statements**: facts ``[-]name[(term, …)].``, ``#const name = term.`` and
  ``#program base.``.  Anything else (rules, ``#show``, intervals, pools, variables, other
  program parts) is refused with a message that says what it is; ``#include`` and
  ``#script`` are never followed.
- **Terms**: numbers, strings, ``#sup``/``#inf``, constants, functions ``f(t, …)`` (``f()``
  is ``f``), tuples ``()``, ``(t,)``, ``(t, u)`` (a trailing comma allowed), ``(t)`` is
  ``t``, and arithmetic evaluated as clingo does: unary ``-`` (on a function or tuple it
  flips the sign: ``-a``, ``-(1,2)``), ``~``, ``|t|``, and binary ``^`` < ``?`` < ``&`` <
  ``+ -`` < ``* / \\`` < ``**`` (right-associative), unary operators binding tightest
  (``-2**2`` is 4).  ``/`` and ``\\`` truncate towards zero, ``x**-n`` is 0.
- **Refused where clingo is silent**: a number beyond 32 bits (clingo wraps ``0xFFFFFFFF``
  to -1 and ``2147483648`` to -2147483648; ``-2147483648`` itself is read), arithmetic
  whose result leaves 32 bits (clingo wraps it), and undefined arithmetic (division by
  zero, ``0**-1``, arithmetic on a term that is not a number: clingo leaves the fact out
  with an info message).  Each is an :class:`InputError` located at its line.
- **Constants**: ``#const`` values are found first (a quick pass over strings and comments
  only, in texts that contain ``#const`` at all), then resolved in the order they use each
  other (a cycle or a second definition is refused), then put in place while the facts
  are read, with the arithmetic around them evaluated.  As in clingo, a constant applies
  to every text read together and may be used before its definition.

Budgets (:mod:`asprilo.limits`): ``depth`` (brackets nested in a statement, constants
written out), ``string-chars`` (characters of one string as written) and ``fact-chars``
(characters of one statement, constants written out); nothing here recurses (explicit
stacks), so 20,000 operators in a row or 500 nested brackets cost time in proportion
only.

Terms are Python values: ``int`` for numbers, :class:`Fn` for functions, constants and
tuples (name ``""``), :class:`Str` for strings, :data:`SUP` and :data:`INF`;
:func:`text_of` writes one as clingo does, :func:`to_symbol` makes a ``clingo.Symbol`` and
:func:`python_value` the value :func:`asprilo.facts.value_of` makes of that symbol.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any, cast

import clingo

from .errors import InputError
from .limits import Limits

INT_MIN, INT_MAX = -(2**31), 2**31 - 1


# --- terms -----------------------------------------------------------------------------------------

class Fn:
    """A function term ``name(args)``: a constant has no arguments, a tuple the name ``""``;
    ``negative`` for ``-name(args)``."""

    __slots__ = ("name", "args", "negative")

    def __init__(self, name: str, args: tuple = (), negative: bool = False):
        self.name = name
        self.args = args
        self.negative = negative

    def __repr__(self) -> str:
        return f"Fn({shown(text_of(self), 80)})"


class Str:
    """A string term (its value, escapes resolved)."""

    __slots__ = ("value",)

    def __init__(self, value: str):
        self.value = value

    def __repr__(self) -> str:
        return f"Str({shown(text_of(self), 80)})"


class Special:
    """``#sup`` or ``#inf``."""

    __slots__ = ("text",)

    def __init__(self, text: str):
        self.text = text

    def __repr__(self) -> str:
        return self.text


SUP, INF = Special("#sup"), Special("#inf")
Term = int | Fn | Str | Special



class _Big(Special):
    """The literal 2147483648 (``text`` as written), read only as the operand of a unary
    minus (-2147483648)."""

    __slots__ = ()


def quoted(value: str) -> str:
    """A string's value written as clingo writes it."""
    return '"' + value.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'


def text_of(term: Term) -> str:
    """The term written as clingo writes it (``str`` of its symbol)."""
    if type(term) is int:
        return str(term)
    out: list[str] = []
    stack: list[Any] = [term]
    while stack:
        item = stack.pop()
        kind = type(item)
        if kind is str:  # a piece of text pushed below
            out.append(item)
        elif kind is int:
            out.append(str(item))
        elif kind is Fn:
            sign = "-" if item.negative else ""
            if not item.args:
                out.append(sign + (item.name or "()"))
                continue
            stack.append(",)" if not item.name and len(item.args) == 1 else ")")
            for index in range(len(item.args) - 1, -1, -1):
                stack.append(item.args[index])
                if index:
                    stack.append(",")
            out.append(sign + item.name + "(")
        elif kind is Str:
            out.append(quoted(item.value))
        else:
            out.append(item.text)
    return "".join(out)


def to_symbol(term: Term) -> clingo.Symbol:
    """The term as a ``clingo.Symbol`` (built bottom-up, without recursion)."""
    if type(term) is not Fn:
        return _leaf_symbol(term)
    # post-order: (term, its arguments' symbols so far)
    stack: list[tuple[Fn, list[clingo.Symbol]]] = [(term, [])]
    while True:
        node, done = stack[-1]
        if len(done) < len(node.args):
            child = node.args[len(done)]
            if type(child) is Fn and child.args:
                stack.append((child, []))
            else:
                done.append(_leaf_symbol(child))
            continue
        stack.pop()
        symbol = clingo.Function(node.name, done, not node.negative)
        if not stack:
            return symbol
        stack[-1][1].append(symbol)


def _leaf_symbol(term: Term) -> clingo.Symbol:
    kind = type(term)
    if kind is int:
        return clingo.Number(term)  # type: ignore[arg-type]
    if kind is Str:
        return clingo.String(term.value)  # type: ignore[union-attr]
    if kind is Fn:
        return clingo.Function(term.name, [], not term.negative)  # type: ignore[union-attr]
    return clingo.Supremum if term is SUP else clingo.Infimum


def python_value(term: Term) -> Any:
    """The term as :func:`asprilo.facts.value_of` makes its symbol: numbers -> int, tuples ->
    tuple, constants -> their name, anything else -> its text."""
    kind = type(term)
    if kind is int:
        return term
    if kind is not Fn or term.negative or (term.name and term.args):  # type: ignore[union-attr]
        return text_of(term)
    if term.name:  # type: ignore[union-attr]
        return term.name  # type: ignore[union-attr]
    args = term.args  # type: ignore[union-attr]
    if all(type(arg) is int for arg in args):
        return args
    # nested tuples, without recursion: (tuple term, values of its arguments so far)
    stack: list[tuple[Fn, list[Any]]] = [(term, [])]  # type: ignore[list-item]
    while True:
        node, done = stack[-1]
        if len(done) < len(node.args):
            child = node.args[len(done)]
            if type(child) is Fn and not child.name and child.args and not child.negative:
                stack.append((child, []))
            else:
                done.append(python_value(child))
            continue
        stack.pop()
        value = tuple(done)
        if not stack:
            return value
        stack[-1][1].append(value)


def from_symbol(symbol: clingo.Symbol) -> Term:
    """A ``clingo.Symbol`` as a term (the inverse of :func:`to_symbol`)."""
    kind = symbol.type
    if kind == clingo.SymbolType.Number:
        return symbol.number
    if kind == clingo.SymbolType.String:
        return Str(symbol.string)
    if kind == clingo.SymbolType.Supremum:
        return SUP
    if kind == clingo.SymbolType.Infimum:
        return INF
    stack: list[tuple[clingo.Symbol, list[Term]]] = [(symbol, [])]
    while True:
        node, done = stack[-1]
        arguments = node.arguments
        if len(done) < len(arguments):
            child = arguments[len(done)]
            if child.type == clingo.SymbolType.Function and child.arguments:
                stack.append((child, []))
            else:
                done.append(from_symbol(child))
            continue
        stack.pop()
        term = Fn(node.name, tuple(done), node.negative)
        if not stack:
            return term
        stack[-1][1].append(term)


# --- messages ------------------------------------------------------------------------------------------

def shown(text: str, most: int = 60) -> str:
    """Text fit for a one-line message: at most ``most`` characters (``...`` where cut) and
    no control character raw (``\\x1b``, ``\\n``, ``\\u202e`` instead)."""
    if len(text) > most:
        text = text[:max(most - 3, 1)] + "..."
    if not text.isprintable():
        text = "".join(char if char.isprintable() else char.encode("unicode_escape").decode("ascii")
                       for char in text)
    return text


def line_at(text: str, offset: int) -> int:
    """The line (from 1) of a character offset; lines end with LF, CRLF or CR."""
    offset = max(0, min(offset, len(text)))
    lines = text.count("\n", 0, offset) + 1
    returns = text.count("\r", 0, offset)
    if returns:
        lines += returns - text.count("\r\n", 0, offset)
    return lines


#: what every refusal of a statement that is more than data ends with
DATA_ONLY = "data holds only facts, #const and '#program base.' (rules need --allow-rules)"


class NotData(InputError):
    """A statement that is more than data (a rule, a directive, an interval, a pool, a
    variable, a program part other than ``base``): read only with ``--allow-rules``."""

    def __reduce__(self):
        return NotData, (self.message, self.file, self.line)


# --- tokens -------------------------------------------------------------------------------------------

# A token, blanks before it skipped; the group says which kind:
#   p punctuation and operators, i identifier, n number, s string (its opening quote),
#   c comment (its %), h '#' word or '#!', v variable, e end of text, x anything else
_TOKEN = re.compile(r"""[ \t\r\n]*+(?:
     (?P<p>\*\*|\.\.|:-|:~|[(),.|+\-*/\\&?^~;:{}\[\]=<>!@$])
    |(?P<i>[_']*+[a-z][A-Za-z0-9_']*+)
    |(?P<n>0x[0-9A-Fa-f]++|0o[0-7]++|0b[01]++|0|[1-9][0-9]*+)
    |(?P<s>")
    |(?P<c>%)
    |(?P<h>\#!|\#[A-Za-z0-9_]*+)
    |(?P<v>[_']*+[A-Z][A-Za-z0-9_']*+|_)
    |(?P<e>\Z)
    |(?P<x>.)
)""", re.X | re.S)
#: a string's body (possessive: no backtracking state, whatever its length)
_STRING_BODY = re.compile(r'(?:[^"\\\r\n]++|\\["\\n])*+')
_ESCAPE = re.compile(r'\\(["\\n])')
_UNESCAPED = {'"': '"', "\\": "\\", "n": "\n"}
_LINE_REST = re.compile(r"[^\r\n]*+")
_IN_BLOCK = re.compile(r"%\*|\*%|%")
_LINE_END = re.compile(r"[\r\n]")
#: where the quick pass for #const looks: strings, comments and directives
_CONST_SCAN = re.compile(r'["%#]')
_DIGITS = {"0x": (16, 8), "0o": (8, 11), "0b": (2, 32)}  # base, most significant digits in 32 bits

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

#: binary operators: precedence, function (unary operators bind tighter than all: 7)
_XOR, _OR, _AND, _ADD, _MUL, _POW, _UNARY = 1, 2, 3, 4, 5, 6, 7
_PRECEDENCE = {"^": _XOR, "?": _OR, "&": _AND, "+": _ADD, "-": _ADD, "*": _MUL, "/": _MUL, "\\": _MUL,
               "**": _POW}
_RANGE = "clingo's numbers are 32-bit: -2147483648..2147483647"

#: directives clingo knows that data never holds (messages name them)
_NESTING = {"(": 1, "[": 1, "{": 1, ")": -1, "]": -1, "}": -1}
#: words of rule bodies and aggregates
_IN_BODIES = {"#true", "#false", "#count", "#sum", "#min", "#max"}
_DIRECTIVES = {"#show", "#external", "#minimize", "#minimise", "#maximize", "#maximise", "#heuristic",
               "#project", "#edge", "#defined", "#theory", "#true", "#false", "#count", "#sum", "#min",
               "#max", "#disjoint"}


def _token_name(kind: str | None, text: str) -> str:
    """A token as clingo's syntax errors name it (never the data itself)."""
    if kind == "e":
        return "EOF"
    if text == ",":
        return '","'
    if kind == "i":
        return "not" if text == "not" else "<IDENTIFIER>"
    if kind == "n":
        return "<NUMBER>"
    if kind == "s":
        return "<STRING>"
    if kind == "v":
        return "<VARIABLE>"
    if kind == "h":
        known = text in _DIRECTIVES or text in _SUPREMUM or text in ("#const", "#program", "#include", "#script")
        return text if known else "#"
    return text


@dataclass(frozen=True)
class Constant:
    """A ``#const`` as resolved: its value, its length written out, its depth."""

    value: Term
    length: int
    depth: int


@dataclass(frozen=True)
class ConstantDefinition:
    """A ``#const name = term.`` as found: where its value stands."""

    name: str
    reader: Reader
    start: int  # the statement
    value_start: int
    value_end: int  # the final period


class Reader:
    """Reads one text: statements one by one from an offset (:meth:`statement`), within the
    limits and with the constants given."""

    def __init__(self, text: str, name: str, limits: Limits, constants: dict[str, Constant] | None = None,
                 quick: bool = True):
        self.text = text
        self.name = name
        self.limits = limits
        self.constants = constants or {}
        self.end = len(text)
        self._start = 0  # the statement being read (for messages)
        self.quick = quick  # plain statements through :meth:`_plain` (a test turns it off)
        self._leaves: dict[str, Any] = {}  # the terms of plain tokens, each made once
        self._peeked: tuple[int, Any] = (-1, None)  # the last token read: (from, token)

    # errors ----------------------------------------------------------------------------------------

    def error(self, message: str, offset: int) -> InputError:
        return InputError(message, self.name, line_at(self.text, offset))

    def _unexpected(self, kind: str | None, text: str, offset: int, expecting: str = "") -> InputError:
        return self.error(f"syntax error, unexpected {_token_name(kind, text)}{expecting}", offset)

    # tokens ----------------------------------------------------------------------------------------

    def token(self, pos: int) -> tuple[str, str, int, int]:
        """The next token from ``pos``, blanks and comments skipped: ``(kind, text, start, end)``
        (for a string, ``text`` is its value).  Raises :class:`InputError` for what clingo's
        lexer refuses."""
        if pos == self._peeked[0]:  # read ahead before (after a name: is a '(' next?)
            return self._peeked[1]
        match = cast(re.Match, _TOKEN.match(self.text, pos))  # (the last alternative matches any character)
        while True:
            kind = cast(str, match.lastgroup)
            start = match.start(kind)
            if kind == "c" or (kind == "h" and match.group("h") == "#!"):
                match = cast(re.Match, _TOKEN.match(self.text, self._comment_end(start)))
                continue
            break
        token: tuple[str, str, int, int]
        if kind == "s":
            value, end = self._string(start)
            token = ("s", value, start, end)
        elif kind == "x":
            raise self._stray(start)
        else:
            token = (kind, match.group(kind), start, match.end())
        self._peeked = (pos, token)
        return token

    def _stray(self, offset: int) -> InputError:
        char = self.text[offset]
        if char == "'":
            return self.error("lexer error, unexpected '", offset)
        shown_char = f"'{char}' " if char.isprintable() else ""
        return self.error(f"character {shown_char}(U+{ord(char):04X}) outside a string or comment", offset)

    def _comment_end(self, start: int) -> int:
        """The end of the comment at ``start`` (``%``, ``#!`` or ``%*``)."""
        text = self.text
        if not text.startswith("%*", start):
            return _LINE_REST.match(text, start).end()  # type: ignore[union-attr]
        depth, pos = 1, start + 2
        while depth:
            found = _IN_BLOCK.search(text, pos)
            if found is None:
                raise self.error("the comment '%*' is never closed ('*%')", start)
            token = found.group()
            if token == "%":
                rest = _LINE_END.search(text, found.end())
                if rest is None:
                    raise self.error("the comment '%*' is never closed ('*%')", start)
                pos = rest.end()
                continue
            depth += 1 if token == "%*" else -1
            pos = found.end()
        return pos

    def _string(self, start: int) -> tuple[str, int]:
        """A string's value and end; its opening quote is at ``start``."""
        text, most = self.text, self.limits.string_chars
        limit = min(self.end, start + 1 + most)
        end = _STRING_BODY.match(text, start + 1, limit).end()  # type: ignore[union-attr]
        next_char = text[end] if end < self.end else ""
        if next_char == '"':
            body = text[start + 1:end]
            return (_ESCAPE.sub(lambda m: _UNESCAPED[m.group(1)], body) if "\\" in body else body), end + 1
        escape = next_char == "\\" and text[end + 1:end + 2] in ('"', "\\", "n")
        if escape or (end == limit < self.end and next_char not in "\r\n"):  # the limit cut the string
            raise self.error(self.limits.exceeded("string_chars", f"a string of more than {most:,} characters")
                             .message, start)
        if next_char == "\\":
            raise self.error(f"lexer error, the escape '\\{shown(text[end + 1:end + 2] or ' ', 1)}' in a string "
                             '(strings know \\", \\\\ and \\n)', end)
        raise self.error("lexer error, a string that does not end on its line", start)

    def _number(self, text: str, offset: int) -> int | Special:
        base, most = _DIGITS.get(text[:2], (10, 10))
        digits = text[2:].lstrip("0") if base != 10 else text
        if len(digits) <= most:
            value = int(digits or "0", base)
            if value <= INT_MAX:
                return value
            if value == INT_MAX + 1:
                return _Big(text)
        shortened = text if len(text) <= 20 else f"{text[:10]}...{text[-5:]} ({len(text):,} digits)"
        return self._out_of_range(shortened, offset)

    def _out_of_range(self, number: str, offset: int):
        raise self.error(f"the number {number} is out of range (at most {INT_MAX})", offset)

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
        tokens = _PLAIN_TOKEN.findall(text, start, end - 1)
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

    def _directive(self, word: str, start: int) -> InputError:
        if word in _SUPREMUM:
            return self._unexpected("h", word, start)
        if word in ("#include", "#script"):
            return self.error(f"{word} is not followed in data (give every file on the command line)", start)
        if word in _DIRECTIVES:
            end = self._statement_end(start)
            return NotData(f"'{self._excerpt(start, end)}' is a directive; {DATA_ONLY}", self.name,
                           line_at(self.text, start))
        return self.error(f"lexer error, unexpected {shown(word, 20)}" if word != "#" else "lexer error, unexpected #",
                          start)

    # constants ----------------------------------------------------------------------------------

    def constant_at(self, start: int) -> tuple[str, int, int, int]:
        """The ``#const`` at ``start``: ``(name, value start, its period, end)``."""
        kind, name, at, pos = self.token(self.token(start)[3])
        if kind != "i" or name == "not":
            raise self._unexpected(kind, name, at)
        kind, text, at, pos = self.token(pos)
        if kind != "p" or text != "=":
            raise self._unexpected(kind, text, at, ", expecting =")
        value_start = pos
        depth = 0
        while True:  # to the period that ends the value (checked when the value is read)
            kind, text, at, pos = self.token(pos)
            if kind == "e" or (kind == "p" and text == "." and depth == 0):
                break
            if kind == "h" and text in ("#include", "#script"):
                raise self._directive(text, at)
            if kind == "p" and text == "(":
                depth += 1
            elif kind == "p" and text == ")":
                depth -= 1
            if pos - start > self.limits.fact_chars:
                raise self._too_long(start, pos - start)
        if kind == "e":
            raise self._unexpected(kind, text, at)
        return name, value_start, at, pos

    def references(self, start: int, end: int) -> Iterator[str]:
        """The names used as constants (identifiers without arguments) in ``[start, end)``."""
        pos = start
        previous: str | None = None
        while pos < end:
            kind, text, _at, pos = self.token(pos)
            if previous is not None and not (kind == "p" and text == "("):
                yield previous
            previous = text if kind == "i" else None
        if previous is not None:
            yield previous

    def constant_value(self, definition: ConstantDefinition) -> Constant:
        """The value of a ``#const`` (the constants it uses already resolved)."""
        self._start = definition.start
        value, pos, extra, depth = self._expression(definition.value_start, None)
        kind, text, at, _end = self.token(pos)
        if at != definition.value_end:
            raise self._unexpected(kind, text, at)
        length = definition.value_end - definition.value_start + extra
        if length > self.limits.fact_chars:
            message = self.limits.exceeded("fact_chars", f"the constant {definition.name} written out "
                                                         f"({length:,} characters)").message
            raise self.error(message, definition.start)
        return Constant(value, length, depth)

    # terms ----------------------------------------------------------------------------------------

    def _arguments(self, pos: int, opening: int) -> tuple[tuple, int, int]:
        """The arguments of an atom whose ``(`` is before ``pos``: ``(arguments, end, extra)``."""
        value, end, extra, _depth = self._expression(pos, opening)
        return value.args, end, extra

    def _expression(self, pos: int, opening: int | None) -> tuple[Any, int, int, int]:
        """Read terms from ``pos`` with an explicit stack of open brackets (:class:`_Terms`);
        ``opening`` is the offset of an atom's ``(`` (its arguments are read, up to its
        ``)``) or ``None`` (one term, up to the ``.`` after it, which is not consumed).
        Returns ``(term, end, extra, depth)``: ``extra`` is what constants add to the length
        written out, ``depth`` the deepest nesting (for an atom, its own bracket counted)."""
        return _Terms(self, pos, opening).read()

    def _too_long(self, start: int, size: int) -> InputError:
        what = f"a statement of more than {self.limits.fact_chars:,} characters"
        return self.error(self.limits.exceeded("fact_chars", what).message, start)

    def _too_deep(self, offset: int) -> InputError:
        return self.error(self.limits.exceeded("depth", "terms nested more deeply").message, offset)

    def _checked(self, value: Any, offset: int) -> Any:
        if type(value) is _Big:
            self._out_of_range(value.text, offset)
        return value

    # arithmetic ----------------------------------------------------------------------------------

    def _apply(self, operator: tuple[int, str, int], vals: list) -> None:
        precedence, symbol, offset = operator
        if precedence == _UNARY:
            vals.append(self._unary(symbol, vals.pop(), offset))
            return
        right = vals.pop()
        left = vals.pop()
        if type(left) is not int or type(right) is not int:
            self._checked(left, offset)
            self._checked(right, offset)
            raise self._undefined(f"{self._operand(left)}{symbol}{self._operand(right)}",
                                  "arithmetic needs numbers", offset)
        result = _ARITHMETIC[symbol](self, left, right, offset)
        if not INT_MIN <= result <= INT_MAX:
            raise self._overflow(f"{left}{symbol}{right}", offset)
        vals.append(result)

    def _divide(self, left: int, right: int, offset: int, symbol: str = "/") -> int:
        if right == 0:
            raise self._undefined(f"{left}{symbol}{right}", "division by zero", offset)
        quotient = abs(left) // abs(right)  # truncated towards zero, as in C
        return -quotient if (left < 0) != (right < 0) else quotient

    def _remainder(self, left: int, right: int, offset: int) -> int:
        return left - right * self._divide(left, right, offset, "\\")

    def _power(self, base: int, exponent: int, offset: int) -> int:
        if exponent < 0:
            if base == 0:
                raise self._undefined(f"{base}**{exponent}", "zero to a negative power", offset)
            return 0  # as clingo: the integer part, 0 even for 1**-1
        if base in (0, 1):
            return base if exponent else 1
        if base == -1:
            return -1 if exponent % 2 else 1
        if exponent >= 32:
            raise self._overflow(f"{base}**{exponent}", offset)
        return base**exponent

    def _unary(self, symbol: str, value: Any, offset: int) -> Any:
        kind = type(value)
        if kind is int:
            if symbol == "~":
                return ~value
            if value == INT_MIN:
                raise self._overflow(f"-({value})", offset)
            return -value
        if type(value) is _Big and symbol == "-":
            return INT_MIN
        self._checked(value, offset)
        if kind is Fn and symbol == "-":
            return Fn(value.name, value.args, not value.negative)
        raise self._undefined(f"{symbol}{self._operand(value)}", "arithmetic needs numbers", offset)

    def _absolute(self, value: Any, offset: int) -> int:
        if type(value) is not int:
            self._checked(value, offset)
            raise self._undefined(f"|{self._operand(value)}|", "arithmetic needs numbers", offset)
        if value == INT_MIN:
            raise self._overflow(f"|{value}|", offset)
        return abs(value)

    def _operand(self, value: Any) -> str:
        text = text_of(value)
        return text if type(value) is int else shown(text, 30)

    def _undefined(self, what: str, why: str, offset: int) -> InputError:
        return self.error(f"{what} is undefined ({why}; clingo would leave the fact out)", offset)

    def _overflow(self, what: str, offset: int) -> InputError:
        return self.error(f"{what} is out of range ({_RANGE}; clingo would wrap it around)", offset)

    # what a statement is, when it is no fact --------------------------------------------------------

    def _beyond_term(self, at: int, kind: str | None, text: str, expecting: str = "") -> InputError:
        return self._beyond(self._start, kind, text, at, expecting)

    def _beyond(self, start: int, kind: str | None, text: str, at: int, expecting: str = "") -> InputError:
        """The error for the statement at ``start`` that goes wrong at ``at``: what it is
        when it is more than data (:class:`NotData`), else a syntax error."""
        found = self._classify(start)
        if found is None:
            if kind == "v":
                found = ("variable", self._statement_end(start))
            else:
                return self._unexpected(kind, text, at, expecting)
        what, end = found
        excerpt = self._excerpt(start, end)
        message = {"rule": f"'{excerpt}' is a rule",
                   "directive": f"'{excerpt}' is a directive",
                   "interval": f"'{excerpt}' holds an interval (..), which stands for many facts",
                   "pool": f"'{excerpt}' holds a pool (;), which stands for several facts",
                   "variable": f"'{excerpt}' holds a variable"}[what]
        return NotData(f"{message}; {DATA_ONLY}", self.name, line_at(self.text, start))

    def _classify(self, start: int) -> tuple[str, int] | None:
        """What the statement at ``start`` is beyond a fact, if anything: ``(what, end)``."""
        pos, first = start, True
        depth = 1 if self.text.startswith("#const", start) else 0  # (a ';' there is a pool)
        found: set[str] = set()
        most = start + self.limits.fact_chars
        while True:
            kind, text, at, pos = self.token(pos)
            if kind == "e" or pos > most or (kind == "p" and text == "."):
                break
            depth += _NESTING.get(text, 0) if kind == "p" else 0
            what = self._what(kind, text, at, depth, first)
            if what is not None:
                found.add(what)
            first = False
        for what in ("rule", "directive", "interval", "pool", "variable"):
            if what in found:
                return what, pos
        return None

    def _what(self, kind: str, text: str, at: int, depth: int, first: bool) -> str | None:
        """What a token makes its statement beyond a fact, if anything."""
        if kind == "v":
            return "variable"
        if kind == "h":
            if text in ("#include", "#script"):
                raise self._directive(text, at)
            return None if text not in _DIRECTIVES else "rule" if text in _IN_BODIES else "directive"
        if kind != "p":
            return None
        if text in (":-", ":~", "{", ":") or (text in (";", "|") and depth <= 0) or (text == "&" and first):
            return "rule"
        return "interval" if text == ".." else "pool" if text == ";" else None

    def _statement_end(self, start: int) -> int:
        pos = start
        most = start + self.limits.fact_chars
        while True:
            kind, text, _at, pos = self.token(pos)
            if kind == "e" or (kind == "p" and text == ".") or pos > most:
                return pos

    def _excerpt(self, start: int, end: int) -> str:
        return shown(" ".join(self.text[start:min(end, start + 400)].split()), 60)


_ARITHMETIC = {
    "+": lambda _reader, a, b, _at: a + b,
    "-": lambda _reader, a, b, _at: a - b,
    "*": lambda _reader, a, b, _at: a * b,
    "/": Reader._divide,
    "\\": Reader._remainder,
    "**": Reader._power,
    "&": lambda _reader, a, b, _at: a & b,
    "?": lambda _reader, a, b, _at: a | b,
    "^": lambda _reader, a, b, _at: a ^ b,
}
_SUPREMUM = {"#sup": SUP, "#supremum": SUP, "#inf": INF, "#infimum": INF}


class _Frame:
    """An open bracket: ``kind`` ``a`` (an atom's arguments), ``f`` (a function's), ``(``,
    ``|`` (absolute value) or ``t`` (the top of a #const value, no bracket); the arguments
    read, and the operators and values of the argument being read."""

    __slots__ = ("kind", "name", "opening", "args", "ops", "vals", "comma")

    def __init__(self, kind: str, name: str, opening: int):
        self.kind = kind
        self.name = name
        self.opening = opening
        self.args: list = []
        self.ops: list[tuple[int, str, int]] = []
        self.vals: list = []
        self.comma = False  # a comma was read: (t,) is a tuple


class _Terms:
    """Terms read token by token with an explicit stack of open brackets (no recursion):
    operands and operators alternate, operators waiting on a stack until one of lower
    precedence, a comma or a closing bracket comes (see :meth:`Reader._expression`)."""

    def __init__(self, reader: Reader, pos: int, opening: int | None):
        self.reader = reader
        self.pos = pos
        top = _Frame("a", "", opening) if opening is not None else _Frame("t", "", pos)
        self.frames = [top]
        self.frame = top
        self.base = 0 if opening is not None else 1  # a #const value's top is no bracket
        self.deepest = 1 if opening is not None else 0
        self.extra = 0
        self.statement = reader._start
        self.most_end = reader._start + reader.limits.fact_chars
        self.result: tuple[Any, int, int, int] | None = None

    def read(self) -> tuple[Any, int, int, int]:
        token, expect = self.reader.token, True
        operand, operator = self._operand, self._operator
        while self.result is None:
            kind, text, start, self.pos = token(self.pos)
            if self.pos > self.most_end:
                raise self.reader._too_long(self.statement, self.pos - self.statement)
            expect = operand(kind, text, start) if expect else operator(kind, text, start)
        return self.result

    # an operand is expected --------------------------------------------------------------------

    def _operand(self, kind: str, text: str, start: int) -> bool:
        """Read a token where an operand belongs; whether an operand is still expected."""
        if kind == "n":
            self.frame.vals.append(self.reader._number(text, start))
        elif kind == "i":
            return self._name(text, start)
        elif kind == "s":
            self.frame.vals.append(Str(text))
        elif kind == "h" and text in _SUPREMUM:
            self.frame.vals.append(_SUPREMUM[text])
        elif kind == "p":
            return self._prefix(text, start)
        else:
            raise self.reader._beyond_term(start, kind, text)
        return False

    def _name(self, text: str, start: int) -> bool:
        """An identifier: a function if a ``(`` follows, else a constant (or its value)."""
        reader = self.reader
        if text == "not":
            raise reader._beyond_term(start, "i", text)
        kind2, text2, start2, end2 = reader.token(self.pos)
        if kind2 == "p" and text2 == "(":
            self.pos = end2
            self._open(_Frame("f", text, start2))
            return True
        constant = reader.constants.get(text)
        if constant is None:
            self.frame.vals.append(Fn(text))
            return False
        depth = len(self.frames) - self.base + constant.depth
        if depth > reader.limits.depth:
            raise reader._too_deep(start)
        self.deepest = max(self.deepest, depth)
        self.extra += constant.length - len(text)
        if self.pos - self.statement + self.extra > reader.limits.fact_chars:
            raise reader._too_long(self.statement, self.pos - self.statement + self.extra)
        self.frame.vals.append(constant.value)
        return False

    def _prefix(self, text: str, start: int) -> bool:
        """Punctuation where an operand belongs: a unary operator, an opening bracket, or
        the ``)`` of ``f()``, ``()`` and a tuple's trailing comma (``(a,)``)."""
        frame = self.frame
        if text == "-" or text == "~":
            frame.ops.append((_UNARY, text, start))
        elif text == "(" or text == "|":
            self._open(_Frame(text, "", start))
        elif text == ")" and not frame.ops and (frame.kind == "(" or (frame.kind in "af" and not frame.args)):
            self._close(self._tuple(frame))
            return False
        else:
            raise self.reader._beyond_term(start, "p", text)
        return True

    def _open(self, frame: _Frame) -> None:
        self.frames.append(frame)
        self.frame = frame
        depth = len(self.frames) - self.base
        if depth > self.reader.limits.depth:
            raise self.reader._too_deep(frame.opening)
        self.deepest = max(self.deepest, depth)

    # an operator (or the end of a term) is expected ------------------------------------------------

    def _operator(self, kind: str, text: str, start: int) -> bool:
        """Read a token after an operand; whether an operand is expected next."""
        frame = self.frame
        precedence = _PRECEDENCE.get(text) if kind == "p" else None
        if precedence is not None:
            ops, vals = frame.ops, frame.vals
            while ops and (ops[-1][0] > precedence or (ops[-1][0] == precedence and precedence != _POW)):
                self.reader._apply(ops.pop(), vals)
            ops.append((precedence, text, start))
            return True
        if kind == "p" and text == "," and frame.kind in "af(":
            frame.args.append(self.reader._checked(self._value(frame), start))
            frame.comma = True
            return True
        if kind == "p" and ((text == ")" and frame.kind in "af(") or (text == "|" and frame.kind == "|")):
            self._close(self._closed(frame, start))
            return False
        if kind == "p" and text == "." and frame.kind == "t":
            self.result = (self.reader._checked(self._value(frame), start), start, self.extra, self.deepest)
            return False
        expecting = "" if kind == "e" else ", expecting , or )" if frame.kind in "af(" else \
            ", expecting |" if frame.kind == "|" else ""
        raise self.reader._beyond_term(start, kind, text, expecting)

    def _value(self, frame: _Frame) -> Any:
        """The argument being read, its operators applied."""
        ops, vals = frame.ops, frame.vals
        while ops:
            self.reader._apply(ops.pop(), vals)
        return vals.pop()

    def _closed(self, frame: _Frame, offset: int) -> Any:
        """The term a closing bracket ends."""
        value = self._value(frame)
        if frame.kind == "|":
            return self.reader._absolute(value, frame.opening)
        if frame.kind == "(" and not frame.args and not frame.comma:
            return value  # (t) is t
        frame.args.append(self.reader._checked(value, offset))
        return self._tuple(frame)

    @staticmethod
    def _tuple(frame: _Frame) -> Fn:
        return Fn(frame.name if frame.kind != "(" else "", tuple(frame.args))

    def _close(self, value: Any) -> None:
        self.frames.pop()
        if not self.frames:
            self.result = (value, self.pos, self.extra, self.deepest)
            return
        self.frame = self.frames[-1]
        self.frame.vals.append(value)


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


# --- constants --------------------------------------------------------------------------------------

def find_constants(reader: Reader) -> list[ConstantDefinition]:
    """The ``#const`` statements of a text, found by a quick pass over its strings,
    comments and directives (the text between them holds no ``"``, ``%`` or ``#``)."""
    text = reader.text
    if "#const" not in text:
        return []
    found: list[ConstantDefinition] = []
    pos = 0
    while (hit := _CONST_SCAN.search(text, pos)) is not None:
        start = hit.start()
        char = hit.group()
        if char == '"':
            try:
                pos = reader._string(start)[1]
            except InputError:
                return found  # the reading proper says what is wrong
        elif char == "%" or text.startswith("#!", start):
            try:
                pos = reader._comment_end(start)
            except InputError:
                return found
        elif text.startswith("#const", start) and not re.match(r"[A-Za-z0-9_]", text[start + 6:start + 7]):
            name, value_start, value_end, pos = reader.constant_at(start)
            found.append(ConstantDefinition(name, reader, start, value_start, value_end))
        else:
            pos = start + 1
    return found


def resolve_constants(definitions: list[ConstantDefinition]) -> dict[str, Constant]:
    """The constants' values, each read once the constants it uses are (refusing a cycle
    and a second definition)."""
    by_name: dict[str, ConstantDefinition] = {}
    for definition in definitions:
        first = by_name.get(definition.name)
        if first is not None:
            where = f"{first.reader.name}:{line_at(first.reader.text, first.start)}"
            raise definition.reader.error(f"the constant {definition.name} is defined twice (also at {where})",
                                          definition.start)
        by_name[definition.name] = definition
    uses = {name: [used for used in definition.reader.references(definition.value_start, definition.value_end)
                   if used in by_name] for name, definition in by_name.items()}
    resolved: dict[str, Constant] = {}
    for root in by_name:
        if root in resolved:
            continue
        path, pending = [root], [iter(uses[root])]
        while path:
            used = next(pending[-1], None)
            if used is None:
                name = path.pop()
                pending.pop()
                definition = by_name[name]
                definition.reader.constants = resolved
                resolved[name] = definition.reader.constant_value(definition)
            elif used in path:
                cycle = " -> ".join([*path[path.index(used):], used])
                definition = by_name[used]
                raise definition.reader.error(f"the constants {cycle} are defined by each other", definition.start)
            elif used not in resolved:
                path.append(used)
                pending.append(iter(uses[used]))
    return resolved


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


# --- text handed to clingo on purpose (--allow-rules) ------------------------------------------------------

def check_program_tokens(text: str, name: str, limits: Limits) -> str:
    """Text with rules that ``--allow-rules`` hands to clingo (in a child process): every
    token is one clingo's lexer reads the same way (so no lexer error lets clingo recover
    somewhere this reader did not look), no ``#include`` or ``#script``; returned with its
    line ends made LF (clingo ends lines and ``%`` comments at LF only)."""
    reader = Reader(text, name, limits)
    pos = 0
    while True:
        kind, word, start, pos = reader.token(pos)
        if kind == "e":
            break
        if kind == "h" and word in ("#include", "#script"):
            raise reader._directive(word, start)
        if kind == "h" and word not in _DIRECTIVES and word not in ("#const", "#program", "#sup", "#supremum",
                                                                    "#inf", "#infimum", "#sum+"):
            raise reader._directive(word, start)
    return text.replace("\r\n", "\n").replace("\r", "\n")
