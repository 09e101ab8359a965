"""Shortest paths and assignment bounds, on hand-checked cases and the MovingAI figures."""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import EXAMPLES

from asprilo.bounds import INFINITE, Floor, bottleneck_assignment, makespan_bound, mapf_bounds, min_cost_assignment
from asprilo.bounds.delivery import Deliveries
from asprilo.bounds.trip import _gaps, _shelf_gaps
from asprilo.domain import Domain
from asprilo.model import Instance, Robot
from asprilo.reader import read_instance
from asprilo.sources import Source


def test_distances_around_a_wall():
    # 3x3 floor without its centre: going from (1,2) to (3,2) takes 4 steps
    floor = Floor({(x, y) for x in range(1, 4) for y in range(1, 4)} - {(2, 2)})
    assert floor.distances([(1, 2)], [(3, 2), (1, 2), (2, 2)]).tolist() == [[4, 0, math.inf]]


def test_assignments():
    costs = np.array([[1, 5, 9], [2, 3, 8]], dtype=float)
    assert bottleneck_assignment(costs) == 3  # goal 0 <- robot 0 (1), goal 1 <- robot 1 (3)
    assert min_cost_assignment(costs) == 4
    assert bottleneck_assignment(np.array([[math.inf, math.inf]])) == math.inf
    assert min_cost_assignment(np.zeros((2, 1))) == math.inf


def test_m_bounds_of_a_paper_instance():
    instance = read_instance(EXAMPLES / "paper-m/1x2x4/x11_y6_n66_r2_s16_ps1_pr16_u16_o2_N001.lp")
    # robots at (1,6) and (2,6); ordered shelves at (5,3) and (3,3) on a full grid:
    # (1,6)->(3,3) = 5 and (2,6)->(5,3) = 6 beats (1,6)->(5,3) = 7 and (2,6)->(3,3) = 4
    assert mapf_bounds(instance) == (6.0, 11.0)


def test_md_bounds_count_each_destination_once():
    instance = read_instance(EXAMPLES / "encodings-repo/x3_y3_n9_r1_s1_ps1_pr1_u1_o1_N1.lp")
    instance.orders.clear()
    instance.robots = {1: Robot(1, (1, 1)), 2: Robot(2, (3, 3))}
    from asprilo.model import Destination
    instance.destinations = {1: Destination(1, (2, 1)), 2: Destination(2, (3, 2))}
    assert mapf_bounds(instance) == (1.0, 2.0)


# --- A, B, C: releases, blocked carrying, station sequencing, the scheduling relaxation ------

def _row_world(width: int, height: int, robots: dict, shelves: dict, station: tuple, lines: dict,
               units: int = 1, demand: int = 1, carries: dict | None = None) -> Instance:
    """A full grid; ``shelves`` id -> cell, product k on shelf k; ``lines`` order -> product."""
    facts = [f"init(object(grid,1),value(xsize,{width})). init(object(grid,1),value(ysize,{height}))."]
    facts += [f"init(object(robot,{r}),value(at,{cell}))." for r, cell in robots.items()]
    facts += [f"init(object(robot,{r}),value(carries,{s}))." for r, s in (carries or {}).items()]
    facts += [f"init(object(shelf,{s}),value(at,{cell})). init(object(product,{s}),value(on,({s},{units})))."
              for s, cell in shelves.items()]
    facts.append(f"init(object(pickingStation,1),value(at,{station})).")
    facts += [f"init(object(order,{o}),value(line,({p},{demand}))). init(object(order,{o}),value(pickingStation,1))."
              for o, p in lines.items()]
    return read_instance(Source("<world>", "\n".join(facts)))


