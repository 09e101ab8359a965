"""Replay a plan step by step (SPEC.md §4) in plain Python: the state after every step and
every rule the plan breaks.

This is the second, independent implementation of the rules that the ASP checker
(``asprilo.checker``) implements; the two report exactly the same violations, named as the
checker's ``err(Module,Check,Params)`` atoms.  The visualizer animates from it.

How a plan that breaks a rule changes the state (the checker does the same):

- An action takes effect only when it is well formed: a robot of the instance acts at a
  step >= 1, it is the robot's only action at that step, the name is an action of the
  domain and the arguments have the right shape.  Otherwise it is reported and ignored.
- ``move`` always takes effect: the robot (and the shelf it carries) goes where the plan
  says, even off the floor, onto another robot or a resting shelf.
- ``pickup`` lifts the shelf resting on the robot's node unless the robot already carries
  one or none rests there.  Where an earlier error left several shelves resting on one
  node the smallest id is lifted; where several robots pick up one shelf at once the
  robot with the smallest id gets it.  (The same tie-break settles an instance in which
  several robots carry one shelf.)
- ``putdown`` puts the carried shelf down wherever the robot stands (also on a highway,
  a picking station, off the floor or onto another shelf); without a shelf it does nothing.
- ``deliver`` takes effect when the robot carries a shelf, stands on the order's picking
  station and, in A and B, the shelf lists the product.  In A the units the order line
  misses and the units on the shelf both drop by N, never below zero: an over-delivery
  is reported and then completes the line instead of spoiling every later step.  In B it
  closes the line (O,P); in C it closes every open line, of every order of that
  station, whose product the shelf lists.
- In A a quantity-free fact (``on S`` / ``line P``) counts as one unit.

State checks are event based: collisions and swaps of robots at every step; a shelf
coming onto a node where another shelf rests is reported by the action that does it.

The timeline keeps robot positions as one array and, for shelves, stock and order lines,
only what each step changed plus a few checkpoints; ``state(t)`` is put together on
demand, quickly for steps in sequence and from the nearest checkpoint otherwise.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .domain import Domain, detect_domain
from .model import DIRECTIONS, Action, Cell, Instance, Plan
from .writer import format_value

#: the actions each domain knows
DOMAIN_ACTIONS: dict[Domain, frozenset[str]] = {
    Domain.A: frozenset({"move", "pickup", "putdown", "deliver"}),
    Domain.B: frozenset({"move", "pickup", "putdown", "deliver"}),
    Domain.C: frozenset({"move", "pickup", "putdown", "deliver"}),
    Domain.M: frozenset({"move"}),
    Domain.MD: frozenset({"move"}),
}

Line = tuple[int, int]  # (order, product)
Stock = tuple[int, int]  # (shelf, product)
_CLOSED = object()  # what a line becomes in the changes of a step when B or C close it


@dataclass
class State:
    """The warehouse after a step (0: the instance)."""

    step: int
    robots: dict[int, Cell]
    carries: dict[int, int]
    shelves: dict[int, Cell]
    stock: dict[Stock, int | None]
    open_lines: dict[Line, int | None]


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


# --- well-formed actions -----------------------------------------------------------------

_MOVES = frozenset(DIRECTIONS)


def _ints(args: Any, lengths: tuple[int, ...]) -> bool:
    return type(args) is tuple and len(args) in lengths and all(type(a) is int for a in args)


def well_formed(name: str, args: Any, domain: Domain) -> bool:
    """Whether ``args`` have the shape action ``name`` takes in ``domain`` (SPEC.md §3)."""
    if name == "move":
        return args in _MOVES and type(args[0]) is int
    if name in ("pickup", "putdown"):
        return args == ()
    if name == "deliver":
        if domain is Domain.A:
            return _ints(args, (3,)) and args[2] >= 1
        return _ints(args, (2, 3))
    return False


# --- the replay --------------------------------------------------------------------------

@dataclass
class _Changes:
    """What one step changed besides robot positions."""

    carries: list[tuple[int, int | None]] = field(default_factory=list)
    resting: list[tuple[int, Cell | None]] = field(default_factory=list)
    stock: list[tuple[Stock, int]] = field(default_factory=list)
    lines: list[tuple[Line, Any]] = field(default_factory=list)  # A: units missing; B/C: _CLOSED


@dataclass
class _Snapshot:
    step: int
    carries: dict[int, int]
    resting: dict[int, Cell]
    stock: dict[Stock, int | None]
    lines: dict[Line, int | None]

    def resting_at(self, cell: Cell) -> list[int]:
        return [shelf for shelf, at in self.resting.items() if at == cell]

    def copy(self) -> _Snapshot:
        return _Snapshot(self.step, dict(self.carries), dict(self.resting), dict(self.stock),
                         dict(self.lines))

    def apply(self, changes: _Changes) -> None:
        for robot, shelf in changes.carries:
            if shelf is None:
                self.carries.pop(robot, None)
            else:
                self.carries[robot] = shelf
        for shelf, cell in changes.resting:
            if cell is None:
                self.resting.pop(shelf, None)
            else:
                self.resting[shelf] = cell
        self.stock.update(changes.stock)
        for line, units in changes.lines:
            if units is _CLOSED:
                self.lines.pop(line, None)
            else:
                self.lines[line] = units


class Timeline:
    """The replay of a plan: ``state(t)`` after every step and the violations found."""

    def __init__(self, instance: Instance, plan: Plan, domain: Domain):
        self.instance = instance
        self.plan = plan
        self.domain = domain
        self.horizon = max(plan.horizon, 0)
        self.robot_ids: list[int] = sorted(instance.robots)
        self._index = {robot: i for i, robot in enumerate(self.robot_ids)}
        self._actions: dict[tuple, list[Action]] | None = None
        self._rows: dict[int, list] = {}  # positions of recent steps, as lists
        self._cached: _Snapshot | None = None  # the last snapshot made
        _Replay(self).run()

    # filled in by _Replay
    violations: list[Violation]
    _positions: np.ndarray              # (horizon+1) x robots x 2, int32
    _changes: dict[int, _Changes]       # step -> what it changed besides positions
    _checkpoints: list[_Snapshot]       # after steps 0, every, 2 * every, ...
    _every: int
    _mapf_lines: dict[Line, list[int]]  # M: line -> shelves holding its product

    @property
    def valid(self) -> bool:
        return not self.violations

    # --- states ------------------------------------------------------------------------

    def position(self, robot: int, step: int) -> Cell:
        """Where ``robot`` stands after ``step``."""
        step = min(max(step, 0), self.horizon)
        row = self._rows.get(step)
        if row is None:
            if len(self._rows) > 3:
                self._rows.clear()
            row = self._rows[step] = self._positions[step].tolist()
        return tuple(row[self._index[robot]])

    def actions_of(self, robot: Any, step: int, kind: str = "robot") -> list[Action]:
        """The plan's actions of one object at one step."""
        if self._actions is None:
            self._actions = defaultdict(list)
            for action in self.plan.actions:
                self._actions[(action.kind, action.robot, action.step)].append(action)
        return self._actions.get((kind, robot, step), [])

    def _snapshot(self, step: int) -> _Snapshot:
        """Carried and resting shelves, stock and order lines after ``step`` (shared: copy it)."""
        step = min(max(step, 0), self.horizon)
        cached = self._cached
        start = self._checkpoints[min(step // self._every, len(self._checkpoints) - 1)]
        if cached is not None and start.step <= cached.step <= step:
            start = cached
        if start.step == step:
            return start
        snapshot = start.copy()
        for t in range(start.step + 1, step + 1):
            changes = self._changes.get(t)
            if changes is not None:
                snapshot.apply(changes)
        snapshot.step = step
        self._cached = snapshot
        return snapshot

    def state(self, t: int) -> State:
        """The state after step ``t`` (0: initial; beyond the horizon: the final state)."""
        last = min(max(t, 0), self.horizon)
        snapshot = self._snapshot(last)
        row = self._positions[last].tolist()
        robots = {robot: (x, y) for robot, (x, y) in zip(self.robot_ids, row)}
        shelves = dict(snapshot.resting)
        for robot, shelf in snapshot.carries.items():
            shelves[shelf] = robots[robot]
        if self.domain is Domain.A:
            lines = {line: units for line, units in snapshot.lines.items() if units > 0}
        elif self.domain is Domain.M:
            occupied = set(robots.values())
            lines = {line: units for line, units in snapshot.lines.items()
                     if not any(shelves.get(shelf) in occupied for shelf in self._mapf_lines[line])}
        else:
            lines = dict(snapshot.lines)
        return State(max(t, 0), robots, dict(snapshot.carries), shelves, dict(snapshot.stock), lines)

    # --- diagnostics ---------------------------------------------------------------------

    def explain(self, module: str, check: str, params: tuple) -> Violation:
        """The violation ``err(module,check,params)`` in plain words, with what to highlight."""
        return _explain(self, module, check, tuple(params))


def simulate(instance: Instance, plan: Plan, domain: Domain | None = None) -> Timeline:
    """Replay ``plan`` on ``instance`` (domain detected when not given)."""
    return Timeline(instance, plan, domain or detect_domain(instance, plan))


class _Replay:
    """Computes a timeline's positions, changes, checkpoints and violations."""

    def __init__(self, timeline: Timeline):
        self.timeline = timeline
        self.instance = instance = timeline.instance
        self.domain = timeline.domain
        self.horizon = timeline.horizon
        self.found: list[tuple[str, str, tuple]] = []
        self.nodes = instance.cells
        self.highways = set(instance.highways.values())
        self.station_cell = {ps: s.at for ps, s in instance.stations.items()}
        self.station_cells = set(self.station_cell.values())
        self.listed: dict[Stock, int | None] = {
            (shelf, product.id): units
            for product in instance.products.values() for shelf, units in product.stock.items()}

    def report(self, module: str, check: str, *params: Any) -> None:
        self.found.append((module, check, params))

    def run(self) -> None:
        timeline = self.timeline
        effective = self.classify_actions()
        self.compute_positions(effective)
        self.check_instance()
        self.check_moves()
        self.replay(effective)
        self.check_goal()
        found = sorted(dict.fromkeys(self.found), key=lambda entry: entry[2][-1])  # by step: cheap lookups
        timeline.violations = sort_violations([timeline.explain(*entry) for entry in found])

    # --- actions -------------------------------------------------------------------------

    def classify_actions(self) -> dict[int, list[Action]]:
        """Report malformed actions; return the effective ones by step."""
        robots, known, domain = self.instance.robots, DOMAIN_ACTIONS[self.domain], self.domain
        report = self.report
        effective: dict[int, list[Action]] = defaultdict(list)
        actions = self.timeline.plan.actions
        # the plan is sorted, so the actions of one object at one step come one after another
        keys = [(a.step, a.robot, a.kind) for a in actions]
        shared = [False] + [a == b for a, b in zip(keys, keys[1:])] + [False]
        for i, action in enumerate(actions):
            step, robot = action.step, action.robot
            if action.kind != "robot":
                report("action", "notRobot", action.kind, robot, step)
            elif robot not in robots:
                report("action", "unknownRobot", robot, step)
            elif step < 1:
                report("action", "badStep", robot, step)
            else:
                alone = not (shared[i] or shared[i + 1])
                if action.name not in known:
                    report("action", "unknownAction", robot, action.name, step)
                elif not well_formed(action.name, action.args, domain):
                    report("action", "badArguments", robot, action.name, step)
                elif alone:
                    effective[step].append(action)
                if not alone:
                    report("action", "concurrent", robot, step)
        return effective

    def compute_positions(self, effective: dict[int, list[Action]]) -> None:
        timeline, index = self.timeline, self.timeline._index
        steps = self.horizon + 1
        moves = np.zeros((steps, len(index), 2), dtype=np.int32)
        for step, actions in effective.items():
            for action in actions:
                if action.name == "move":
                    moves[step, index[action.robot]] = action.args
        start = np.array([self.instance.robots[r].at for r in timeline.robot_ids], dtype=np.int32)
        moves[0] = start.reshape(len(index), 2)
        timeline._positions = np.cumsum(moves, axis=0)

    # --- the instance --------------------------------------------------------------------

    def check_instance(self) -> None:
        instance, nodes, report = self.instance, self.nodes, self.report
        carriers: dict[int, list[int]] = defaultdict(list)
        for robot in sorted(instance.robots.values(), key=lambda r: r.id):
            if robot.at not in nodes:
                report("instance", "robotOffFloor", robot.id, 0)
            if robot.carries is not None:
                carriers[robot.carries].append(robot.id)
                shelf = instance.shelves.get(robot.carries)
                if shelf is not None and shelf.at != robot.at:
                    report("instance", "carriedShelfElsewhere", robot.id, robot.carries, 0)
        self.holder = {shelf: min(robots) for shelf, robots in carriers.items()}
        for shelf, robots in carriers.items():
            if len(robots) > 1:
                report("instance", "sharedShelf", shelf, 0)
        resting = {s.id: s.at for s in instance.shelves.values() if s.id not in self.holder}
        for shelf, cell in resting.items():
            if cell not in nodes:
                report("instance", "shelfOffFloor", shelf, 0)
            if cell in self.highways:
                report("instance", "shelfOnHighway", shelf, 0)
            if cell in self.station_cells:
                report("instance", "shelfOnStation", shelf, 0)
        for station in instance.stations.values():
            if station.at not in nodes:
                report("instance", "stationOffFloor", station.id, 0)
        robot_cells = {r.id: r.at for r in instance.robots.values()}
        shelf_cells = dict(resting)
        shelf_cells.update({shelf: robot_cells[robot] for shelf, robot in self.holder.items()})
        for first, second in _pairs_sharing(robot_cells):
            report("instance", "robotCollision", first, second, 0)
        for first, second in _pairs_sharing(shelf_cells):
            report("instance", "shelfCollision", first, second, 0)
        self.existing_shelves = set(shelf_cells)
        for order in instance.orders.values():
            if self.domain.delivers:
                if order.station is None:
                    report("instance", "orderStation", order.id, 0)
                elif order.station not in instance.stations:
                    report("instance", "unknownStation", order.id, order.station, 0)
            for product in order.lines:
                stock = instance.products[product].stock if product in instance.products else {}
                if not any(shelf in self.existing_shelves for shelf in stock):
                    report("instance", "unknownProduct", order.id, product, 0)
        self.initial_resting = resting

    # --- where robots go ---------------------------------------------------------------

    def check_moves(self) -> None:
        """Moves off the floor, two robots on one node and swaps, at every step >= 1."""
        positions, ids = self.timeline._positions, self.timeline.robot_ids
        if self.horizon < 1 or not ids:
            return
        low = int(positions.min())
        span = int(positions.max()) - low + 1
        codes = (positions[..., 0].astype(np.int64) - low) * span + (positions[..., 1] - low)  # steps x robots
        floor = np.zeros(span * span, dtype=bool)
        for x, y in self.nodes:
            if low <= x < low + span and low <= y < low + span:
                floor[(x - low) * span + (y - low)] = True
        moved = codes[1:] != codes[:-1]
        for step, i in zip(*np.nonzero(moved & ~floor[codes[1:]])):
            self.report("move", "offFloor", ids[i], int(step) + 1)
        ordered = np.sort(codes[1:], axis=1)
        shared = ordered[:, 1:] == ordered[:, :-1]
        for step in np.nonzero(shared.any(axis=1))[0] + 1:
            row = codes[step]
            crowded = np.isin(row, ordered[step - 1, 1:][shared[step - 1]])
            on_cell = {ids[i]: code for i, code in zip(np.nonzero(crowded)[0].tolist(), row[crowded].tolist())}
            for first, second in _pairs_sharing(on_cell):
                self.report("collision", "sameNode", first, second, int(step))
        for step in np.nonzero(moved.any(axis=1))[0] + 1:
            movers = np.nonzero(moved[step - 1])[0]
            origin, target = codes[step - 1, movers], codes[step, movers]
            swapped = np.isin(origin * span * span + target, target * span * span + origin)
            for i in movers[swapped].tolist():
                for j in movers[(origin == codes[step, i]) & (target == codes[step - 1, i])].tolist():
                    if ids[i] < ids[j]:
                        self.report("collision", "swap", ids[i], ids[j], int(step))

    # --- shelves, deliveries -------------------------------------------------------------

    def initial_lines(self) -> dict[Line, int | None]:
        lines = {}
        for order in self.instance.orders.values():
            for product, units in order.lines.items():
                lines[(order.id, product)] = (1 if units is None else units) if \
                    self.domain is Domain.A else units
        return lines

    def replay(self, effective: dict[int, list[Action]]) -> None:
        timeline, domain = self.timeline, self.domain
        carries = {robot: shelf for shelf, robot in self.holder.items()}
        resting = dict(self.initial_resting)
        resting_at: dict[Cell, set[int]] = defaultdict(set)
        for shelf, cell in resting.items():
            resting_at[cell].add(shelf)
        stock = {key: (1 if units is None else units) if domain is Domain.A else units
                 for key, units in self.listed.items()}
        lines = self.initial_lines()
        self.lines = lines
        every = max(64, self.horizon // 32)
        timeline._every = every
        timeline._checkpoints = [_Snapshot(0, dict(carries), dict(resting), dict(stock), dict(lines))]
        timeline._changes = changes_by_step = {}
        timeline._mapf_lines = {line: [s for s in self.instance.products[line[1]].stock
                                       if s in self.existing_shelves]
                                if line[1] in self.instance.products else []
                                for line in lines}
        position = timeline.position
        for step in range(1, self.horizon + 1):
            actions = effective.get(step, ())
            if carries or any(action.name != "move" for action in actions):
                changes = self.step(step, actions, carries, resting, resting_at, stock, lines, position)
                if changes is not None:
                    changes_by_step[step] = changes
            if step % every == 0:
                timeline._checkpoints.append(
                    _Snapshot(step, dict(carries), dict(resting), dict(stock), dict(lines)))

    def step(self, step, actions, carries, resting, resting_at, stock, lines, position):
        report, domain = self.report, self.domain
        before = step - 1
        lifts: dict[int, list[int]] = defaultdict(list)
        putdowns: list[tuple[int, int, Cell]] = []
        deliveries: list[tuple[int, Action]] = []
        for action in actions:
            robot = action.robot
            shelf = carries.get(robot)
            if action.name == "move":
                if shelf is not None and resting_at.get(position(robot, step)):
                    report("move", "ontoShelf", robot, step)
            elif action.name == "pickup":
                cell = position(robot, before)
                if shelf is not None:
                    report("pickup", "carrying", robot, step)
                elif not resting_at.get(cell):
                    report("pickup", "noShelf", robot, step)
                else:
                    lifts[min(resting_at[cell])].append(robot)
            elif action.name == "putdown":
                if shelf is None:
                    report("putdown", "notCarrying", robot, step)
                    continue
                cell = position(robot, before)
                if cell not in self.nodes:
                    report("putdown", "offFloor", robot, step)
                if cell in self.highways:
                    report("putdown", "onHighway", robot, step)
                if cell in self.station_cells:
                    report("putdown", "onStation", robot, step)
                if resting_at.get(cell):
                    report("putdown", "ontoShelf", robot, step)
                putdowns.append((robot, shelf, cell))
            elif action.name == "deliver":
                if self.check_delivery(step, action, shelf, stock, lines, position):
                    deliveries.append((shelf, action))
        changes = _Changes()
        for robot, shelf, cell in putdowns:
            del carries[robot]
            resting[shelf] = cell
            resting_at[cell].add(shelf)
            changes.carries.append((robot, None))
            changes.resting.append((shelf, cell))
        for shelf, robots in lifts.items():
            if len(robots) > 1:
                report("pickup", "sharedShelf", shelf, step)
            robot = min(robots)
            carries[robot] = shelf
            resting_at[resting.pop(shelf)].discard(shelf)
            changes.carries.append((robot, shelf))
            changes.resting.append((shelf, None))
        for shelf, action in deliveries:
            self.deliver(shelf, action, stock, lines, changes)
        if changes.carries or changes.stock or changes.lines:
            return changes
        return None

    def check_delivery(self, step, action, shelf, stock, lines, position) -> bool:
        """Report what is wrong with a well-formed delivery; whether it takes effect."""
        report, robot, domain = self.report, action.robot, self.domain
        order_id, product = action.args[0], action.args[1]
        order = self.instance.orders.get(order_id)
        if shelf is None:
            report("deliver", "notCarrying", robot, step)
        at_station = False
        if order is None:
            report("deliver", "unknownOrder", robot, step)
        else:
            at_station = self.station_cell.get(order.station) == position(robot, step - 1)
            if not at_station:
                report("deliver", "wrongStation", robot, step)
            if domain is Domain.A:
                if action.args[2] > (lines.get((order_id, product)) or 0):
                    report("deliver", "orderAmount", robot, step)
            elif (order_id, product) not in lines:
                report("deliver", "lineClosed", robot, step)
        listed = shelf is not None and (shelf, product) in stock
        if shelf is not None:
            if not listed:
                report("deliver", "notOnShelf", robot, step)
            elif domain is Domain.A and action.args[2] > stock[(shelf, product)]:
                report("deliver", "shelfAmount", robot, step)
        return shelf is not None and at_station and (listed or domain is Domain.C)

    def deliver(self, shelf: int, action: Action, stock, lines, changes: _Changes) -> None:
        order_id, product = action.args[0], action.args[1]
        if self.domain is Domain.A:
            units = action.args[2]
            if (order_id, product) in lines:
                lines[(order_id, product)] = max(0, lines[(order_id, product)] - units)
                changes.lines.append(((order_id, product), lines[(order_id, product)]))
            stock[(shelf, product)] = max(0, stock[(shelf, product)] - units)
            changes.stock.append(((shelf, product), stock[(shelf, product)]))
            return
        if self.domain is Domain.B:
            closing = [(order_id, product)] if (order_id, product) in lines else []
        else:
            station = self.instance.orders[order_id].station
            closing = [(o, p) for (o, p) in lines
                       if self.instance.orders[o].station == station and (shelf, p) in stock]
        for line in closing:
            del lines[line]
            changes.lines.append((line, _CLOSED))

    # --- the goal ------------------------------------------------------------------------

    def check_goal(self) -> None:
        horizon, domain, report = self.horizon, self.domain, self.report
        timeline = self.timeline
        if self.instance.assignment and not domain.delivers:
            final = timeline.state(horizon)
            for robot, (kind, goal) in sorted(self.instance.assignment.items()):
                cell = final.shelves.get(goal) if kind == "shelf" else self.instance.destinations[goal].at
                if cell is not None and final.robots[robot] != cell:
                    report("goal", "missedAssignedGoal", robot, cell, horizon)
        if domain is Domain.MD:
            occupied = {timeline.position(r, horizon) for r in timeline.robot_ids}
            for destination in sorted(self.instance.destinations.values(), key=lambda d: d.id):
                if destination.at not in occupied:
                    report("goal", "unoccupiedDestination", destination.id, horizon)
            return
        if domain is Domain.M:
            final = timeline.state(horizon)
            for (order, product), units in sorted(self.initial_lines().items()):
                if (order, product) in final.open_lines:
                    report("goal", "unfilledOrder", order, product, 1 if units is None else units, horizon)
            return
        for (order, product), units in sorted(self.lines.items()):
            if domain is Domain.A:
                if units > 0:
                    report("goal", "unfilledOrder", order, product, units, horizon)
            else:
                report("goal", "unfilledOrder", order, product, 1 if units is None else units, horizon)


def _pairs_sharing(cells: dict[int, Cell]) -> Iterable[tuple[int, int]]:
    """Pairs ``(a, b)``, ``a < b``, of keys mapped to the same cell."""
    by_cell: dict[Cell, list[int]] = defaultdict(list)
    for key, cell in cells.items():
        by_cell[cell].append(key)
    for keys in by_cell.values():
        keys.sort()
        for i, first in enumerate(keys):
            for second in keys[i + 1:]:
                yield first, second


# --- violations in plain words -----------------------------------------------------------

def _cell(cell: Any) -> str:
    return f"({cell[0]},{cell[1]})" if isinstance(cell, tuple) and len(cell) == 2 else format_value(cell)


def _units(count: int, what: str = "unit") -> str:
    return f"{count} {what}" + ("" if count == 1 else "s")


def _station_words(timeline: Timeline, station: Any) -> str:
    found = timeline.instance.stations.get(station)
    return f"picking station {station}" + (f" at {_cell(found.at)}" if found else "")


def _explain(timeline: Timeline, module: str, check: str, params: tuple) -> Violation:
    step = params[-1] if params and isinstance(params[-1], int) else 0
    describe = _DESCRIPTIONS.get((module, check))
    try:
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


_DESCRIPTIONS: dict[tuple[str, str], Any] = {}


def _describes(module: str, check: str):
    def register(function):
        _DESCRIPTIONS[(module, check)] = function
        return function
    return register


# the instance

@_describes("instance", "robotOffFloor")
def _(timeline, robot, _step):
    cell = timeline.instance.robots[robot].at
    return f"robot {robot} starts at {_cell(cell)}, which is not a floor node", \
        {"robots": [robot], "cells": [cell]}


@_describes("instance", "shelfOffFloor")
def _(timeline, shelf, _step):
    cell = timeline.instance.shelves[shelf].at
    return f"shelf {shelf} stands at {_cell(cell)}, which is not a floor node", \
        {"shelves": [shelf], "cells": [cell]}


@_describes("instance", "stationOffFloor")
def _(timeline, station, _step):
    cell = timeline.instance.stations[station].at
    return f"picking station {station} is at {_cell(cell)}, which is not a floor node", {"cells": [cell]}


@_describes("instance", "robotCollision")
def _(timeline, first, second, _step):
    cell = timeline.instance.robots[first].at
    return f"robots {first} and {second} both start on {_cell(cell)}", \
        {"robots": [first, second], "cells": [cell]}


@_describes("instance", "shelfCollision")
def _(timeline, first, second, _step):
    cell = timeline.state(0).shelves.get(first)
    return f"shelves {first} and {second} both stand on {_cell(cell)}", \
        {"shelves": [first, second], "cells": [cell]}


@_describes("instance", "shelfOnHighway")
def _(timeline, shelf, _step):
    cell = timeline.instance.shelves[shelf].at
    return f"shelf {shelf} rests on the highway node {_cell(cell)}", {"shelves": [shelf], "cells": [cell]}


@_describes("instance", "shelfOnStation")
def _(timeline, shelf, _step):
    cell = timeline.instance.shelves[shelf].at
    return f"shelf {shelf} rests on the picking station at {_cell(cell)}", \
        {"shelves": [shelf], "cells": [cell]}


@_describes("instance", "carriedShelfElsewhere")
def _(timeline, robot, shelf, _step):
    robot_cell, shelf_cell = timeline.instance.robots[robot].at, timeline.instance.shelves[shelf].at
    return (f"robot {robot} at {_cell(robot_cell)} carries shelf {shelf}, but shelf {shelf} "
            f"stands at {_cell(shelf_cell)}"), \
        {"robots": [robot], "shelves": [shelf], "cells": [robot_cell, shelf_cell]}


@_describes("instance", "sharedShelf")
def _(timeline, shelf, _step):
    robots = sorted(r.id for r in timeline.instance.robots.values() if r.carries == shelf)
    names = ", ".join(map(str, robots[:-1])) + f" and {robots[-1]}"
    return f"robots {names} all carry shelf {shelf} (robot {robots[0]} keeps it)", \
        {"robots": robots, "shelves": [shelf]}


@_describes("instance", "orderStation")
def _(timeline, order, _step):
    return f"order {order} names no picking station", {}


@_describes("instance", "unknownStation")
def _(timeline, order, station, _step):
    return f"order {order} is to be delivered at picking station {station}, which does not exist", {}


@_describes("instance", "unknownProduct")
def _(timeline, order, product, _step):
    return f"order {order} asks for product {product}, which no shelf holds", {}


# the plan's actions

def _action_words(actions: list[Action]) -> str:
    return ", ".join(f"{a.name}{format_value(a.args) if a.args != () else ''}" for a in actions)


@_describes("action", "notRobot")
def _(timeline, kind, ident, step):
    actions = timeline.actions_of(ident, step, kind)
    return f"the plan gives {kind} {ident} the action {_action_words(actions)}, but only robots act", {}


@_describes("action", "unknownRobot")
def _(timeline, robot, step):
    return f"the plan moves robot {robot}, but the instance has no robot {robot}", {}


@_describes("action", "badStep")
def _(timeline, robot, step):
    return f"robot {robot} acts at step {step} ({_action_words(timeline.actions_of(robot, step))}); " \
           "steps start at 1", {"robots": [robot]}


@_describes("action", "unknownAction")
def _(timeline, robot, name, step):
    return f"robot {robot} does '{name}', which is not an action of domain {timeline.domain.label}", \
        {"robots": [robot]}


_SHAPES = {"move": "(1,0), (-1,0), (0,1) or (0,-1)", "pickup": "()", "putdown": "()"}


@_describes("action", "badArguments")
def _(timeline, robot, name, step):
    args = [a.args for a in timeline.actions_of(robot, step) if a.name == name]
    if name == "deliver":
        shape = "(Order,Product,Units) with Units >= 1" if timeline.domain is Domain.A else \
            "(Order,Product) or (Order,Product,Units)"
    else:
        shape = _SHAPES.get(name, "other arguments")
    given = " or ".join(format_value(a) for a in args)
    return f"robot {robot} does {name} with {given}, but {name} takes {shape}", {"robots": [robot]}


@_describes("action", "concurrent")
def _(timeline, robot, step):
    actions = timeline.actions_of(robot, step)
    return f"robot {robot} does {len(actions)} actions at once ({_action_words(actions)}); " \
           "a robot does at most one action per step", {"robots": [robot]}


# where robots go

@_describes("collision", "sameNode")
def _(timeline, first, second, step):
    cell = timeline.position(first, step)
    return f"robots {first} and {second} are both on {_cell(cell)}", \
        {"robots": [first, second], "cells": [cell]}


@_describes("collision", "swap")
def _(timeline, first, second, step):
    a, b = timeline.position(first, step - 1), timeline.position(second, step - 1)
    return f"robots {first} and {second} swap nodes {_cell(a)} and {_cell(b)}", \
        {"robots": [first, second], "cells": [a, b]}


@_describes("move", "offFloor")
def _(timeline, robot, step):
    cell = timeline.position(robot, step)
    return f"robot {robot} moves to {_cell(cell)}, which is not a floor node", \
        {"robots": [robot], "cells": [cell]}


def _resting_on(timeline: Timeline, cell: Cell, step: int) -> list[int]:
    """Shelves resting on ``cell`` after ``step``."""
    return sorted(timeline._snapshot(step).resting_at(cell))


@_describes("move", "ontoShelf")
def _(timeline, robot, step):
    shelf = timeline.state(step - 1).carries.get(robot)
    cell = timeline.position(robot, step)
    resting = _resting_on(timeline, cell, step - 1)
    return f"robot {robot} carries shelf {shelf} onto {_cell(cell)}, where shelf " \
           f"{', '.join(map(str, resting))} rests", \
        {"robots": [robot], "shelves": [shelf, *resting], "cells": [cell]}


# pickup and putdown

@_describes("pickup", "carrying")
def _(timeline, robot, step):
    shelf = timeline.state(step - 1).carries.get(robot)
    return f"robot {robot} picks up, but it already carries shelf {shelf}", \
        {"robots": [robot], "shelves": [shelf]}


@_describes("pickup", "noShelf")
def _(timeline, robot, step):
    cell = timeline.position(robot, step - 1)
    return f"robot {robot} picks up at {_cell(cell)}, but no shelf rests there", \
        {"robots": [robot], "cells": [cell]}


@_describes("pickup", "sharedShelf")
def _(timeline, shelf, step):
    cell = timeline.state(step - 1).shelves.get(shelf)
    takers = sorted(a.robot for a in timeline.plan.at_step(step)
                    if a.kind == "robot" and a.name == "pickup" and a.robot in timeline.instance.robots
                    and timeline.position(a.robot, step) == cell)
    winner = next((r for r, s in timeline.state(step).carries.items() if s == shelf), None)
    return f"robots {', '.join(map(str, takers))} pick up shelf {shelf} at once (robot {winner} gets it)", \
        {"robots": takers, "shelves": [shelf], "cells": [cell]}


@_describes("putdown", "notCarrying")
def _(timeline, robot, step):
    return f"robot {robot} puts down, but it carries no shelf", {"robots": [robot]}


def _putdown(timeline: Timeline, robot: int, step: int, where: str):
    shelf = timeline.state(step - 1).carries.get(robot)
    cell = timeline.position(robot, step)
    return f"robot {robot} puts shelf {shelf} down {where.format(cell=_cell(cell))}", \
        {"robots": [robot], "shelves": [shelf], "cells": [cell]}


@_describes("putdown", "offFloor")
def _(timeline, robot, step):
    return _putdown(timeline, robot, step, "at {cell}, which is not a floor node")


@_describes("putdown", "onHighway")
def _(timeline, robot, step):
    return _putdown(timeline, robot, step, "on the highway node {cell}")


@_describes("putdown", "onStation")
def _(timeline, robot, step):
    return _putdown(timeline, robot, step, "on the picking station at {cell}")


@_describes("putdown", "ontoShelf")
def _(timeline, robot, step):
    cell = timeline.position(robot, step)
    resting = _resting_on(timeline, cell, step - 1)
    text, highlight = _putdown(timeline, robot, step, "on {cell}, where shelf "
                               + ", ".join(map(str, resting)) + " already rests")
    highlight["shelves"] += resting
    return text, highlight


# deliveries

def _delivery(timeline: Timeline, robot: int, step: int) -> tuple[Any, Any, Any, int | None]:
    args = timeline.actions_of(robot, step)[0].args
    return args[0], args[1], (args[2] if len(args) > 2 else None), \
        timeline.state(step - 1).carries.get(robot)


def _delivers(timeline: Timeline, robot: int, step: int) -> str:
    order, product, units, _shelf = _delivery(timeline, robot, step)
    amount = f"{_units(units)} of " if units is not None and timeline.domain is Domain.A else ""
    return f"robot {robot} delivers {amount}product {product} for order {order}"


@_describes("deliver", "notCarrying")
def _(timeline, robot, step):
    return f"{_delivers(timeline, robot, step)}, but it carries no shelf", {"robots": [robot]}


@_describes("deliver", "unknownOrder")
def _(timeline, robot, step):
    order = _delivery(timeline, robot, step)[0]
    return f"{_delivers(timeline, robot, step)}, but there is no order {order}", {"robots": [robot]}


@_describes("deliver", "wrongStation")
def _(timeline, robot, step):
    order = timeline.instance.orders[_delivery(timeline, robot, step)[0]]
    cell = timeline.position(robot, step)
    target = timeline.instance.stations.get(order.station)
    where = _station_words(timeline, order.station) if order.station is not None else "no picking station"
    return f"{_delivers(timeline, robot, step)} at {_cell(cell)}, but order {order.id} goes to {where}", \
        {"robots": [robot], "cells": [cell] + ([target.at] if target else [])}


@_describes("deliver", "notOnShelf")
def _(timeline, robot, step):
    _order, product, _units, shelf = _delivery(timeline, robot, step)
    return f"{_delivers(timeline, robot, step)}, but its shelf {shelf} holds no product {product}", \
        {"robots": [robot], "shelves": [shelf]}


@_describes("deliver", "orderAmount")
def _(timeline, robot, step):
    order, product, _units, _shelf = _delivery(timeline, robot, step)
    missing = timeline.state(step - 1).open_lines.get((order, product), 0)
    needs = f"needs only {missing} more" if missing else "needs none"
    return f"{_delivers(timeline, robot, step)}, but the order {needs}", {"robots": [robot]}


@_describes("deliver", "shelfAmount")
def _(timeline, robot, step):
    _order, product, _units, shelf = _delivery(timeline, robot, step)
    left = timeline.state(step - 1).stock.get((shelf, product), 0)
    holds = f"holds only {left}" if left else "has none left"
    return f"{_delivers(timeline, robot, step)}, but shelf {shelf} {holds}", \
        {"robots": [robot], "shelves": [shelf]}


@_describes("deliver", "lineClosed")
def _(timeline, robot, step):
    order, product, _units, _shelf = _delivery(timeline, robot, step)
    return f"{_delivers(timeline, robot, step)}, but order {order} has no open line for product " \
           f"{product}", {"robots": [robot]}


# the goal

@_describes("goal", "unfilledOrder")
def _(timeline, order, product, missing, _step):
    if timeline.domain is Domain.M:
        return f"order {order} is not fulfilled: no robot stands under a shelf holding product " \
               f"{product}", {}
    if timeline.domain is Domain.A:
        return f"order {order} still lacks {_units(missing)} of product {product}", {}
    return f"order {order} still waits for product {product}", {}


@_describes("goal", "missedAssignedGoal")
def _(timeline, robot, cell, _step):
    kind, goal = timeline.instance.assignment[robot]
    return f"robot {robot} does not end on its assigned goal, {kind} {goal} at {_cell(cell)}", \
        {"robots": [robot], "cells": [cell]}


@_describes("goal", "unoccupiedDestination")
def _(timeline, destination, _step):
    cell = timeline.instance.destinations[destination].at
    return f"no robot stands on destination {destination} at {_cell(cell)}", {"cells": [cell]}
