"""Random small A/B/C warehouses for the soundness tests, and a minimal-makespan search that
runs an encoding with extra constants (to switch one pruning technique off)."""

from __future__ import annotations

import random

from asprilo.checker import check
from asprilo.domain import Domain
from asprilo.encodings import find_encoding
from asprilo.encodings.solving import name_robots
from asprilo.model import Instance, Order, PickingStation, Product, Robot, Shelf
from asprilo.reader import plan_from_atoms
from asprilo.solver import Solver
from asprilo.writer import format_instance


def random_warehouse(seed: int, width: int = 4, height: int = 3, robots: int = 2, shelves: int = 3,
                     lines: int = 2, units: bool = False) -> Instance:
    """A full grid with one picking station in the top row, a highway row under it, robots and
    shelves on distinct other cells, one product per shelf (some products on two shelves) and
    ``lines`` order lines over them (A: with small quantities when ``units``)."""
    rng = random.Random(seed)
    instance = _grid(rng, width, height, highway_share=0.5)
    instance.stations[1] = PickingStation(1, (rng.randint(1, width), 1))
    _place(rng, instance, robots, shelves)
    for ident in range(1, shelves + 1):
        stock = {ident: rng.randint(1, 2) if units else None}
        if ident > 1 and rng.random() < 0.3:
            stock[rng.randint(1, ident - 1)] = rng.randint(1, 2) if units else None
        instance.products[ident] = Product(ident, stock)
    wanted = rng.sample(sorted(instance.products), min(lines, shelves))
    for number, product in enumerate(wanted, 1):
        available = sum(u or 1 for u in instance.products[product].stock.values())
        amount = rng.randint(1, available) if units else None
        instance.orders[number] = Order(number, {product: amount}, 1)
    return instance


def _grid(rng: random.Random, width: int, height: int, highway_share: float) -> Instance:
    """A full ``width`` x ``height`` grid; each cell of row 2 a highway with ``highway_share``."""
    instance = Instance()
    cells = [(x, y) for y in range(1, height + 1) for x in range(1, width + 1)]
    for ident, cell in enumerate(cells, 1):
        instance.nodes[ident] = cell
        if cell[1] == 2 and rng.random() < highway_share:
            instance.highways[ident] = cell
    return instance


def _place(rng: random.Random, instance: Instance, robots: int, shelves: int) -> None:
    """Shelves on random storage cells, then robots on random other cells (never a station)."""
    stations = {station.at for station in instance.stations.values()}
    free = [cell for cell in instance.nodes.values() if cell not in stations]
    rng.shuffle(free)
    storage = [c for c in free if c not in instance.highways.values()]
    for ident in range(1, shelves + 1):
        cell = storage.pop()
        free.remove(cell)
        instance.shelves[ident] = Shelf(ident, cell)
    for ident in range(1, robots + 1):
        instance.robots[ident] = Robot(ident, free.pop())


def minimal_makespan(instance: Instance, domain: Domain, constants: dict[str, int] | None = None,
                     program=None, start: int = 0, limit: int = 40) -> int | None:
    """The first horizon from ``start`` at which the encoding (the reference ``plain`` one, or
    ``program``) has a plan; each plan is checked.  ``None``: none up to ``limit``."""
    encoding = find_encoding(domain, "plain")
    facts = format_instance(instance, [])
    for horizon in range(start, limit + 1):
        solver = Solver(options=["--warn=none"], constants={"horizon": horizon, **(constants or {})})
        solver.add(facts)
        solver.load(program or encoding.program)
        solver.ground()
        result = solver.solve()
        if result.satisfiable:
            plan = name_robots(encoding, facts, result.symbols) if program is None else \
                plan_from_atoms(result.symbols)  # the oracle shows occurs/3 itself
            report = check(instance, plan, domain)
            assert report.valid, [error.message for error in report.errors]
            return horizon
    return None


def random_two_station_warehouse(seed: int, width: int = 5, height: int = 3, robots: int = 2,
                                 shelves: int = 3, orders: int = 2) -> Instance:
    """A full grid with two picking stations in the top row, some highways in the row under
    them, three products on one or two shelves each (so shelves often hold several ordered
    products), and ``orders`` orders of one or two lines with quantities at random stations."""
    rng = random.Random(seed)
    instance = _grid(rng, width, height, highway_share=0.3)
    columns = rng.sample(range(1, width + 1), 2)
    instance.stations = {k: PickingStation(k, (x, 1)) for k, x in enumerate(columns, 1)}
    _place(rng, instance, robots, shelves)
    for product in range(1, 4):
        holders = rng.sample(range(1, shelves + 1), rng.randint(1, 2))
        instance.products[product] = Product(product, {s: rng.randint(1, 2) for s in holders})
    for ident in range(1, orders + 1):
        products = rng.sample(sorted(instance.products), rng.randint(1, 2))
        lines = {p: rng.randint(1, sum(instance.products[p].stock.values())) for p in products}
        instance.orders[ident] = Order(ident, lines, rng.randint(1, 2))
    return instance
