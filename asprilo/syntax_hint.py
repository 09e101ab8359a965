"""The hint for clingo's syntax error that a missing ``.`` causes.

clingo reads on past a statement whose ``.`` is missing and reports the error where the
next statement starts (``enc.lp:2: column 1: syntax error, unexpected <IDENTIFIER>``), one
line after the mistake.  :func:`missing_period` finds that case in the program's text, so
the message can point to the line that lacks its ``.``, as the reader does for instance and
plan files.
"""

from __future__ import annotations

import re

#: the end of what could be a complete statement without its period: a name, a number,
#: a closing parenthesis or brace, a string's quote
_STATEMENT_END = re.compile(r"[\w)}\"']$")


def missing_period(text: str, line: int, column: int) -> str | None:
    """`` (a missing '.' at the end of line N?)`` where clingo's error at ``line``:``column``
    (1-based) of ``text`` is the first token of its line (or the end of the text) and the
    code line before it ends like a statement without its ``.``; ``None`` otherwise."""
    lines = text.splitlines()
    if line <= len(lines):
        current = lines[line - 1]
        if column != len(current) - len(current.lstrip()) + 1:
            return None  # the error is not where a statement starts
    for number in range(min(line - 1, len(lines)), 0, -1):
        code = _code(lines[number - 1])
        if code:
            return f" (a missing '.' at the end of line {number}?)" if _STATEMENT_END.search(code) else None
    return None


def _code(line: str) -> str:
    """The line without its ``%`` comment (outside strings) and trailing blanks."""
    quoted = False
    for index, char in enumerate(line):
        if char == '"':
            quoted = not quoted
        elif char == "%" and not quoted:
            return line[:index].rstrip()
    return line.rstrip()