def test_a_line_is_released_after_reaching_lifting_and_carrying_its_shelf():
    # R.S.P: 2 moves to the shelf, a pickup, 2 moves to the station, the delivery
    instance = _row_world(5, 1, {1: (1, 1)}, {1: (3, 1)}, (5, 1), {1: 1})
    assert [makespan_bound(instance, d) for d in (Domain.A, Domain.B, Domain.C)] == [6, 6, 6]
    # a robot that starts carrying the shelf needs neither the walk nor the pickup
    carried = _row_world(5, 1, {1: (3, 1)}, {1: (3, 1)}, (5, 1), {1: 1}, carries={1: 1})
    assert makespan_bound(carried, Domain.B) == 3


def test_a_carried_shelf_waits_until_the_shelf_in_its_way_can_be_gone():
    # R.SSP: shelf 2 on (4,1) blocks the way; the robot reaches it at 3 at the earliest, lifts
    # it at 4, and the cell is free at 5: shelf 1 (lifted at 3) is on (4,1) at 5 and on the
    # station at 6, delivered at 7 (one more than on an empty floor)
    instance = _row_world(5, 1, {1: (1, 1)}, {1: (3, 1), 2: (4, 1)}, (5, 1), {1: 1})
    assert makespan_bound(instance, Domain.B) == 7


def test_one_station_and_one_near_robot_serve_two_lines_in_turn():
    # 8x2 floor, station (1,1), shelves (3,1) and (4,1), robot 1 at (4,2), robot 2 far at (8,2).
    # Releases: shelf 1 at 6 (robot 1: 2 moves, pickup, 2 moves, deliver), shelf 2 at 7 (its way
    # west waits for shelf 1 to be lifted, at 3, gone at 4).  One station: 6, then 8 at best.
    # But both are robot 1's: its second delivery needs a whole cycle (>= 7 steps), and robot 2
    # delivers at 10 at the earliest (5 moves, pickup, 3 moves, deliver): the bound is 10.
    instance = _row_world(8, 2, {1: (4, 2), 2: (8, 2)}, {1: (3, 1), 2: (4, 1)}, (1, 1), {1: 1, 2: 2})
    assert makespan_bound(instance, Domain.B) == 10
    # the same with robot 2 next to robot 1: robot 1 at 6, robot 2 at 8 (station bound)
    close = _row_world(8, 2, {1: (4, 2), 2: (5, 2)}, {1: (3, 1), 2: (4, 1)}, (1, 1), {1: 1, 2: 2})
    assert makespan_bound(close, Domain.B) == 8


def test_a_line_that_needs_two_shelves_needs_two_visits():
    # A: the line asks for 2 units, each shelf holds 1: two deliveries from two shelves, so the
    # second comes two steps after the first at the earliest
    facts = """
        init(object(grid,1),value(xsize,5)). init(object(grid,1),value(ysize,2)).
        init(object(robot,1),value(at,(1,2))). init(object(robot,2),value(at,(2,2))).
        init(object(shelf,1),value(at,(3,1))). init(object(shelf,2),value(at,(3,2))).
        init(object(product,1),value(on,(1,1))). init(object(product,1),value(on,(2,1))).
        init(object(pickingStation,1),value(at,(5,1))).
        init(object(order,1),value(line,(1,2))). init(object(order,1),value(pickingStation,1)).
    """
    instance = read_instance(Source("<world>", facts))
    # shelf 1: robot 1 walks (1,2)->(3,1) in 3, lifts at 4, carries 2 moves: station at 6,
    # delivers at 7; shelf 2 likewise (robot 2, 1 move + lift = 2; (3,2)->(5,1) 3 moves) at 6.
    # Two visits: 6 + 1 delivery + 1 change of shelf = 8 in A; B needs one delivery: 6
    assert makespan_bound(instance, Domain.A) == 8
    assert makespan_bound(instance, Domain.B) == 6


def test_a_product_ordered_beyond_its_stock_has_no_plan_in_a_only():
    # two orders want product 1, one unit each, and the one shelf holds one unit
    short = _row_world(5, 1, {1: (1, 1)}, {1: (3, 1)}, (5, 1), {1: 1, 2: 1})
    assert makespan_bound(short, Domain.A) == math.inf
    assert makespan_bound(short, Domain.B) < math.inf


