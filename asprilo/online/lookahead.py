"""What the multi-shot online planners of every domain share: one clingo ``Control`` for a
whole run, time counted from *now*, and the search of a call over horizons.

A subclass says what the world is now (:meth:`Lookahead.prepare`: a lower bound and the horizon
to try first; :meth:`Lookahead.assign_world`: the externals) and how a model reads as a plan
(:meth:`Lookahead.read_plan`).  This class grounds ``step(k)`` the first time a call looks k
steps ahead and ``check(h)`` the first time it tries horizon h (each part once, kept for later
calls), makes ``query(h)`` true for the one solve call that tries h, and searches: from the
first horizon up (by :attr:`Lookahead.rise` steps) to the first plan, then, where
:attr:`Lookahead.shortest` says so, a bisection between the lower bound and the shortest plan
found (a horizon without a plan proves those below it empty too; time running out first
leaves the shortest plan found).  ``fresh=True`` starts every call on a new ``Control`` (the
same program, grounded again from nothing): the baseline that multi-shot solving is measured
against.
"""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Callable, Iterable, Sequence
from dataclasses import replace
from pathlib import Path

import clingo

from asprilo.errors import InputError
from asprilo.facts import instance_facts
from asprilo.model import Cell, Instance, Plan

#: the most steps after now a call looks (each grounded once, and kept for later calls)
MOST_LOOKAHEAD = 64


class Lookahead:
    """The control and the search of a multi-shot online planner (see the module docstring)."""

    #: steps between two horizons tried up to the first plan
    rise = 1
    #: whether a call searches on for the shortest plan once it has one
    shortest = True
    #: the most steps beyond its first horizon a call tries (None: up to the lookahead's end)
    most_rise: int | None = None

    def __init__(self, instance: Instance, encoding: Sequence[str], *, arguments: Sequence[str] = (),
                 most_lookahead: int = MOST_LOOKAHEAD, clock: Callable[[], float] = time.monotonic,
                 fresh: bool = False):
        self.instance, self.encoding, self.arguments = instance, list(encoding), list(arguments)
        self.most_lookahead, self.clock, self.fresh = most_lookahead, clock, fresh
        for path in self.encoding:
            if not Path(path).is_file():
                raise InputError(f"{path}: no such encoding file")
        self.solves = 0
        self._start()

    def _start(self) -> None:
        """A new control with the program and the instance's base (no orders) grounded."""
        own_heuristic = any(argument.startswith("--heuristic") for argument in self.arguments)
        self.control = clingo.Control(["--warn=none", *([] if own_heuristic else ["--heuristic=Domain"]),
                                       *self.arguments])
        for path in self.encoding:
            try:
                self.control.load(path)
            except RuntimeError as error:
                raise InputError(f"{path}: clingo cannot read it ({error})") from None
        self.control.add("base", [], " ".join(instance_facts(replace(self.instance, orders={}))))
        self.control.ground([("base", [])])
        self.lookahead = 0                 # steps after now grounded
        self.horizons: set[int] = set()    # check(h) grounded
        self.queried: int | None = None
        self.assigned: dict[clingo.Symbol, bool] = {}  # externals as last assigned
        self.true_sets: dict[str, set[clingo.Symbol]] = {}  # see assign_set

    # --- for the subclasses ------------------------------------------------------------------------

    def prepare(self) -> tuple[int, int]:
        """(A lower bound on the horizon from now, the horizon to try first)."""
        raise NotImplementedError

    def assign_world(self) -> None:
        """Assign the externals that say what the world is now (for the steps grounded)."""
        raise NotImplementedError

    def read_plan(self, symbols: list[clingo.Symbol], horizon: int) -> Plan:
        """The actions of steps 1..``horizon`` after now, from a model's shown atoms."""
        raise NotImplementedError

    def ground_parts(self, parts: list[tuple[str, list[clingo.Symbol]]]) -> None:
        """Ground program parts (a fresh control grounds them again at its start: see
        :meth:`restart_parts`)."""
        if parts:
            self.control.ground(parts)

    def restart_parts(self) -> list[tuple[str, list[clingo.Symbol]]]:
        """The parts beyond base that a fresh control grounds first (none by default)."""
        return []

    def assign(self, truths: dict[clingo.Symbol, bool]) -> None:
        """Set externals: each one only when its truth value changes."""
        for symbol, truth in truths.items():
            if self.assigned.get(symbol) != truth:
                self.control.assign_external(symbol, truth)
                self.assigned[symbol] = truth

    def assign_set(self, name: str, now: Iterable[clingo.Symbol]) -> None:
        """Make exactly ``now`` true among the externals of ``name`` this planner set true."""
        now = set(now)
        before = self.true_sets.get(name, set())
        self.assign({symbol: False for symbol in before - now} | {symbol: True for symbol in now - before})
        self.true_sets[name] = now

    # --- a call -------------------------------------------------------------------------------------

    def search(self, seconds: float, cancel: threading.Event) -> Plan | None:
        """The shortest plan from now found in ``seconds`` (``None``: none found)."""
        deadline = self.clock() + seconds
        if self.fresh:
            self._start()
            self.ground_parts(self.restart_parts())
        bound, horizon = self.prepare()
        horizon = max(bound, horizon)
        if horizon > self.most_lookahead:
            return None
        self._ground(horizon)
        self.assign_world()
        best, last = None, self.most_lookahead if self.most_rise is None else \
            min(self.most_lookahead, horizon + self.most_rise)
        while best is None and horizon <= last:
            found, best = self._attempt(horizon, deadline, cancel)
            if found is None:
                return None
            horizon += self.rise if best is None else 0
        if best is None:
            return None
        while self.shortest and bound < horizon:
            middle = (bound + horizon) // 2
            found, plan = self._attempt(middle, deadline, cancel)
            if found is None:
                break
            if found:
                best, horizon = plan, middle
            else:
                bound = middle + 1
        return best

    def _attempt(self, horizon: int, deadline: float, cancel: threading.Event) -> tuple[bool | None, Plan | None]:
        """One solve call for ``horizon``: (True, its plan), (False, None) when there is none,
        (None, None) when time ran out or the call was cancelled first."""
        if cancel.is_set() or self.clock() >= deadline:
            return None, None
        self._ground(horizon)
        if self.queried is not None:
            self.control.assign_external(_query(self.queried), False)
        self.control.assign_external(_query(horizon), True)
        self.queried = horizon
        found, symbols = self._solve(deadline, cancel)
        return found, self.read_plan(symbols, horizon) if found else None

    def _ground(self, horizon: int) -> None:
        """The steps up to ``horizon`` and ``check(horizon)``, those not grounded before."""
        parts = [("step", [clingo.Number(k)]) for k in range(self.lookahead + 1, horizon + 1)]
        if horizon not in self.horizons:
            parts.append(("check", [clingo.Number(horizon)]))
            self.horizons.add(horizon)
        self.lookahead = max(self.lookahead, horizon)
        if parts:
            self.control.ground(parts)

    def _solve(self, deadline: float, cancel: threading.Event) -> tuple[bool | None, list[clingo.Symbol]]:
        """One solve call: (True, the model's shown atoms), (False, []) when there is none,
        (None, []) when time ran out or the call was cancelled first."""
        shown: list[clingo.Symbol] = []

        def keep(model: clingo.Model) -> bool:
            shown.extend(model.symbols(shown=True))
            return False

        self.solves += 1
        with self.control.solve(on_model=keep, async_=True) as handle:
            while not handle.wait(0.02):
                if cancel.is_set() or self.clock() >= deadline:
                    handle.cancel()
                    handle.wait()
                    return None, []
            result = handle.get()
        if result.satisfiable:
            return True, shown
        return (False, []) if result.unsatisfiable else (None, [])


