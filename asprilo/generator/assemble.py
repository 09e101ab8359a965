"""Turn the stages' decisions into an :class:`~asprilo.model.Instance` with numbered objects.

Objects keep the ids of the template; new ones continue after them, numbered row by row
from the top-left corner (as in the original generator's files).  Node and highway ids are
the cell's position in the grid, ``(Y-1) * width + X``.  For domains B and C, which ignore
quantities, products and order lines are written without them (``on S``, ``line P``).
"""

from __future__ import annotations

from collections.abc import Callable
from copy import deepcopy

from asprilo.model import Cell, Instance, Order, PickingStation, Product, Robot, Shelf

from .pipeline import World
from .plan import GenerationPlan


def _reading_order(cell: Cell) -> tuple[int, int]:
    return cell[1], cell[0]


def _add(table: dict, cells: list[Cell], make: Callable[[int, Cell], object]) -> dict[Cell, int]:
    """Number new objects after the existing ones; return cell -> id for all of them."""
    ids = {obj.at: ident for ident, obj in table.items()}
    next_id = max(table, default=0) + 1
    for cell in sorted(cells, key=_reading_order):
        table[next_id] = make(next_id, cell)
        ids[cell] = next_id
        next_id += 1
    return ids


def assemble(plan: GenerationPlan, world: World) -> Instance:
    instance = deepcopy(plan.template) if plan.template is not None else Instance()
    if plan.template is None:
        for x, y in sorted(world.nodes, key=_reading_order):
            instance.nodes[(y - 1) * plan.width + x] = (x, y)
        for x, y in sorted(world.highways, key=_reading_order):
            instance.highways[(y - 1) * plan.width + x] = (x, y)
    stations = _add(instance.stations, world.stations, PickingStation)
    _add(instance.robots, world.robots, Robot)
    shelves = _add(instance.shelves, world.shelves, Shelf)
    for (product, cell), units in sorted(world.stock.items()):
        units = units if plan.quantities else None
        instance.products.setdefault(product, Product(product)).stock[shelves[cell]] = units
    for (order, product), units in sorted(world.lines.items()):
        units = units if plan.quantities else None
        instance.orders.setdefault(order, Order(order)).lines[product] = units
    for order, cell in world.order_stations.items():
        instance.orders.setdefault(order, Order(order)).station = stations[cell]
    return instance
