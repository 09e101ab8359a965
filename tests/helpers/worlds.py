"""Tiny warehouses and plans for the checker, simulator and solver tests.

``world("R.S", ...)`` draws a floor row by row: ``.`` a storage node, ``#`` a highway,
``P`` a picking station (ids 1, 2, ... in reading order), ``R`` a robot, ``S`` a shelf
(resting), ``B`` both (a robot under a shelf), ``D`` a destination, `` `` (space) no node.
Ids count in reading order from 1; rows are separated by ``/``.
"""

from __future__ import annotations

from typing import Any

from asprilo.model import Action, Cell, Destination, Instance, Order, PickingStation, Plan, Product, Robot, Shelf


def world(layout: str, products: dict[int, dict[int, int | None]] | None = None,
          orders: dict[int, tuple[dict[int, int | None], int | None]] | None = None,
          carries: dict[int, int] | None = None) -> Instance:
    """An instance drawn as text; ``products``: product -> shelf -> units; ``orders``:
    order -> (product -> units, station); ``carries``: robot -> shelf."""
    instance = Instance()
    for y, row in enumerate(layout.split("/"), start=1):
        for x, mark in enumerate(row, start=1):
            if mark != " ":
                _place(instance, mark, (x, y))
    for product, stock in (products or {}).items():
        instance.products[product] = Product(product, dict(stock))
    for order, (lines, station) in (orders or {}).items():
        instance.orders[order] = Order(order, dict(lines), station)
    for robot, shelf in (carries or {}).items():
        instance.robots[robot].carries = shelf
    return instance


def _place(instance: Instance, mark: str, cell: Cell) -> None:
    """A node at ``cell`` and what ``mark`` puts on it (ids in reading order)."""
    node = len(instance.nodes) + 1
    instance.nodes[node] = cell
    if mark == "#":
        instance.highways[node] = cell
    tables = {"P": (instance.stations, PickingStation), "R": (instance.robots, Robot),
              "S": (instance.shelves, Shelf), "D": (instance.destinations, Destination)}
    for kind in "RS" if mark == "B" else mark:
        if kind in tables:
            table, make = tables[kind]
            table[len(table) + 1] = make(len(table) + 1, cell)


_DIRECTIONS = {"E": (1, 0), "W": (-1, 0), "S": (0, 1), "N": (0, -1)}


def plan(*actions: tuple) -> Plan:
    """``plan((step, robot, name, args), ...)``; ``name`` may be ``E W S N`` for moves;
    a tuple ``(kind, id)`` as robot gives another object type."""
    result = []
    for step, robot, name, *rest in actions:
        args: Any = rest[0] if rest else ()
        if name in _DIRECTIONS:
            name, args = "move", _DIRECTIONS[name]
        kind = "robot"
        if isinstance(robot, tuple):
            kind, robot = robot
        result.append(Action(step, robot, name, args, kind))
    return Plan(result)


def walk(robot: int, directions: str, start: int = 1) -> list[tuple]:
    """Moves of one robot, one per step from ``start``: ``walk(1, "EES")``."""
    return [(start + i, robot, d) for i, d in enumerate(directions)]


# --- domain Md ---------------------------------------------------------------------------

def md(cells: list[Cell], starts: list[Cell], goals: list[Cell]) -> Instance:
    """A domain-Md instance: nodes, robots at ``starts``, destinations at ``goals`` (ids from 1)."""
    return Instance(nodes={i: c for i, c in enumerate(cells, 1)},
                    robots={i: Robot(i, c) for i, c in enumerate(starts, 1)},
                    destinations={i: Destination(i, c) for i, c in enumerate(goals, 1)})


#: a 4x4 floor with three walls on which the bottleneck bound (3) is one step short of
#: the minimal makespan (4): robots have to queue
WALLED = md([(x, y) for x in range(1, 5) for y in range(1, 5) if (x, y) not in {(1, 4), (3, 1), (3, 2)}],
            [(1, 2), (4, 2), (2, 1), (1, 1)], [(3, 3), (2, 4), (4, 4), (2, 1)])
