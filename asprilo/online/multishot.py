"""The multi-shot ASP online planner of domain M: one clingo ``Control`` for a whole online run
(:mod:`.lookahead` has the control and the search over horizons; :mod:`.multishot_a` plans
domain A).

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
A call searches the smallest h (:meth:`.Lookahead.search`), one solve call a horizon,
within its seconds (cancel honoured); the first horizon tried is that of the hints (or the
lower bound, if larger).  The plan is read
from the model's ``go(B,C,K)`` (anonymous robots, named here by following their cells) or
``occurs(object(robot,R),action(A,X),K)`` atoms, K steps after now.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Sequence
from pathlib import Path

import clingo

from asprilo.domain import Domain, Goal
from asprilo.errors import InputError
from asprilo.model import Action, Cell, Instance, Order, Plan

from .lookahead import MOST_LOOKAHEAD, Lookahead, cell_of, cell_term, distances, number, trip

#: the reference online encoding of domain M
REFERENCE = Path(__file__).resolve().parent.parent / "encodings" / "online" / "m.lp"
#: lines done between two cleanups (the grounder then drops what released externals made false)
CLEANUP_EVERY = 10

Line = tuple[int, int]  # (order, product)


class MultiShot(Lookahead):
    """An :class:`~asprilo.online.planning.OnlinePlanning` planner on one clingo Control.

    ``encoding``: the program files (default: the reference encoding of domain M);
    ``arguments``: clingo's command-line options; ``clock``: the wall clock of the budget;
    ``fresh``: a new Control every call (the baseline of :mod:`.lookahead`)."""

    def __init__(self, instance: Instance, domain: Domain, encoding: Sequence[str] = (), *,
                 arguments: Sequence[str] = (), most_lookahead: int = MOST_LOOKAHEAD,
                 clock: Callable[[], float] = time.monotonic, fresh: bool = False):
        if domain.goal is not Goal.SHELVES:
            raise InputError(f"the multi-shot planner of domain M does not plan domain {domain.label}")
        super().__init__(instance, encoding or (str(REFERENCE),), arguments=arguments,
                         most_lookahead=most_lookahead, clock=clock, fresh=fresh)
        self.domain = domain
        self.positions: dict[int, Cell] = {r: robot.at for r, robot in sorted(instance.robots.items())}
        self.shelf_cells = {product: {instance.shelves[s].at for s in item.stock if s in instance.shelves}
                            for product, item in instance.products.items()}
        self.covered = self._covered()
        self.open: dict[Line, int] = {}    # line -> release step
        self.parts: dict[Line, list[clingo.Symbol]] = {}  # line -> its part's arguments
        self.done: dict[Line, int] = {}    # line -> the step it was done
        self.fields: dict[int, dict[Cell, int]] = {}  # product -> steps to its shelves
        self.planned_trips: dict[int, list[Cell]] = {}

    # --- what happens in the world ---------------------------------------------------------------

    def released(self, orders: list[Order], step: int) -> None:
        """Ground one ``line`` part per line of the orders released after ``step``; open them."""
        lines = []
        for order in orders:
            for product, units in sorted(order.lines.items()):
                line = (order.id, product)
                lines.append(line)
                self.open[line] = step
                self.parts[line] = [number(order.id), number(product), number(1 if units is None else units),
                                    number(0 if order.station is None else order.station), number(step)]
        self.ground_parts([("line", self.parts[line]) for line in lines])
        self.assign({_open(*line): True for line in lines})

    def carried_out(self, step: int, actions: list[Action]) -> None:
        """Follow the robots through step ``step``; release ``open`` for the lines it did."""
        moves = {action.robot: action.args for action in actions if action.name == "move"}
        for robot, (x, y) in self.positions.items():
            dx, dy = moves.get(robot, (0, 0))
            self.positions[robot] = (x + dx, y + dy)
        self.covered = self._covered()
        for line, release in sorted(self.open.items()):
            if release < step and line[1] in self.covered:
                del self.open[line], self.parts[line]
                self.done[line] = step
                self.control.release_external(_open(*line))
                self.assigned.pop(_open(*line), None)
                if len(self.done) % CLEANUP_EVERY == 0:
                    self.control.cleanup()

    # --- planning ----------------------------------------------------------------------------------

    def plan(self, step: int, seconds: float, cancel: threading.Event) -> Plan | None:
        """The shortest plan from the state after ``step`` that serves every open line (steps
        1..H counted from ``step``) found in ``seconds``; ``None`` when none is found."""
        if not self.open:
            return Plan([])
        return self.search(seconds, cancel)

    def restart_parts(self) -> list[tuple[str, list[clingo.Symbol]]]:
        return [("line", arguments) for _line, arguments in sorted(self.parts.items())]

    def prepare(self) -> tuple[int, int]:
        self.planned_trips = self.trips()
        return self.lower_bound(), max((len(cells) for cells in self.planned_trips.values()), default=0)

    def assign_world(self) -> None:
        """``at(R,C)`` where the robots stand now, ``open`` for the open lines (a fresh control's
        externals start false) and ``hint(B,C,K)`` along every robot's trip (standing once
        there, or when sent nowhere), within the steps grounded."""
        self.assign_set("at", (_at(robot, cell) for robot, cell in self.positions.items()))
        self.assign({_open(*line): True for line in self.open})
        hints = set()
        for robot, cell in self.positions.items():
            cells = self.planned_trips.get(robot, [])
            for k in range(1, self.lookahead + 1):
                after = cells[k - 1] if k <= len(cells) else cell
                hints.add(_hint(cell, after, k))
                cell = after
        self.assign_set("hint", hints)

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
                trips[robot] = trip(self.positions[robot], self._field(product))
                served.add(product)
        return trips

    def _field(self, product: int) -> dict[Cell, int]:
        """Steps from every cell to the nearest shelf holding ``product`` (computed once)."""
        if product not in self.fields:
            self.fields[product] = distances(self.instance.cells, sorted(self.shelf_cells.get(product, ())))
        return self.fields[product]

    def lower_bound(self) -> int:
        """No plan serves every open line in fewer steps: for each, the floor distance of the
        nearest robot to a shelf holding its product (at least 1: served after now)."""
        distance = distances(self.instance.cells, list(self.positions.values()))
        bound = 1
        for _order, product in self.open:
            near = min((distance[cell] for cell in self.shelf_cells.get(product, ()) if cell in distance),
                       default=None)
            if near is None:
                return self.most_lookahead + 1
            bound = max(bound, near)
        return bound

    def _covered(self) -> set[int]:
        """The products some robot stands under a shelf of now."""
        cells = set(self.positions.values())
        return {product for product, shelves in self.shelf_cells.items() if shelves & cells}

    def read_plan(self, symbols: list[clingo.Symbol], horizon: int) -> Plan:
        """The actions of steps 1..``horizon`` after now: from ``occurs/3`` or ``go/3``."""
        named = [action for symbol in symbols if (action := _named(symbol, horizon)) is not None]
        goes: dict[int, dict[Cell, Cell]] = {}
        for symbol in symbols:
            if symbol.match("go", 3) and 0 < symbol.arguments[2].number <= horizon:
                b, c = (cell_of(argument) for argument in symbol.arguments[:2])
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


def _hint(before: Cell, after: Cell, k: int) -> clingo.Symbol:
    return clingo.Function("hint", [cell_term(before), cell_term(after), clingo.Number(k)])


def _open(order: int, product: int) -> clingo.Symbol:
    return clingo.Function("open", [clingo.Number(order), clingo.Number(product)])


def _at(robot: int, cell: Cell) -> clingo.Symbol:
    return clingo.Function("at", [clingo.Number(robot), cell_term(cell)])
