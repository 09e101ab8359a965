"""The multi-shot ASP online planner: one clingo ``Control`` for a whole online run.

Time in the program is counted from *now*, the step a call plans from: ``step(k)`` is the k-th
step after now.  What the driver grounds, each part once (docs/ONLINE.md is the contract an
encoding follows):

- ``base``: the encoding's base part and the instance's facts without its orders;
- ``step(k)``: the first time a call looks k steps ahead (later calls use it again);
- ``line(o,p,q,s,r)``: when order o is released after step r, one part per line (product p,
  q units, 1 where the instance gives none; station s, 0 where it gives none);
- ``check(h)``: the first time a call tries horizon h.

What the driver assigns: ``at(R,C)`` before every call (robot R stands on cell C now: the
actions carried out are fixed by the state they led to, so no step of the past is ever
grounded and memory is that of the lookahead window); ``open(O,P)`` true when the line is
released, released for good when it is done in the world (domain M: some robot stands
under a shelf holding P at a step after the release: docs/SPEC.md, the checker and
:mod:`asprilo.simulate`); ``hint(B,C,K)`` along a trip of the nearest robot to every open
line (a heuristic, never a rule); ``query(h)`` true for one solve call, every other false.
A call searches the smallest h (see :meth:`MultiShot.plan`), one solve call a horizon,
within its seconds (cancel honoured).  The plan is read
from the model's ``go(B,C,K)`` (anonymous robots, named here by following their cells) or
``occurs(object(robot,R),action(A,X),K)`` atoms, K steps after now.
"""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Callable, Sequence
from dataclasses import replace
from pathlib import Path

import clingo

from asprilo.domain import Domain, Goal
from asprilo.errors import InputError
from asprilo.facts import instance_facts
from asprilo.model import Action, Cell, Instance, Order, Plan

#: the reference online encoding of domain M
REFERENCE = Path(__file__).resolve().parent.parent / "encodings" / "online" / "m.lp"
#: the most steps after now a call looks (each grounded once, and kept for later calls)
MOST_LOOKAHEAD = 64
#: lines done between two cleanups (the grounder then drops what released externals made false)
CLEANUP_EVERY = 10

Line = tuple[int, int]  # (order, product)


