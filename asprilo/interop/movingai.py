"""The MovingAI MAPF benchmark formats: maps, scenarios, and LaCAM/PIBT result files.

MovingAI coordinates are 0-based ``(x, y)`` = (column, row) from the top-left corner;
asprilo's are 1-based ``(X, Y)`` with the same orientation, so ``X = x + 1, Y = y + 1``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import shortest_path

from asprilo.errors import InputError
from asprilo.limits import Limits, current
from asprilo.model import Cell
from asprilo.sources import Source

#: Characters of passable terrain: ground, plus swamp and the goal/start markers some maps use.
PASSABLE = frozenset(".GS")


@dataclass
class Map:
    """A MovingAI map: ``rows[y][x]`` is the terrain character of cell ``(x, y)``."""

    rows: list[str]
    kind: str = "octile"

    @property
    def width(self) -> int:
        return len(self.rows[0]) if self.rows else 0

    @property
    def height(self) -> int:
        return len(self.rows)

    def passable(self, x: int, y: int) -> bool:
        return 0 <= y < self.height and 0 <= x < self.width and self.rows[y][x] in PASSABLE

    def free_cells(self) -> list[tuple[int, int]]:
        """0-based ``(x, y)`` of every passable cell, row by row."""
        return [(x, y) for y, row in enumerate(self.rows) for x, char in enumerate(row) if char in PASSABLE]


def parse_map(source: Source, limits: Limits | None = None) -> Map:
    """Parse ``type``, ``height``, ``width``, ``map`` and the rows of a ``.map`` file; a map
    wider or higher than ``coordinate`` or of more cells than ``facts`` is refused after its
    header (its floor would be an instance every command refuses)."""
    lines = source.text.splitlines()
    header: dict[str, str] = {}
    for number, line in enumerate(lines[:4], 1):
        words = line.split()
        if words == ["map"] and number == 4:
            break
        if len(words) != 2 or words[0] not in ("type", "height", "width"):
            raise InputError(f"expected the MovingAI header 'type', 'height', 'width', 'map', got {line!r}",
                             source.name, number)
        header[words[0]] = words[1]
    else:
        raise InputError("the MovingAI header ends without a 'map' line", source.name)
    try:
        height, width = int(header["height"]), int(header["width"])
    except (KeyError, ValueError):
        raise InputError("the header needs integer 'height' and 'width'", source.name, 2) from None
    require_map_size(width, height, limits or current(), source.name)
    rows = lines[4:4 + height]
    if len(rows) != height:
        raise InputError(f"the header promises {height} rows, the file has {len(rows)}", source.name)
    for number, row in enumerate(rows, 5):
        if len(row) != width:
            raise InputError(f"row of {len(row)} cells, the header says width {width}", source.name, number)
    if any(line.strip() for line in lines[4 + height:]):
        raise InputError(f"text after the {height} map rows", source.name, 5 + height)
    return Map(rows, header.get("type", "octile"))


def require_map_size(width: int, height: int, limits: Limits, name: str | None = None) -> None:
    """Refuse a map size beyond ``coordinate`` (width or height) or ``facts`` (cells)."""
    if width < 0 or height < 0:
        raise InputError(f"a map of width {width} and height {height}: neither may be negative", name)
    if max(width, height) > limits.coordinate:
        raise limits.exceeded("coordinate", f"a map {width:,} cells wide and {height:,} high").at(name)
    if width * height > limits.facts:
        raise limits.exceeded("facts", f"a map of {width:,}x{height:,} = {width * height:,} cells").at(name)


def is_cell_char(char: str) -> bool:
    """Whether ``char`` can stand for one cell in a map's row (one visible character)."""
    return len(char) == 1 and char.isprintable() and not char.isspace()


def format_map(grid: Map) -> str:
    return "".join(f"{line}\n" for line in
                   [f"type {grid.kind}", f"height {grid.height}", f"width {grid.width}", "map", *grid.rows])


@dataclass(slots=True)
class Task:
    """One scenario row: an agent's start and goal (0-based) and its octile optimum."""

    start: tuple[int, int]
    goal: tuple[int, int]
    bucket: int = 0
    optimal: float = 0.0
    map_name: str = ""
    width: int = 0
    height: int = 0


