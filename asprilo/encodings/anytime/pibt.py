"""One step of all robots at once: priority inheritance with backtracking (PIBT, Okumura et
al., 2019) with the swap move of LaCAM* (Okumura, 2024), written here from the papers'
descriptions; :mod:`.lacam` searches with it.

Robots are numbered ``0 .. n-1`` and cells are vertices of a :class:`~.roadmap.Roadmap`; a
configuration is the list of the robots' vertices.  In a step every robot picks its next
vertex in the order of its priority, nearest to its goal first (equally near ones in a random
order, drawn anew each time: fixed ties let two robots push each other back and forth for
ever).  A robot that wants a vertex where another robot stands pushes that robot, which then
picks at once and may not come to the pusher's vertex (no swaps); a robot that finds no
vertex stays, and its pusher tries its next choice.  Some robots may have their next vertex
fixed beforehand (LaCAM's constraints).

Plain PIBT cannot let two robots pass each other in a corridor: each pushes the other back.
The swap move sees this coming: pushing on along the corridor ahead meets no room to pass
before the robots' ways part, while the corridor behind leads to room.  Then the robot backs
away from its goal and pulls the other after it, until both reach a branch where they can
pass.  It also sees the case the other way round: a robot right behind this one will have
to pass it in the corridor ahead, so this one backs away first, pulling that one along.
"""

from __future__ import annotations

import random
from collections.abc import Sequence

from .roadmap import FAR, Roadmap

#: no robot, no vertex
NONE = -1