def test_no_line_or_an_unreachable_line():
    assert makespan_bound(_row_world(5, 1, {1: (1, 1)}, {1: (3, 1)}, (5, 1), {}), Domain.B) == 0
    missing = _row_world(5, 1, {1: (1, 1)}, {1: (3, 1)}, (5, 1), {1: 7})
    assert makespan_bound(missing, Domain.B) == math.inf


def test_the_trip_steps_follow_the_cells_a_robot_must_use():
    # 3x3: highways in rows 1 and 2 except the station P (2,1); storage row 3 with shelf 1 on
    # (2,3) and shelf 2 on (1,3), both holding the ordered product.  P's neighbours are all
    # highway, so a shelf goes down two cells from P at the nearest, on (2,3).
    facts = """
        init(object(grid,1),value(xsize,3)). init(object(grid,1),value(ysize,3)).
        init(object(highway,1),value(at,(1,1))). init(object(highway,2),value(at,(3,1))).
        init(object(highway,3),value(at,(1,2))). init(object(highway,4),value(at,(2,2))).
        init(object(highway,5),value(at,(3,2))). init(object(pickingStation,1),value(at,(2,1))).
        init(object(robot,1),value(at,(3,3))).
        init(object(shelf,1),value(at,(2,3))). init(object(shelf,2),value(at,(1,3))).
        init(object(product,1),value(on,(1,1))). init(object(product,1),value(on,(2,1))).
        init(object(order,1),value(line,(1,1))). init(object(order,1),value(pickingStation,1)).
    """
    instance = read_instance(Source("<world>", facts))
    station = (2, 1)
    gaps = _gaps(Deliveries(instance, Domain.B, Floor(instance.cells)), [station], [1, 2])
    # deliver, 2 moves to (2,3), put down, 1 move to (1,3), lift, 3 moves back, deliver: 9
    # (with the next shelf on (2,3) itself: 2 moves off and back, lift, 2 moves: 9 as well)
    assert gaps["gap_any", station, station] == 9
    # the same shelf to another robot: put down on (2,3), the first robot moves off as the
    # second moves on, lift, 2 moves, deliver: 8
    assert gaps["gap_hand", station, station] == 8
    # after a delivery, lift shelf 1 where it stands: never put down on its own cell, so on
    # (1,3) or (3,3): 3 moves, put down, 1 move, lift: 6; shelf 2: via (2,3): 2 + 1 + 1 + 1 = 5
    assert (gaps["fetch", station, 1], gaps["fetch", station, 2]) == (6, 5)
    # ...then carry it and deliver: shelf 1: 4 + 2 moves + 3 = 9; shelf 2: 3 + 3 moves + 3 = 9
    assert (gaps["gap_fresh", station, 1, station], gaps["gap_fresh", station, 2, station]) == (9, 9)
    # shelf 1 lifted where it stands, 1 move to (1,3), put down; the next shelf on (2,3) at
    # best: 1 move, lift, 2 moves, deliver: 7.  Shelf 2: 1 move to (2,3), put down; the next
    # shelf 1 move off and 3 from P (or on (2,3): 2 moves off and back, then 2): 8
    assert (gaps["aside", 1, station], gaps["aside", 2, station]) == (7, 8)
    # the way of a shelf through another storage cell: (2,3)->(1,3)->P 4, (1,3)->(2,3)->P 3
    assert (gaps["detour", 1, station], gaps["detour", 2, station]) == (4, 3)
    # lift one, put it down on the third cell (3,3) or through it, walk to the other, lift: 5
    assert _shelf_gaps(Deliveries(instance, Domain.B, Floor(instance.cells)), [1, 2]) == \
        ["between(1,2,5).", "between(2,1,5)."]
    # a robot that starts under shelf 1 carrying it may set it down right there and lift it
    # again: its detour is the plain way, 2
    carried = read_instance(Source("<world>", facts.replace("value(at,(3,3))", "value(at,(2,3))")
                                   + "init(object(robot,1),value(carries,1))."))
    gaps = _gaps(Deliveries(carried, Domain.B, Floor(carried.cells)), [station], [1, 2])
    assert (gaps["detour", 1, station], gaps["detour", 2, station]) == (2, 3)


