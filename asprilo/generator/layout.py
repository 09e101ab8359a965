"""The floor of a generation plan: which layout, its size and nodes, and where shelves may go.

Each check names the options involved (:class:`~asprilo.errors.InputError`).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

from asprilo.errors import InputError
from asprilo.model import Instance

from .config import GeneratorConfig, given_flags, value_of


@dataclass(frozen=True)
class Zones:
    """The geometry of the structured layout (-H), as structured.lp computes it."""

    columns: int  # zones side by side
    rows: int     # zones on top of each other
    cells: int    # storage cells in all zones
    robot_room: int  # cells below the zones and the bottom border


def zones(width: int, height: int, zone_x: int, zone_y: int, border: int) -> Zones:
    columns = max(0, (width - 2 * border - zone_x) // (zone_x + 1) + 1)
    rows = max(0, (height - 2 * border - 2 - zone_y) // (zone_y + 1) + 1)
    last_zone_row = border + 2 + (rows - 1) * (zone_y + 1) + zone_y - 1
    return Zones(columns, rows, columns * rows * zone_x * zone_y,
                 width * max(0, height - last_zone_row - border))


@dataclass(frozen=True)
class Floor:
    """The floor a plan generates on (or the template's)."""

    layout: str  # structured | random | template
    width: int
    height: int
    nodes: int
    gap_size: int
    zone_x: int
    zone_y: int
    border: int

    def zones(self) -> Zones:
        return zones(self.width, self.height, self.zone_x, self.zone_y, self.border)


def plan_floor(c: GeneratorConfig, template: Instance | None) -> Floor:
    """The floor of ``c``: a template's, the structured layout (-H) or a random one."""
    if template is not None:
        return _template_floor(c, template)
    missing = [flag for flag, name in (("-x", "width"), ("-y", "height")) if getattr(c, name) is None]
    if missing:
        raise InputError(f"give the grid size ({' and '.join(missing)}) or a template (-T)")
    return _structured_floor(c) if c.structured else _random_floor(c)


def _floor(c: GeneratorConfig, layout: str, width: int, height: int, nodes: int) -> Floor:
    return Floor(layout, width, height, nodes, *(value_of(c, name) for name in ("gap_size", "zone_x", "zone_y",
                                                                                 "border")))


def _template_floor(c: GeneratorConfig, template: Instance) -> Floor:
    given = given_flags(c, "width", "height", "nodes", "gap_size", "structured", "zone_x", "zone_y", "border")
    if given:
        raise InputError(f"-T: the template fixes the floor; leave out {', '.join(given)}")
    if not template.nodes:
        raise InputError("-T: the template has no nodes")
    width, height = template.size
    return _floor(c, "template", width, height, len(template.nodes))


def _structured_floor(c: GeneratorConfig) -> Floor:
    given = given_flags(c, "nodes", "gap_size")
    if given:
        raise InputError(f"-H uses the full grid; leave out {', '.join(given)}")
    return _floor(c, "structured", c.width, c.height, c.width * c.height)


def _random_floor(c: GeneratorConfig) -> Floor:
    width, height = c.width, c.height
    given = given_flags(c, "zone_x", "zone_y", "border")
    if given:
        raise InputError(f"{', '.join(given)} only appl{'ies' if len(given) == 1 else 'y'} to the "
                         f"structured layout (-H)")
    nodes = c.nodes if c.nodes is not None else width * height
    if nodes > width * height:
        raise InputError(f"-n {nodes} nodes do not fit into the grid of -x {width} x -y {height} "
                         f"= {width * height} cells")
    if c.gap_size is not None and c.nodes is None:
        raise InputError("--gs only applies to a partial grid (-n)")
    floor = _floor(c, "random", width, height, nodes)
    most = most_missing(width, height, floor.gap_size)
    if width * height - nodes > most:
        raise InputError(f"-n {nodes}: at most {most} of the {width * height} cells can be missing with "
                         f"--gs {floor.gap_size} (gaps do not touch each other)")
    return floor


def most_missing(width: int, height: int, gap_size: int) -> int:
    """An upper bound on the missing cells of a partial grid (floor.lp's gaps).

    Gaps are W x H blocks (W*H <= gap_size, W < width, H < height) that do not touch, not
    even at a corner; so the blocks grown by one column and one row are disjoint and lie in
    (width+1) x (height+1) cells.
    """
    ratios = [w * h / ((w + 1) * (h + 1)) for w in range(1, width) for h in range(1, height)
              if w * h <= gap_size]
    return int(max(ratios, default=0) * (width + 1) * (height + 1))


def shelf_room(floor: Floor, existing: Instance, stations: tuple[int, int], robots: tuple[int, int],
               shelves: int = 0) -> tuple[int, int]:
    """(shelf sites, free sites) on ``floor``: where shelves may go, and how many more fit.

    ``stations`` and ``robots`` are (total, new) counts; ``shelves`` the shelves asked for
    (the options advised to make room for the robots keep room for them).
    """
    if floor.layout == "structured":
        geometry = floor.zones()
        _check_structured(floor, geometry, stations[0], robots[0], shelves)
        return geometry.cells, geometry.cells
    if floor.layout == "random":
        sites = floor.nodes - stations[0] - robots[0]
        if sites < 0:
            raise InputError(f"-p {stations[0]} picking stations and -r {robots[0]} robots "
                             f"do not fit on {floor.nodes} nodes (-x, -y, -n)")
        return sites, sites
    storage = existing.cells - set(existing.highways.values())
    taken = {s.at for s in existing.stations.values()} | {r.at for r in existing.robots.values()}
    new = stations[1] + robots[1]
    free = len(storage - taken - {s.at for s in existing.shelves.values()}) - new
    if free < 0:
        raise InputError(f"-p {stations[0]} picking stations and -r {robots[0]} robots do not "
                         f"fit on the template's free storage nodes")
    return len(storage - taken) - new, free


def _check_structured(floor: Floor, geometry: Zones, stations: int, robots: int, shelves: int) -> None:
    width, height = floor.width, floor.height
    if geometry.cells == 0:
        raise InputError(f"-H: no storage zone of -X {floor.zone_x} x -Y {floor.zone_y} fits into "
                         f"-x {width} x -y {height} with border -B {floor.border}")
    if stations > width:
        raise InputError(f"-H: -p {stations} picking stations do not fit into the top row (-x {width})")
    if robots > geometry.robot_room:
        raise InputError(f"-H: -r {robots} robots do not fit below the storage zones "
                         f"(room for {geometry.robot_room}); {room_advice(floor, robots, shelves)}")


def room_advice(floor: Floor, robots: int, shelves: int = 0) -> str:
    """Why ``robots`` find no room below the zones and which options give it, in words: a
    taller floor where that is enough, else a wider one, or taller zones on a taller floor.

    The robots stand in the rows between the bottom border and the last zone row, and one
    zone row more fits as soon as ``zone_y + 1`` rows are free there: so below zones of
    height ``zone_y`` lie at most ``zone_y + 1`` rows of ``width`` robots, however tall the
    floor.  Every option named keeps room for ``shelves`` in the zones.
    """
    width, height, zone_y = floor.width, floor.height, floor.zone_y

    def room(x: int, y: int, zy: int) -> int:
        """The robots' room on ``x`` by ``y`` with zones ``zy`` high; 0 where the shelves do not fit."""
        geometry = zones(x, y, floor.zone_x, zy, floor.border)
        return geometry.robot_room if geometry.cells >= max(1, shelves) else 0

    def first_taller(x: int, zy: int, reach: int) -> int | None:
        """The lowest -y from ``height`` up to ``height + reach`` with room for the robots."""
        return next((y for y in range(height, height + reach + 1) if room(x, y, zy) >= robots), None)

    taller = first_taller(width, zone_y, zone_y + 1)
    if taller is not None:
        return f"-y {taller} gives room for {room(width, taller, zone_y)}"
    # the floor up to zone_y + 1 rows taller that leaves the most rows, made as wide as needed
    rows, deepest = max((zones(width, y, floor.zone_x, zone_y, floor.border).robot_room // width, -y)
                        for y in range(height, height + zone_y + 2))
    deepest = -deepest
    wider = next(x for x in itertools.count(max(width, -(-robots // rows))) if room(x, deepest, zone_y) >= robots)
    wide = f"-x {wider}" + (f" -y {deepest}" if deepest != height else "")
    options = [f"{wide} gives room for {room(wider, deepest, zone_y)}"]
    zone_rows = -(-robots // width) - 1  # zones this high leave enough rows below them
    tall = first_taller(width, zone_rows, 2 * (zone_rows + 2))
    if tall is not None:
        options.append(f"-Y {zone_rows} -y {tall} for {room(width, tall, zone_rows)}")
    return (f"below zones of -Y {zone_y} lie at most {zone_y + 1} rows of {width} robots, whatever -y; "
            f"{', '.join(options)}")


def where_shelves_go(floor: Floor) -> str:
    """Where new shelves go, for messages."""
    return {"structured": f"in the storage zones (-H with -X {floor.zone_x} -Y {floor.zone_y})",
            "random": "on the nodes left by picking stations and robots (-x, -y, -n, -p, -r)",
            "template": "on the template's free storage nodes"}[floor.layout]