class Pibt:
    """Steps on one roadmap towards fixed aims (robot number -> vertex); ``swap``: with the
    swap move."""

    def __init__(self, roadmap: Roadmap, aims: list[int], seed: int = 0, swap: bool = True):
        self.roadmap, self.aims, self.swap = roadmap, aims, swap
        self.to = roadmap.distances_to(aims)  # robot -> its distance table
        self.random = random.Random(seed)
        self.neighbours = roadmap.neighbours
        self._now = [NONE] * roadmap.size    # vertex -> the robot on it (during a step)
        self._taken = [NONE] * roadmap.size  # vertex -> the robot going there next
        self._after: list[int] = []          # robot -> its next vertex (NONE: undecided)
        self._at: list[int] = []

    def reachable(self, starts: list[int]) -> bool:
        """Whether every robot can reach its aim at all."""
        return all(self.to[robot][start] < FAR for robot, start in enumerate(starts))

    def step(self, at: list[int], order: list[int], fixed: Sequence[tuple[int, int]] = ()) -> list[int] | None:
        """Where every robot is after one step from ``at``: the robots of ``fixed``
        (robot, vertex) go where it says, the others pick in the order of ``order``;
        ``None`` when the fixed moves leave no valid step."""
        now, taken = self._now, self._taken
        after = [NONE] * len(at)
        self._after, self._at = after, at
        for robot, vertex in enumerate(at):
            now[vertex] = robot
        try:
            if not self._fix(fixed):
                return None
            aims = self.aims
            for robot in order:
                if after[robot] != NONE:
                    continue
                here = at[robot]
                if here == aims[robot] and taken[here] == NONE:
                    after[robot], taken[here] = here, robot  # at its goal, nobody pushing: it stays
                elif not self._pick(robot):
                    return None  # a robot could not even stay (a fixed move took its vertex)
            return after
        finally:
            for vertex in at:
                now[vertex] = NONE
            for vertex in after:
                if vertex != NONE:
                    taken[vertex] = NONE

    def _fix(self, fixed: Sequence[tuple[int, int]]) -> bool:
        """Send the robots of ``fixed`` where it says; whether no two of them come onto one
        vertex or swap theirs."""
        now, taken, after, at = self._now, self._taken, self._after, self._at
        for robot, vertex in fixed:
            other = now[vertex]
            if taken[vertex] != NONE or (other != NONE and after[other] == at[robot]):
                return False
            after[robot], taken[vertex] = vertex, robot
        return True

    def _pick(self, robot: int) -> bool:
        """Choose ``robot``'s next vertex, pushing the robot there; whether it could move
        (or stay, when staying was its choice)."""
        now, taken, after, at = self._now, self._taken, self._after, self._at
        here = at[robot]
        to = self.to[robot]
        draw = self.random.random
        options = [here, *self.neighbours[here]]
        ranked = [vertex for _, vertex in sorted([(to[vertex] + draw(), vertex) for vertex in options])]
        partner = self._swap_partner(robot, ranked[0]) if self.swap and ranked[0] != here else NONE
        if partner != NONE:
            ranked.reverse()  # back away from the goal first
        for vertex in ranked:
            if taken[vertex] != NONE:
                continue
            other = now[vertex]
            if other != NONE and after[other] == here:
                continue  # the robot there comes here: a swap
            after[robot], taken[vertex] = vertex, robot
            if other != NONE and other != robot and after[other] == NONE and not self._pick(other):
                continue  # it could not get out of the way (it keeps its vertex)
            if vertex == ranked[0] and partner != NONE and after[partner] == NONE and taken[here] == NONE:
                after[partner], taken[here] = here, partner  # pulled into the vertex left
            return True
        after[robot], taken[here] = here, robot
        return False

    # --- the swap move -----------------------------------------------------------------------

    def _swap_partner(self, robot: int, wanted: int) -> int:
        """The robot to pull after ``robot`` as it backs away (``NONE``: no swap): the one on
        the vertex it wants, when the two must pass each other; or one right behind it that
        must pass it on the corridor ahead; in either case only where there is room behind."""
        now, after, here = self._now, self._after, self._at[robot]
        ahead = now[wanted]
        if (ahead != NONE and after[ahead] == NONE and self._must_pass(robot, ahead, here, wanted)
                and self._room(wanted, here)):
            return ahead
        for vertex in self.neighbours[here]:
            behind = now[vertex]
            if (behind != NONE and vertex != wanted and after[behind] == NONE
                    and self._must_pass(behind, robot, here, wanted) and self._room(wanted, here)):
                return behind
        return NONE

    def _must_pass(self, pusher: int, puller: int, pusher_at: int, puller_at: int) -> bool:
        """Whether ``pusher`` (on ``pusher_at``, going towards ``puller`` on ``puller_at``)
        and ``puller`` must pass each other: pushing on along the corridor ahead brings
        ``pusher`` nearer its aim without meeting room to pass, and there ``puller``'s way
        leads back past ``pusher``."""
        to_pusher, to_puller = self.to[pusher], self.to[puller]
        behind, ahead = pusher_at, puller_at
        while to_pusher[ahead] < to_pusher[behind]:
            ways, onward = self._onward(ahead, behind)
            if ways >= 2:
                return False  # room to pass on the way
            if ways == 0:
                break
            behind, ahead = ahead, onward
        return (to_puller[behind] < to_puller[ahead]
                and (to_pusher[behind] == 0 or to_pusher[ahead] < to_pusher[behind]))

    def _room(self, behind: int, ahead: int) -> bool:
        """Whether the corridor from ``behind`` through ``ahead`` (away from ``behind``) leads
        to a vertex with room to pass (two ways on) before a dead end or a loop back."""
        start = behind
        for _ in range(self.roadmap.size):
            if ahead == start:
                return False
            ways, onward = self._onward(ahead, behind)
            if ways >= 2:
                return True
            if ways == 0:
                return False
            behind, ahead = ahead, onward
        return False

    def _onward(self, vertex: int, came_from: int) -> tuple[int, int]:
        """How many ways lead on from ``vertex`` other than back to ``came_from``, and one of
        them, leaving out dead ends where a robot already stands on its aim (it need not
        move)."""
        now, aims, neighbours = self._now, self.aims, self.neighbours
        ways, onward = 0, NONE
        for next_vertex in neighbours[vertex]:
            if next_vertex == came_from:
                continue
            resting = now[next_vertex]
            if resting != NONE and len(neighbours[next_vertex]) == 1 and aims[resting] == next_vertex:
                continue
            ways, onward = ways + 1, next_vertex
        return ways, onward
