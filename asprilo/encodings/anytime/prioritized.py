"""Prioritized planning: route robots one after the other, each around those routed before.

Robots not routed yet stand still on their start cells, so the robots routed before them
go around them.  A robot that finds no route takes the routed robots in its way out again
(they are routed once more right after it), and robots without work standing on its way
are sent to park off it first.  When that does not help, planning starts over
with that robot first (and robots not routed yet in the way only at step 0: they have to
get out of the way when their turn comes), after a few restarts in a shuffled order.  Both the first plan and the
repairs of the large-neighbourhood search (:mod:`.improve`) plan this way.
"""

from __future__ import annotations

import random
from collections import Counter, deque
from collections.abc import Callable

from .reservations import Reservations, Track
from .room import depths
from .router import Router
from .work import Work

#: how often one robot may bump others before planning starts over, and how many at once
BUMPS, BUMPED = 3, 6
#: the routes an attempt at a first plan may try per robot before planning starts over in
#: another order (bumping can go on for long where the floor is crowded, and another order
#: often gets through at once: 46 robots on 46x15 took 170 routes in the first order, 46 in
#: the third)
TRIES_PER_ROBOT = 2


def route_in_turn(order: list[int], work: Work, router: Router, reservations: Reservations,
                  stopped: Callable[[], bool]) -> int | None:
    """Route the robots of ``order`` one after the other into ``reservations`` (they must be
    held there, not routed).  A robot that finds no route bumps the routed robots in its
    way: they are taken out, it is routed, then they are routed again.  Returns the robot that
    failed once too often (or was being routed when ``stopped``, or when the robots had had
    :data:`TRIES_PER_ROBOT` routes each), else ``None``."""
    queue = deque(order)
    bumps: Counter[int] = Counter()
    tries = 0
    while queue:
        robot = queue.popleft()
        tries += 1
        if stopped() or tries > TRIES_PER_ROBOT * len(order) + 1:
            return robot
        start = reservations.instance.robots[robot].at
        errand = work.errand(robot, set(reservations.tracks), parked=reservations.parked_cells(robot))
        found = router.route(robot, errand, start, avoid=work.parking())
        if found is not None:
            reservations.add(Track(robot, *found))
            continue
        bumps[robot] += 1
        tasks = work.errand(robot, set())
        in_the_way = [r for r in router.in_the_way(robot, tasks, start) if r in reservations.tracks]
        blockers = [r for r in in_the_way if reservations.tracks[r].parked > 0][:BUMPED]
        standing = work.make_room([r for r in in_the_way if reservations.tracks[r].parked == 0][:BUMPED],
                                  router.way(robot, tasks, start))
        if bumps[robot] > BUMPS or not blockers + standing:
            return robot
        for other in blockers + standing:
            reservations.remove(other)
        # robots without work standing in the way make room first, then it goes, then the bumped
        queue.extendleft(reversed([*standing, robot, *blockers]))
    return None


def first_tracks(work: Work, router: Router, reservations: Reservations, stopped: Callable[[], bool],
                 seed: int = 0) -> dict[int, Track] | None:
    """Tracks for every robot of the instance, or ``None`` when stopped first.

    Robots with work go longest errand first (they decide the makespan); the third attempt
    tries shortest first (robots crowding at a station then come and go in turn)."""
    robots = sorted(reservations.instance.robots)
    depth = depths(reservations.instance)
    on_the_way = {r for r in robots if reservations.instance.robots[r].at in work.needed_cells()}

    def ordered(longest_first: bool) -> list[int]:
        # shallow robots first, and of those first the ones standing where others must go;
        # robots making room go before the workers as deep (a deeper one cannot leave before
        # those in front of it: on 200x200, movers in the second of three rows waited for the
        # workers in the first)
        sign = -1 if longest_first else 1
        workers = sorted(work.workers(), key=lambda r: (depth[r] > 1, r not in on_the_way, depth[r],
                                                        sign * work.estimate(r), r))
        return sorted(work.movers() + workers, key=lambda r: depth[r])

    order = ordered(True)
    shuffler = random.Random(seed)
    attempt, waiting = 0, set()
    while not stopped():
        reservations.reset(still=attempt == 0)  # after a failure, robots not routed yet may be passed
        for robot in robots:
            reservations.hold(robot)
        for robot in set(robots) - set(work.workers()) - set(work.movers()):  # idle: they stay where they are
            reservations.add(Track(robot, [reservations.instance.robots[robot].at]))
        failed = route_in_turn(order, work, router, reservations, stopped)
        if failed is None:
            return dict(reservations.tracks)
        attempt += 1
        order = [robot for robot in work.movers() if robot not in order] + order  # movers made on the way
        if attempt == 2:
            order = ordered(False)
            continue
        # it goes first now; or last, if it failed first already (it waits for the others:
        # a shelf it cannot carry past, say, is moved by another robot)
        if order[0] == failed:
            waiting.add(failed)
        order.remove(failed)
        order.insert(len(order) if failed in waiting else 0, failed)
        if attempt % 4 == 0:
            shuffler.shuffle(order)
        # stable: a robot still leaves after those in front of it
        order.sort(key=lambda r: (r in waiting, depth[r]))
    return None
