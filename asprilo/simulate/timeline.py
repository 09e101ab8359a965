"""The timeline of a replayed plan: where robots stand after every step, what each step
changed besides, and the state after any step, put together on demand.

Robot positions are kept as one array; for shelves, stock and order lines only what each
step changed is kept, plus a checkpoint every so many steps.  ``state(t)`` starts from the
nearest checkpoint (or from the last state made, when steps are asked in sequence).
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..domain import Domain, Goal
from ..model import Action, Cell, Instance, Plan
from .violations import Finding, Violation, explain, sort_violations

if TYPE_CHECKING:
    import numpy as np

Line = tuple[int, int]  # (order, product)
Stock = tuple[int, int]  # (shelf, product)
#: what a line becomes in the changes of a step when B or C close it
CLOSED = object()


@dataclass
class State:
    """The warehouse after a step (0: the instance)."""

    step: int
    robots: dict[int, Cell]
    carries: dict[int, int]
    shelves: dict[int, Cell]
    stock: dict[Stock, int | None]
    open_lines: dict[Line, int | None]


@dataclass
class Changes:
    """What one step changed besides robot positions."""

    carries: list[tuple[int, int | None]] = field(default_factory=list)
    resting: list[tuple[int, Cell | None]] = field(default_factory=list)
    stock: list[tuple[Stock, int]] = field(default_factory=list)
    lines: list[tuple[Line, Any]] = field(default_factory=list)  # A: units missing; B/C: CLOSED

    def __bool__(self) -> bool:
        return bool(self.carries or self.stock or self.lines)


@dataclass
class Snapshot:
    """Carried and resting shelves, stock and order lines after ``step``."""

    step: int
    carries: dict[int, int]
    resting: dict[int, Cell]
    stock: dict[Stock, int | None]
    lines: dict[Line, int | None]

    def resting_at(self, cell: Cell) -> list[int]:
        return [shelf for shelf, at in self.resting.items() if at == cell]

    def copy(self, step: int | None = None) -> Snapshot:
        return Snapshot(self.step if step is None else step, dict(self.carries), dict(self.resting),
                        dict(self.stock), dict(self.lines))

    def apply(self, changes: Changes) -> None:
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
            if units is CLOSED:
                self.lines.pop(line, None)
            else:
                self.lines[line] = units


class Positions:
    """Where every robot stands after every step: a (steps x robots x 2) array."""

    def __init__(self, robot_ids: list[int], table: np.ndarray):
        self.robot_ids = robot_ids
        self.table = table
        self.horizon = len(table) - 1
        self._index = {robot: i for i, robot in enumerate(robot_ids)}
        self._rows: dict[int, list] = {}  # rows of recent steps, as lists

    def at(self, robot: int, step: int) -> Cell:
        """Where ``robot`` stands after ``step`` (clamped to 0..horizon)."""
        step = min(max(step, 0), self.horizon)
        row = self._rows.get(step)
        if row is None:
            if len(self._rows) > 3:
                self._rows.clear()
            row = self._rows[step] = self.table[step].tolist()
        return tuple(row[self._index[robot]])

    def robots(self, step: int) -> dict[int, Cell]:
        """Robot id -> cell after ``step`` (within 0..horizon)."""
        return {robot: (x, y) for robot, (x, y) in zip(self.robot_ids, self.table[step].tolist(), strict=True)}


class History:
    """What a replay recorded, step by step; the state after any step.

    Built from the positions and the state at step 0; the replay then hands over, step
    after step, what each step changed (:meth:`record`).
    """

    def __init__(self, domain: Domain, positions: Positions, start: Snapshot,
                 mapf_lines: dict[Line, list[int]], releases: dict[int, int] | None = None):
        self.domain = domain
        self.positions = positions
        self.horizon = positions.horizon
        self.mapf_lines = mapf_lines  # M: line -> shelves holding its product
        self.releases = releases or {}  # online orders -> their release steps
        self._served: dict[Line, int] | None = None  # M: an online line -> the step it was served at
        self.every = max(64, self.horizon // 32)
        self._checkpoints = [start.copy(0)]  # after steps 0, every, 2 * every, ...
        self._changes: dict[int, Changes] = {}  # step -> what it changed besides positions
        self._cached: Snapshot | None = None  # the last snapshot made

    def record(self, step: int, changes: Changes | None, now: Snapshot) -> None:
        """What ``step`` changed (``None``: nothing); ``now`` is the state after it."""
        if changes:
            self._changes[step] = changes
        if step % self.every == 0:
            self._checkpoints.append(now.copy(step))

    def snapshot(self, step: int) -> Snapshot:
        """Carried and resting shelves, stock and order lines after ``step`` (shared: copy it)."""
        step = min(max(step, 0), self.horizon)
        cached = self._cached
        start = self._checkpoints[min(step // self.every, len(self._checkpoints) - 1)]
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
        snapshot = self.snapshot(last)
        robots = self.positions.robots(last)
        shelves = dict(snapshot.resting)
        for robot, shelf in snapshot.carries.items():
            shelves[shelf] = robots[robot]
        return State(max(t, 0), robots, dict(snapshot.carries), shelves, dict(snapshot.stock),
                     self._open_lines(snapshot, robots, shelves))

    def _open_lines(self, snapshot: Snapshot, robots: dict[int, Cell],
                    shelves: dict[int, Cell]) -> dict[Line, int | None]:
        if self.domain.counts_units:
            return {line: units for line, units in snapshot.lines.items() if units is not None and units > 0}
        if self.domain.goal is Goal.SHELVES:
            occupied = set(robots.values())
            served = self.served(shelves) if self.releases else {}
            return {line: units for line, units in snapshot.lines.items()
                    if (served.get(line, self.horizon + 1) > snapshot.step if line[0] in self.releases else
                        not any(shelves.get(shelf) in occupied for shelf in self.mapf_lines[line]))}
        return dict(snapshot.lines)

    def served(self, shelves: dict[int, Cell]) -> dict[Line, int]:
        """M, online orders: the first step after its order's release at which some robot stands
        under a shelf holding a line's product (a line served then stays served: lifelong
        goals); lines never served are missing.  Found once (M's shelves never move)."""
        if self._served is None:
            cells = {line: {shelves[shelf] for shelf in self.mapf_lines[line] if shelf in shelves}
                     for line in self.mapf_lines if line[0] in self.releases}
            self._served = {}
            for step in range(1, self.horizon + 1):
                occupied = {tuple(cell) for cell in self.positions.table[step].tolist()}
                for line, targets in cells.items():
                    if line not in self._served and step > self.releases[line[0]] and targets & occupied:
                        self._served[line] = step
        return self._served


class Timeline:
    """The replay of a plan: ``state(t)`` after every step and the violations found."""

    def __init__(self, instance: Instance, plan: Plan, domain: Domain, history: History,
                 findings: Iterable[Finding] = ()):
        self.instance = instance
        self.plan = plan
        self.domain = domain
        self.history = history
        self.horizon = history.horizon
        self.robot_ids: list[int] = history.positions.robot_ids
        self._actions: dict[tuple, list[Action]] | None = None
        found = sorted(dict.fromkeys(findings), key=lambda entry: entry[2][-1])  # by step: cheap lookups
        self.violations: list[Violation] = sort_violations([self.explain(*entry) for entry in found])

    @property
    def valid(self) -> bool:
        return not self.violations

    def position(self, robot: int, step: int) -> Cell:
        """Where ``robot`` stands after ``step``."""
        return self.history.positions.at(robot, step)

    def state(self, t: int) -> State:
        """The state after step ``t`` (0: initial; beyond the horizon: the final state)."""
        return self.history.state(t)

    def resting_on(self, cell: Cell, step: int) -> list[int]:
        """The shelves resting on ``cell`` after ``step``, by id."""
        return sorted(self.history.snapshot(step).resting_at(cell))

    def actions_of(self, robot: Any, step: int, kind: str = "robot") -> list[Action]:
        """The plan's actions of one object at one step."""
        if self._actions is None:
            self._actions = defaultdict(list)
            for action in self.plan.actions:
                self._actions[(action.kind, action.robot, action.step)].append(action)
        return self._actions.get((kind, robot, step), [])

    def explain(self, module: str, check: str, params: tuple) -> Violation:
        """The violation ``err(module,check,params)`` in plain words, with what to highlight."""
        return explain(self, module, check, tuple(params))
