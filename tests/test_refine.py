"""The refinement of M/Md plans with goals of their own (asprilo/encodings/anytime/refine.py)
and its safe-interval search (spacetime.py): arrivals derived by hand on corridors, the same
earliest arrivals as a breadth-first search over every (vertex, step) on random small floors,
and refined plans that keep the rules and reach an optimum worked out by hand; the search for
the path that meets the fewest robots by a deadline (deadline.py) against counts by hand and a
search over every (vertex, step), and deadlines met where a hand derivation says they can be."""

from __future__ import annotations

import random

import numpy as np
import pytest

from asprilo.bounds import Floor
from asprilo.encodings.anytime.deadline import Crowd, Moves, Shortener, fewest_collisions
from asprilo.encodings.anytime.lacam import lacam_configs, paths_of
from asprilo.encodings.anytime.refine import Refiner
from asprilo.encodings.anytime.roadmap import Roadmap
from asprilo.encodings.anytime.spacetime import Occupancy, fastest_path


def _at(path: list[int], step: int) -> int:
    return path[min(step, len(path) - 1)]


def _random_roadmap(draw: random.Random, rows: int) -> Roadmap | None:
    """A floor of up to 5 columns and ``rows`` rows with a few cells missing (None: under 3 cells)."""
    cells = [(x, y) for x in range(1, draw.randint(2, 5) + 1) for y in range(1, draw.randint(2, rows) + 1)
             if draw.random() < 0.85]
    return Roadmap(Floor(cells)) if len(cells) >= 3 else None


def _occupied(roadmap: Roadmap, paths: list[list[int]]) -> Occupancy:
    occupancy = Occupancy(roadmap, 2)
    for robot, path in enumerate(paths):
        occupancy.add(robot, path)
    return occupancy


def _search(roadmap: Roadmap, cells: list[tuple[int, int]], others: list[list[tuple[int, int]]],
            start: tuple[int, int], goal: tuple[int, int], limit: int = 30, begin: int = 0
            ) -> list[tuple[int, int]] | None:
    occupancy = _occupied(roadmap, [[roadmap.vertex(cell) for cell in path] for path in others])
    goal_vertex = roadmap.vertex(goal)
    path = fastest_path(occupancy, roadmap.vertex(start), goal_vertex, roadmap.distances_to([goal_vertex])[0], limit,
                        begin)
    return None if path is None else [roadmap.cells[vertex] for vertex in path]


def test_a_robot_waits_for_another_to_pass_the_branch():
    # a corridor (1,1)-(2,1)-(3,1) with a pocket (2,2): the other robot walks (1,1) -> (3,1)
    # and parks there at step 2; from the pocket to (1,1) takes 2 steps, but (2,1) is taken
    # at step 1, so by hand: wait a step in the pocket, (2,1) at 2, (1,1) at 3
    roadmap = Roadmap(Floor([(1, 1), (2, 1), (3, 1), (2, 2)]))
    found = _search(roadmap, [], [[(1, 1), (2, 1), (3, 1)]], (2, 2), (1, 1))
    assert found == [(2, 2), (2, 2), (2, 1), (1, 1)]
    # from the pocket at step 2 (the tail of a path planned again): (2,1) is free from step 2
    # on, so by hand (2,1) at 3, (1,1) at 4; the path lists the steps from 2 on
    assert _search(roadmap, [], [[(1, 1), (2, 1), (3, 1)]], (2, 2), (1, 1), begin=2) == [(2, 2), (2, 1), (1, 1)]
    # nor may it start on a vertex taken at that step: (2,1) at step 1
    assert _search(roadmap, [], [[(1, 1), (2, 1), (3, 1)]], (2, 1), (1, 1), begin=1) is None


def test_a_robot_arrives_only_after_the_last_visit_to_its_goal():
    # a line (1,1)..(5,1): the other robot stands on (1,1), (2,1), (3,1), (4,1), (3,1), (2,1) at
    # steps 0..5 and parks on (2,1).  Ours, from (5,1), wants (3,1), busy at steps 2 and 4: by
    # hand it cannot stay there before step 5; at step 5 it can, coming from (4,1) (free at 4)
    # behind the other robot.  No arrival is at step 4 or before.
    roadmap = Roadmap(Floor([(x, 1) for x in range(1, 6)]))
    other = [(1, 1), (2, 1), (3, 1), (4, 1), (3, 1), (2, 1)]
    found = _search(roadmap, [], [other], (5, 1), (3, 1))
    assert found is not None and len(found) - 1 == 5 and found[-1] == (3, 1)
    assert _search(roadmap, [], [other], (5, 1), (3, 1), limit=4) is None