class MultiShot:
    """An :class:`~asprilo.online.planning.OnlinePlanning` planner on one clingo Control.

    ``encoding``: the program files (default: the reference encoding of domain M);
    ``arguments``: clingo's command-line options; ``clock``: the wall clock of the budget."""

    def __init__(self, instance: Instance, domain: Domain, encoding: Sequence[str] = (), *,
                 arguments: Sequence[str] = (), most_lookahead: int = MOST_LOOKAHEAD,
                 clock: Callable[[], float] = time.monotonic):
        if domain.goal is not Goal.SHELVES:
            raise InputError(f"the multi-shot planner plans for domain M, not {domain.label}")
        self.instance, self.domain = instance, domain
        self.most_lookahead, self.clock = most_lookahead, clock
        self.control = clingo.Control(["--warn=none", "--heuristic=Domain", *arguments])
        for path in encoding or (str(REFERENCE),):
            if not Path(path).is_file():
                raise InputError(f"{path}: no such encoding file")
            try:
                self.control.load(path)
            except RuntimeError as error:
                raise InputError(f"{path}: clingo cannot read it ({error})") from None
        self.control.add("base", [], " ".join(instance_facts(replace(instance, orders={}))))
        self.control.ground([("base", [])])
        self.lookahead = 0                 # steps after now grounded
        self.horizons: set[int] = set()    # check(h) grounded
        self.positions: dict[int, Cell] = {r: robot.at for r, robot in sorted(instance.robots.items())}
        self.assigned: set[tuple[int, Cell]] = set()  # at(R,C) now true
        self.shelf_cells = {product: {instance.shelves[s].at for s in item.stock if s in instance.shelves}
                            for product, item in instance.products.items()}
        self.covered = self._covered()
        self.open: dict[Line, int] = {}    # line -> release step
        self.done: dict[Line, int] = {}    # line -> the step it was done
        self.fields: dict[int, dict[Cell, int]] = {}  # product -> steps to its shelves
        self.hinted: set[tuple[Cell, Cell, int]] = set()
        self.queried: int | None = None
        self.solves = 0

    # --- what happens in the world ---------------------------------------------------------------

    def released(self, orders: list[Order], step: int) -> None:
        """Ground one ``line`` part per line of the orders released after ``step``; open them."""
        parts, lines = [], []
        for order in orders:
            for product, units in sorted(order.lines.items()):
                lines.append((order.id, product))
                self.open[(order.id, product)] = step
                parts.append(("line", [_num(order.id), _num(product), _num(1 if units is None else units),
                                       _num(0 if order.station is None else order.station), _num(step)]))
        if parts:
            self.control.ground(parts)
        for number, product in lines:
            self.control.assign_external(_open(number, product), True)

    def carried_out(self, step: int, actions: list[Action]) -> None:
        """Follow the robots through step ``step``; release ``open`` for the lines it did."""
        moves = {action.robot: action.args for action in actions if action.name == "move"}
        for robot, (x, y) in self.positions.items():
            dx, dy = moves.get(robot, (0, 0))
            self.positions[robot] = (x + dx, y + dy)
        self.covered = self._covered()
        for line, release in sorted(self.open.items()):
            if release < step and line[1] in self.covered:
                del self.open[line]
                self.done[line] = step
                self.control.release_external(_open(*line))
                if len(self.done) % CLEANUP_EVERY == 0:
                    self.control.cleanup()

    # --- planning ----------------------------------------------------------------------------------

    def plan(self, step: int, seconds: float, cancel: threading.Event) -> Plan | None:
        """The shortest plan from the state after ``step`` that serves every open line (steps
        1..H counted from ``step``) found in ``seconds``; ``None`` when none is found.

        The first horizon tried is that of the hints (or the lower bound, if larger); up from
        there to the first plan, then a bisection between the lower bound and the shortest
        plan found: a horizon without a plan proves those below it empty too (time running
        out first leaves the shortest plan found)."""
        if not self.open:
            return Plan([])
        deadline = self.clock() + seconds
        bound, trips = self.lower_bound(), self.trips()
        horizon = max([bound, *(len(trip) for trip in trips.values())])
        if horizon > self.most_lookahead:
            return None
        self._ground(horizon)
        self._assign_state()
        self._assign_hints(trips)
        best = None
        while best is None and horizon <= self.most_lookahead:
            found, best = self._attempt(horizon, deadline, cancel)
            if found is None:
                return None
            horizon += best is None
        if best is None:
            return None
        while bound < horizon:
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
        self._query(horizon)
        found, symbols = self._solve(deadline, cancel)
        return found, self._read_plan(symbols, horizon) if found else None

    def trips(self) -> dict[int, list[Cell]]:
        """The hints: robots sent to the products of the open lines, the nearest pair of a
        robot not sent yet and a product not served yet first, along a shortest trip on the
        empty floor to a shelf holding it (a robot under one now stays); robot -> the cells
        it enters, step by step."""
        products = sorted({product for _order, product in self.open})
        pairs = sorted((field[cell], robot, product) for product in products
                       for field in [self._field(product)] for robot, cell in self.positions.items() if cell in field)
        trips: dict[int, list[Cell]] = {}
        served: set[int] = set()
        for _steps, robot, product in pairs:
            if robot not in trips and product not in served:
                trips[robot] = self._trip(self.positions[robot], self._field(product))
                served.add(product)
        return trips

    def _field(self, product: int) -> dict[Cell, int]:
        """Steps from every cell to the nearest shelf holding ``product`` (computed once)."""
        if product not in self.fields:
            self.fields[product] = _distances(self.instance, sorted(self.shelf_cells.get(product, ())))
        return self.fields[product]

    def _trip(self, cell: Cell, field: dict[Cell, int]) -> list[Cell]:
        trip = []
        while field[cell] > 0:
            cell = next(near for near in _neighbours(cell) if field.get(near, -1) == field[cell] - 1)
            trip.append(cell)
        return trip

    def lower_bound(self) -> int:
        """No plan serves every open line in fewer steps: for each, the floor distance of the
        nearest robot to a shelf holding its product (at least 1: served after now)."""
        distance = _distances(self.instance, list(self.positions.values()))
        bound = 1
        for _order, product in self.open:
            near = min((distance[cell] for cell in self.shelf_cells.get(product, ()) if cell in distance),
                       default=None)
            if near is None:
                return self.most_lookahead + 1
            bound = max(bound, near)
        return bound

    # --- helpers ----------------------------------------------------------------------------------

    def _covered(self) -> set[int]:
        """The products some robot stands under a shelf of now."""
        cells = set(self.positions.values())
        return {product for product, shelves in self.shelf_cells.items() if shelves & cells}

    def _assign_state(self) -> None:
        """``at(R,C)`` true where the robots stand now, false where they stood at the last call."""
        now = set(self.positions.items())
        for robot, cell in self.assigned - now:
            self.control.assign_external(_at(robot, cell), False)
        for robot, cell in now - self.assigned:
            self.control.assign_external(_at(robot, cell), True)
        self.assigned = now

    def _assign_hints(self, trips: dict[int, list[Cell]]) -> None:
        """``hint(B,C,K)`` true along every robot's trip (standing once there, or when sent
        nowhere), false for the hints of the last call; within the steps grounded."""
        hints = set()
        for robot, cell in self.positions.items():
            trip = trips.get(robot, [])
            for k in range(1, self.lookahead + 1):
                after = trip[k - 1] if k <= len(trip) else cell
                hints.add((cell, after, k))
                cell = after
        for hint in self.hinted - hints:
            self.control.assign_external(_hint(*hint), False)
        for hint in hints - self.hinted:
            self.control.assign_external(_hint(*hint), True)
        self.hinted = hints

    def _ground(self, horizon: int) -> None:
        """The steps up to ``horizon`` and ``check(horizon)``, those not grounded before."""
        parts = [("step", [_num(k)]) for k in range(self.lookahead + 1, horizon + 1)]
        if horizon not in self.horizons:
            parts.append(("check", [_num(horizon)]))
            self.horizons.add(horizon)
        self.lookahead = max(self.lookahead, horizon)
        if parts:
            self.control.ground(parts)

    def _query(self, horizon: int) -> None:
        if self.queried is not None:
            self.control.assign_external(_query(self.queried), False)
        self.control.assign_external(_query(horizon), True)
        self.queried = horizon

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

    def _read_plan(self, symbols: list[clingo.Symbol], horizon: int) -> Plan:
        """The actions of steps 1..``horizon`` after now: from ``occurs/3`` or ``go/3``."""
        named = [action for symbol in symbols if (action := _named(symbol, horizon)) is not None]
        goes: dict[int, dict[Cell, Cell]] = {}
        for symbol in symbols:
            if symbol.match("go", 3) and 0 < symbol.arguments[2].number <= horizon:
                b, c = (_as_cell(argument) for argument in symbol.arguments[:2])
                goes.setdefault(symbol.arguments[2].number, {})[b] = c
        at = dict(self.positions)
        for k in range(1, horizon + 1):
            for robot, cell in sorted(at.items()):
                after = goes.get(k, {}).get(cell, cell)
                if after != cell:
                    named.append(Action(k, robot, "move", (after[0] - cell[0], after[1] - cell[1])))
                at[robot] = after
        return Plan(named)


