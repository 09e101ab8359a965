"""The words and the resources of a rule variant, as data that pickles (child processes get
the domain whole): a check's sentence as a template over its ``err/3`` parameters, and a
per-robot resource that actions consume."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

#: what a parameter of a check may be, and what the viewer highlights for it
KINDS = {"robot": "robots", "shelf": "shelves", "cell": "cells", "station": None, "order": None, "product": None,
         "step": None, "number": None, "word": None, "term": None}


@dataclass(frozen=True)
class Words:
    """The sentence of one check: ``params`` name the ``err/3`` parameters in order (the step
    last, as in every check) with their kinds, ``text`` says the violation with ``{NAME}``
    where a parameter's value goes.  Called as the built-in message functions are, with the
    timeline and the parameters: the sentence and what to highlight."""

    params: tuple[tuple[str, str], ...]
    text: str

    def __call__(self, _timeline: Any, *values: Any) -> tuple[str, dict[str, list]]:
        from ..facts import format_value  # clingo's types: only once a sentence is said

        named = {name: format_value(value) for (name, _kind), value in zip(self.params, values, strict=False)}
        highlight: dict[str, list] = {}
        for (_name, kind), value in zip(self.params, values, strict=False):
            group = KINDS.get(kind)
            if group is not None:
                highlight.setdefault(group, []).append(value)
        return self.text.format_map(named), highlight


@dataclass(frozen=True)
class Resource:
    """A robot attribute that actions consume (a variant's energy, say): ``costs`` per action
    name (``carrying move``: a move with a shelf), never below ``least``."""

    attribute: str
    costs: tuple[tuple[str, int], ...]
    least: int = 0

    def cost(self, action: str, carrying: bool = False) -> int:
        """What one ``action`` costs (a move while carrying: ``carrying move`` where given)."""
        costs = dict(self.costs)
        if action == "move" and carrying and "carrying move" in costs:
            return costs["carrying move"]
        return costs.get(action, 0)

    def constants(self) -> tuple[tuple[str, int], ...]:
        """The costs as the checker's constants: ``cost_move``, ``cost_carrying_move``, ..., ``least``."""
        return (*((f"cost_{action.replace(' ', '_')}", cost) for action, cost in self.costs), ("least", self.least))