def test_no_path_swaps_with_a_robot_that_comes_to_park():
    # a line of 3: the other robot goes (1,1) -> (2,1) and parks; ours on (2,1) wants (1,1):
    # the only move is the swap, which the rules forbid, and then (2,1) is taken for good
    roadmap = Roadmap(Floor([(1, 1), (2, 1), (3, 1)]))
    assert _search(roadmap, [], [[(1, 1), (2, 1)]], (2, 1), (1, 1)) is None


def _brute(roadmap: Roadmap, others: list[list[int]], start: int, goal: int, limit: int) -> int | None:
    """The earliest step at which a robot from ``start`` can be on ``goal`` for good, by a
    breadth-first search over every (vertex, step) up to ``limit``."""
    last = max((len(path) for path in others), default=1) + limit
    reached = {start} if all(_at(path, 0) != start for path in others) else set()
    for step in range(limit + 1):
        if goal in reached and all(_at(path, later) != goal for path in others for later in range(step, last)):
            return step
        reached = {onto for vertex in reached for onto in (vertex, *roadmap.neighbours[vertex])
                   if all(_at(path, step + 1) != onto for path in others)
                   and not any(onto != vertex and _at(path, step) == onto and _at(path, step + 1) == vertex
                               for path in others)}
    return None


@pytest.mark.parametrize("seed", range(6))
def test_the_earliest_arrival_is_that_of_a_search_over_every_step(seed):
    draw, compared = random.Random(seed), 0
    for _ in range(40):
        roadmap = _random_roadmap(draw, 5)
        if roadmap is None:
            continue
        vertices = draw.sample(range(roadmap.size), roadmap.size)
        starts, others = vertices[:draw.randint(1, min(5, roadmap.size - 1))], []
        for start in starts[:-1]:  # the others, each planned around those before it
            goals = [v for v in range(roadmap.size) if v not in starts[len(others) + 1:] and
                     all(v != path[-1] for path in others)]
            goal = draw.choice(goals)
            path = fastest_path(_occupied(roadmap, others), start, goal, roadmap.distances_to([goal])[0], 20)
            if path is None:
                break
            others.append(path)
        else:
            goal = draw.choice([v for v in range(roadmap.size) if all(v != path[-1] for path in others)])
            to_goal = roadmap.distances_to([goal])[0]
            for limit in (4, 9, 20):
                path = fastest_path(_occupied(roadmap, others), starts[-1], goal, to_goal, limit)
                expected = _brute(roadmap, others, starts[-1], goal, limit)
                assert (None if path is None else len(path) - 1) == expected
                compared += expected is not None
                if path is not None:
                    _assert_keeps_the_rules(roadmap, [*others, path])
    assert compared >= 40  # most floors drawn give arrivals to compare


def _assert_keeps_the_rules(roadmap: Roadmap, paths: list[list[int]]) -> None:
    """Moves to neighbours, one robot per vertex at every step, no two robots swapping."""
    for path in paths:
        assert all(path[step] in (path[step - 1], *roadmap.neighbours[path[step - 1]]) for step in range(1, len(path)))
    for step in range(max(len(path) for path in paths) + 1):
        now = [_at(path, step) for path in paths]
        assert len(set(now)) == len(now)
        if step:
            before = [_at(path, step - 1) for path in paths]
            assert not any(now[a] == before[b] and now[b] == before[a] and a != b
                           for a in range(len(paths)) for b in range(len(paths)))


def test_refining_reaches_the_optimum_of_two_robots_passing_on_a_ring():
    # a 3x2 block; robot 0 goes (1,1) -> (3,1), robot 1 the other way.  By hand: both cannot
    # go straight (they would swap), so one goes round by row 2 (4 steps) while the other
    # goes straight (2 steps): sum of costs 6, makespan 4, and neither can do better.  The
    # plan given is valid but poor: robot 1 first waits, both go round.
    roadmap = Roadmap(Floor([(x, y) for x in (1, 2, 3) for y in (1, 2)]))
    v = roadmap.vertex
    paths = [[v((1, 1)), v((1, 2)), v((2, 2)), v((3, 2)), v((3, 1))],
             [v((3, 1)), v((3, 1)), v((2, 1)), v((2, 1)), v((2, 1)), v((2, 2)), v((1, 2)), v((1, 1))]]
    _assert_keeps_the_rules(roadmap, paths)
    refiner = Refiner(roadmap, [v((3, 1)), v((1, 1))], paths, seed=3)
    assert refiner.score() == (7, 11)
    for _ in range(50):
        refiner.step(lambda: False)
    assert refiner.score() == (4, 6)
    _assert_keeps_the_rules(roadmap, refiner.paths)
    assert [path[-1] for path in refiner.paths] == [v((3, 1)), v((1, 1))]


