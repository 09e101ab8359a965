"""Check a :class:`GeneratorConfig` and work out every number the stages need (a :class:`Plan`).

Inconsistent options are rejected here, before any solving, with a message that names the
options involved (:class:`~asprilo.errors.InputError`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.model import Instance
from asprilo.reader import read_instance

from .config import GeneratorConfig

#: Objects placed per round with -I when --split-threshold is not given.
DEFAULT_SPLIT = 100

DEFAULTS = {"gap_size": 2, "zone_x": 2, "zone_y": 2, "border": 1, "pus_min": 1, "pus_max": 10,
            "prs_min": 0, "prs_max": 20, "spr_min": 1, "spr_max": 4, "ol_min": 1, "ol_max": 1,
            "threads": 1, "time_limit": 300.0}

FLAGS = {"width": "-x", "height": "-y", "nodes": "-n", "gap_size": "--gs", "structured": "-H",
         "zone_x": "-X", "zone_y": "-Y", "border": "-B", "stations": "-p", "robots": "-r",
         "shelves": "-s", "shelf_coverage": "--sc", "products": "-P", "units": "-u",
         "pus_min": "--pusmin", "pus_max": "--pusmax", "prs_min": "--prsmin", "prs_max": "--prsmax",
         "spr_min": "--sprmin", "spr_max": "--sprmax", "orders": "-o", "ol_min": "--olmin",
         "ol_max": "--olmax", "threads": "-t", "time_limit": "-w", "split_threshold": "--split-threshold"}


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
class Plan:
    """Every number the generator needs, checked.  Counts of *new* objects unless named total."""

    layout: str                 # structured | random | template
    width: int
    height: int
    nodes: int                  # floor nodes (total)
    gap_size: int
    zone_x: int
    zone_y: int
    border: int
    template: Instance | None
    stations: int
    robots: int
    shelves: int
    station_total: int
    robot_total: int
    shelf_total: int
    reachable: bool
    products: range             # ids of the new products
    product_total: int
    units: int | None           # units on the new products' shelves (None: any number)
    quantities: bool            # write quantities (not for domains B and C, which ignore them)
    pus_min: int
    pus_max: int
    prs_min: int
    prs_max: int
    spr_min: int
    spr_max: int
    pairs: tuple[int, int, int]  # least, aimed-at and most new (product, shelf) pairs
    orders: range               # ids of the new orders
    order_total: int
    ol_min: int
    ol_max: int
    order_all: bool
    threads: int
    time_limit: float
    split: int | None           # objects per round (None: one round per stage)
    one_shot: bool

    @property
    def partial_floor(self) -> bool:
        return self.layout == "random" and self.nodes < self.width * self.height

    def constants(self) -> dict[str, int]:
        """The ``#const`` values of the logic programs."""
        return {"width": self.width, "height": self.height, "zone_x": self.zone_x,
                "zone_y": self.zone_y, "border": self.border, "station_count": self.station_total,
                "robot_count": self.robot_total, "gap_size": self.gap_size,
                "prs_max": self.prs_max, "spr_min": self.spr_min, "spr_max": self.spr_max,
                "pus_min": self.pus_min, "pus_max": self.pus_max, "ol_min": self.ol_min,
                "ol_max": self.ol_max, "order_all": int(self.order_all)}


def _given(config: GeneratorConfig, *names: str) -> list[str]:
    return [FLAGS[name] for name in names if getattr(config, name) not in (None, False)]


def _value(config: GeneratorConfig, name: str) -> Any:
    value = getattr(config, name)
    return DEFAULTS[name] if value is None else value


def _at_least(config: GeneratorConfig, name: str, least: float) -> Any:
    value = _value(config, name)
    if value < least:
        raise InputError(f"{FLAGS[name]} must be at least {least}, got {value}")
    return value


def load_template(config: GeneratorConfig) -> Instance | None:
    if config.template is not None and config.templates:
        raise InputError("give a template either as an Instance or as -T files, not both")
    if config.templates:
        return read_instance(list(config.templates))
    return config.template


