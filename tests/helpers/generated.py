"""The generator's guarantees and calls shared by the generator tests."""

from __future__ import annotations

from collections import Counter, deque

from asprilo.generator import GeneratorConfig, generate
from asprilo.model import Cell, Instance

PAPER = {  # SPEC.md §6: size directory -> (options, robot counts)
    "1x2x4": ({"-x": 11, "-y": 6, "-X": 4, "-Y": 2, "-p": 1, "-s": 16, "-P": 16, "-u": 16}, (2, 5, 8, 11)),
    "2x3x5": ({"-x": 19, "-y": 9, "-X": 5, "-Y": 2, "-p": 3, "-s": 60, "-P": 60, "-u": 60}, (5, 10, 15, 19)),
    "4x5x8": ({"-x": 46, "-y": 15, "-X": 8, "-Y": 2, "-p": 10, "-s": 320, "-P": 320, "-u": 320}, (12, 23, 35, 46)),
}
FIGURE_1 = {"-x": 19, "-y": 9, "-X": 5, "-Y": 2, "-p": 3, "-s": 45, "-r": 6, "-P": 180, "-u": 540, "-o": 12,
            "-H": True}


def one(options: dict, seed: int = 1) -> Instance:
    return generate(GeneratorConfig.from_options(options), 1, seed)[0].instance


def cells_of(objects: dict) -> set[Cell]:
    return {obj.at for obj in objects.values()}


def reachable(cells: set[Cell], start: Cell, blocked: set[Cell] = frozenset()) -> set[Cell]:
    """Cells reached from ``start`` through neighbouring cells that are not blocked."""
    seen, queue = {start}, deque([start])
    while queue:
        x, y = queue.popleft()
        for step in ((x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)):
            if step in cells and step not in seen and step not in blocked:
                seen.add(step)
                queue.append(step)
    return seen


def check_instance(instance: Instance, reach: bool = False) -> None:
    """The guarantees of every generated instance (SPEC.md §1, §6 and the generator's issue)."""
    cells = instance.cells
    highways = set(instance.highways.values())
    assert len(cells) == len(instance.nodes) and highways <= cells
    for objects in (instance.stations, instance.robots, instance.shelves):
        at = [obj.at for obj in objects.values()]
        assert len(set(at)) == len(at), "two objects of a type on one node"
        assert set(at) <= cells
    assert not cells_of(instance.stations) & highways, "a picking station on a highway"
    assert cells_of(instance.shelves) <= instance.storage_cells, "a shelf off the storage nodes"
    held = Counter()
    for product in instance.products.values():
        assert product.stock and set(product.stock) <= set(instance.shelves)
        held[product.id] = sum(1 if units is None else units for units in product.stock.values())
    asked = Counter()
    for order in instance.orders.values():
        assert order.lines and order.station in instance.stations
        assert set(order.lines) <= set(instance.products)
        for product, units in order.lines.items():
            asked[product] += 1 if units is None else units
    if all(u is not None for p in instance.products.values() for u in p.stock.values()):
        assert all(asked[p] <= held[p] for p in asked), "orders ask for more units than the shelves hold"
    if reach:
        shelves = cells_of(instance.shelves)
        for shelf in shelves:
            assert cells_of(instance.stations) <= reachable(cells, shelf, shelves - {shelf})