CORRIDOR = """
    init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))).
    init(object(node,3),value(at,(3,1))). init(object(node,4),value(at,(4,1))).
    init(object(node,5),value(at,(2,2))). init(object(pickingStation,1),value(at,(1,1))).
    init(object(robot,1),value(at,(4,1))).
    init(object(shelf,1),value(at,(3,1))). init(object(shelf,2),value(at,(2,1))).
    init(object(product,1),value(on,(1,2))). init(object(product,2),value(on,(2,1))).
    init(object(order,1),value(line,(1,1))). init(object(order,1),value(pickingStation,1)).
    init(object(order,2),value(line,(1,1))). init(object(order,2),value(pickingStation,1)).
"""


def test_a_shelf_behind_another_waits_for_its_lift():
    """A corridor (1,1)..(4,1) with a pocket (2,2); station P on (1,1), the robot on (4,1),
    shelf 1 (two units of the product both orders ask for) on (3,1) behind shelf 2 (nothing
    ordered) on (2,1).  By hand, the minimum is 12: walk 2, lift shelf 2, into the pocket,
    put it down, walk 2, lift shelf 1, carry 2, deliver twice.  ``asprilo solve --method asp``
    refutes horizons 9, 10 and 11.  Without the lift, shelf 1 enters (2,1) one step after the
    nearest robot could lift shelf 2 (step 3): there at 4, on P at 5, delivers at 6 and 7: 7.
    With it (trip.lp's lift/3): shelf 1 has no way around (clear/3), so shelf 2 is lifted
    at step 3 at the earliest (walk 2, lift), and the robot that then lifts shelf 1 needs
    lift_gap(2,1) = 3 more steps (shelf 2 may be put back on its own cell, 0 moves, put down,
    1 move, lift; floor distances only), lifts shelf 1 at 6 at the earliest, carries it 2,
    delivers at 9 and 10: the bound is 10, between the old 7 and the minimum 12."""
    from asprilo.bounds.trip import blocker_facts
    instance = read_instance(Source("<corridor>", CORRIDOR))
    facts = Deliveries(instance, Domain.A, Floor(instance.cells))
    assert "clear(1,0,1000000)." in blocker_facts(facts, [1], [(1, 1)])  # no way around
    assert {"passage(1,0,0,2).", "passes(1,0,0,2,1)."} <= set(blocker_facts(facts, [1], [(1, 1)]))
    assert "lift_gap(2,1,3)." in blocker_facts(facts, [1], [(1, 1)])
    assert makespan_bound(instance, Domain.A) == 10
    # a second robot in the pocket clears the way: it steps onto (2,1) at 1, lifts shelf 2 at
    # 2 and steps back at 3 as robot 1 (lifted shelf 1 at 2) follows it onto (2,1); P at 4,
    # deliveries at 5 and 6.  The minimum is 6 (the exact search refutes 5), and so is the bound.
    helped = read_instance(Source("<corridor>", CORRIDOR + "init(object(robot,2),value(at,(2,2)))."))
    assert makespan_bound(helped, Domain.A) == 6


@pytest.mark.parametrize("name, domain, minimal", [
    ("x2_y2_n4_r2_s2_ps1_pr2_u4_o2_N1", Domain.C, 4), ("x2_y2_n4_r2_s2_ps1_pr2_u4_o2_N1", Domain.B, 5),
    ("x3_y3_n9_r1_s1_ps1_pr1_u1_o1_N1", Domain.B, 9), ("x4_y4_n16_r2_s3_ps1_pr2_u4_o2_N1", Domain.C, 7),
    ("x4_y4_n16_r2_s3_ps1_pr2_u4_o2_N1", Domain.A, 8)])
