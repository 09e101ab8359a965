"""The replay: robot positions from the moves, then shelves, stock and order lines step by
step, reporting every rule the plan breaks (see :mod:`asprilo.simulate` for how a broken
rule changes the state).

numpy is imported inside the functions that use it: the checker imports this package to
explain violations, and a valid plan is checked without a replay (and without numpy)."""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..domain import Delivery, Domain
from ..model import Action, Cell, Instance, Plan, Term
from .actions import Report, effective_actions, robot_of
from .checks import Start, check_goal, check_instance, pairs_sharing
from .timeline import CLOSED, Changes, History, Line, Positions, Snapshot, Stock
from .violations import Finding

if TYPE_CHECKING:
    import numpy as np


def replay(instance: Instance, plan: Plan, domain: Domain) -> tuple[History, list[Finding]]:
    """The history of ``plan`` on ``instance`` and every rule it breaks."""
    findings: list[Finding] = []

    def report(module: str, check: str, *params: Any) -> None:
        findings.append((module, check, params))

    effective = effective_actions(instance, plan, domain, report)
    positions = robot_positions(instance, effective, max(plan.horizon, 0))
    start = check_instance(instance, domain, report)
    check_moves(positions, instance.cells, report)
    history = _ShelfReplay(instance, domain, positions, start, report).run(effective)
    check_goal(instance, domain, history, report)
    return history, findings


def robot_positions(instance: Instance, effective: dict[int, list[Action]], horizon: int) -> Positions:
    """Where every robot stands after every step, from its effective moves."""
    import numpy as np
    robot_ids = sorted(instance.robots)
    index: dict[Term, int] = {robot: i for i, robot in enumerate(robot_ids)}
    moves = np.zeros((horizon + 1, len(index), 2), dtype=np.int32)
    for step, actions in effective.items():
        for action in actions:
            if action.name == "move":
                moves[step, index[action.robot]] = action.args
    start = np.array([instance.robots[r].at for r in robot_ids], dtype=np.int32)
    moves[0] = start.reshape(len(index), 2)
    return Positions(robot_ids, np.cumsum(moves, axis=0))


# --- where robots go ---------------------------------------------------------------------

@dataclass
class _Codes:
    """Robot positions as one integer per cell: ``(x - low) * span + (y - low)``."""

    codes: np.ndarray  # steps x robots
    low: int
    span: int

    @classmethod
    def of(cls, positions: np.ndarray) -> _Codes:
        import numpy as np
        low = int(positions.min())
        span = int(positions.max()) - low + 1
        codes = (positions[..., 0].astype(np.int64) - low) * span + (positions[..., 1] - low)
        return cls(codes, low, span)

    def on_floor(self, codes: np.ndarray, nodes: Iterable[Cell]) -> np.ndarray:
        """Whether each of ``codes`` is the cell of a floor node."""
        import numpy as np
        low, span = self.low, self.span
        floor = [(x - low) * span + (y - low) for x, y in nodes if low <= x < low + span and low <= y < low + span]
        return np.isin(codes, np.array(floor, dtype=np.int64))


def check_moves(positions: Positions, nodes: set[Cell], report: Report) -> None:
    """Moves off the floor, two robots on one node and swaps, at every step >= 1."""
    import numpy as np
    if positions.horizon < 1 or not positions.robot_ids:
        return
    ids = positions.robot_ids
    codes = _Codes.of(positions.table)
    moved = codes.codes[1:] != codes.codes[:-1]
    for step, i in zip(*np.nonzero(moved & ~codes.on_floor(codes.codes[1:], nodes)), strict=True):
        report("move", "offFloor", ids[i], int(step) + 1)
    _same_node(codes.codes, ids, report)
    _swaps(codes, moved, ids, report)


def _same_node(codes: np.ndarray, ids: list[int], report: Report) -> None:
    import numpy as np
    ordered = np.sort(codes[1:], axis=1)
    shared = ordered[:, 1:] == ordered[:, :-1]
    for step in np.nonzero(shared.any(axis=1))[0] + 1:
        row = codes[step]
        crowded = np.isin(row, ordered[step - 1, 1:][shared[step - 1]])
        on_cell = {ids[i]: code for i, code in zip(np.nonzero(crowded)[0].tolist(), row[crowded].tolist(),
                                                   strict=True)}
        for first, second in pairs_sharing(on_cell):
            report("collision", "sameNode", first, second, int(step))


