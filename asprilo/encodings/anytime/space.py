"""The search space of one routing call: what ``route.lp`` reads, as Python data.

The router (:mod:`.router`) decides the windows (which cells, at which steps, on the way to
each task); this module gathers what the reservation table says inside them: who passes,
who stays for good, who moves where, where other robots' shelves rest, when a parking cell
is free and when a shelf may be put down.  Both routing engines read a :class:`Space`: the
logic program gets it as facts (:meth:`Space.facts`), the Python search
(:mod:`.timed_search`) reads it directly.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass, field

from asprilo.model import Cell

from .errands import Task
from .reservations import FOREVER, Reservations


@dataclass
class Space:
    """One robot's routing problem, numbered as in ``route.lp``: tasks ``1 .. last``.

    ``windows[k][cell] = (first, last)``: on its way to task ``k`` the robot may be on
    ``cell`` at the steps ``first .. last``.  The rest is the reservation table inside the
    windows (the docstring of ``route.lp`` says what each part means).
    """

    begin: Cell
    step: int
    tasks: list[Task]
    windows: list[dict[Cell, tuple[int, int]]]
    task_cells: list[set[Cell]] = field(default_factory=list)
    busy: dict[Cell, set[int]] = field(default_factory=lambda: defaultdict(set))
    stays: dict[Cell, int] = field(default_factory=dict)
    crossings: set[tuple[Cell, Cell, int]] = field(default_factory=set)
    rests: dict[Cell, list[tuple[int, int]]] = field(default_factory=lambda: defaultdict(list))
    free_from: dict[Cell, int] = field(default_factory=dict)
    settle: dict[int, int] = field(default_factory=dict)
    due: dict[int, int] = field(default_factory=dict)
    deadlines: list[int] = field(default_factory=list)
    tails: list[int] = field(default_factory=list)
    #: where a lazy space looks up the cells not looked at yet (:meth:`look`): the table,
    #: the robot, and each cell's steps (first, last) over all windows
    source: tuple[Reservations, int, dict[Cell, list[int]]] | None = field(default=None, repr=False)
    looked: set[Cell] = field(default_factory=set, repr=False)

    @property
    def last(self) -> int:
        return len(self.tasks)

    def acts(self, number: int) -> bool:
        """Whether task ``number`` is an action of one step (not the final parking)."""
        return self.tasks[number - 1].name != "park"

    def carrying(self, number: int) -> bool:
        return self.tasks[number - 1].carrying

    def estimate(self, deadlines: list[int], lengths: list[int]) -> None:
        """Say how far the robot still has to go: on the way to task ``k`` it may reach
        ``cell`` at step ``windows[k][cell][1]`` at the latest, when it is to reach the task
        by step ``deadlines[k]``; ``lengths[k]`` is the length of a shortest way to task ``k``
        from task ``k - 1``."""
        self.deadlines = deadlines
        self.tails = [sum(1 + length for length in lengths[number:]) for number in range(1, len(lengths) + 1)]

    def to_go(self, number: int, cell: Cell) -> int:
        """A lower bound of the steps from ``cell`` on the way to task ``number`` until parked
        (:meth:`estimate` was called): the way to the task, and then the rest of the errand."""
        return self.deadlines[number - 1] - self.windows[number - 1][cell][1] + self.tails[number - 1]

    @classmethod
    def gather(cls, robot: int, table: Reservations, tasks: list[Task], windows: list[dict[Cell, tuple[int, int]]],
               begin: Cell, step: int, lazy: bool = False) -> Space:
        """The space of routing ``robot`` through ``tasks`` inside ``windows``, around the
        other robots' tracks held in ``table``.  ``lazy``: who passes, stays or moves where
        is looked up cell by cell when the search first comes near (:meth:`look`; a wide
        window on a big floor holds tens of thousands of cells, the search visits a few)."""
        space = cls(begin, step, tasks, windows)
        spans: dict[Cell, list[int]] = {}
        for window in windows:
            for cell, (first, last) in window.items():
                span = spans.setdefault(cell, [first, last])
                span[0], span[1] = min(span[0], first), max(span[1], last)
        for number, task in enumerate(tasks, 1):
            space.task_cells.append(space._task_cells(robot, table, number, task))
        space.source = (table, robot, spans)
        if not lazy:
            for cell in spans:
                space.look(cell)
        space._shelves(table, tasks)
        return space

    def look(self, cell: Cell) -> None:
        """Take what the table says about ``cell`` within its steps in the windows: the steps
        other robots pass it, from when one stays there, who moves into it from where."""
        if self.source is None or cell in self.looked:
            return
        self.looked.add(cell)
        table, robot, spans = self.source
        if cell not in spans:
            return
        first, last = spans[cell]
        steps = table.busy(cell, first, last, robot)
        if steps:
            self.busy[cell].update(steps)
        since = table.stay(cell, robot)
        if since is not None and since <= last:
            self.stays[cell] = since
        self.crossings.update((source, cell, t) for source, t in table.crossings(cell, first, last + 1, robot)
                              if source in spans)

    def _task_cells(self, robot: int, table: Reservations, number: int, task: Task) -> set[Cell]:
        cells = set()
        for cell in task.cells:
            if task.name == "putdown" and task.shelf is not None and cell != table.homes.get(task.shelf):
                cells.add(cell)
                settle = table.last_loaded_visit(cell, robot) + 1
                if settle > 0:
                    self.settle[number] = min(settle, FOREVER)
            elif task.name != "park":
                cells.add(cell)
                if task.name == "pickup":  # before another robot comes there with a shelf
                    due = table.first_loaded_visit(cell, robot) - 1
                    if due < FOREVER - 1:
                        self.due[number] = due
            elif table.stay(cell, robot) is None:
                cells.add(cell)
                last = table.last_visit(cell, robot)
                if last >= 0:
                    self.free_from[cell] = last + 1
        return cells

    def _shelves(self, table: Reservations, tasks: list[Task]) -> None:
        """The shelves of other robots that rest in a carrying leg's window part of the time."""
        own = {task.shelf for task in tasks if task.shelf is not None}
        cells = {cell for task, window in zip(tasks, self.windows, strict=True) if task.carrying for cell in window}
        for shelf, cell in table.moving_shelves(own).items():
            if cell in cells:
                self.rests[cell] += [(first, min(last, FOREVER)) for first, last in table.resting(shelf)]
        for cell, since in table.placed(own).values():  # put down away from their cells
            if cell in cells:
                self.rests[cell].append((since, FOREVER))

    def facts(self) -> str:
        """The space as the input facts of ``route.lp`` (every cell looked up first)."""
        for cell in self.source[2] if self.source is not None else ():
            self.look(cell)
        out = [f"begin({_c(self.begin)},{self.step}).", f"last({self.last})."]
        for number, window in enumerate(self.windows, 1):
            if self.acts(number):
                out.append(f"acts({number}).")
            if self.carrying(number):
                out.append(f"carrying({number}).")
            out += [f"window({number},{_c(cell)},{first},{last})." for cell, (first, last) in window.items()]
            out += [f"task({number},{_c(cell)})." for cell in self.task_cells[number - 1]]
        out += [f"settle({number},{since})." for number, since in self.settle.items()]
        out += [f"due({number},{by})." for number, by in self.due.items()]
        out += [f"free_from({_c(cell)},{since})." for cell, since in self.free_from.items()]
        out += [f"busy({_c(cell)},{t})." for cell, steps in self.busy.items() for t in steps]
        out += [f"stays({_c(cell)},{since})." for cell, since in self.stays.items()]
        out += [f"crossing({_c(source)},{_c(cell)},{t})." for source, cell, t in self.crossings]
        out += [f"rests({_c(cell)},{first},{last})." for cell, periods in self.rests.items() for first, last in periods]
        return "\n".join(out)


def _c(cell: Cell) -> str:
    return f"({cell[0]},{cell[1]})"