def parse_scenario(source: Source, limits: Limits | None = None) -> list[Task]:
    """Parse a ``.scen`` file (``version 1`` then tab-separated rows); more rows than the
    ``facts`` limit (each an agent: a robot and its goal) are refused as they are read."""
    limits = limits or current()
    tasks: list[Task] = []
    for number, line in enumerate(source.text.splitlines(), 1):
        if not line.strip() or (number == 1 and line.startswith("version")):
            continue
        if len(tasks) >= limits.facts:
            raise limits.exceeded("facts", f"a scenario of more than {limits.facts:,} rows").at(source.name, number)
        fields = line.split("\t") if "\t" in line else line.split()
        if len(fields) != 9:
            raise InputError(f"a scenario row has 9 fields (bucket map width height start_x start_y "
                             f"goal_x goal_y optimal_length), this one has {len(fields)}", source.name, number)
        try:
            bucket, width, height, sx, sy, gx, gy = (int(fields[i]) for i in (0, 2, 3, 4, 5, 6, 7))
            optimal = float(fields[8])
        except ValueError:
            raise InputError("scenario fields must be numbers (but the map name)", source.name, number) from None
        tasks.append(Task((sx, sy), (gx, gy), bucket, optimal, fields[1], width, height))
    if not tasks:
        raise InputError("the scenario has no rows", source.name)
    return tasks


def format_scenario(tasks: list[Task]) -> str:
    rows = ["version 1"]
    for task in tasks:
        rows.append("\t".join(str(v) for v in (
            task.bucket, task.map_name, task.width, task.height, *task.start, *task.goal,
            f"{task.optimal:.8f}")))
    return "\n".join(rows) + "\n"


def octile_lengths(grid: Map, tasks: list[tuple[tuple[int, int], tuple[int, int]]]) -> list[float]:
    """Shortest path lengths with diagonal moves (cost sqrt 2) that cut no corners, as the
    MovingAI scenarios state them (``inf`` if unreachable)."""
    cells = grid.free_cells()
    index = {cell: i for i, cell in enumerate(cells)}
    rows, columns, weights = [], [], []
    for (x, y), i in index.items():
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                j = index.get((x + dx, y + dy))
                if j is None or (dx, dy) == (0, 0):
                    continue
                if dx and dy and not (grid.passable(x + dx, y) and grid.passable(x, y + dy)):
                    continue
                rows.append(i)
                columns.append(j)
                weights.append(math.sqrt(2) if dx and dy else 1.0)
    graph = csr_matrix((weights, (rows, columns)), shape=(len(cells), len(cells)))
    starts = sorted({start for start, _ in tasks if start in index})
    if not starts:
        return [math.inf] * len(tasks)
    table = np.atleast_2d(shortest_path(graph, method="D", indices=[index[s] for s in starts]))
    row_of = {start: k for k, start in enumerate(starts)}
    return [float(table[row_of[s], index[g]]) if s in index and g in index else math.inf for s, g in tasks]


@dataclass
class LacamResult:
    """A LaCAM/PIBT ``result.txt``: header fields and one configuration per time step."""

    fields: dict[str, str] = field(default_factory=dict)
    configurations: list[list[tuple[int, int]]] = field(default_factory=list)


def _pairs(text: str, name: str, number: int) -> list[tuple[int, int]]:
    cells = []
    for item in text.replace(" ", "").split("),"):
        item = item.strip("(),")
        if not item:
            continue
        try:
            x, y = (int(v) for v in item.split(","))
        except ValueError:
            raise InputError(f"expected (x,y) pairs, got {item!r}", name, number) from None
        cells.append((x, y))
    return cells


def parse_result(source: Source) -> LacamResult:
    """Parse ``key=value`` header lines and ``t:(x,y),(x,y),...`` configuration lines."""
    result = LacamResult()
    for number, line in enumerate(source.text.splitlines(), 1):
        line = line.strip()
        if not line:
            continue
        head, colon, rest = line.partition(":")
        if colon and head.isdigit():
            if int(head) != len(result.configurations):
                raise InputError(f"expected time step {len(result.configurations)}, got {head}",
                                 source.name, number)
            result.configurations.append(_pairs(rest, source.name, number))
        elif "=" in line:
            key, _, value = line.partition("=")
            result.fields[key] = value
        else:
            raise InputError("expected 'key=value' or 't:(x,y),...'", source.name, number)
    if not result.configurations:
        raise InputError("no solution lines 't:(x,y),...' found", source.name)
    counts = {len(configuration) for configuration in result.configurations}
    if len(counts) != 1:
        raise InputError("the time steps list different numbers of agents", source.name)
    return result


def format_result(result: LacamResult) -> str:
    lines = [f"{key}={value}" for key, value in result.fields.items()]
    lines += [f"{t}:" + "".join(f"({x},{y})," for x, y in configuration)
              for t, configuration in enumerate(result.configurations)]
    return "\n".join(lines) + "\n"


def to_cell(x: int, y: int) -> Cell:
    """MovingAI ``(x, y)`` -> asprilo ``(X, Y)``."""
    return (x + 1, y + 1)


def from_cell(cell: Cell) -> tuple[int, int]:
    """asprilo ``(X, Y)`` -> MovingAI ``(x, y)``."""
    return (cell[0] - 1, cell[1] - 1)
