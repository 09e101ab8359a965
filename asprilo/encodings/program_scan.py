"""One pass over a program file, as clingo's lexer sees it: the files it ``#include``\\ s,
whether it uses clingcon 3's ``$``-constraints, and (on request) its text with comments and
include directives blanked out, for clingo's parser.

Programs are code from anyone: any size, any shape.  The scan reads the file in pieces of
:data:`CHUNK` characters and moves from one interesting character to the next with
regular expressions that only match single characters or fixed words (no repetition of
groups, which costs memory per repetition in Python), so its time is linear in the file's
size and its memory, without the blanked text, bounded by a piece; nothing recurses.

What it knows of clingo's syntax: ``%`` comments to the end of the line, ``%* ... *%`` block
comments (nested), strings with ``\\``-escapes (a line break ends one: clingo refuses it),
``#script (...) ... #end.`` blocks (not read: another language), and ``#include "file".`` /
``#include <name>.`` with blanks and comments anywhere between their tokens.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from asprilo.errors import InputError
from asprilo.paths import shown

#: characters read at a time (the memory of a scan without the text is a few of these)
CHUNK = 1 << 16
#: the longest file name an ``#include`` is followed for (longer: left to clingo)
NAME_LIMIT = 4096

_CODE, _LINE, _BLOCK, _STRING, _SCRIPT, _BLOCK_LINE = range(6)
_STRING_BODY = r'"(?:[^"\\\n]++|\\.)*+"'
#: a run of code, complete strings and line comments (possessive: no memory per repetition)
_RUN = re.compile(rf'(?:[^%"#$]++|%(?!\*)[^\n]*+|{_STRING_BODY})*+')
#: a run of code and complete strings on one line, up to a comment
_LINE_CODE = re.compile(rf'(?:[^%"#$\n]++|[#$]|{_STRING_BODY})*+')
#: a complete string (kept) or a line comment (dropped), in a run
_STRING_OR_COMMENT = re.compile(rf'({_STRING_BODY})|%[^\n]*+')
_COMMENT = re.compile(r"%[^\n]*+")
_SPECIAL = re.compile(r'[%"#$]')
_SIGNIFICANT = re.compile(r"[^ \t\r\n]")
_IN_STRING = re.compile(r'["\\\n]')
_IN_BLOCK = re.compile(r"%\*|\*%|%")  # (a lone % in a block comment: up to the line's end)
_CSP3 = re.compile(r"\$[<>!=+*\-\w]")
_WORD = re.compile(r"\w")
_ESCAPES = {"\\n": "\n", '\\"': '"', "\\\\": "\\"}


@dataclass(frozen=True)
class Include:
    """An ``#include`` directive: the name it gives, its line, whether ``<name>`` (clingo's own)."""

    name: str
    line: int
    system: bool = False


@dataclass
class Scan:
    """What a scan found: the includes in order, the line of the first ``$``-constraint,
    and the text with comments and includes blanked (``None`` unless asked)."""

    includes: list[Include] = field(default_factory=list)
    csp3_line: int | None = None
    code: str | None = None


def scan(path: Path, keep_code: bool = False) -> Scan:
    """Scan the program file ``path`` (see the module docstring); ``keep_code``: also its text
    with comments and ``#include`` directives replaced by blanks, line breaks kept, so that
    every other character stays on its line and column.  A file that is not UTF-8 text or
    cannot be read: :class:`InputError`."""
    scanner = _Scanner(keep_code)
    try:
        with open(path, encoding="utf-8", newline="") as file:
            carried = ""
            while True:
                piece = file.read(CHUNK)
                text = carried + piece
                used = scanner.feed(text, not piece)
                carried = text[used:]
                if not piece:
                    break
    except UnicodeDecodeError:
        raise InputError("not a UTF-8 text file", shown(path)) from None
    except OSError as error:
        raise InputError(f"cannot be read ({error.strerror or error})", shown(path)) from None
    return scanner.result()


def _blank(text: str) -> str:
    """What stands for ``text`` (a comment, a directive) in the blanked text: its line breaks,
    and as many blanks as it has characters on its last line (what follows it on that line
    keeps its column; nothing follows it on the lines before)."""
    return "\n" * text.count("\n") + " " * (len(text) - text.rfind("\n") - 1)


