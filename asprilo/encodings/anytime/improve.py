"""Large-neighbourhood search: free a few robots (or the tail of their tracks), route them
again around all the others, and keep the result when the plan got better.

A plan is better when its makespan is shorter, or equal with a smaller sum of costs.
Neighbourhoods, chosen with weights that grow with their successes:

- ``alone``: a robot that finishes last, routed again on its own; it may now park near
  its last station, since every other track is known.
- ``crowd``: that robot and the robots that came near its track; it goes first.
- ``tail``: the same group, but only from a step some way before the robot finishes:
  the tracks up to that step stay, the rest is routed again (a window of steps).
- ``random``: a few robots drawn at random.
- ``swap``: a late robot and its nearest neighbours, whose work (goals, shelves, order
  lines) is assigned among them anew by the grounded assignment program first; half of the
  time one of the late robot's shelves (A/B/C) must go to another robot, so that the swap
  leaves the program's own optimum (an estimate) for another assignment.
- ``order``: a late robot with several shelves brings them in another order (A/B/C).
- ``clear``: a late robot with several shelves may put one down on a cell nearer its way
  once a robot that finishes early has carried that cell's shelf, which serves no order,
  away to a spare cell (A/B/C; :meth:`.work.Work.clear`).  Robots that clear go first.
- ``vacate``: a robot with several shelves (the late one if it is) may put one down on the
  cell of a shelf that never comes back there (the last shelf of another robot, or one put
  down elsewhere: :meth:`.work.Work.vacated`), drawn at random; the robot of that shelf goes
  first (it lifts the shelf before the cell is used) and parks elsewhere (A/B/C).
- ``hold``: robots without work lift the shelves serving no order that stand on a short way
  of a late robot's carry to its station, and park holding them off that way
  (:mod:`.asides`); they go first (A/B/C, only where some robot is without work at the
  start: elsewhere the search runs as it did without it).

Robots parked for good on a station the freed robots deliver at are freed as well (routed
after them): a changed errand may need that station later than before.

Restarts (A/B/C with few robots, some of which bring several shelves): once the search has
not bettered its best plan for :data:`STALL` neighbourhoods, it routes from scratch the next
of the best assignments of a relaxed schedule (:mod:`.relaxed`: walks, carries and the
queues at the stations, without collisions) and searches from that plan for as long; then
it goes back to its best plan (unless the new one became better), and so on in turn.  Only
a plan better than the best counts as an improvement.
"""

from __future__ import annotations

import random
from collections.abc import Callable

from asprilo.domain import Job
from asprilo.model import Cell

from .asides import hold_aside, idle_robots
from .prioritized import first_tracks
from .relaxed import Assignment, Schedules
from .reservations import Reservations, Track
from .router import Router
from .work import Work

KINDS = ("alone", "crowd", "tail", "random", "swap", "order", "clear", "vacate", "hold")
#: the most robots one neighbourhood frees: in M/Md many robots cross paths and give way to
#: each other, and larger groups find more (200 MovingAI agents, sum of costs after 60 s:
#: 1.31 times its bound with 8, 1.27-1.29 with 16, 1.28 with 24 or 32)
GROUP = {Job.TRIPS: 8, Job.GOALS: 16}
#: how many steps before a robot's finish a ``tail`` neighbourhood starts
TAIL = 30
#: how often a neighbourhood forms around a robot that finishes last rather than one that
#: lost many steps: in M/Md most of the sum of costs is lost by robots that finish early (on
#: 200 MovingAI agents, sum of costs after 30 s 6,143 instead of 6,297 at 0.7)
LAST_SHARE = {Job.TRIPS: 0.7, Job.GOALS: 0.3}
#: seconds a ``swap`` may spend re-assigning
SWAP_SECONDS = 0.5
#: whether a neighbourhood that gives a plan as good (same makespan and sum of costs) keeps it
PLATEAU = True
#: restarts from the relaxed schedule's assignments: the most robots (routing a whole plan
#: again must be cheap; the 46x15 paper instances have 12 to 46 robots), the neighbourhoods
#: without a better plan before one, and the seconds the relaxed schedule's search may take
RESTART_ROBOTS, STALL, RELAX_SECONDS = 12, 300, 2.0
#: how often every robot of a restart's first plan is routed again alone
POLISH = 2