def make_plan(config: GeneratorConfig) -> Plan:
    """Check ``config`` and resolve defaults, template contents and the M alignment."""
    c = config
    for name in ("width", "height", "nodes", "stations", "robots", "shelves", "products", "units",
                 "orders", "shelf_coverage"):
        if getattr(c, name) is not None:
            _at_least(c, name, 0 if name not in ("width", "height", "nodes") else 1)
    domain = c.domain or Domain.A  # A: no alignment
    threads = _at_least(c, "threads", 1)
    time_limit = _value(c, "time_limit")
    if time_limit <= 0:
        raise InputError(f"-w must be positive, got {time_limit}")
    if c.one_shot and (c.incremental or c.split_threshold is not None):
        raise InputError("--one-shot solves once: it cannot be combined with -I/--split-threshold")
    split = _at_least(c, "split_threshold", 1) if c.split_threshold is not None else \
        (DEFAULT_SPLIT if c.incremental else None)

    template = load_template(c)
    floor = _floor(c, template)
    layout, width, height, nodes = floor["layout"], floor["width"], floor["height"], floor["nodes"]

    existing = template or Instance()
    station_total = c.stations if c.stations is not None else len(existing.stations)
    robot_total = c.robots if c.robots is not None else len(existing.robots)
    new_stations = _new(station_total, len(existing.stations), "-p", "picking stations")
    new_robots = _new(robot_total, len(existing.robots), "-r", "robots")

    # where shelves may go: how many sites, and how many shelves (-s or --sc)
    if c.shelves is not None and c.shelf_coverage is not None:
        raise InputError("give either -s or --sc, not both")
    if layout == "structured":
        geometry = zones(width, height, floor["zone_x"], floor["zone_y"], floor["border"])
        _check_structured(floor, geometry, station_total, robot_total)
        sites, free = geometry.cells, geometry.cells
    elif layout == "random":
        sites = free = nodes - station_total - robot_total
        if sites < 0:
            raise InputError(f"-p {station_total} picking stations and -r {robot_total} robots "
                             f"do not fit on {nodes} nodes (-x, -y, -n)")
    else:
        storage = existing.cells - set(existing.highways.values())
        taken = {s.at for s in existing.stations.values()} | {r.at for r in existing.robots.values()}
        free = len(storage - taken - {s.at for s in existing.shelves.values()}) - new_stations - new_robots
        sites = len(storage - taken) - new_stations - new_robots
        if free < 0:
            raise InputError(f"-p {station_total} picking stations and -r {robot_total} robots do not "
                             f"fit on the template's free storage nodes")
    if c.shelf_coverage is not None:
        if c.shelf_coverage > 100:
            raise InputError(f"--sc is a percentage (0..100), got {c.shelf_coverage}")
        shelf_total = int(c.shelf_coverage * sites / 100 + 0.5)
    else:
        shelf_total = c.shelves if c.shelves is not None else len(existing.shelves)
    new_shelves = _new(shelf_total, len(existing.shelves), "-s", "shelves")
    if new_shelves > free:
        where = {"structured": f"in the storage zones (-H with -X {floor['zone_x']} -Y {floor['zone_y']})",
                 "random": "on the nodes left by picking stations and robots (-x, -y, -n, -p, -r)",
                 "template": "on the template's free storage nodes"}[layout]
        raise InputError(f"-s {shelf_total} shelves do not fit: room for {free} more {where}")

    ranges = _ranges(c, domain, shelf_total, robot_total)
    inventory = _inventory(ranges, existing, shelf_total)
    orders = _orders(c, ranges, inventory, existing, station_total)
    return Plan(
        layout=layout, width=width, height=height, nodes=nodes, gap_size=floor["gap_size"],
        zone_x=floor["zone_x"], zone_y=floor["zone_y"], border=floor["border"], template=template,
        stations=new_stations, robots=new_robots, shelves=new_shelves, station_total=station_total,
        robot_total=robot_total, shelf_total=shelf_total, reachable=c.reachable,
        threads=threads, time_limit=float(time_limit), split=split, one_shot=c.one_shot,
        quantities=_with_quantities(c.domain, existing), **inventory, **orders)


def _with_quantities(domain: Domain | None, template: Instance) -> bool:
    """Whether products and lines are written with quantities: not for B and C, and without
    --domain not when the template writes its own without them."""
    if domain is not None:
        return domain not in (Domain.B, Domain.C)
    entries = [u for p in template.products.values() for u in p.stock.values()]
    entries += [u for o in template.orders.values() for u in o.lines.values()]
    return None not in entries


def _new(total: int, existing: int, flag: str, what: str) -> int:
    if total < existing:
        raise InputError(f"{flag} {total}: the template has {existing} {what} already")
    return total - existing


