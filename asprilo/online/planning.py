"""How an online run (:mod:`asprilo.online.run`) talks to its planner.

The planner is told what happens, in the order it happens, and asked for plans:

- ``released(orders, step)``: these orders are known after ``step`` (step 0: before the first);
- ``carried_out(step, actions)``: the actions of ``step`` were done (an empty list: robots stood);
- ``plan(step, seconds, cancel)``: a plan from the state after ``step``, its actions at steps
  1..H counted from there, within ``seconds`` (``None``: none found).

:class:`FromScratch` plans every call anew from the world as an instance of its own, with any
:data:`~asprilo.online.planner.Planner` (the exact search, the anytime planner).  A planner that
keeps its state between calls (the multi-shot ASP planner) implements the same three methods.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import Any, Protocol

from asprilo.domain import Domain, Goal
from asprilo.model import Action, Instance, Order, Plan
from asprilo.simulate import simulate

from .planner import Planner, world_at


class OnlinePlanning(Protocol):
    """A planner of an online run (see the module docstring)."""

    def released(self, orders: list[Order], step: int) -> None: ...

    def carried_out(self, step: int, actions: list[Action]) -> None: ...

    def plan(self, step: int, seconds: float, cancel: threading.Event) -> Plan | None: ...


def multishot(instance: Instance, domain: Domain, encoding: Sequence[str] = (), **options: Any) -> OnlinePlanning:
    """The multi-shot ASP planner of the domain: :class:`~.multishot_a.MultiShotA` for A,
    :class:`~.multishot.MultiShot` for M (options: theirs)."""
    from .multishot import MultiShot
    from .multishot_a import MultiShotA

    if domain.goal is Goal.LINES:
        return MultiShotA(instance, domain, encoding, **options)
    return MultiShot(instance, domain, encoding, **options)


class FromScratch:
    """Every call plans anew from the world after the step, by ``planner_for(seconds)``."""

    def __init__(self, instance: Instance, domain: Domain, planner_for: Callable[[float], Planner]):
        self.instance = replace(instance, orders={})
        self.domain, self.planner_for = domain, planner_for
        self.done: list[Action] = []

    def released(self, orders: list[Order], step: int) -> None:
        self.instance.orders.update({order.id: order for order in orders})

    def carried_out(self, step: int, actions: list[Action]) -> None:
        self.done += actions

    def now(self, step: int) -> Instance:
        """The world after ``step`` as an instance of its own."""
        return world_at(self.instance, simulate(self.instance, Plan(list(self.done)), self.domain).state(step))

    def plan(self, step: int, seconds: float, cancel: threading.Event) -> Plan | None:
        return self.planner_for(seconds)(self.now(step), self.domain, cancel)