def score(tracks: dict[int, Track]) -> tuple[int, int]:
    """(makespan, sum of costs) of the tracks."""
    finishes = [track.finish for track in tracks.values()]
    return max(finishes, default=0), sum(finishes)


class Improver:
    """Improves the tracks held in a reservation table, one neighbourhood at a time."""

    def __init__(self, work: Work, router: Router, reservations: Reservations, seed: int = 0):
        self.work, self.router, self.table = work, router, reservations
        self.random = random.Random(seed)
        self.weights = dict.fromkeys(KINDS, 1.0)
        self.last_share, self.group = LAST_SHARE[work.domain.work], GROUP[work.domain.work]
        if work.domain.work is Job.GOALS:  # a robot of M/Md has one goal and no place to park near it
            for kind in ("alone", "order", "clear", "vacate"):
                self.weights[kind] = 0.0
        if work.domain.work is Job.GOALS or not idle_robots(work):  # nobody to hold a shelf aside
            self.weights["hold"] = 0.0
        if not work.reassignable():
            self.weights["swap"] = 0.0
        #: whether a plan as good as the present one is kept (moves on plateaus)
        self.plateau = PLATEAU
        self.tried = dict.fromkeys(KINDS, 0)
        self.won = dict.fromkeys(KINDS, 0)
        self.seed = seed
        #: the best plan so far: its score, tracks and assignment
        self.best = (self.score(), dict(self.table.tracks), self.work.save())
        self.stall, self.exploring = 0, False
        #: the relaxed schedule's assignments not routed yet (None: not sought yet; no restarts
        #: where the work cannot be re-assigned or the robots are many)
        self.candidates: list[Assignment] | None = None
        self.restarts = (work.domain.work is Job.TRIPS and len(self.table.instance.robots) <= RESTART_ROBOTS
                         and any(len(trips) > 1 for trips in work.trips.values()))

    def score(self) -> tuple[int, int]:
        return score(self.table.tracks)

    def step(self, stopped: Callable[[], bool]) -> bool:
        """Try one neighbourhood (or a restart, see the module's text); whether the plan got
        better than the best so far."""
        if self.restarts and self.stall >= STALL:
            self._restart(stopped)
        else:
            self._neighbourhood_step(stopped)
        if self.score() < self.best[0]:
            self.best, self.stall = (self.score(), dict(self.table.tracks), self.work.save()), 0
            self.exploring = False  # the new plan is the best one now
            return True
        self.stall += 1
        return False

    def _restart(self, stopped: Callable[[], bool]) -> None:
        """Go back to the best plan after a search from another assignment; else route the next
        assignment of the relaxed schedule from scratch (none left: no more restarts)."""
        self.stall = 0
        if self.exploring:
            self.exploring = False
            self._back_to_best()
            return
        if self.candidates is None:
            self.candidates = Schedules(self.work, self.seed).search(RELAX_SECONDS, stopped)
        current = set(self.work.choice.atoms)
        while self.candidates:
            candidate = self.candidates.pop(0)
            self.work.adopt(candidate.choice(), candidate.by_robot())
            if set(self.work.choice.atoms) != current or self.work.trips != self.best[2][1]:
                break
        else:
            self.restarts = False
            self._back_to_best()
            return
        if first_tracks(self.work, self.router, self.table, stopped, self.seed) is None:
            self._back_to_best()
            return
        self.exploring = True
        # the first plan parks every last shelf back on its own cell, where it may close the way
        # of another robot's shelf: each robot is routed again alone, knowing the others' tracks
        # (it may now park near its station), the latest first, twice (on seed 4520 of
        # a_multiline.py: 43 -> 31 steps before any neighbourhood)
        for _ in range(POLISH):
            for robot in sorted(self.work.workers(), key=lambda robot: -self.table.tracks[robot].finish):
                if stopped():
                    return
                self._repair([robot], 0, False, stopped, self.work.save())

    def _back_to_best(self) -> None:
        """The best plan's tracks and assignment again."""
        _, tracks, saved = self.best
        self.table.reset(still=False)
        for track in tracks.values():
            self.table.add(track)
        self.work.restore(saved)

    def _neighbourhood_step(self, stopped: Callable[[], bool]) -> None:
        """One neighbourhood, kept when the plan got better or stayed as good."""
        kind = self.random.choices(KINDS, [self.weights[k] for k in KINDS])[0]
        late = self._late_robot()
        saved = self.work.save()  # before a neighbourhood that changes the work (order)
        group, start, reassign = self._neighbourhood(kind, late)
        self.tried[kind] += 1
        outcome = self._repair(group, start, reassign, stopped, saved) if group else None
        better = outcome == "better"
        if outcome is None:
            self.work.restore(saved)
        self.weights[kind] = min(10.0, self.weights[kind] * 1.5) if better else max(0.1, self.weights[kind] * 0.97)
        self.won[kind] += better

    # --- choosing a neighbourhood ---------------------------------------------------------------

    def _late_robot(self) -> int:
        """A robot that finishes last (while the makespan can still drop), else one of the
        robots that lose most steps against their estimate (:data:`LAST_SHARE`: how often)."""
        tracks = self.table.tracks
        workers = self.work.workers() or list(tracks)
        makespan = max(tracks[r].finish for r in workers)
        last = [r for r in workers if tracks[r].finish == makespan]
        if self.random.random() < self.last_share:
            return self.random.choice(last)
        delays = sorted(workers, key=lambda r: self.work.estimate(r) - tracks[r].finish)
        return self.random.choice(delays[:max(1, len(delays) // 5)])

    def _neighbourhood(self, kind: str, late: int) -> tuple[list[int], int, bool]:
        """The robots to free (the first goes first), the step from which they are routed
        again, and whether their work is re-assigned."""
        size = self.random.randint(2, self.group)
        if kind == "alone":
            return [late], 0, False
        if kind == "order":
            return ([late], 0, False) if self._reorder(late) else ([], 0, False)
        if kind == "clear":
            return self._clearing(late), 0, False
        if kind == "vacate":
            return self._vacating(late), 0, False
        if kind == "hold":  # the robots holding shelves aside go first
            helpers = hold_aside(self.work, late, self.random)
            return ([*helpers, late] if helpers else []), 0, False
        if kind in ("crowd", "tail"):
            group = [late, *self._met(late)[:size - 1]]
            if kind == "crowd":
                return group, 0, False
            return group, max(0, self.table.tracks[late].finish - self.random.randint(TAIL // 2, TAIL)), False
        if kind == "random":
            others = [r for r in self.work.workers() if r != late]
            return [late, *self.random.sample(others, min(len(others), size - 1))], 0, False
        return [late, *self._nearest(late)[:size - 1]], 0, True

    def _met(self, robot: int) -> list[int]:
        """Other robots that were within a step of ``robot``'s track, most often first."""
        track, met = self.table.tracks[robot], {}
        for step, (x, y) in enumerate(track.cells):
            for cell in ((x, y), (x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)):
                for near in (step - 1, step, step + 1):
                    other = self.table.visits.get(cell, {}).get(near)
                    if other is not None and other != robot:
                        met[other] = met.get(other, 0) + 1
                for other in self.table.stays.get(cell, {}):
                    if other != robot:
                        met[other] = met.get(other, 0) + 1
        ranked = sorted(met, key=lambda r: -met[r])
        return ranked

    def _clearing(self, late: int) -> list[int]:
        """A ``clear`` neighbourhood, the robots to route again (those that clear first):

        - half of the time, when robots clear cells, one of them (``late`` if it is one)
          stops, with the robots that put shelves down on its cells;
        - else ``late`` and its nearest neighbours, half of the time with their work assigned
          anew first (one of ``late``'s shelves going to another robot, no cells cleared),
          and among them a robot with several shelves gets a cell cleared by another.
        """
        work = self.work
        if work.clearings and self.random.random() < 0.5:
            clearer = late if late in work.clearings else self.random.choice(sorted(work.clearings))
            group = self._with_users([clearer])
            work.unclear(clearer)
            return group
        group = [late, *self._nearest(late)[:self.random.randint(1, self.group - 1)]]
        reassign = self.random.random() < 0.5
        if reassign:
            shelves = [trip.shelf for trip in work.trips.get(late, [])]
            if not shelves:
                return []
            group = self._with_users(group)
            for robot in [robot for robot in group if robot in work.clearings]:  # the new work starts uncleared
                work.unclear(robot)
            if not work.reassign(set(group), SWAP_SECONDS, self.random.choice(shelves)):
                return []
        several = [robot for robot in group if len(work.trips.get(robot, [])) >= 2]
        if not several:
            return []
        robot = late if late in several else self.random.choice(several)
        helpers = [r for r in group if r != robot and r in work.trips]
        helper = self.random.choice(helpers) if helpers else robot
        if helper == robot or not work.clear(robot, helper):
            return []
        return [helper, *(r for r in group if r != helper)] if reassign else [helper, robot]

    def _vacating(self, late: int) -> list[int]:
        """A ``vacate`` neighbourhood: the robot of the shelf whose cell is offered, then the
        robot with several shelves that may put one down there (none when there is no such
        robot or cell)."""
        work = self.work
        several = [robot for robot in work.workers() if len(work.trips.get(robot, [])) >= 2]
        if not several:
            return []
        robot = late if late in several else self.random.choice(several)
        cells = [cell for cell in work.vacated({trip.shelf for trip in work.trips[robot]}) if cell not in work.offered]
        if not cells:
            return []
        cell = self.random.choice(cells)
        work.offered = work.offered | {cell}
        owners = [other for other, trips in work.trips.items() if any(work.homes[t.shelf] == cell for t in trips)]
        return [*owners[:1], robot]

    def _with_users(self, group: list[int]) -> list[int]:
        """The ``group`` and, after it, the other robots that come on the cells its robots
        clear: their tracks count on the cleared shelf being gone by then."""
        table = self.table
        cells = {self.work.homes[shelf] for robot in group for shelf, _ in self.work.clearings.get(robot, [])}
        users = [robot for cell in sorted(cells)
                 for robot in (*table.visits.get(cell, {}).values(), *table.stays.get(cell, {}))]
        return [*group, *(robot for robot in dict.fromkeys(users) if robot not in group)]

    def _on_vacated(self, group: list[int], saved: tuple) -> list[int]:
        """The other robots that put a shelf down on the cell of a shelf that a robot of the
        ``group`` brought before the neighbourhood (``saved`` work) or brings now: their tracks
        count on that shelf being gone by then, which a changed errand may no longer make so
        (a swap left seed 4509 of a_multiline.py with a shelf put down on a resting one)."""
        work = self.work
        shelves = {trip.shelf for robot in group for trips in (saved[1].get(robot, []), work.trips.get(robot, []))
                   for trip in trips}
        cells = {work.homes[shelf] for shelf in shelves}
        return [robot for robot, trips in sorted(work.trips.items())
                if robot not in group and any(work.claims.get(trip.shelf) in cells for trip in trips)]

    def _parked_on_stations(self, group: list[int]) -> list[int]:
        """The other robots whose tracks end on a station that the ``group`` delivers at."""
        stations = {cell for robot in group for cell in self.work.stations_of(robot)}
        return [robot for robot, track in self.table.tracks.items()
                if robot not in group and track.cells[-1] in stations]

    def _reorder(self, robot: int) -> bool:
        """Let ``robot`` bring its shelves in another order (whether it has several)."""
        trips = self.work.trips.get(robot, [])
        if len(trips) < 2:
            return False
        order = trips[:]
        while order == trips:
            self.random.shuffle(order)
        self.work.trips = {**self.work.trips, robot: order}  # a new table: a restore brings the old one back
        return True

    def _shaken(self, late: int) -> int | None:
        """Half of the time, a shelf of the ``late`` robot that must go to another robot in a
        swap (A/B/C; ``None``: the program's optimum may keep it)."""
        shelves = [trip.shelf for trip in self.work.trips.get(late, [])]
        if not shelves or self.random.random() < 0.5:
            return None
        return self.random.choice(shelves)

    def _nearest(self, robot: int) -> list[int]:
        """The robots with work whose start cells are nearest to ``robot``'s."""
        x, y = self.table.instance.robots[robot].at
        others = [r for r in self.work.workers() if r != robot]
        return sorted(others, key=lambda r: abs(self.table.instance.robots[r].at[0] - x)
                      + abs(self.table.instance.robots[r].at[1] - y))

    # --- routing the neighbourhood again -----------------------------------------------------------

    def _repair(self, group: list[int], start: int, reassign: bool, stopped: Callable[[], bool],
                saved: tuple) -> str | None:
        """Route the ``group`` again: ``"better"``, ``"same"`` (a plan as good, kept: the search
        moves on a plateau), or ``None`` (worse or no route: the tracks and work as before)."""
        before = self.score()
        old = {robot: self.table.tracks[robot] for robot in group}
        if reassign and not self.work.reassign(set(group), SWAP_SECONDS, self._shaken(late=group[0])):
            return None
        group = self._with_users(group)
        group += [robot for robot in self._on_vacated(group, saved) if robot not in group]
        old.update({robot: self.table.tracks[robot] for robot in group if robot not in old})
        if start > 0:
            group = [r for r in group if old[r].finish > start]
        else:  # the robots parked for good on the group's stations go too (the group may need them later now)
            group += self._parked_on_stations(group)
            old.update({robot: self.table.tracks[robot] for robot in group if robot not in old})
        for robot in group:
            self.table.remove(robot)
            if start > 0:
                self.table.add(_prefix(old[robot], start))
        order = group[:1] + self.random.sample(group[1:], len(group) - 1)
        order.sort(key=lambda robot: robot not in self.work.clearings)  # a cell is cleared before it is used
        routed = set(self.table.instance.robots) - set(group)
        for robot in order:
            if stopped() or not self._route(robot, old[robot], start, routed):
                self._restore(old, saved)
                return None
            routed.add(robot)
        after = self.score()
        if after < before:
            return "better"
        if after == before and self.plateau:
            return "same"
        self._restore(old, saved)
        return None

    def _route(self, robot: int, old: Track, start: int, routed: set[int]) -> bool:
        tasks = self.work.errand(robot, routed, roomy=True, parked=self.table.parked_cells(robot))
        begin: Cell = self.table.instance.robots[robot].at
        if start > 0:
            tasks = tasks[sum(1 for step in old.done if step <= start):]
            begin = old.at(start)
        found = self.router.route(robot, tasks, begin, start, quick=True, avoid=self.work.parking())
        if found is None:
            return False
        cells, done = found
        if start > 0:
            cells = old.cells[:start] + cells
            done = {**{s: t for s, t in old.done.items() if s <= start}, **done}
            self.table.remove(robot)
        self.table.add(Track(robot, cells, done))
        return True

    def _restore(self, old: dict[int, Track], saved) -> None:
        for robot in old:
            if robot in self.table.tracks:
                self.table.remove(robot)
        for track in old.values():
            self.table.add(track)
        self.work.restore(saved)


def _prefix(track: Track, step: int) -> Track:
    """The track up to ``step``, the robot staying there afterwards."""
    return Track(track.robot, track.cells[:step + 1], {s: t for s, t in track.done.items() if s <= step})