class _Scanner:
    """The scan's state between pieces of the text: where it is (code, a comment, a string,
    a script), the ``#include`` being read, the line, the blanked text so far."""

    def __init__(self, keep: bool):
        self.keep = keep
        self.pieces: list[str] = []
        self.state, self.depth = _CODE, 0
        self.line, self.counted, self.emitted = 1, 0, 0
        self.directive: list | None = None   # an #include being read: [what is next, start, line, name, system]
        self.name: list[str] | None = None   # the pieces of an #include's file name being read
        self.named = 0
        self.found = Scan()
        self.spans: list[tuple[int, int]] = []  # where the #include directives are in the blanked text

    def result(self) -> Scan:
        if self.keep:
            if self.state in (_BLOCK, _BLOCK_LINE):  # a block comment still open: clingo says so at the end
                self._emit("%*")
            code = "".join(self.pieces)
            if self.spans:
                parts, at = [], 0
                for start, end in self.spans:
                    parts += [code[at:start], _blank(code[start:end])]
                    at = end
                code = "".join([*parts, code[at:]])
            self.found.code = code
        return self.found

    def feed(self, text: str, last: bool) -> int:
        """Scan ``text`` (``last``: nothing follows); return how much of it was used (the rest,
        at most a few characters of a token cut in two, comes again before the next piece)."""
        at, end = 0, len(text)
        handlers = (self._code, self._line, self._block, self._string, self._script, self._block_line)
        while at < end:
            moved = handlers[self.state](text, at, end, last)
            if moved is None:  # a token cut at the end of the piece: wait for the next one
                break
            at = moved
        self.line += text.count("\n", self.counted, at)
        self.counted = 0
        return at

    def _line_of(self, text: str, at: int) -> int:
        self.line += text.count("\n", self.counted, at)
        self.counted = at
        return self.line

    def _copy(self, text: str, start: int, end: int, blank: bool = False) -> None:
        if self.keep and end > start:
            self._emit(_blank(text[start:end]) if blank else text[start:end])

    def _emit(self, piece: str) -> None:
        self.pieces.append(piece)
        self.emitted += len(piece)

    def _code(self, text: str, at: int, end: int, last: bool) -> int | None:
        if self.directive is None:
            stop = self._run(text, at, end, last)
            if stop > at:
                return stop
        match = (_SIGNIFICANT if self.directive is not None else _SPECIAL).search(text, at)
        if match is None:
            self._copy(text, at, end)
            return end
        start = match.start()
        self._copy(text, at, start)
        wait = None if start == at else start  # a token cut at the end: what is before it is done
        char = text[start]
        if char == "%":
            return self._comment(text, start, end, last, wait)
        if self.directive is not None:
            return self._directive(text, start, end, last, wait)
        if char == '"':
            self.state = _STRING
            self._copy(text, start, start + 1)
            return start + 1
        if end - start < 9 and not last:  # '$' and what follows it, '#include' and what follows it
            return wait
        return self._mark(text, start)

    def _mark(self, text: str, start: int) -> int:
        """A ``$`` or a ``#`` in code, at ``start``: a clingcon 3 constraint, a directive?"""
        if text[start] == "$":
            if self.found.csp3_line is None and _CSP3.match(text, start):
                self.found.csp3_line = self._line_of(text, start)
        elif _keyword(text, start, "#include"):
            self.directive = ["name", self.emitted, self._line_of(text, start), "", False]
            self._copy(text, start, start + 8)
            return start + 8
        elif _keyword(text, start, "#script"):
            self.state = _SCRIPT
        self._copy(text, start, start + 1)
        return start + 1

    def _run(self, text: str, at: int, end: int, last: bool) -> int:
        """The end of the run of code, complete strings and line comments at ``at`` (copied); a
        run that reaches the end of the piece ends before a comment still open there."""
        stop = _matched(_RUN, text, at)
        if stop == end and not last:
            stop = _matched(_LINE_CODE, text, max(at, text.rfind("\n", at, end) + 1))
        if self.keep and stop > at:
            self._emit(_uncommented(text[at:stop]))
        return stop

    def _comment(self, text: str, at: int, end: int, last: bool, wait: int | None) -> int | None:
        """A comment starts at ``at``: ``%*`` a block comment, ``%`` one to the end of the line."""
        if at + 1 >= end and not last:
            return wait
        if text.startswith("%*", at):
            self.state, self.depth = _BLOCK, 1
            self._copy(text, at, at + 2, blank=True)
            return at + 2
        self.state = _LINE
        return at

    def _directive(self, text: str, at: int, end: int, last: bool, wait: int | None) -> int | None:
        """The next token of an ``#include`` directive, at ``at`` (``wait``: what to return
        for a token cut at the end of the piece)."""
        assert self.directive is not None
        char, (what, start, line, name, _system) = text[at], self.directive
        if what == "name" and char == '"':
            self.name, self.named, self.state = [], 0, _STRING
            self._copy(text, at, at + 1)
            return at + 1
        if what == "name" and char == "<":
            close = text.find(">", at, at + NAME_LIMIT)
            if close < 0 and not last and end - at < NAME_LIMIT:
                return wait
            if close >= 0:
                self.directive = ["dot", start, line, text[at + 1:close], True]
                self._copy(text, at, close + 1)
                return close + 1
        if what == "dot" and char == ".":
            self.found.includes.append(Include(name, line, _system))
            self.directive = None
            self._copy(text, at, at + 1)
            self.spans.append((start, self.emitted))
            return at + 1
        self.directive = None  # not an #include clingo reads: the token is code again
        return at

    def _line(self, text: str, at: int, end: int, last: bool) -> int:
        newline = text.find("\n", at)
        stop = end if newline < 0 else newline
        if newline >= 0:
            self.state = _CODE
        return stop

    def _block(self, text: str, at: int, end: int, last: bool) -> int | None:
        match = _IN_BLOCK.search(text, at)
        if match is None:
            stop = end - 1 if not last and text[end - 1] in "%*" else end
            if stop <= at:
                return None
            self._copy(text, at, stop, blank=True)
            return stop
        if match.group() == "%":
            if match.end() >= end and not last:  # perhaps '%*'
                self._copy(text, at, match.start(), blank=True)
                return None if match.start() == at else match.start()
            self.state = _BLOCK_LINE
        else:
            self.depth += 1 if match.group() == "%*" else -1
            if self.depth == 0:
                self.state = _CODE
        self._copy(text, at, match.end(), blank=True)
        return match.end()

    def _block_line(self, text: str, at: int, end: int, last: bool) -> int:
        """A ``%`` in a block comment hides the rest of its line (a ``*%`` too), as in clingo."""
        newline = text.find("\n", at)
        stop = end if newline < 0 else newline
        self._copy(text, at, stop, blank=True)
        if newline >= 0:
            self.state = _BLOCK
        return stop

    def _string(self, text: str, at: int, end: int, last: bool) -> int | None:
        match = _IN_STRING.search(text, at)
        stop = end if match is None else match.start()
        self._copy(text, at, stop)
        self._named(text[at:stop])
        if match is None:
            return end
        char = text[stop]
        if char == "\\":
            if stop + 1 >= end and not last:
                return None if stop == at else stop
            self._named(_ESCAPES.get(text[stop:stop + 2], text[stop:stop + 2]))
            self._copy(text, stop, stop + 2)
            return stop + 2
        self.state = _CODE
        if char == "\n":  # clingo refuses a line break in a string: no #include here
            self.name = self.directive = None
            return stop
        self._copy(text, stop, stop + 1)
        if self.name is not None and self.directive is not None:
            self.directive[0], self.directive[3] = "dot", "".join(self.name)
            self.name = None
        return stop + 1

    def _named(self, piece: str) -> None:
        """Keep ``piece`` of an ``#include``'s file name (a name too long is not followed)."""
        if self.name is None or not piece:
            return
        self.named += len(piece)
        if self.named > NAME_LIMIT:
            self.name = self.directive = None
        else:
            self.name.append(piece)

    def _script(self, text: str, at: int, end: int, last: bool) -> int | None:
        found = text.find("#end", at)
        if found < 0:
            stop = max(at, end - 3) if not last else end
            self._copy(text, at, stop)
            return stop if stop > at else None
        self._copy(text, at, found + 4)
        self.state = _CODE
        return found + 4


def _uncommented(run: str) -> str:
    """A run of code without its line comments (nothing follows them on their line)."""
    if "%" not in run:
        return run
    if '"' not in run:
        return _COMMENT.sub("", run)
    return _STRING_OR_COMMENT.sub(lambda match: match.group(1) or "", run)


def _matched(pattern: re.Pattern[str], text: str, at: int) -> int:
    """Where ``pattern`` (which may match nothing) matched at ``at`` ends."""
    match = pattern.match(text, at)
    return at if match is None else match.end()


def _keyword(text: str, at: int, word: str) -> bool:
    """Whether ``word`` (a directive) starts at ``at`` of ``text``, not followed by a letter."""
    after = at + len(word)
    return text.startswith(word, at) and (after >= len(text) or not _WORD.match(text, after))