def test_the_delivery_bound_never_exceeds_a_minimal_makespan(name, domain, minimal):
    """Minimal makespans found by brute force over all joint moves (tests/test_brute_force.py)."""
    bound = makespan_bound(read_instance(EXAMPLES / f"encodings-repo/{name}.lp"), domain)
    assert 0 < bound <= minimal


def _scipy_distances(cells: set, sources: list, targets: list) -> np.ndarray:
    """An independent implementation: SciPy's shortest paths on the floor's adjacency matrix."""
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import shortest_path
    index = {cell: i for i, cell in enumerate(sorted(cells))}
    edges = [(i, index[(x + dx, y + dy)]) for (x, y), i in index.items()
             for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1)) if (x + dx, y + dy) in index]
    graph = csr_matrix((np.ones(len(edges)), tuple(zip(*edges, strict=True))), shape=(len(index), len(index)))
    rows = shortest_path(graph, unweighted=True, indices=[index.get(s, 0) for s in sources])
    return np.array([[rows[k][index[t]] if s in index and t in index else math.inf for t in targets]
                     for k, s in enumerate(sources)])


@pytest.mark.parametrize("walls", [set(), {(10, 5), (11, 5), (10, 6)}, {(x, 5) for x in range(1, 20)}])
def test_the_distances_are_those_of_an_independent_search(walls):
    """With walls, without (a full rectangle: Manhattan distances) and cut in two (unreachable
    halves); more sources than targets and fewer (the engine searches from the smaller side)."""
    instance = read_instance(EXAMPLES / "paper-m/2x3x5/x19_y9_n171_r19_s60_ps3_pr60_u60_o19_N001.lp")
    cells = instance.cells - walls
    floor = Floor(cells)
    every = sorted(cells)
    sources, targets = every[::7] + [(0, 0)], every[::2] + [(40, 40)]  # and one cell off the floor each
    expected = _scipy_distances(cells, sources, targets)
    assert np.array_equal(floor.distances(sources, targets), expected)
    assert np.array_equal(floor.distances(targets, sources), expected.T)
    assert np.isinf(expected[-1]).all() and np.isinf(expected[:, -1]).all()
    assert np.isinf(expected[:-1, :-1]).any() == (len(walls) > 3)  # only the long wall cuts the floor


def test_the_array_view_has_the_same_distances_and_keeps_to_the_passable_cells():
    floor = Floor({(x, y) for x in range(1, 5) for y in range(1, 4)})  # 4x3
    plane = floor.plane()
    assert plane.shape == (6, 5) and plane.sum() == 12 and not plane[0].any() and not plane[:, 4].any()
    everywhere = floor.plane_distances([(1, 1), (4, 3)])
    assert everywhere[2, 2] == 2 and everywhere[4, 1] == 2 and everywhere[0, 0] == INFINITE
    passable = plane.copy()
    passable[2, 1:3] = False  # a wall from (2,1) to (2,2): around it through (2,3)
    around = floor.plane_distances([(1, 1)], passable)
    assert (around[1, 1], around[1, 3], around[2, 3], around[3, 1], around[2, 1]) == (0, 2, 3, 6, INFINITE)
    # a source counts as passable though the mask says otherwise
    assert floor.plane_distances([(2, 1)], passable)[3, 1] == 1


def test_the_python_and_the_scipy_matchings_agree(monkeypatch):
    from asprilo.bounds import mapf
    rng = np.random.default_rng(5)
    costs = [rng.integers(0, 9, size=(n, n + 2)).astype(float) for n in range(1, 9)]
    costs.append(np.array([[1, math.inf], [2, math.inf]]))  # two goals, one usable robot
    by_python = [(bottleneck_assignment(c), min_cost_assignment(c)) for c in costs]
    monkeypatch.setattr(mapf, "_PYTHON_MATCHING", 0)
    assert [(bottleneck_assignment(c), min_cost_assignment(c)) for c in costs] == by_python
    assert by_python[-1] == (math.inf, math.inf)
    # by hand: goal 0 <- robot 1 (1), goal 1 <- robot 0 (2): 3, better than 1 + 5 or 4 + 2
    assert min_cost_assignment(np.array([[4.0, 1.0], [2.0, 5.0]])) == 3


