"""Tiny warehouses and plans for the checker and simulator tests (this file holds no tests).

``world("R.S", ...)`` draws a floor row by row: ``.`` a storage node, ``#`` a highway,
``P`` a picking station (ids 1, 2, ... in reading order), ``R`` a robot, ``S`` a shelf
(resting), ``B`` both (a robot under a shelf), ``D`` a destination, `` `` (space) no node.
Ids count in reading order from 1; rows are separated by ``/``.
"""

from __future__ import annotations

from typing import Any

from asprilo.model import Action, Destination, Instance, Order, PickingStation, Plan, Product, Robot, Shelf


def world(layout: str, products: dict[int, dict[int, int | None]] | None = None,
          orders: dict[int, tuple[dict[int, int | None], int | None]] | None = None,
          carries: dict[int, int] | None = None) -> Instance:
    """An instance drawn as text; ``products``: product -> shelf -> units; ``orders``:
    order -> (product -> units, station); ``carries``: robot -> shelf."""
    instance = Instance()
    node = 0
    for y, row in enumerate(layout.split("/"), start=1):
        for x, mark in enumerate(row, start=1):
            if mark == " ":
                continue
            node += 1
            cell = (x, y)
            instance.nodes[node] = cell
            if mark == "#":
                instance.highways[node] = cell
            if mark == "P":
                ident = len(instance.stations) + 1
                instance.stations[ident] = PickingStation(ident, cell)
            if mark in "RB":
                ident = len(instance.robots) + 1
                instance.robots[ident] = Robot(ident, cell)
            if mark in "SB":
                ident = len(instance.shelves) + 1
                instance.shelves[ident] = Shelf(ident, cell)
            if mark == "D":
                ident = len(instance.destinations) + 1
                instance.destinations[ident] = Destination(ident, cell)
    for product, stock in (products or {}).items():
        instance.products[product] = Product(product, dict(stock))
    for order, (lines, station) in (orders or {}).items():
        instance.orders[order] = Order(order, dict(lines), station)
    for robot, shelf in (carries or {}).items():
        instance.robots[robot].carries = shelf
    return instance


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
