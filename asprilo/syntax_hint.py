"""The hint for clingo's syntax error that a missing ``.`` causes.

clingo reads on past a statement whose ``.`` is missing and reports the error where the
next statement starts (``enc.lp:2: column 1: syntax error, unexpected <IDENTIFIER>``), one
line after the mistake.  :func:`missing_period` finds that case in the program's text, so
the message can point to the line that lacks its ``.``, as the reader does for instance and
plan files.

Programs may be huge: the text is never split into lines (a line is found by counting line
breaks, piece by piece), the search goes back at most :data:`LOOK_BACK` lines, and the
expressions repeat only single characters or possessive groups, so time and memory stay
linear in the text.
"""

from __future__ import annotations

import re

#: the end of what could be a complete statement without its period: a name, a number,
#: a closing parenthesis or brace, a string's quote
_STATEMENT_END = re.compile(r"[\w)}\"']$")
#: a line's code before its ``%`` comment: text and strings (an unclosed one to the end)
_CODE = re.compile(r'(?:[^"%]++|"(?:[^"\\]++|\\.)*+"?)*+')
#: the most lines looked at before the error for the code line that lacks its ``.``
LOOK_BACK = 10_000
_PIECE = 1 << 16


def missing_period(text: str, line: int, column: int) -> str | None:
    """`` (a missing '.' at the end of line N?)`` where clingo's error at ``line``:``column``
    (1-based) of ``text`` is the first token of its line (or the end of the text) and the
    code line before it ends like a statement without its ``.``; ``None`` otherwise."""
    start = _line_start(text, line)
    if start is not None and start < len(text):
        stop = text.find("\n", start)
        current = text[start:stop if stop >= 0 else len(text)]
        if column != len(current) - len(current.lstrip()) + 1:
            return None  # the error is not where a statement starts
        end, number = start - 1, line - 1
    else:  # the end of the text: from its last line
        end = len(text) - 1 if text.endswith("\n") else len(text)
        number = text.count("\n", 0, end) + 1
        line = number + 1
    while end >= 0 and number >= max(1, line - LOOK_BACK):
        begin = text.rfind("\n", 0, end) + 1
        code = _code(text[begin:end])
        if code:
            return f" (a missing '.' at the end of line {number}?)" if _STATEMENT_END.search(code) else None
        end, number = begin - 1, number - 1
    return None


def _line_start(text: str, line: int) -> int | None:
    """Where line ``line`` (1-based) of ``text`` starts; ``None`` past the last line."""
    at, seen = 0, 1
    while seen < line:
        stop = min(len(text), at + _PIECE)
        breaks = text.count("\n", at, stop)
        if seen + breaks < line:
            if stop == len(text):
                return None
            at, seen = stop, seen + breaks
            continue
        while seen < line:
            at, seen = text.index("\n", at) + 1, seen + 1
    return at


def _code(line: str) -> str:
    """The line without its ``%`` comment (outside strings) and trailing blanks."""
    match = _CODE.match(line)
    return line[:match.end() if match else 0].rstrip()