def test_refined_plans_keep_the_rules_and_only_get_better():
    draw = random.Random(7)
    cells = [(x, y) for x in range(1, 9) for y in range(1, 9) if (x, y) not in {(3, 3), (3, 4), (6, 5), (6, 6), (2, 7)}]
    roadmap = Roadmap(Floor(cells))
    starts = draw.sample(range(roadmap.size), 20)
    aims = draw.sample(range(roadmap.size), 20)
    configs = lacam_configs(roadmap, starts, aims, lambda: False, seed=1)
    refiner = Refiner(roadmap, aims, paths_of(configs), seed=2)
    scores = [refiner.score()]
    for _ in range(300):
        refiner.step(lambda: False)
        scores.append(refiner.score())
    assert scores == sorted(scores, reverse=True)
    _assert_keeps_the_rules(roadmap, refiner.paths)
    assert [path[0] for path in refiner.paths] == starts and [path[-1] for path in refiner.paths] == aims
    assert refiner.score()[1] == sum(len(path) - 1 for path in refiner.paths)


# --- shorter makespans with a deadline (deadline.py) -------------------------------------------

def _fewest(roadmap: Roadmap, others: list[list[int]], start: int, goal: int, deadline: int):
    crowd = Crowd(roadmap, Moves(roadmap), others, deadline)
    return fewest_collisions(crowd, start, goal, deadline, random.Random(0))


def _collisions(roadmap: Roadmap, others: list[list[int]], path: list[int], horizon: int) -> int:
    """A path's collisions with the others counted one by one up to ``horizon``: a robot on
    its vertex at a step, or one coming the other way over the edge it takes."""
    count = 0
    for step in range(horizon + 1):
        here = _at(path, step)
        count += sum(_at(other, step) == here for other in others)
        if step:
            there = _at(path, step - 1)
            count += sum(here != there and _at(other, step - 1) == here and _at(other, step) == there
                         for other in others)
    return count


def test_the_path_meeting_fewest_robots_passes_a_parked_one_by_hand():
    # a line (1,1)..(5,1) with a robot parked on (3,1) from the start: ours from (1,1) to
    # (5,1) must pass it (one collision) and arrives at step 4 at the earliest
    roadmap = Roadmap(Floor([(x, 1) for x in range(1, 6)]))
    v = roadmap.vertex
    path, collisions = _fewest(roadmap, [[v((3, 1))]], v((1, 1)), v((5, 1)), 6)
    assert [roadmap.cells[vertex] for vertex in path] == [(1, 1), (2, 1), (3, 1), (4, 1), (5, 1)]
    assert collisions == 1
    # by the deadline 3 the goal is too far
    assert _fewest(roadmap, [[v((3, 1))]], v((1, 1)), v((5, 1)), 3) is None


def test_passing_on_an_edge_counts_as_a_collision_by_hand():
    # two cells: the other robot goes (2,1) -> (1,1) at step 1 and parks; ours goes the other
    # way.  Moving at step 1 passes it on the edge (one collision); staying on (1,1) meets it
    # there at every step it stays, so by hand: one collision, arrival at step 1
    roadmap = Roadmap(Floor([(1, 1), (2, 1)]))
    v = roadmap.vertex
    path, collisions = _fewest(roadmap, [[v((2, 1)), v((1, 1))]], v((1, 1)), v((2, 1)), 3)
    assert [roadmap.cells[vertex] for vertex in path] == [(1, 1), (2, 1)] and collisions == 1


def _brute_fewest(roadmap: Roadmap, others: list[list[int]], start: int, goal: int, deadline: int
                  ) -> tuple[int, int] | None:
    """The fewest collisions of a path onto ``goal`` by ``deadline`` (staying there up to it)
    and the earliest arrival with that many, by a search over every (vertex, step)."""
    to_goal = roadmap.distances_to([goal])[0]
    fewest = {start: _collisions(roadmap, others, [start], 0)}
    found = []
    for step in range(deadline + 1):
        if goal in fewest:
            staying = sum(_at(other, later) == goal for other in others for later in range(step + 1, deadline + 1))
            found.append((fewest[goal] + staying, step))
        following: dict[int, int] = {}
        for vertex, count in fewest.items():
            for onto in (vertex, *roadmap.neighbours[vertex]):
                if step + 1 + to_goal[onto] > deadline:
                    continue
                meets = sum(_at(other, step + 1) == onto for other in others)
                meets += sum(onto != vertex and _at(other, step) == onto and _at(other, step + 1) == vertex
                             for other in others)
                following[onto] = min(following.get(onto, count + meets), count + meets)
        fewest = following
    return min(found) if found else None


