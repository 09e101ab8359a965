"""Every violation in plain words: one function per ``(module, check)`` of the checker, found
through the table :data:`MESSAGES` at the end.

Each function takes the timeline and the ``err/3`` parameters (the step last) and returns
the text and what to highlight: ``{"robots": [...], "shelves": [...], "cells": [...]}``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from ..domain import Goal
from ..facts import format_value  # not the writer, which re-exports it: explaining writes no file
from ..model import Action

if TYPE_CHECKING:
    from .timeline import Timeline

#: a message function: (timeline, *params) -> (text, highlight)
Describe = Callable[..., tuple[str, dict[str, list]]]


def _cell(cell: Any) -> str:
    return f"({cell[0]},{cell[1]})" if isinstance(cell, tuple) and len(cell) == 2 else format_value(cell)


def _units(count: int, what: str = "unit") -> str:
    return f"{count} {what}" + ("" if count == 1 else "s")


def _station_words(timeline: Timeline, station: Any) -> str:
    found = timeline.instance.stations.get(station)
    return f"picking station {station}" + (f" at {_cell(found.at)}" if found else "")


# the instance

def instance_robot_off_floor(timeline, robot, _step):
    cell = timeline.instance.robots[robot].at
    return f"robot {robot} starts at {_cell(cell)}, which is not a floor node", \
        {"robots": [robot], "cells": [cell]}


def instance_shelf_off_floor(timeline, shelf, _step):
    cell = timeline.instance.shelves[shelf].at
    return f"shelf {shelf} stands at {_cell(cell)}, which is not a floor node", \
        {"shelves": [shelf], "cells": [cell]}


def instance_station_off_floor(timeline, station, _step):
    cell = timeline.instance.stations[station].at
    return f"picking station {station} is at {_cell(cell)}, which is not a floor node", {"cells": [cell]}


def instance_destination_off_floor(timeline, destination, _step):
    cell = timeline.instance.destinations[destination].at
    return f"destination {destination} is at {_cell(cell)}, which is not a floor node", {"cells": [cell]}


def instance_station_collision(timeline, first, second, _step):
    cell = timeline.instance.stations[first].at
    return f"picking stations {first} and {second} are both on {_cell(cell)}", {"cells": [cell]}


def instance_destination_collision(timeline, first, second, _step):
    cell = timeline.instance.destinations[first].at
    return f"destinations {first} and {second} are both on {_cell(cell)}", {"cells": [cell]}


def instance_robot_collision(timeline, first, second, _step):
    cell = timeline.instance.robots[first].at
    return f"robots {first} and {second} both start on {_cell(cell)}", \
        {"robots": [first, second], "cells": [cell]}


def instance_shelf_collision(timeline, first, second, _step):
    cell = timeline.state(0).shelves.get(first)
    return f"shelves {first} and {second} both stand on {_cell(cell)}", \
        {"shelves": [first, second], "cells": [cell]}


def instance_shelf_on_highway(timeline, shelf, _step):
    cell = timeline.instance.shelves[shelf].at
    return f"shelf {shelf} rests on the highway node {_cell(cell)}", {"shelves": [shelf], "cells": [cell]}


def instance_shelf_on_station(timeline, shelf, _step):
    cell = timeline.instance.shelves[shelf].at
    return f"shelf {shelf} rests on the picking station at {_cell(cell)}", \
        {"shelves": [shelf], "cells": [cell]}


def instance_carried_shelf_elsewhere(timeline, robot, shelf, _step):
    robot_cell, shelf_cell = timeline.instance.robots[robot].at, timeline.instance.shelves[shelf].at
    return (f"robot {robot} at {_cell(robot_cell)} carries shelf {shelf}, but shelf {shelf} "
            f"stands at {_cell(shelf_cell)}"), \
        {"robots": [robot], "shelves": [shelf], "cells": [robot_cell, shelf_cell]}


def instance_shared_shelf(timeline, shelf, _step):
    robots = sorted(r.id for r in timeline.instance.robots.values() if r.carries == shelf)
    names = ", ".join(map(str, robots[:-1])) + f" and {robots[-1]}"
    return f"robots {names} all carry shelf {shelf} (robot {robots[0]} keeps it)", \
        {"robots": robots, "shelves": [shelf]}


def instance_order_station(timeline, order, _step):
    return f"order {order} names no picking station", {}


def instance_unknown_station(timeline, order, station, _step):
    return f"order {order} is to be delivered at picking station {station}, which does not exist", {}


def instance_unknown_product(timeline, order, product, _step):
    return f"order {order} asks for product {product}, which no shelf holds", {}


# the plan's actions

def _action_words(actions: list[Action]) -> str:
    return ", ".join(f"{a.name}{format_value(a.args) if a.args != () else ''}" for a in actions)


def action_not_robot(timeline, kind, ident, step):
    actions = timeline.actions_of(ident, step, kind)
    return f"the plan gives {kind} {ident} the action {_action_words(actions)}, but only robots act", {}


def action_unknown_robot(timeline, robot, step):
    return f"the plan moves robot {robot}, but the instance has no robot {robot}", {}


def action_bad_step(timeline, robot, step):
    return f"robot {robot} acts at step {step} ({_action_words(timeline.actions_of(robot, step))}); " \
           "steps start at 1", {"robots": [robot]}


def action_unknown_action(timeline, robot, name, step):
    return f"robot {robot} does '{name}', which is not an action of domain {timeline.domain.label}", \
        {"robots": [robot]}


_SHAPES = {"pickup": "()", "putdown": "()"}


def action_bad_arguments(timeline, robot, name, step):
    args = [a.args for a in timeline.actions_of(robot, step) if a.name == name]
    if name == "deliver":
        shape = "(Order,Product,Units) with Units >= 1" if timeline.domain.counts_units else \
            "(Order,Product) or (Order,Product,Units)"
    elif name == "move":  # the domain's moves: a variant may give others
        *others, last = (format_value(direction) for direction in timeline.domain.directions)
        shape = f"{', '.join(others)} or {last}" if others else last
    else:
        shape = _SHAPES.get(name, "other arguments")
    given = " or ".join(format_value(a) for a in args)
    return f"robot {robot} does {name} with {given}, but {name} takes {shape}", {"robots": [robot]}


def action_concurrent(timeline, robot, step):
    actions = timeline.actions_of(robot, step)
    return f"robot {robot} does {len(actions)} actions at once ({_action_words(actions)}); " \
           "a robot does at most one action per step", {"robots": [robot]}


# where robots go

def collision_same_node(timeline, first, second, step):
    cell = timeline.position(first, step)
    return f"robots {first} and {second} are both on {_cell(cell)}", \
        {"robots": [first, second], "cells": [cell]}


def collision_swap(timeline, first, second, step):
    a, b = timeline.position(first, step - 1), timeline.position(second, step - 1)
    return f"robots {first} and {second} swap nodes {_cell(a)} and {_cell(b)}", \
        {"robots": [first, second], "cells": [a, b]}


def move_off_floor(timeline, robot, step):
    cell = timeline.position(robot, step)
    return f"robot {robot} moves to {_cell(cell)}, which is not a floor node", \
        {"robots": [robot], "cells": [cell]}


def move_onto_shelf(timeline, robot, step):
    shelf = timeline.state(step - 1).carries.get(robot)
    cell = timeline.position(robot, step)
    resting = timeline.resting_on(cell, step - 1)
    return f"robot {robot} carries shelf {shelf} onto {_cell(cell)}, where shelf " \
           f"{', '.join(map(str, resting))} rests", \
        {"robots": [robot], "shelves": [shelf, *resting], "cells": [cell]}


# pickup and putdown

def pickup_carrying(timeline, robot, step):
    shelf = timeline.state(step - 1).carries.get(robot)
    return f"robot {robot} picks up, but it already carries shelf {shelf}", \
        {"robots": [robot], "shelves": [shelf]}


def pickup_no_shelf(timeline, robot, step):
    cell = timeline.position(robot, step - 1)
    return f"robot {robot} picks up at {_cell(cell)}, but no shelf rests there", \
        {"robots": [robot], "cells": [cell]}


def pickup_shared_shelf(timeline, shelf, step):
    cell = timeline.state(step - 1).shelves.get(shelf)
    takers = sorted(a.robot for a in timeline.plan.at_step(step)
                    if a.kind == "robot" and a.name == "pickup" and a.robot in timeline.instance.robots
                    and timeline.position(a.robot, step) == cell)
    winner = next((r for r, s in timeline.state(step).carries.items() if s == shelf), None)
    return f"robots {', '.join(map(str, takers))} pick up shelf {shelf} at once (robot {winner} gets it)", \
        {"robots": takers, "shelves": [shelf], "cells": [cell]}


def putdown_not_carrying(timeline, robot, step):
    return f"robot {robot} puts down, but it carries no shelf", {"robots": [robot]}


def _putdown(timeline: Timeline, robot: int, step: int, where: str):
    shelf = timeline.state(step - 1).carries.get(robot)
    cell = timeline.position(robot, step)
    return f"robot {robot} puts shelf {shelf} down {where.format(cell=_cell(cell))}", \
        {"robots": [robot], "shelves": [shelf], "cells": [cell]}


def putdown_off_floor(timeline, robot, step):
    return _putdown(timeline, robot, step, "at {cell}, which is not a floor node")


def putdown_on_highway(timeline, robot, step):
    return _putdown(timeline, robot, step, "on the highway node {cell}")


def putdown_on_station(timeline, robot, step):
    return _putdown(timeline, robot, step, "on the picking station at {cell}")


def putdown_onto_shelf(timeline, robot, step):
    cell = timeline.position(robot, step)
    resting = timeline.resting_on(cell, step - 1)
    text, highlight = _putdown(timeline, robot, step, "on {cell}, where shelf "
                               + ", ".join(map(str, resting)) + " already rests")
    highlight["shelves"] += resting
    return text, highlight


# deliveries

def _delivery(timeline: Timeline, robot: int, step: int) -> tuple[Any, Any, Any, int | None]:
    args = timeline.actions_of(robot, step)[0].args
    return args[0], args[1], (args[2] if len(args) > 2 else None), \
        timeline.state(step - 1).carries.get(robot)


def _delivers(timeline: Timeline, robot: int, step: int) -> str:
    order, product, units, _shelf = _delivery(timeline, robot, step)
    amount = f"{_units(units)} of " if units is not None and timeline.domain.counts_units else ""
    return f"robot {robot} delivers {amount}product {product} for order {order}"


def deliver_not_carrying(timeline, robot, step):
    return f"{_delivers(timeline, robot, step)}, but it carries no shelf", {"robots": [robot]}


def deliver_unknown_order(timeline, robot, step):
    order = _delivery(timeline, robot, step)[0]
    return f"{_delivers(timeline, robot, step)}, but there is no order {order}", {"robots": [robot]}


def deliver_wrong_station(timeline, robot, step):
    order = timeline.instance.orders[_delivery(timeline, robot, step)[0]]
    cell = timeline.position(robot, step)
    target = timeline.instance.stations.get(order.station)
    where = _station_words(timeline, order.station) if order.station is not None else "no picking station"
    return f"{_delivers(timeline, robot, step)} at {_cell(cell)}, but order {order.id} goes to {where}", \
        {"robots": [robot], "cells": [cell] + ([target.at] if target else [])}


def deliver_before_release(timeline, robot, step):
    order = timeline.instance.orders[_delivery(timeline, robot, step)[0]]
    return (f"{_delivers(timeline, robot, step)}, but order {order.id} is released at step {order.release}: "
            f"it is known after that step only"), {"robots": [robot]}


def deliver_not_on_shelf(timeline, robot, step):
    _order, product, _units, shelf = _delivery(timeline, robot, step)
    return f"{_delivers(timeline, robot, step)}, but its shelf {shelf} holds no product {product}", \
        {"robots": [robot], "shelves": [shelf]}


def deliver_order_amount(timeline, robot, step):
    order, product, _units, _shelf = _delivery(timeline, robot, step)
    missing = timeline.state(step - 1).open_lines.get((order, product), 0)
    needs = f"needs only {missing} more" if missing else "needs none"
    return f"{_delivers(timeline, robot, step)}, but the order {needs}", {"robots": [robot]}


def deliver_shelf_amount(timeline, robot, step):
    _order, product, _units, shelf = _delivery(timeline, robot, step)
    left = timeline.state(step - 1).stock.get((shelf, product), 0)
    holds = f"holds only {left}" if left else "has none left"
    return f"{_delivers(timeline, robot, step)}, but shelf {shelf} {holds}", \
        {"robots": [robot], "shelves": [shelf]}


def deliver_line_closed(timeline, robot, step):
    order, product, _units, _shelf = _delivery(timeline, robot, step)
    return f"{_delivers(timeline, robot, step)}, but order {order} has no open line for product " \
           f"{product}", {"robots": [robot]}


# the goal

def goal_unfilled_order(timeline, order, product, missing, _step):
    if timeline.domain.goal is Goal.SHELVES:
        release = timeline.instance.orders[order].release if order in timeline.instance.orders else None
        if release is not None:
            return f"order {order} is not fulfilled: no robot came under a shelf holding product {product} " \
                   f"after its release (step {release})", {}
        return f"order {order} is not fulfilled: no robot stands under a shelf holding product " \
               f"{product}", {}
    if timeline.domain.counts_units:
        return f"order {order} still lacks {_units(missing)} of product {product}", {}
    return f"order {order} still waits for product {product}", {}


def goal_missed_assigned_goal(timeline, robot, cell, _step):
    kind, goal = timeline.instance.assignment[robot]
    return f"robot {robot} does not end on its assigned goal, {kind} {goal} at {_cell(cell)}", \
        {"robots": [robot], "cells": [cell]}


def goal_unoccupied_destination(timeline, destination, _step):
    cell = timeline.instance.destinations[destination].at
    return f"no robot stands on destination {destination} at {_cell(cell)}", {"cells": [cell]}


#: (module, check) -> the function that says it in words
MESSAGES: dict[tuple[str, str], Describe] = {
    ("instance", "robotOffFloor"): instance_robot_off_floor,
    ("instance", "shelfOffFloor"): instance_shelf_off_floor,
    ("instance", "stationOffFloor"): instance_station_off_floor,
    ("instance", "destinationOffFloor"): instance_destination_off_floor,
    ("instance", "stationCollision"): instance_station_collision,
    ("instance", "destinationCollision"): instance_destination_collision,
    ("instance", "robotCollision"): instance_robot_collision,
    ("instance", "shelfCollision"): instance_shelf_collision,
    ("instance", "shelfOnHighway"): instance_shelf_on_highway,
    ("instance", "shelfOnStation"): instance_shelf_on_station,
    ("instance", "carriedShelfElsewhere"): instance_carried_shelf_elsewhere,
    ("instance", "sharedShelf"): instance_shared_shelf,
    ("instance", "orderStation"): instance_order_station,
    ("instance", "unknownStation"): instance_unknown_station,
    ("instance", "unknownProduct"): instance_unknown_product,
    ("action", "notRobot"): action_not_robot,
    ("action", "unknownRobot"): action_unknown_robot,
    ("action", "badStep"): action_bad_step,
    ("action", "unknownAction"): action_unknown_action,
    ("action", "badArguments"): action_bad_arguments,
    ("action", "concurrent"): action_concurrent,
    ("collision", "sameNode"): collision_same_node,
    ("collision", "swap"): collision_swap,
    ("move", "offFloor"): move_off_floor,
    ("move", "ontoShelf"): move_onto_shelf,
    ("pickup", "carrying"): pickup_carrying,
    ("pickup", "noShelf"): pickup_no_shelf,
    ("pickup", "sharedShelf"): pickup_shared_shelf,
    ("putdown", "notCarrying"): putdown_not_carrying,
    ("putdown", "offFloor"): putdown_off_floor,
    ("putdown", "onHighway"): putdown_on_highway,
    ("putdown", "onStation"): putdown_on_station,
    ("putdown", "ontoShelf"): putdown_onto_shelf,
    ("deliver", "notCarrying"): deliver_not_carrying,
    ("deliver", "unknownOrder"): deliver_unknown_order,
    ("deliver", "wrongStation"): deliver_wrong_station,
    ("deliver", "beforeRelease"): deliver_before_release,
    ("deliver", "notOnShelf"): deliver_not_on_shelf,
    ("deliver", "orderAmount"): deliver_order_amount,
    ("deliver", "shelfAmount"): deliver_shelf_amount,
    ("deliver", "lineClosed"): deliver_line_closed,
    ("goal", "unfilledOrder"): goal_unfilled_order,
    ("goal", "missedAssignedGoal"): goal_missed_assigned_goal,
    ("goal", "unoccupiedDestination"): goal_unoccupied_destination,
}
