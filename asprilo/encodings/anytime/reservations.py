"""Tracks (timed routes of single robots) and the reservation table they fill.

A :class:`Track` says where its robot is at every step from 0 until it parks, which task it
does at which step, and from which step on it stays where it is.  :class:`Reservations`
holds the tracks of the robots planned so far, indexed for the questions routing asks:
who stands on a cell at a step, who moves from where into a cell at a step, who stays on
a cell for good, when a shelf rests on its own cell, and where and from when a shelf put
down elsewhere rests (:meth:`Reservations.placed`).
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass, field
from functools import cached_property

from asprilo.model import Cell, Instance

from .errands import Task

#: "until the end of time" for resting shelves and parked robots
FOREVER = 1 << 30


@dataclass
class Track:
    """A robot's route: ``cells[t]`` is its cell after step ``t`` (``t`` = 0 .. ``parked``),
    ``done[t]`` the task it does at step ``t``; after step ``parked`` it stays put."""

    robot: int
    cells: list[Cell]
    done: dict[int, Task] = field(default_factory=dict)

    @property
    def parked(self) -> int:
        return len(self.cells) - 1

    def at(self, step: int) -> Cell:
        return self.cells[min(step, self.parked)]

    @cached_property
    def finish(self) -> int:
        """The step of the robot's last action (0 when it never acts; tracks never change)."""
        last = 0
        for step in range(1, len(self.cells)):
            if self.cells[step] != self.cells[step - 1]:
                last = step
        return max([last, *self.done])

    def placed(self, homes: dict[int, Cell]) -> dict[int, tuple[Cell, int]]:
        """Shelf -> (cell, step) of the shelves the robot puts down elsewhere than on their
        own cells (``homes``): they rest there from that step on."""
        return {task.shelf: (self.at(step), step) for step, task in self.done.items()
                if task.name == "putdown" and task.shelf is not None and self.at(step) != homes.get(task.shelf)}

    def loaded(self, carried: int | None) -> list[tuple[int, int]]:
        """The steps ``(first, last)`` during which the robot carries a shelf."""
        return [period for periods in self.shelf_periods(carried).values() for period in periods]

    def shelf_periods(self, carried: int | None) -> dict[int, list[tuple[int, int]]]:
        """Shelf -> the steps ``(first, last)`` during which the robot carries it
        (``carried``: the shelf it carries from the start)."""
        periods: dict[int, list[tuple[int, int]]] = defaultdict(list)
        open_since: dict[int, int] = {} if carried is None else {carried: 0}
        for step in sorted(self.done):
            task = self.done[step]
            if task.name == "pickup":
                open_since[task.shelf] = step
            elif task.name == "putdown":
                periods[task.shelf].append((open_since.pop(task.shelf, 0), step - 1))
        for shelf, since in open_since.items():
            periods[shelf].append((since, FOREVER))
        return periods