def neighbours(cell: Cell) -> list[Cell]:
    x, y = cell
    return [(x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)]


def distances(cells: set[Cell] | dict, sources: list[Cell]) -> dict[Cell, int]:
    """Steps within ``cells`` from the nearest of ``sources`` to every cell reached."""
    distance = {cell: 0 for cell in sources}
    queue = deque(sources)
    while queue:
        cell = queue.popleft()
        for near in neighbours(cell):
            if near in cells and near not in distance:
                distance[near] = distance[cell] + 1
                queue.append(near)
    return distance


def trip(cell: Cell, field: dict[Cell, int]) -> list[Cell]:
    """The cells a robot on ``cell`` enters, step by step, going down ``field`` to its 0."""
    cells = []
    while field[cell] > 0:
        cell = next(near for near in neighbours(cell) if field.get(near, -1) == field[cell] - 1)
        cells.append(cell)
    return cells


def number(value: int) -> clingo.Symbol:
    return clingo.Number(value)


def cell_term(cell: Cell) -> clingo.Symbol:
    return clingo.Tuple_([clingo.Number(cell[0]), clingo.Number(cell[1])])


def cell_of(symbol: clingo.Symbol) -> Cell:
    return symbol.arguments[0].number, symbol.arguments[1].number


def _query(horizon: int) -> clingo.Symbol:
    return clingo.Function("query", [clingo.Number(horizon)])
