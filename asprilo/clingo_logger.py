"""A logger callback for clingo that never fails.

clingo hands its logger messages cut inside a multi-byte character (a syntax error next
to an umlaut or a dash); its Python binding decodes them strictly, and the decoding error,
raised inside clingo, aborts the whole process ("PANIC: exception in nothrow scope").
:func:`install` replaces the binding's callback by one that decodes leniently (an
undecodable byte becomes U+FFFD) and passes the message on to the logger given to clingo.
It cannot raise either: a stop signal that comes while it runs is handled once clingo is
done (:func:`asprilo.exits.deferring`).
"""

from __future__ import annotations

import contextlib

import clingo.core

from asprilo.exits import NOTHROW_CALLBACKS

_installed = False


def install() -> None:
    """Decode clingo's messages leniently from now on (once per process; idempotent)."""
    global _installed
    ffi = getattr(clingo.core, "_ffi", None)
    panic = getattr(clingo.core, "_cb_error_panic", None)
    if _installed or ffi is None or panic is None or not hasattr(clingo.core, "_pyclingo_logger_callback"):
        return

    @ffi.def_extern(onerror=panic, name="pyclingo_logger_callback")
    def _logger(code, message, data):
        logger = ffi.from_handle(data)
        text = ffi.string(message).decode("utf-8", errors="replace")
        with contextlib.suppress(Exception):  # a logger must not fail inside clingo: the message is dropped
            logger(clingo.core.MessageCode(code), text)

    NOTHROW_CALLBACKS.add(_logger.__code__)
    _installed = True


def first_error(messages: list[str]) -> str | None:
    """The message to show of those clingo logged: the first error, preferring one whose
    characters all decoded (clingo repeats a lexer error with more and more bytes of a
    multi-byte character)."""
    errors = [message for message in messages if ": error:" in message] or messages
    whole = [message for message in errors if "\ufffd" not in message]
    return (whole or errors)[0].strip() if errors else None
