"""Prioritized planning: route robots one after the other, each around those routed before.

Robots not routed yet stand still on their start cells, so the robots routed before them
go around them.  When a robot finds no route, planning starts over with that robot first
(and, after a few such restarts, in a shuffled order).  Both the first plan and the
repairs of the large-neighbourhood search (:mod:`.improve`) plan this way.
"""

from __future__ import annotations

import random
from collections.abc import Callable

from .reservations import Reservations, Track
from .room import depths
from .router import Router
from .work import Work


def route_in_turn(order: list[int], work: Work, router: Router, reservations: Reservations,
                  stopped: Callable[[], bool]) -> int | None:
    """Route the robots of ``order`` one after the other into ``reservations`` (they must be
    held there, not routed); the first robot that finds no route (then the robots routed
    so far stay in the table), or ``None``."""
    routed = set(reservations.tracks)
    for robot in order:
        if stopped():
            return robot
        start = reservations.instance.robots[robot].at
        found = router.route(robot, work.errand(robot, routed), start, avoid=work.parking())
        if found is None:
            return robot
        cells, done = found
        reservations.add(Track(robot, cells, done))
        routed.add(robot)
    return None


def first_tracks(work: Work, router: Router, reservations: Reservations, stopped: Callable[[], bool],
                 seed: int = 0) -> dict[int, Track] | None:
    """Tracks for every robot of the instance, or ``None`` when stopped first."""
    robots = sorted(reservations.instance.robots)
    idle = [r for r in robots if r not in set(work.workers())]
    movers = work.movers()
    depth = depths(reservations.instance)
    workers = sorted(work.workers(), key=lambda r: (depth[r] > 1, depth[r], -work.estimate(r), r))
    order = movers + workers
    shuffler = random.Random(seed)
    attempt = 0
    while not stopped():
        for robot in list(reservations.tracks):
            reservations.remove(robot)
        for robot in robots:
            reservations.hold(robot)
        for robot in idle:
            if robot not in movers:
                reservations.add(Track(robot, [reservations.instance.robots[robot].at]))
        failed = route_in_turn(order, work, router, reservations, stopped)
        if failed is None:
            return dict(reservations.tracks)
        attempt += 1
        order.remove(failed)
        order.insert(0, failed)
        if attempt % 4 == 0:
            shuffler.shuffle(order)
        order.sort(key=lambda r: depth[r])  # stable: a robot still leaves after those in front of it
    return None
