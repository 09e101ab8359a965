"""Check a :class:`GeneratorConfig` and work out every number the stages need (a :class:`GenerationPlan`).

Inconsistent options are rejected here, before any solving, with a message that names the
options involved (:class:`~asprilo.errors.InputError`).  The floor is worked out in
:mod:`.layout`, products and orders in :mod:`.inventory`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from asprilo.domain import DEFAULT, Domain
from asprilo.errors import InputError
from asprilo.limits import Limits, current
from asprilo.model import Instance
from asprilo.reader import read_instance

from .attributes import drawn_attributes
from .config import GeneratorConfig, check_given, value_of
from .inventory import inventory, new_count, orders, ranges
from .layout import Floor, plan_floor, shelf_room, where_shelves_go
from .options import option_for


@dataclass(frozen=True)
class GenerationPlan:
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
    attributes: tuple = ()      # (kind, attribute, least, most): drawn for every object (attributes.py)
    releases: tuple | None = None  # (process, over, burst): the orders' release steps (releases.py)

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


def load_template(config: GeneratorConfig) -> Instance | None:
    if config.template is not None and config.templates:
        raise InputError("give a template either as an Instance or as -T files, not both")
    if config.templates:
        return read_instance(list(config.templates))
    return config.template


#: options that are sizes on the floor (at most the limit ``coordinate``, as in data)
FLOOR_SIZES = ("width", "height", "zone_x", "zone_y", "border")
#: options that count what gen makes (at most the limit ``gen-objects``)
COUNTS = ("nodes", "gap_size", "stations", "robots", "shelves", "products", "units", "orders", "pus_min", "pus_max",
          "prs_min", "prs_max", "spr_min", "spr_max", "ol_min", "ol_max", "split_threshold")


def check_budgets(config: object, limits: Limits | None = None) -> None:
    """Refuse sizes of a :class:`GeneratorConfig` beyond the budgets (README, "Reading data"): floor
    sizes beyond ``coordinate``, a floor of more than ``gen-cells`` cells, counts beyond
    ``gen-objects``."""
    limits = limits or current()
    sizes = {name: getattr(config, name) for name in FLOOR_SIZES}
    for name, value in sizes.items():
        if value is not None and value > limits.coordinate:
            raise limits.exceeded("coordinate", f"{option_for(name).flag} {value:,}")
    width, height = sizes["width"], sizes["height"]
    if width is not None and height is not None and width * height > limits.gen_cells:
        raise limits.exceeded("gen_cells", f"-x {width:,} -y {height:,}: a floor of {width * height:,} cells")
    for name in COUNTS:
        value = getattr(config, name)
        if value is not None and value > limits.gen_objects:
            raise limits.exceeded("gen_objects", f"{option_for(name).flag} {value:,}")


def make_plan(config: GeneratorConfig) -> GenerationPlan:
    """Check ``config`` and resolve defaults, template contents and the M alignment."""
    check_given(config)
    check_budgets(config)
    solving = _solving(config)
    template = load_template(config)
    floor = plan_floor(config, template)
    existing = template or Instance()
    objects = _objects(config, floor, existing)
    r = ranges(config, config.domain or DEFAULT, objects["shelf_total"], objects["robot_total"])
    stock = inventory(r, existing, objects["shelf_total"])
    lines = orders(config, r, stock, existing, objects["station_total"])
    given = vars(config)  # (a dataclass made at run time: its fields by name)
    drawn = drawn_attributes(given["domain"] or DEFAULT, given["variants"], given["energy"])
    plan = GenerationPlan(
        layout=floor.layout, width=floor.width, height=floor.height, nodes=floor.nodes, gap_size=floor.gap_size,
        zone_x=floor.zone_x, zone_y=floor.zone_y, border=floor.border, template=template,
        reachable=config.reachable, quantities=_with_quantities(config.domain, existing),
        attributes=drawn, releases=_releases(given, lines["order_total"]), **objects, **solving, **stock, **lines)
    _check_memory(plan)
    return plan


#: what generating costs, measured (``benchmarks/limits_edges.py``; clingo 5.8): a base, and
#: per cell of the floor kilobytes for the floor and for each stage that places objects on it
#: (the floor of a partial grid once per gap shape), and more for -R's reachability; the limit is on
#: address space, which runs ahead of resident memory: 1000x800 with one robot failed at 1.99 GB resident
_BASE_MB, _CELL_KB, _REACHABLE_KB = 60, 1.4, 7.0


def estimated_mb(plan: GenerationPlan) -> int:
    """About how many megabytes generating ``plan`` takes at its peak (the floor dominates)."""
    cells = plan.width * plan.height
    floor = 1
    if plan.partial_floor:  # a gap of every shape W x H <= gap_size may start at every cell
        widths = range(1, min(plan.gap_size, plan.width - 1) + 1)
        floor += sum(min(plan.gap_size // width, plan.height - 1) for width in widths)
    placing = sum(1 for count in (plan.stations, plan.robots, plan.shelves) if count)
    kilobytes = _CELL_KB * (floor + placing) + (_REACHABLE_KB if plan.reachable and plan.shelves else 0)
    return round(_BASE_MB + cells * kilobytes / 1024)


def _check_memory(plan: GenerationPlan) -> None:
    """Refuse, before any grounding, a plan whose estimate is beyond the limit ``gen-mb``."""
    limits, needed = current(), estimated_mb(plan)
    if needed > limits.gen_mb:
        reachable = " with -R" if plan.reachable and plan.shelves else ""
        raise limits.exceeded("gen_mb", f"a floor of {plan.width:,}x{plan.height:,} cells{reachable} takes about "
                                        f"{needed:,} MB to generate")


def _releases(given: Mapping[str, Any], orders: int) -> tuple | None:
    """``--release`` (of a config's fields by name): (process, over, burst); refused where it
    releases nothing."""
    if given["release"] is None:
        if given["release_over"] is not None:
            raise InputError("--release-over: give --release too (steady, poisson or bursts)")
        return None
    if not orders:
        raise InputError("--release: there are no orders to release (give -o)")
    return given["release"], given["release_over"] or 2 * orders, given["burst"]


def _solving(c: GeneratorConfig) -> dict:
    if c.one_shot and (c.incremental or c.split_threshold is not None):
        raise InputError("--one-shot solves once: it cannot be combined with -I/--split-threshold")
    split = value_of(c, "split_threshold") if c.incremental or c.split_threshold is not None else None
    return {"threads": value_of(c, "threads"), "time_limit": float(value_of(c, "time_limit")), "split": split,
            "one_shot": c.one_shot}


def _objects(c: GeneratorConfig, floor: Floor, existing: Instance) -> dict[str, int]:
    """Picking stations, robots and shelves: totals and new ones; shelves fit where they may go."""
    station_total = c.stations if c.stations is not None else len(existing.stations)
    robot_total = c.robots if c.robots is not None else len(existing.robots)
    stations = new_count(station_total, len(existing.stations), "-p", "picking stations")
    robots = new_count(robot_total, len(existing.robots), "-r", "robots")
    if c.shelves is not None and c.shelf_coverage is not None:
        raise InputError("give either -s or --sc, not both")
    sites, free = shelf_room(floor, existing, (station_total, stations), (robot_total, robots),
                             value_of(c, "shelves") or 0)
    if c.shelf_coverage is not None:
        shelf_total = int(c.shelf_coverage * sites / 100 + 0.5)
    else:
        shelf_total = c.shelves if c.shelves is not None else len(existing.shelves)
    shelves = new_count(shelf_total, len(existing.shelves), "-s", "shelves")
    if shelves > free:
        raise InputError(f"-s {shelf_total} shelves do not fit: room for {free} more {where_shelves_go(floor)}")
    return {"stations": stations, "robots": robots, "shelves": shelves, "station_total": station_total,
            "robot_total": robot_total, "shelf_total": shelf_total}


def _with_quantities(domain: Domain | None, template: Instance) -> bool:
    """Whether products and lines are written with quantities: as the domain says (not for B
    and C), and without --domain not when the template writes its own without them."""
    if domain is not None and domain.generation is not None:
        return domain.generation.quantities
    entries = [u for p in template.products.values() for u in p.stock.values()]
    entries += [u for o in template.orders.values() for u in o.lines.values()]
    return None not in entries