def _swaps(codes: _Codes, moved: np.ndarray, ids: list[int], report: Report) -> None:
    import numpy as np
    table, cells = codes.codes, codes.span * codes.span
    for step in np.nonzero(moved.any(axis=1))[0] + 1:
        movers = np.nonzero(moved[step - 1])[0]
        origin, target = table[step - 1, movers], table[step, movers]
        swapped = np.isin(origin * cells + target, target * cells + origin)
        for i in movers[swapped].tolist():
            for j in movers[(origin == table[step, i]) & (target == table[step - 1, i])].tolist():
                if ids[i] < ids[j]:
                    report("collision", "swap", ids[i], ids[j], int(step))


# --- shelves, stock and order lines ------------------------------------------------------

@dataclass
class _Pending:
    """What the actions of one step do to shelves, applied once all are checked."""

    lifts: dict[int, list[int]] = field(default_factory=lambda: defaultdict(list))  # shelf -> robots
    putdowns: list[tuple[int, int, Cell]] = field(default_factory=list)  # (robot, shelf, cell)
    deliveries: list[tuple[int, Action]] = field(default_factory=list)  # (shelf, action)


class _ShelfReplay:
    """Carries, resting shelves, stock and order lines through the steps of a plan."""

    def __init__(self, instance: Instance, domain: Domain, positions: Positions, start: Start,
                 report: Report):
        self.instance, self.domain, self.positions, self.report = instance, domain, positions, report
        self.nodes = instance.cells
        self.highways = set(instance.highways.values())
        self.station_cell = {ps: s.at for ps, s in instance.stations.items()}
        self.station_cells = set(self.station_cell.values())
        self.now = Snapshot(0, {robot: shelf for shelf, robot in start.holder.items()}, dict(start.resting),
                            self._initial_stock(), self._initial_lines())
        self.resting_at: dict[Cell, set[int]] = defaultdict(set)
        for shelf, cell in self.now.resting.items():
            self.resting_at[cell].add(shelf)
        products = instance.products
        mapf_lines = {line: [s for s in products[line[1]].stock if s in start.shelves]
                      if line[1] in products else [] for line in self.now.lines}
        releases = {order.id: order.release for order in instance.orders.values() if order.release is not None}
        self.history = History(domain, positions, self.now, mapf_lines, releases)

    def _initial_stock(self) -> dict[Stock, int | None]:
        counts = self.domain.counts_units
        return {(shelf, product.id): (1 if units is None and counts else units)
                for product in self.instance.products.values() for shelf, units in product.stock.items()}

    def _initial_lines(self) -> dict[Line, int | None]:
        counts = self.domain.counts_units
        return {(order.id, product): (1 if units is None and counts else units)
                for order in self.instance.orders.values() for product, units in order.lines.items()}

    def run(self, effective: dict[int, list[Action]]) -> History:
        for step in range(1, self.history.horizon + 1):
            actions = effective.get(step, ())
            changes = None
            if self.now.carries or any(action.name != "move" for action in actions):
                changes = self.step(step, actions)
            self.history.record(step, changes, self.now)
        return self.history

    def step(self, step: int, actions: Iterable[Action]) -> Changes:
        """Check the actions of one step, then apply what takes effect."""
        pending = _Pending()
        for action in actions:
            self._CHECKS[action.name](self, step, robot_of(action), action, pending)
        changes = Changes()
        self.put_down(pending.putdowns, changes)
        self.lift(step, pending.lifts, changes)
        for shelf, action in pending.deliveries:
            self.deliver(shelf, action, changes)
        return changes

    # --- one check per action ------------------------------------------------------------

    def _move(self, step: int, robot: int, _action: Action, _pending: _Pending) -> None:
        if robot in self.now.carries and self.resting_at.get(self.positions.at(robot, step)):
            self.report("move", "ontoShelf", robot, step)

    def _pickup(self, step: int, robot: int, _action: Action, pending: _Pending) -> None:
        cell = self.positions.at(robot, step - 1)
        if robot in self.now.carries:
            self.report("pickup", "carrying", robot, step)
        elif not self.resting_at.get(cell):
            self.report("pickup", "noShelf", robot, step)
        else:
            pending.lifts[min(self.resting_at[cell])].append(robot)

    def _putdown(self, step: int, robot: int, _action: Action, pending: _Pending) -> None:
        report = self.report
        shelf = self.now.carries.get(robot)
        if shelf is None:
            report("putdown", "notCarrying", robot, step)
            return
        cell = self.positions.at(robot, step - 1)
        if cell not in self.nodes:
            report("putdown", "offFloor", robot, step)
        if cell in self.highways:
            report("putdown", "onHighway", robot, step)
        if cell in self.station_cells:
            report("putdown", "onStation", robot, step)
        if self.resting_at.get(cell):
            report("putdown", "ontoShelf", robot, step)
        pending.putdowns.append((robot, shelf, cell))

    def _deliver(self, step: int, robot: int, action: Action, pending: _Pending) -> None:
        shelf = self.now.carries.get(robot)
        if self.check_delivery(step, robot, action, shelf) and shelf is not None:  # (False without a shelf)
            pending.deliveries.append((shelf, action))

    _CHECKS = {"move": _move, "pickup": _pickup, "putdown": _putdown, "deliver": _deliver}

    # --- what takes effect ---------------------------------------------------------------

    def put_down(self, putdowns: list[tuple[int, int, Cell]], changes: Changes) -> None:
        for robot, shelf, cell in putdowns:
            del self.now.carries[robot]
            self.now.resting[shelf] = cell
            self.resting_at[cell].add(shelf)
            changes.carries.append((robot, None))
            changes.resting.append((shelf, cell))

    def lift(self, step: int, lifts: dict[int, list[int]], changes: Changes) -> None:
        """Each lifted shelf goes to the smallest robot id that picks it up."""
        for shelf, robots in lifts.items():
            if len(robots) > 1:
                self.report("pickup", "sharedShelf", shelf, step)
            robot = min(robots)
            self.now.carries[robot] = shelf
            self.resting_at[self.now.resting.pop(shelf)].discard(shelf)
            changes.carries.append((robot, shelf))
            changes.resting.append((shelf, None))

    def check_delivery(self, step: int, robot: int, action: Action, shelf: int | None) -> bool:
        """Report what is wrong with a well-formed delivery; whether it takes effect."""
        report = self.report
        order = self.instance.orders.get(action.args[0])
        if shelf is None:
            report("deliver", "notCarrying", robot, step)
        at_station = False
        if order is None:
            report("deliver", "unknownOrder", robot, step)
        else:
            at_station = (order.station is not None
                          and self.station_cell.get(order.station) == self.positions.at(robot, step - 1))
            if not at_station:
                report("deliver", "wrongStation", robot, step)
            if order.release is not None and step <= order.release:
                report("deliver", "beforeRelease", robot, step)
            self._check_line(step, action)
        listed = shelf is not None and (shelf, action.args[1]) in self.now.stock
        if shelf is not None:
            self._check_shelf(step, action, shelf, listed)
        return shelf is not None and at_station and (listed or self.domain.delivery is Delivery.STATION)

    def _check_line(self, step: int, action: Action) -> None:
        line = (action.args[0], action.args[1])
        if self.domain.counts_units:
            if action.args[2] > (self.now.lines.get(line) or 0):
                self.report("deliver", "orderAmount", action.robot, step)
        elif line not in self.now.lines:
            self.report("deliver", "lineClosed", action.robot, step)

    def _check_shelf(self, step: int, action: Action, shelf: int, listed: bool) -> None:
        if not listed:
            self.report("deliver", "notOnShelf", action.robot, step)
        elif self.domain.counts_units and action.args[2] > self.now.stock[(shelf, action.args[1])]:
            self.report("deliver", "shelfAmount", action.robot, step)

    def deliver(self, shelf: int, action: Action, changes: Changes) -> None:
        order_id, product = action.args[0], action.args[1]
        lines, stock = self.now.lines, self.now.stock
        if self.domain.counts_units:
            units = action.args[2]
            if (order_id, product) in lines:
                lines[(order_id, product)] = max(0, lines[(order_id, product)] - units)
                changes.lines.append(((order_id, product), lines[(order_id, product)]))
            left = max(0, stock[(shelf, product)] - units)
            stock[(shelf, product)] = left
            changes.stock.append(((shelf, product), left))
            return
        if self.domain.delivery is Delivery.LINE:
            closing = [(order_id, product)] if (order_id, product) in lines else []
        else:
            station = self.instance.orders[order_id].station
            closing = [(o, p) for (o, p) in lines
                       if self.instance.orders[o].station == station and (shelf, p) in stock]
        for line in closing:
            del lines[line]
            changes.lines.append((line, CLOSED))