class Reservations:
    """The tracks of the robots planned so far, and the robots not planned yet standing still."""

    def __init__(self, instance: Instance, homes: dict[int, Cell]):
        self.instance = instance
        self.homes = homes  # shelf -> its cell
        self.tracks: dict[int, Track] = {}
        self.visits: dict[Cell, dict[int, int]] = defaultdict(dict)   # cell -> step -> robot
        self.entries: dict[Cell, list[tuple[Cell, int, int]]] = defaultdict(list)  # to -> (from, step, robot)
        self.stays: dict[Cell, dict[int, int]] = defaultdict(dict)     # cell -> robot -> from step
        self.away: dict[int, list[tuple[int, int]]] = {}               # shelf -> carried periods
        self.moved: dict[int, tuple[Cell, int]] = {}                   # shelf -> cell and step put down there
        self.loads: dict[int, list[tuple[int, int]]] = {}              # robot -> carrying periods
        self.carried_from_start = {r.carries: r.id for r in instance.robots.values() if r.carries is not None}
        self.still = True

    # --- changing the table --------------------------------------------------------------

    def reset(self, still: bool) -> None:
        """Forget all tracks and holds; ``still``: how robots not planned are held."""
        self.tracks.clear()
        for table in (self.visits, self.entries, self.stays, self.away, self.moved, self.loads):
            table.clear()
        self.still = still

    def hold(self, robot: int) -> None:
        """A robot not planned (yet) stays on its start cell for good (with ``still`` off:
        stands there at step 0 only, and will have to get out of the way when planned)."""
        start = self.instance.robots[robot].at
        if self.still:
            self.stays[start][robot] = 0
        else:
            self.visits[start][0] = robot

    def add(self, track: Track) -> None:
        robot = track.robot
        self.stays[self.instance.robots[robot].at].pop(robot, None)
        self.tracks[robot] = track
        for step, cell in enumerate(track.cells[:-1]):
            self.visits[cell][step] = robot
        for step in range(1, len(track.cells)):
            if track.cells[step] != track.cells[step - 1]:
                self.entries[track.cells[step]].append((track.cells[step - 1], step, robot))
        self.stays[track.cells[-1]][robot] = track.parked
        carried = self.instance.robots[robot].carries
        self.away.update(track.shelf_periods(carried))
        self.moved.update(track.placed(self.homes))
        self.loads[robot] = track.loaded(carried)

    def remove(self, robot: int) -> Track:
        """Take a robot's track out of the table (the robot is then held on its start cell)."""
        track = self.tracks.pop(robot)
        for step, cell in enumerate(track.cells[:-1]):
            if self.visits[cell].get(step) == robot:
                del self.visits[cell][step]
        for step in range(1, len(track.cells)):
            cell = track.cells[step]
            self.entries[cell] = [entry for entry in self.entries[cell] if entry[2] != robot]
        self.stays[track.cells[-1]].pop(robot, None)
        for shelf in track.shelf_periods(self.instance.robots[robot].carries):
            self.away.pop(shelf, None)
            self.moved.pop(shelf, None)
        self.loads.pop(robot, None)
        self.hold(robot)
        return track

    # --- questions routing asks ------------------------------------------------------------

    def busy(self, cell: Cell, first: int, last: int, robot: int) -> list[int]:
        """The steps in ``first .. last`` at which another robot passes ``cell``."""
        return [step for step, other in self.visits.get(cell, {}).items()
                if first <= step <= last and other != robot]

    def stay(self, cell: Cell, robot: int) -> int | None:
        """From which step on another robot stays on ``cell`` for good (``None``: nobody)."""
        return min((since for other, since in self.stays.get(cell, {}).items() if other != robot), default=None)

    def parked_cells(self, robot: int) -> set[Cell]:
        """The cells where other robots stay for good."""
        return {cell for cell, who in self.stays.items() if any(other != robot for other in who)}

    def last_visit(self, cell: Cell, robot: int) -> int:
        """The last step at which another robot is on ``cell`` (-1: never)."""
        steps = [step for step, other in self.visits.get(cell, {}).items() if other != robot]
        return max(steps, default=-1)

    def crossings(self, cell: Cell, first: int, last: int, robot: int) -> list[tuple[Cell, int]]:
        """``(from, step)`` of the other robots' moves into ``cell`` at steps ``first .. last``."""
        return [(source, step) for source, step, other in self.entries.get(cell, ())
                if first <= step <= last and other != robot]

    def resting(self, shelf: int) -> list[tuple[int, int]]:
        """The steps ``(first, last)`` during which ``shelf`` rests on its own cell."""
        periods = sorted(self.away.get(shelf, []))
        if not periods and shelf in self.carried_from_start:
            return []  # carried from the start by a robot not planned yet: it is never put down
        result, since = [], 0
        for first, last in periods:
            if first > since:
                result.append((since, first - 1))
            since = last + 1
        if since < FOREVER and shelf not in self.moved:  # a shelf put down elsewhere never comes back
            result.append((since, FOREVER))
        return result

    def placed(self, skip: set[int]) -> dict[int, tuple[Cell, int]]:
        """Shelf -> (cell, step) of the shelves put down elsewhere than on their own cells,
        resting there from that step on (none of ``skip``)."""
        return {shelf: where for shelf, where in self.moved.items() if shelf not in skip}

    def last_loaded_visit(self, cell: Cell, robot: int) -> int:
        """The last step at which another robot carrying a shelf is on ``cell`` (-1: never):
        a shelf put down there must come later."""
        steps, parked = self._loaded_visits(cell, robot)
        return FOREVER if parked else max(steps, default=-1)

    def first_loaded_visit(self, cell: Cell, robot: int) -> int:
        """The first step at which another robot carrying a shelf is on ``cell``
        (``FOREVER``: never): the shelf resting there must be lifted earlier."""
        steps, parked = self._loaded_visits(cell, robot)
        return min(steps + parked, default=FOREVER)

    def _loaded_visits(self, cell: Cell, robot: int) -> tuple[list[int], list[int]]:
        """The steps at which other robots carrying a shelf pass ``cell``, and those from
        which others stay there with a shelf for good."""
        def loaded(other: int, step: int) -> bool:
            return any(first <= step <= end for first, end in self.loads.get(other, ()))

        steps = [step for step, other in self.visits.get(cell, {}).items() if other != robot and loaded(other, step)]
        parked = [since for other, since in self.stays.get(cell, {}).items()
                  if other != robot and any(end >= since for _first, end in self.loads.get(other, ()))]
        return steps, parked

    def still_shelves(self, skip: set[int]) -> list[Cell]:
        """The cells of the shelves that rest there all the time (none of ``skip``)."""
        return [cell for shelf, cell in self.homes.items()
                if shelf not in skip and shelf not in self.away and shelf not in self.carried_from_start]

    def moving_shelves(self, skip: set[int]) -> dict[int, Cell]:
        """Shelf -> cell of the shelves that are carried some of the time (none of ``skip``)."""
        return {shelf: self.homes[shelf] for shelf in self.away if shelf not in skip}
