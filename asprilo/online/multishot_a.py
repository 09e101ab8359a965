"""The multi-shot ASP online planner of domain A: one clingo ``Control`` for a whole run.

The driver chooses the tasks (:mod:`.tasks`: which free robot brings which shelf to which
order line's station, oldest line first) and the program (``encodings/online/a.lp``) plans
the steps: moves, pickups, deliveries and put-downs of every robot, without collisions, and
with no shelf carried over another.  Time counts from *now* as in :mod:`.lookahead`: steps
and horizons are grounded once; the world enters as externals (docs/ONLINE.md):

- ``at(R,C)``, ``carries_now(R)``, ``delivered_now(R)``: where robot R stands, whether it
  carries its task's shelf, whether it has made its task's delivery;
- ``rests_now(C)``: a shelf rests on C;
- ``pick(R,C)``, ``deliver_at(R,C)``: R's task (its shelf's cell, which is also where the
  shelf goes back, and the station's cell);
- ``aim(R,G)``, ``way(R,C)``: what R must achieve in this call: the next step of its task
  (pickup, deliver, putdown) when a shortest way gets there within :data:`WINDOW` steps, else
  to stand at the end of the call on one of the cells that way reaches after :data:`WINDOW`
  to :data:`WINDOW` + :data:`SLACK` steps (its way points);
- ``hint(R,A,K)``: R's actions along a shortest way through its task (wait, without one).

A call tries one horizon, that of the hints plus :data:`SLACK` steps: the first plan found in
which every robot with a task achieves its aim is the answer (a shorter one would take a proof
that none exists, which costs the robots time).  When it has none, or none is found in half
the call's time (robots in each other's way for longer), the aims are let go (``strict``
false) for one more try in the rest: robots then do what they can along their hints, and the
next call aims again.  The run asks again when a
plan has been carried out, so plans (and the steps grounded) stay short however far the tasks
lead; a call that gives no robot a new task answers what is left of the last plan (the world
has followed it).  Way points of two robots differ.  The units of a delivery are the
driver's: the line's units not in another task, at most what the shelf holds.
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

from .lookahead import MOST_LOOKAHEAD, Lookahead, cell_term, neighbours, number
from .tasks import DELIVER, PICKUP, PUTDOWN, Floor, Line, Task, assign_tasks

#: the reference online encoding of domain A
REFERENCE_A = Path(__file__).resolve().parent.parent / "encodings" / "online" / "a.lp"
#: the most steps of a task a call plans before a way point
WINDOW = 6
#: the steps a call allows beyond its hints for robots to make way for each other
SLACK = 4

Hint = tuple[str, tuple[int, ...]]  # ("move", (dx, dy)) or (action, ())
STRICT = clingo.Function("strict")


class MultiShotA(Lookahead):
    """An :class:`~asprilo.online.planning.OnlinePlanning` planner of domain A on one Control
    (options as :class:`~asprilo.online.multishot.MultiShot`)."""

    rise, shortest, most_rise = SLACK, False, 0

    def __init__(self, instance: Instance, domain: Domain, encoding: Sequence[str] = (), *,
                 arguments: Sequence[str] = (), most_lookahead: int = MOST_LOOKAHEAD,
                 clock: Callable[[], float] = time.monotonic, fresh: bool = False):
        if domain.goal is not Goal.LINES or not domain.counts_units or domain.variants:
            raise InputError(f"the multi-shot planner of domain A (docs/SPEC.md's rules) does not plan "
                             f"domain {domain.label}")
        super().__init__(instance, encoding or (str(REFERENCE_A),), arguments=arguments,
                         most_lookahead=most_lookahead, clock=clock, fresh=fresh)
        self.positions: dict[int, Cell] = {r: robot.at for r, robot in sorted(instance.robots.items())}
        self.resting: dict[int, Cell] = {s: shelf.at for s, shelf in sorted(instance.shelves.items())}
        self.stock: dict[tuple[int, int], int] = {
            (shelf, product): 1 if units is None else units
            for product, item in instance.products.items() for shelf, units in item.stock.items()}
        self.stations = {station.id: station.at for station in instance.stations.values()}
        self.floor = Floor(instance.cells, set(self.resting.values()))
        self.lines: dict[Line, tuple[Cell, int]] = {}  # open line -> (its station's cell, units left)
        self.in_tasks: dict[Line, int] = {}            # line -> units in tasks under way
        self.tasks: dict[int, Task] = {}
        for robot in instance.robots.values():
            if robot.carries is not None:
                self.resting.pop(robot.carries, None)
                self.tasks[robot.id] = Task(robot.id, robot.carries, self._spare(robot.at), robot.at, None, 0,
                                            PUTDOWN)
        self.hints: dict[int, list[Hint]] = {}
        self.aims: dict[int, str] = {}
        self.ways: dict[int, list[Cell]] = {}
        self.ahead: list[list[Action]] = []  # the steps of the last plan not carried out yet

    # --- what happens in the world ---------------------------------------------------------------

    def released(self, orders: list[Order], step: int) -> None:
        """Open the lines of the orders released after ``step``."""
        for order in orders:
            station = self.stations.get(order.station) if order.station is not None else None
            for product, units in sorted(order.lines.items()):
                if station is None:
                    raise InputError(f"order {order.id} names no picking station of the instance")
                self.lines[(order.id, product)] = (station, 1 if units is None else units)

    def carried_out(self, step: int, actions: list[Action]) -> None:
        """Follow the robots, shelves, stock and lines through step ``step``."""
        if self.ahead and sorted(a._replace(step=0) for a in actions) == sorted(self.ahead[0]):
            self.ahead.pop(0)
        elif actions:
            self.ahead = []
        for action in actions:
            robot = int(action.robot)  # type: ignore[arg-type]  # robot ids: the run carries out our plans
            task = self.tasks.get(robot)
            if action.name == "move":
                x, y = self.positions[robot]
                self.positions[robot] = (x + action.args[0], y + action.args[1])
            elif task is not None and action.name == "pickup":
                del self.resting[task.shelf]
                task.next = DELIVER
            elif task is not None and action.name == "deliver" and task.line is not None:
                self.stock[(task.shelf, task.line[1])] -= task.units
                self.in_tasks[task.line] -= task.units
                station, left = self.lines[task.line]
                if left > task.units:
                    self.lines[task.line] = (station, left - task.units)
                else:
                    del self.lines[task.line]
                task.next = PUTDOWN
            elif task is not None and action.name == "putdown":
                self.resting[task.shelf] = task.home
                del self.tasks[robot]

    # --- planning ----------------------------------------------------------------------------------

    def plan(self, step: int, seconds: float, cancel: threading.Event) -> Plan | None:
        """A plan from the state after ``step`` in which every robot with a task (new ones given
        to free robots first) achieves its aim, found within ``seconds`` (``None``: none)."""
        started = self.clock()
        if not self._give_tasks() and self.ahead:
            return Plan([action._replace(step=k) for k, actions in enumerate(self.ahead, 1) for action in actions])
        if not self.tasks:
            return Plan([])
        self.assign({STRICT: True})
        plan = self.search(seconds / 2, cancel)
        if plan is None and not cancel.is_set():
            self.assign({STRICT: False})
            plan = self.search(seconds - (self.clock() - started), cancel)
        self.ahead = [] if plan is None else \
            [[a._replace(step=0) for a in plan.actions if a.step == k] for k in range(1, plan.horizon + 1)]
        return plan

    def _give_tasks(self) -> bool:
        """Tasks for the free robots, while lines wait; whether any was given."""
        waiting = [(line, station, left - self.in_tasks.get(line, 0))
                   for line, (station, left) in self.lines.items() if left > self.in_tasks.get(line, 0)]
        free = {robot: cell for robot, cell in self.positions.items() if robot not in self.tasks}
        taken = {task.shelf for task in self.tasks.values()}
        shelves = {shelf: cell for shelf, cell in self.resting.items() if shelf not in taken}
        given = assign_tasks(free, waiting, shelves, self.stock, self.floor)
        for task in given:
            self.tasks[task.robot] = task
            if task.line is not None:
                self.in_tasks[task.line] = self.in_tasks.get(task.line, 0) + task.units
        return bool(given)

    def prepare(self) -> tuple[int, int]:
        """The hints and aims; (the most steps any robot needs for its aim on the floor without
        other robots and shelves, the most steps its hints take to it)."""
        self.hints, self.aims, self.ways = {}, {}, {}
        bound = first = 1
        for robot, task in self.tasks.items():
            hints = self.hints[robot] = self._hints(task)
            to_next = next(k for k, (name, _args) in enumerate(hints, 1) if name == task.next)
            if to_next <= WINDOW:
                self.aims[robot], target = task.next, task.station if task.next == DELIVER else task.home
                first = max(first, to_next)
                extra = 1
            else:
                self.aims[robot], first, extra = "way", max(first, WINDOW), 0
                self.ways[robot] = self._way_points(robot, hints)
                target = self.ways[robot][0]
            walk = Floor.steps(self.positions[robot], self.floor.walk(target))
            bound = max(bound, self.most_lookahead + 1 if walk is None else walk + extra)
        return bound, first + SLACK

    def _way_points(self, robot: int, hints: list[Hint]) -> list[Cell]:
        """The cells :data:`WINDOW` to :data:`WINDOW` + :data:`SLACK` steps along ``hints`` that
        no other robot has as a way point (at least the robot's own cell)."""
        taken = {cell for cells in self.ways.values() for cell in cells}
        cells = [self.positions[robot]]
        for name, args in hints[:WINDOW + SLACK]:
            cells.append((cells[-1][0] + args[0], cells[-1][1] + args[1]) if name == "move" else cells[-1])
        return [cell for cell in dict.fromkeys(cells[WINDOW:]) if cell not in taken] or [cells[0]]

    def _hints(self, task: Task) -> list[Hint]:
        """The robot's actions through its task on the floor without other robots."""
        cell, hints = self.positions[task.robot], []  # type: tuple[Cell, list[Hint]]
        legs = [(task.home, self.floor.walk, PICKUP), (task.station, self.floor.carry, DELIVER),
                (task.home, self.floor.carry, PUTDOWN)]
        started = [PICKUP, DELIVER, PUTDOWN].index(task.next)
        for target, field_of, action in legs[started:]:
            cell = _walk(cell, field_of(target), hints)
            hints.append((action, ()))
        return hints

    def assign_world(self) -> None:
        tasks = self.tasks.values()
        self.assign_set("at", (_fact("at", number(r), cell_term(c)) for r, c in self.positions.items()))
        self.assign_set("rests", (_fact("rests_now", cell_term(c)) for c in self.resting.values()))
        self.assign_set("carries", (_fact("carries_now", number(t.robot)) for t in tasks if t.next != PICKUP))
        self.assign_set("delivered", (_fact("delivered_now", number(t.robot)) for t in tasks if t.next == PUTDOWN))
        self.assign_set("pick", (_fact("pick", number(t.robot), cell_term(t.home)) for t in tasks))
        self.assign_set("station", (_fact("deliver_at", number(t.robot), cell_term(t.station))
                                    for t in tasks if t.next != PUTDOWN))
        self.assign_set("aim", (_fact("aim", number(robot), clingo.Function(aim)) for robot, aim in self.aims.items()))
        self.assign_set("way", (_fact("way", number(robot), cell_term(cell))
                                for robot, cells in self.ways.items() for cell in cells))
        hints = set()
        for robot in self.positions:
            planned = self.hints.get(robot, [])
            for k in range(1, self.lookahead + 1):
                name, args = planned[k - 1] if k <= len(planned) else ("wait", ())
                hints.add(_fact("hint", number(robot), _act(name, args), number(k)))
        self.assign_set("hint", hints)

    def read_plan(self, symbols: list[clingo.Symbol], horizon: int) -> Plan:
        """``does(R,A,K)``, K in 1..``horizon``, as actions (a delivery with its task's line)."""
        actions = []
        for symbol in symbols:
            if not symbol.match("does", 3) or not 0 < symbol.arguments[2].number <= horizon:
                continue
            robot, act, step = symbol.arguments[0].number, symbol.arguments[1], symbol.arguments[2].number
            if act.name == "move":
                actions.append(Action(step, robot, "move", tuple(a.number for a in act.arguments[0].arguments)))
            elif act.name == "deliver":
                task = self.tasks[robot]
                order, product = task.line if task.line is not None else (0, 0)
                actions.append(Action(step, robot, "deliver", (order, product, task.units)))
            elif act.name in (PICKUP, PUTDOWN):
                actions.append(Action(step, robot, act.name, ()))
        return Plan(actions)

    def _spare(self, cell: Cell) -> Cell:
        """The storage cell nearest ``cell`` with no shelf (where a shelf carried at the start
        is put down)."""
        taken = set(self.resting.values()) | set(self.stations.values())
        highways = set(self.instance.highways.values())
        for spare, _steps in sorted(self.floor.walk(cell).items(), key=lambda item: (item[1], item[0])):
            if spare not in taken and spare not in highways:
                return spare
        raise InputError("no storage cell is free for the shelf a robot starts carrying")


def _walk(cell: Cell, field: dict[Cell, int], hints: list[Hint]) -> Cell:
    """Append the moves from ``cell`` down ``field`` to its 0; the cell reached."""
    steps = Floor.steps(cell, field)
    while steps:
        after = min((near for near in neighbours(cell) if near in field), key=lambda near: field[near])
        hints.append(("move", (after[0] - cell[0], after[1] - cell[1])))
        cell, steps = after, field[after]
    return cell


def _act(name: str, args: tuple[int, ...]) -> clingo.Symbol:
    if name == "move":
        return clingo.Function("move", [clingo.Tuple_([clingo.Number(a) for a in args])])
    return clingo.Function(name)


def _fact(name: str, *arguments: clingo.Symbol) -> clingo.Symbol:
    return clingo.Function(name, list(arguments))
