"""The reading policy for data: what an instance, a plan or an online message may hold
(README: "Reading data").

- Bytes: UTF-8, a byte-order mark is dropped; other encodings and NUL bytes are refused
  (:func:`decode`, here).
- Text: the fact language of :mod:`asprilo.parse` -- facts, ``#const`` and
  ``#program base.``, comments; outside strings and comments only printable ASCII; numbers
  and arithmetic within clingo's 32 bits; terms within the ``depth``, ``string-chars`` and
  ``fact-chars`` limits; never ``#include`` or ``#script``.  The parser reads it into terms:
  clingo never sees the text of data.
- Rules, intervals (``1..N``), pools and directives only with ``allow_rules``: the text is
  then checked token by token (:func:`asprilo.parse.check_program_tokens`) and grounded in a
  child process, under limits (:mod:`asprilo.sources`).
"""

from __future__ import annotations

from .errors import InputError
from .parse import line_at

BOM = "\ufeff"


def decode(data: bytes, name: str) -> str:
    """The text of a file or message: UTF-8 (a leading byte-order mark dropped), no NUL."""
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        line = _line(data, error.start)
        raise InputError(f"not a UTF-8 text file (byte 0x{data[error.start]:02x} cannot be read)",
                         name, line) from None
    text = text.removeprefix(BOM)
    nul = text.find("\x00")
    if nul >= 0:
        raise InputError("not a text file (it holds a NUL byte)", name, line_at(text, nul))
    return text


def _line(data: bytes, offset: int) -> int:
    """The line of a byte offset; lines end with LF, CRLF or CR."""
    return data.count(b"\n", 0, offset) + data.count(b"\r", 0, offset) - data.count(b"\r\n", 0, offset) + 1
