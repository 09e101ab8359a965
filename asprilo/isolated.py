"""Grounding rules from data in a child process, under a hard time and memory limit.

Rules in an instance or plan (allowed with ``--allow-rules``) may ground for ever or
without bound in memory (``p(0). p(X+1) :- p(X).``); clingo cannot be stopped while it
grounds, so the child that grounds them is ended when its time is up, and it runs with
its address space limited.  The atoms of the first answer come back as fact text.
"""

from __future__ import annotations

import multiprocessing
from collections.abc import Sequence
from typing import TYPE_CHECKING

from .errors import InputError
from .limits import Limits

if TYPE_CHECKING:
    from .sources import Source


def ground(programs: Sequence[Source], limits: Limits) -> str:
    """The atoms of the first answer of ``programs`` (grounded together) as facts, one a line."""
    names = ", ".join(program.name for program in programs) or None
    context = multiprocessing.get_context("spawn")
    receive, send = context.Pipe(duplex=False)
    child = context.Process(target=_child, args=([(p.name, p.text) for p in programs], limits.rule_mb, send),
                            daemon=True)
    child.start()
    send.close()
    try:
        if not receive.poll(limits.rule_seconds):
            raise InputError(limits.exceeded("rule_seconds", "grounding the rules takes longer").message, names)
        kind, payload = receive.recv()
    except EOFError:  # the child died without a word: out of memory, most likely
        raise InputError(limits.exceeded("rule_mb", "grounding the rules failed, it probably needs more "
                                                    "memory").message, names) from None
    finally:
        child.kill()
        child.join()
        receive.close()
    if kind == "error":
        message, file, line = payload
        raise InputError(message, file, line)
    if kind == "memory":
        raise InputError(limits.exceeded("rule_mb", "grounding the rules needs more memory").message, names)
    return payload


def _child(programs: list[tuple[str, str]], megabytes: int, send) -> None:
    """Ground in the child: ("facts", text), ("error", (message, file, line)) or ("memory", None)."""
    import resource  # POSIX only, like the limit itself

    from .sources import Source, _ground  # the child imports what it needs itself

    size = megabytes * 2**20
    resource.setrlimit(resource.RLIMIT_AS, (size, size))
    try:
        atoms = _ground([Source(name, text) for name, text in programs])
        send.send(("facts", "".join(f"{atom}.\n" for atom in atoms)))
    except InputError as error:
        send.send(("error", (error.message, error.file, error.line)))
    except MemoryError:
        send.send(("memory", None))
    except RuntimeError as error:  # clingo's bad_alloc, when it comes as a runtime error
        if "alloc" not in str(error):
            raise
        send.send(("memory", None))
