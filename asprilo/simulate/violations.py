"""A broken rule, named like the checker's ``err(Module,Check,Params)`` atom and said in
plain words (the words come from :mod:`asprilo.simulate.messages`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..facts import format_value  # not the writer, which re-exports it: explaining writes no file
from ..model import Cell
from .messages import MESSAGES

if TYPE_CHECKING:
    from .timeline import Timeline

#: what a replay finds: ``(module, check, params)``, the last parameter being the step
Finding = tuple[str, str, tuple]


@dataclass(frozen=True)
class Violation:
    """One broken rule, named like the checker's ``err(Module,Check,Params)`` atom."""

    module: str
    check: str
    params: tuple
    step: int
    message: str
    robots: tuple[int, ...] = ()
    shelves: tuple[int, ...] = ()
    cells: tuple[Cell, ...] = ()

    @property
    def atom(self) -> str:
        """The ``err/3`` term, exactly as clingo prints it."""
        return f"err({self.module},{self.check},{format_value(self.params)})"


def sort_violations(violations: list[Violation]) -> list[Violation]:
    """Sort by step, module, check and params (in place; also returned)."""
    try:
        violations.sort(key=lambda v: (v.step, v.module, v.check, v.params))
    except TypeError:  # ids of several types (robot 3 and robot "a")
        violations.sort(key=lambda v: (v.step, v.module, v.check, _term_key(v.params)))
    return violations


def _term_key(value: Any) -> tuple:
    if isinstance(value, int):
        return (0, value, "")
    if isinstance(value, tuple):
        return (1, 0, "", tuple(_term_key(v) for v in value))
    return (2, 0, str(value))


def explain(timeline: Timeline, module: str, check: str, params: tuple) -> Violation:
    """``err(module,check,params)`` of ``timeline`` in plain words, with what to highlight."""
    step = params[-1] if params and isinstance(params[-1], int) else 0
    describe = timeline.domain.messages.get((module, check)) or MESSAGES.get((module, check))
    try:
        if describe is None:
            raise KeyError((module, check))
        text, highlight = describe(timeline, *params)
    except (TypeError, KeyError, IndexError, ValueError):  # no words for it (raw facts only)
        text, highlight = f"{module} rule '{check}' is broken ({format_value(params)})", {}
    if module == "instance":
        prefix = "instance: "
    elif module == "goal":
        prefix = f"step {step} (the horizon): "
    else:
        prefix = f"step {step}: "
    return Violation(module, check, params, step, prefix + text,
                     tuple(highlight.get("robots", ())), tuple(highlight.get("shelves", ())),
                     tuple(highlight.get("cells", ())))
