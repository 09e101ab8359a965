"""The lexer: tokens as clingo 5.8's lexer makes them, blanks and comments skipped, and the
lines of offsets (:func:`line_at`); what the lexer refuses is an :class:`InputError` at its
line."""

from __future__ import annotations

import re
from typing import Any, cast

from ..errors import InputError
from ..limits import Limits
from .terms import INF, INT_MAX, SUP, Special, _Big, shown


def line_at(text: str, offset: int) -> int:
    """The line (from 1) of a character offset; lines end with LF, CRLF or CR."""
    offset = max(0, min(offset, len(text)))
    lines = text.count("\n", 0, offset) + 1
    returns = text.count("\r", 0, offset)
    if returns:
        lines += returns - text.count("\r\n", 0, offset)
    return lines


# A token, blanks before it skipped; the group says which kind:
#   p punctuation and operators, i identifier, n number, s string (its opening quote),
#   c comment (its %), h '#' word or '#!', v variable, e end of text, x anything else
_TOKEN = re.compile(r"""[ \t\r\n]*+(?:
     (?P<p>\*\*|\.\.|:-|:~|==|[(),.|+\-*/\\&?^~;:{}\[\]=<>!@$])
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
_DIGITS = {"0x": (16, 8), "0o": (8, 11), "0b": (2, 32)}  # base, most significant digits in 32 bits

#: directives clingo knows that data never holds (messages name them)
_DIRECTIVES = {"#show", "#external", "#minimize", "#minimise", "#maximize", "#maximise", "#heuristic",
               "#project", "#edge", "#defined", "#theory", "#true", "#false", "#count", "#sum", "#min",
               "#max", "#disjoint"}
#: the words of #sup and #inf
_SUPREMUM = {"#sup": SUP, "#supremum": SUP, "#inf": INF, "#infimum": INF}


def _token_name(kind: str | None, text: str) -> str:
    """A token as clingo's syntax errors name it (never the data itself)."""
    if kind == "e":
        return "EOF"
    if text == ",":
        return '","'
    if text == "==":  # clingo's lexer reads '=' and '==' alike
        return "="
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


class Lexer:
    """The tokens of one text, one by one from an offset (:meth:`token`), within the limits
    given."""

    def __init__(self, text: str, name: str, limits: Limits):
        self.text = text
        self.name = name
        self.limits = limits
        self.end = len(text)
        self._start = 0  # the statement being read (for messages)
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