@pytest.mark.parametrize("seed", range(4))
def test_the_fewest_collisions_are_those_of_a_search_over_every_step(seed):
    draw, compared = random.Random(seed), 0
    for _ in range(30):
        roadmap = _random_roadmap(draw, 4)
        if roadmap is None:
            continue
        deadline = draw.randint(2, 9)
        others = []  # random walks (they may meet each other: only ours is counted)
        for _ in range(draw.randint(1, 4)):
            walk = [draw.randrange(roadmap.size)]
            for _ in range(draw.randint(0, deadline)):
                walk.append(draw.choice([walk[-1], *roadmap.neighbours[walk[-1]]]))
            others.append(walk)
        start = draw.randrange(roadmap.size)
        goal = draw.choice([v for v in range(roadmap.size) if all(v != walk[-1] for walk in others)] or [start])
        found = _fewest(roadmap, others, start, goal, deadline)
        expected = _brute_fewest(roadmap, others, start, goal, deadline)
        assert (None if found is None else (found[1], len(found[0]) - 1)) == expected
        if found is not None:
            path = found[0]
            assert path[0] == start and path[-1] == goal and len(path) - 1 <= deadline
            assert all(path[k] in (path[k - 1], *roadmap.neighbours[path[k - 1]]) for k in range(1, len(path)))
            assert _collisions(roadmap, others, path, deadline) == found[1]
            compared += 1
    assert compared >= 20


def test_a_deadline_is_met_where_it_can_be_and_only_there_by_hand():
    # the 3x2 block of the ring test: robot 0 (1,1) -> (3,1), robot 1 the other way.  By hand
    # (see above) the makespan 4 is the least: with 3 steps both must cross (2,1), and the
    # one that crosses first meets the other on (3,1) or (1,1) or passes it on the edge
    roadmap = Roadmap(Floor([(x, y) for x in (1, 2, 3) for y in (1, 2)]))
    v = roadmap.vertex
    aims = [v((3, 1)), v((1, 1))]
    paths = [[v((1, 1)), v((1, 2)), v((2, 2)), v((3, 2)), v((3, 1))],
             [v((3, 1)), v((3, 1)), v((2, 1)), v((2, 1)), v((2, 1)), v((2, 2)), v((1, 2)), v((1, 1))]]
    shortener = Shortener(roadmap, aims, roadmap.distances_to(aims), seed=1)
    shorter = shortener.attempt(paths, 4, lambda: False)
    assert shorter is not None and max(len(path) - 1 for path in shorter) == 4
    _assert_keeps_the_rules(roadmap, shorter)
    assert [path[0] for path in shorter] == [v((1, 1)), v((3, 1))] and [path[-1] for path in shorter] == aims
    assert shortener.attempt(paths, 3, lambda: False) is None
    assert shortener.attempt(paths, 1, lambda: False) is None  # below a robot's distance


def test_shortened_plans_keep_the_rules_and_meet_their_deadlines():
    draw = random.Random(11)
    cells = [(x, y) for x in range(1, 9) for y in range(1, 9) if (x, y) not in {(3, 3), (3, 4), (6, 5), (6, 6), (2, 7)}]
    roadmap = Roadmap(Floor(cells))
    starts, aims = draw.sample(range(roadmap.size), 30), draw.sample(range(roadmap.size), 30)
    paths = paths_of(lacam_configs(roadmap, starts, aims, lambda: False, seed=1))
    shortener = Shortener(roadmap, aims, roadmap.distances_to(aims), seed=2)
    met = 0
    for _ in range(12):
        deadline = max(len(path) for path in paths) - 2
        shorter = shortener.attempt(paths, deadline, lambda: False)
        if shorter is None:
            continue
        met += 1
        assert max(len(path) - 1 for path in shorter) <= deadline
        _assert_keeps_the_rules(roadmap, shorter)
        assert [path[0] for path in shorter] == starts and [path[-1] for path in shorter] == aims
        paths = shorter
    assert met >= 3


def test_the_move_tables_grow_with_the_vertices_not_their_pairs():
    """A 100x100 floor: the rows of moves on its 10,000 vertices (a table of every pair of
    vertices would be 800 MB), and each neighbour's row in a vertex's column, by hand."""
    roadmap = Roadmap(Floor([(x, y) for x in range(1, 101) for y in range(1, 101)]))
    moves = Moves(roadmap)
    tables = sum(value.nbytes for value in vars(moves).values() if hasattr(value, "nbytes"))
    assert tables <= 10 * (moves.wide + 1) * roadmap.size * 8
    corner, right, below = (roadmap.vertex(cell) for cell in ((1, 1), (2, 1), (1, 2)))
    # the corner's neighbours in Roadmap's order (0,1), (1,0): below is row 1, right row 2
    found = moves.slots(np.array([below, right, corner]), np.array([corner, corner, corner]))
    assert found.tolist() == [1, 2, moves.wide]
