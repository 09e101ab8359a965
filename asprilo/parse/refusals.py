"""What is refused: a statement that is more than data (a rule, a directive, an interval, a
pool, a variable: :class:`NotData`, worded by what it is), a directive data never holds, a
statement or nesting beyond the limits; and the tokens of text with rules that
``--allow-rules`` hands to clingo (:func:`check_program_tokens`)."""

from __future__ import annotations

from ..errors import InputError
from ..limits import Limits
from .terms import shown
from .tokens import _DIRECTIVES, _SUPREMUM, Lexer, line_at

#: what every refusal of a statement that is more than data ends with
DATA_ONLY = "data holds only facts, #const and '#program base.' (rules need --allow-rules)"


class NotData(InputError):
    """A statement that is more than data (a rule, a directive, an interval, a pool, a
    variable, a program part other than ``base``): read only with ``--allow-rules``."""

    def __reduce__(self):
        return NotData, (self.message, self.file, self.line)


#: how brackets change the nesting
_NESTING = {"(": 1, "[": 1, "{": 1, ")": -1, "]": -1, "}": -1}
#: words of rule bodies and aggregates
_IN_BODIES = {"#true", "#false", "#count", "#sum", "#min", "#max"}


class Refuser(Lexer):
    """A lexer that says what a statement is when it is no fact, and refuses what the limits
    do not allow."""

    # the limits ---------------------------------------------------------------------------------

    def _too_long(self, start: int, size: int) -> InputError:
        what = f"a statement of more than {self.limits.fact_chars:,} characters"
        return self.error(self.limits.exceeded("fact_chars", what).message, start)

    def _too_deep(self, offset: int) -> InputError:
        return self.error(self.limits.exceeded("depth", "terms nested more deeply").message, offset)

    # what a statement is, when it is no fact --------------------------------------------------------

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


# --- text handed to clingo on purpose (--allow-rules) ------------------------------------------------------

def check_program_tokens(text: str, name: str, limits: Limits) -> str:
    """Text with rules that ``--allow-rules`` hands to clingo (in a child process): every
    token is one clingo's lexer reads the same way (so no lexer error lets clingo recover
    somewhere this reader did not look), no ``#include`` or ``#script``; returned with its
    line ends made LF (clingo ends lines and ``%`` comments at LF only)."""
    reader = Refuser(text, name, limits)
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