def test_the_carrying_distances_are_the_same_searched_per_station_or_all_at_once(monkeypatch):
    from asprilo.bounds import delivery

    instance = read_instance(EXAMPLES / "paper-m/4x5x8/x46_y15_n690_r23_s320_ps10_pr320_u320_o23_N001.lp")
    floor = Floor(instance.cells)
    one_by_one = Deliveries(instance, Domain.A, floor)
    monkeypatch.setattr(delivery, "NUMPY_SEARCH", 0)
    all_at_once = Deliveries(instance, Domain.A, floor)
    pairs = [(shelf, station.at) for shelf in instance.shelves for station in instance.stations.values()]
    assert len(pairs) == 320 * 10
    # two searches written apart: breadth first in Python per station, numpy's for all at once
    assert [all_at_once.carry(*pair) for pair in pairs] == [one_by_one.carry(*pair) for pair in pairs]


# --- the carried shelf's arrival: forward from each shelf, or back from the stations ---------

def test_a_carried_shelf_goes_around_a_cell_free_late_where_that_is_sooner():
    # a 3x2 floor; from (1,1) to the station (3,1), where (2,1) may be entered from step 7 on:
    # straight on, (2,1) at 7 and the station at 8; around through row 2, four moves
    from asprilo.bounds.delivery import arrivals_back, carry_arrivals

    floor = Floor({(x, y) for x in range(1, 4) for y in range(1, 3)})
    station, start, late = (3, 1), (1, 1), (2, 1)
    for lifted, expected in [(0, 4), (3, 7), (5, 8)]:  # around: lifted + 4; straight on: 8
        forward = carry_arrivals(set(floor.cells), {start: lifted}, {late: 7})
        assert forward[station] == expected
        starts, free_at = np.zeros(len(floor.cells)), np.full(len(floor.cells), -math.inf)
        starts[floor.index[start]], free_at[floor.index[late]] = lifted, 7
        back = arrivals_back(floor, [station], starts, free_at)[0]
        assert back[floor.index[start]] == expected
        # the others start at 0: (1,2) 3 moves around; (2,1) is not kept from itself: 1 move;
        # (2,2) 1 move up to (3,2) and down, or down onto (2,1) at 7: 2; the station itself 0
        assert [back[floor.index[cell]] for cell in [(1, 2), (2, 1), (2, 2), station]] == [3, 1, 2, 0]


def test_a_cell_that_is_no_node_or_a_start_never_lifted_arrives_nowhere():
    from asprilo.bounds.delivery import arrivals_back

    floor = Floor({(1, 1), (2, 1), (4, 1)})  # (4,1) is cut off
    starts = np.array([math.inf, 0.0, 0.0])
    back = arrivals_back(floor, [(2, 1), (4, 1), (9, 9)], starts, np.full(3, -math.inf))
    assert back.tolist() == [[math.inf, 0, math.inf], [math.inf, math.inf, 0], [math.inf] * 3]


