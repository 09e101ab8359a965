"""Tracks -> a plan (``occurs/3`` actions), and the two figures the search improves.

Domains B and C need one last look at the deliveries.  In C a delivery closes every open
line of its station that the shelf can serve, so a line planned for one shelf may already be
closed when its own shelf arrives.  In B a line is closed by its first delivery, whatever the
units: tracks planned under A's reading (a stronger one, see :mod:`.search`) may bring a
line's units from two shelves.  Going through the deliveries in time order, each one names a
line that is still open (the planned one if it is), and one with nothing left to close is
left out: the robot just waits on the station for that step.
"""

from __future__ import annotations

from asprilo.domain import Delivery, Domain
from asprilo.model import Action, Instance, Plan

from .reservations import Track


def plan_of(tracks: dict[int, Track], instance: Instance, domain: Domain) -> Plan:
    """The actions of all tracks."""
    actions = []
    for robot, track in tracks.items():
        cells = track.cells
        for step in range(1, len(cells)):
            (x0, y0), (x1, y1) = cells[step - 1], cells[step]
            if (x0, y0) != (x1, y1):
                actions.append(Action(step, robot, "move", (x1 - x0, y1 - y0)))
        for step, task in track.done.items():
            if task.name in ("pickup", "putdown"):
                actions.append(Action(step, robot, task.name, ()))
            elif task.name == "deliver":
                actions.append(Action(step, robot, "deliver", task.args))
    if domain.delivery in (Delivery.LINE, Delivery.STATION):
        actions = _named_deliveries(actions, tracks, instance, domain.delivery is Delivery.STATION)
    return Plan(actions)


def _named_deliveries(actions: list[Action], tracks: dict[int, Track], instance: Instance,
                      whole_station: bool) -> list[Action]:
    """The deliveries that close lines, in time order, each naming an open line (B: only
    the planned line closes; C, ``whole_station``: every open line of the station that the
    shelf holds a product of); those that close nothing are left out."""
    stock = instance.shelf_stock()
    open_lines = {(o.id, p) for o in instance.orders.values() for p in o.lines}
    result = [a for a in actions if a.name != "deliver"]
    for action in sorted((a for a in actions if a.name == "deliver"), key=lambda a: (a.step, a.robot)):
        task = tracks[action.robot].done[action.step]
        planned = tuple(task.args[:2])
        if whole_station:
            station = instance.orders[task.args[0]].station
            closable = sorted(line for line in open_lines if instance.orders[line[0]].station == station
                              and line[1] in stock.get(task.shelf, {}))
        else:
            closable = [planned] if planned in open_lines else []
        if not closable:
            continue
        named = planned if planned in closable else closable[0]
        result.append(Action(action.step, action.robot, "deliver", named))
        open_lines -= set(closable)
    return result


def makespan(tracks: dict[int, Track]) -> int:
    """The step of the last action of any robot."""
    return max((track.finish for track in tracks.values()), default=0)


def sum_of_costs(tracks: dict[int, Track]) -> int:
    """The steps of the robots' last actions, added up (as the checker's metrics count)."""
    return sum(track.finish for track in tracks.values())