def _floor(c: GeneratorConfig, template: Instance | None) -> dict[str, Any]:
    floor = {name: _value(c, name) for name in ("gap_size", "zone_x", "zone_y", "border")}
    if template is not None:
        given = _given(c, "width", "height", "nodes", "gap_size", "structured", "zone_x", "zone_y", "border")
        if given:
            raise InputError(f"-T: the template fixes the floor; leave out {', '.join(given)}")
        if not template.nodes:
            raise InputError("-T: the template has no nodes")
        width, height = template.size
        return {**floor, "layout": "template", "width": width, "height": height,
                "nodes": len(template.nodes)}
    missing = [flag for flag, name in (("-x", "width"), ("-y", "height")) if getattr(c, name) is None]
    if missing:
        raise InputError(f"give the grid size ({' and '.join(missing)}) or a template (-T)")
    width, height = c.width, c.height
    if c.structured:
        given = _given(c, "nodes", "gap_size")
        if given:
            raise InputError(f"-H uses the full grid; leave out {', '.join(given)}")
        for name in ("zone_x", "zone_y", "border"):
            _at_least(c, name, 1)
        return {**floor, "layout": "structured", "width": width, "height": height, "nodes": width * height}
    given = _given(c, "zone_x", "zone_y", "border")
    if given:
        raise InputError(f"{', '.join(given)} only appl{'ies' if len(given) == 1 else 'y'} to the "
                         f"structured layout (-H)")
    nodes = c.nodes if c.nodes is not None else width * height
    if nodes > width * height:
        raise InputError(f"-n {nodes} nodes do not fit into the grid of -x {width} x -y {height} "
                         f"= {width * height} cells")
    if c.gap_size is not None:
        if c.nodes is None:
            raise InputError("--gs only applies to a partial grid (-n)")
        _at_least(c, "gap_size", 1)
    most = most_missing(width, height, floor["gap_size"])
    if width * height - nodes > most:
        raise InputError(f"-n {nodes}: at most {most} of the {width * height} cells can be missing with "
                         f"--gs {floor['gap_size']} (gaps do not touch each other)")
    return {**floor, "layout": "random", "width": width, "height": height, "nodes": nodes}


def most_missing(width: int, height: int, gap_size: int) -> int:
    """An upper bound on the missing cells of a partial grid (floor.lp's gaps).

    Gaps are W x H blocks (W*H <= gap_size, W < width, H < height) that do not touch, not
    even at a corner; so the blocks grown by one column and one row are disjoint and lie in
    (width+1) x (height+1) cells.
    """
    ratios = [w * h / ((w + 1) * (h + 1)) for w in range(1, width) for h in range(1, height)
              if w * h <= gap_size]
    return int(max(ratios, default=0) * (width + 1) * (height + 1))


def _check_structured(floor: dict, geometry: Zones, stations: int, robots: int) -> None:
    width, height = floor["width"], floor["height"]
    if geometry.cells == 0:
        raise InputError(f"-H: no storage zone of -X {floor['zone_x']} x -Y {floor['zone_y']} fits into "
                         f"-x {width} x -y {height} with border -B {floor['border']}")
    if stations > width:
        raise InputError(f"-H: -p {stations} picking stations do not fit into the top row (-x {width})")
    if robots > geometry.robot_room:
        raise InputError(f"-H: -r {robots} robots do not fit below the storage zones "
                         f"(room for {geometry.robot_room}; make -y larger)")


def _ranges(c: GeneratorConfig, domain: Domain, shelves: int, robots: int) -> dict[str, Any]:
    """The ranges and totals after the M alignment; the flags of clashing options in messages."""
    values = {name: getattr(c, name) for name in
              ("products", "units", "orders", "pus_min", "pus_max", "prs_min", "prs_max",
               "spr_min", "spr_max", "ol_min", "ol_max")}
    if domain is Domain.M:
        aligned = {"products": shelves, "units": shelves, "orders": robots, "pus_min": 1, "pus_max": 1,
                   "prs_min": 1, "prs_max": 1, "spr_min": 1, "spr_max": 1, "ol_min": 1, "ol_max": 1}
        why = {"products": f"as many products as shelves ({shelves})",
               "units": f"one unit per shelf ({shelves})", "orders": f"as many orders as robots ({robots})"}
        for name, wanted in aligned.items():
            if values[name] is not None and values[name] != wanted:
                reason = why.get(name, "one product per shelf, on one shelf, one unit, one line per order")
                raise InputError(f"--domain m: {reason}; got {FLAGS[name]} {values[name]}")
            values[name] = wanted
    for name, default in DEFAULTS.items():
        if name in values and values[name] is None:
            values[name] = default
    for name in ("pus_min", "ol_min"):
        if values[name] < 1:
            raise InputError(f"{FLAGS[name]} must be at least 1, got {values[name]}")
    for low, high in (("pus_min", "pus_max"), ("prs_min", "prs_max"), ("spr_min", "spr_max"),
                      ("ol_min", "ol_max")):
        if values[low] < 0:
            raise InputError(f"{FLAGS[low]} must be at least 0, got {values[low]}")
        if values[high] >= 1 and values[low] > values[high]:
            raise InputError(f"{FLAGS[low]} {values[low]} exceeds {FLAGS[high]} {values[high]}")
    return values