@pytest.mark.parametrize("visits", [10**9, -1])  # forward from each shelf; back from the stations
def test_the_hand_derived_blocked_releases_hold_searched_either_way(visits, monkeypatch):
    from asprilo.bounds import delivery

    monkeypatch.setattr(delivery, "FORWARD_VISITS", visits)
    # the cases above, derived by hand there: R.SSP 7; the 8x2 floor 10, and 8 with the robots close
    assert makespan_bound(_row_world(5, 1, {1: (1, 1)}, {1: (3, 1), 2: (4, 1)}, (5, 1), {1: 1}), Domain.B) == 7
    far = _row_world(8, 2, {1: (4, 2), 2: (8, 2)}, {1: (3, 1), 2: (4, 1)}, (1, 1), {1: 1, 2: 2})
    close = _row_world(8, 2, {1: (4, 2), 2: (5, 2)}, {1: (3, 1), 2: (4, 1)}, (1, 1), {1: 1, 2: 2})
    assert [makespan_bound(far, Domain.B), makespan_bound(close, Domain.B)] == [10, 8]
    # robot 1 starts on (3,1) carrying shelf 1 (lifted at 0); shelf 2 on (4,1) is lifted at 2
    # at the earliest (robot 1 is 1 move away), so (4,1) is free at 3: shelf 1 is there at 3 and
    # on the station (5,1) at 4; shelf 2 is there at 3 (the carried shelf is in no one's way)
    carried = _row_world(5, 1, {1: (3, 1)}, {1: (3, 1), 2: (4, 1)}, (5, 1), {1: 1}, carries={1: 1})
    facts = Deliveries(carried, Domain.B, Floor(carried.cells))
    assert (facts.lifted, facts.arrival(1, (5, 1)), facts.arrival(2, (5, 1))) == ({1: 0, 2: 2}, 4, 3)


def _random_world(seed: int) -> Instance:
    """A 12x8 floor with 30 holes, 20 shelves, 3 stations with a line each, 4 robots and
    2 more that start carrying a shelf."""
    import random
    draw = random.Random(seed)
    grid = [(x, y) for x in range(1, 13) for y in range(1, 9)]
    cells = sorted(set(grid) - set(draw.sample(grid, 30)))
    chosen = draw.sample(cells, 27)
    shelves, robots, stations = chosen[:20], chosen[20:24], chosen[24:]
    facts = [f"init(object(node,{k}),value(at,{cell}))." for k, cell in enumerate(cells, 1)]
    facts += [f"init(object(shelf,{s}),value(at,{cell})). init(object(product,{s}),value(on,({s},1)))."
              for s, cell in enumerate(shelves, 1)]
    facts += [f"init(object(pickingStation,{p}),value(at,{cell})). init(object(order,{p}),value(line,({p},1))). "
              f"init(object(order,{p}),value(pickingStation,{p}))." for p, cell in enumerate(stations, 1)]
    facts += [f"init(object(robot,{r}),value(at,{cell}))." for r, cell in enumerate(robots, 1)]
    facts += [f"init(object(robot,{r}),value(at,{shelves[r - 1]})). init(object(robot,{r}),value(carries,{r})). "
              for r in (5, 6)]
    return read_instance(Source("<world>", "\n".join(facts)))


def test_the_arrivals_are_the_same_searched_forward_from_each_shelf_or_back_from_the_stations(monkeypatch):
    """Two searches written apart: forward from each shelf's cell (a heap in Python), back from
    every station at once (numpy, round by round); on floors with holes, carried shelves, and
    stations asked about without a line (every station of the instance)."""
    from asprilo.bounds import delivery

    monkeypatch.setattr(delivery, "STATIONS_AT_ONCE", 2)  # the three stations searched back in two passes
    waits = nowhere = 0
    for seed in range(8):
        instance = _random_world(seed)
        pairs = [(shelf, station.at) for shelf in sorted(instance.shelves) for station in instance.stations.values()]
        searched = []
        for visits in (10**9, -1):
            monkeypatch.setattr(delivery, "FORWARD_VISITS", visits)
            facts = Deliveries(instance, Domain.B, Floor(instance.cells))
            searched.append([facts.arrival(*pair) for pair in pairs])
        assert len(pairs) == 60 and searched[0] == searched[1]
        unhindered = [facts.lifted[shelf] + facts.carry(shelf, station) for shelf, station in pairs]
        waits += sum(arrival > plain for arrival, plain in zip(searched[0], unhindered, strict=True))
        nowhere += sum(math.isinf(arrival) for arrival in searched[0])
    assert waits and nowhere  # what is compared covers shelves that wait and shelves cut off