def _named(symbol: clingo.Symbol, horizon: int) -> Action | None:
    """``occurs(object(robot,R),action(Name,Args),K)``, K in 1..``horizon``, as an action."""
    if not symbol.match("occurs", 3) or not 0 < symbol.arguments[2].number <= horizon:
        return None
    thing, action, when = symbol.arguments
    args = action.arguments[1]
    value = tuple(a.number for a in args.arguments) if args.type is clingo.SymbolType.Function else args.number
    return Action(when.number, thing.arguments[1].number, action.arguments[0].name, value)


def _neighbours(cell: Cell) -> list[Cell]:
    x, y = cell
    return [(x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)]


def _distances(instance: Instance, sources: list[Cell]) -> dict[Cell, int]:
    """Steps on the empty floor from the nearest of ``sources`` to every cell reached."""
    cells = instance.cells
    distance = {cell: 0 for cell in sources}
    queue = deque(sources)
    while queue:
        cell = queue.popleft()
        for near in _neighbours(cell):
            if near in cells and near not in distance:
                distance[near] = distance[cell] + 1
                queue.append(near)
    return distance


def _num(value: int) -> clingo.Symbol:
    return clingo.Number(value)


def _cell(cell: Cell) -> clingo.Symbol:
    return clingo.Tuple_([clingo.Number(cell[0]), clingo.Number(cell[1])])


def _as_cell(symbol: clingo.Symbol) -> Cell:
    return symbol.arguments[0].number, symbol.arguments[1].number


def _query(horizon: int) -> clingo.Symbol:
    return clingo.Function("query", [clingo.Number(horizon)])


def _hint(before: Cell, after: Cell, k: int) -> clingo.Symbol:
    return clingo.Function("hint", [_cell(before), _cell(after), clingo.Number(k)])


def _open(order: int, product: int) -> clingo.Symbol:
    return clingo.Function("open", [clingo.Number(order), clingo.Number(product)])


def _at(robot: int, cell: Cell) -> clingo.Symbol:
    return clingo.Function("at", [clingo.Number(robot), _cell(cell)])