def _inventory(r: dict[str, Any], existing: Instance, shelves: int) -> dict[str, Any]:
    product_total = r["products"] if r["products"] is not None else len(existing.products)
    new = _new(product_total, len(existing.products), "-P", "products")
    first = max(existing.products, default=0) + 1
    spr_max = min(r["spr_max"] if r["spr_max"] >= 1 else shelves, shelves)
    prs_max = min(r["prs_max"] if r["prs_max"] >= 1 else product_total, product_total)
    fixed_pairs = sum(len(p.stock) for p in existing.products.values())
    fixed_units = existing.units
    units = r["units"] - fixed_units if r["units"] is not None else None
    if units is not None and units < 0:
        raise InputError(f"-u {r['units']}: the template's products hold {fixed_units} units already")
    if new and not shelves:
        raise InputError(f"-P {product_total} products need shelves (-s or --sc)")
    if new and r["spr_min"] > shelves:
        raise InputError(f"--sprmin {r['spr_min']} exceeds the number of shelves (-s {shelves})")
    if shelves and r["prs_min"] > product_total:
        raise InputError(f"--prsmin {r['prs_min']} exceeds the number of products (-P {product_total})")
    least = max(new * r["spr_min"], shelves * r["prs_min"] - fixed_pairs)
    most = min(new * spr_max, shelves * prs_max - fixed_pairs)
    ranges = (f"-P {product_total}, -s {shelves}, --sprmin/--sprmax {r['spr_min']}/{r['spr_max']}, "
              f"--prsmin/--prsmax {r['prs_min']}/{r['prs_max']}")
    if new and least > most:
        raise InputError(f"the products do not fit on the shelves: {ranges}")
    if not new:
        if units:
            raise InputError(f"-u {r['units']}: there are no new products (-P) to hold the units")
        least = most = 0
    pus_max = r["pus_max"] if r["pus_max"] >= 1 else \
        (max(units, r["pus_min"]) if units is not None else r["pus_min"] + 9)
    if units is not None and new:
        low, high = max(least, -(-units // pus_max)), min(most, units // r["pus_min"])
        if low > high:
            raise InputError(f"-u {r['units']}: with {ranges}, --pusmin/--pusmax "
                             f"{r['pus_min']}/{r['pus_max']} the shelves hold "
                             f"{least * r['pus_min'] + fixed_units}..{most * pus_max + fixed_units} units")
        least, most = low, high
        pus_max = min(pus_max, units - (least - 1) * r["pus_min"])  # room left by the other pairs
    spr_min, prs_min = r["spr_min"], r["prs_min"]
    if new:  # tighten the ranges by the totals, so the solver need not count across products
        spr_max = min(spr_max, most - (new - 1) * spr_min)
        spr_min = max(spr_min, least - (new - 1) * spr_max)
        prs_max = min(prs_max, most + fixed_pairs - (shelves - 1) * prs_min)
        prs_min = max(prs_min, least + fixed_pairs - (shelves - 1) * prs_max)
    target = min(most, max(least, round(math.sqrt(max(least, 1) * most))))
    return {"products": range(first, first + new), "product_total": product_total, "units": units,
            "pus_min": r["pus_min"], "pus_max": pus_max, "prs_min": prs_min, "prs_max": prs_max,
            "spr_min": spr_min, "spr_max": spr_max, "pairs": (least, target, most)}


def _orders(c: GeneratorConfig, r: dict[str, Any], inventory: dict[str, Any], existing: Instance,
            stations: int) -> dict[str, Any]:
    order_total = r["orders"] if r["orders"] is not None else len(existing.orders)
    new = _new(order_total, len(existing.orders), "-o", "orders")
    first = max(existing.orders, default=0) + 1
    products = inventory["product_total"]
    ol_max = min(r["ol_max"] if r["ol_max"] >= 1 else products, products)
    if new:
        if not products:
            raise InputError(f"-o {order_total} orders need products (-P)")
        if not stations:
            raise InputError(f"-o {order_total} orders need picking stations (-p)")
        if r["ol_min"] > products:
            raise InputError(f"--olmin {r['ol_min']} exceeds the number of products (-P {products})")
        fixed = sum(q or 1 for o in existing.orders.values() for q in o.lines.values())
        units = r["units"] if r["units"] is not None else \
            existing.units + inventory["pairs"][2] * inventory["pus_max"]
        if new * r["ol_min"] + fixed > units:
            raise InputError(f"-o {order_total} orders with --olmin {r['ol_min']} lines each ask for "
                             f"more units than the shelves hold ({units}, -u)")
    if c.order_all:
        ordered = {p for o in existing.orders.values() for p in o.lines}
        if new * ol_max + len(ordered) < products:
            raise InputError(f"--oap: -o {order_total} orders with --olmax {r['ol_max']} lines "
                             f"cannot ask for all -P {products} products")
    return {"orders": range(first, first + new), "order_total": order_total, "ol_min": r["ol_min"],
            "ol_max": ol_max, "order_all": c.order_all}
