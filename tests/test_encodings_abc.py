"""The A/B/C encodings: exact minimal makespans on tiny instances, checked plans, assignments."""

from __future__ import annotations

import pytest
from helpers import EXAMPLES, SMALL_A
from oracles.brute_force import minimal_makespan as brute_force

from asprilo.checker import check
from asprilo.domain import Domain
from asprilo.encodings import SolveStatus, reference_encodings, solve
from asprilo.encodings.assignment import assign_tasks, assignment_of_plan, distance_facts
from asprilo.encodings.solving.bounds import LowerBounds
from asprilo.encodings.solving.methods import assigned, program
from asprilo.errors import InputError
from asprilo.model import Action, Plan
from asprilo.reader import read_instance

STYLES = {d: [e.name for e in reference_encodings(d)] for d in (Domain.A, Domain.B, Domain.C)}
TINY = {  # instance -> minimal makespan per domain, by brute force (tests/test_brute_force.py)
    "x2_y2_n4_r2_s2_ps1_pr2_u4_o2_N1.lp": {Domain.C: 4, Domain.B: 5, Domain.A: 5},
    "x3_y3_n9_r1_s1_ps1_pr1_u1_o1_N1.lp": {Domain.C: 9, Domain.B: 9, Domain.A: 9},
    "x4_y4_n16_r2_s3_ps1_pr2_u4_o2_N1.lp": {Domain.C: 7, Domain.B: 8, Domain.A: 8},
}
CASES = [(name, domain, style, makespan) for name, spans in TINY.items()
         for domain, makespan in spans.items() for style in STYLES[domain]]

#: one robot that has to fetch two shelves in turn: the bound (8, C: 7) is far below 14
TWO_SHELVES = """
init(object(grid,1),value(xsize,4)). init(object(grid,1),value(ysize,3)).
init(object(pickingStation,1),value(at,(1,1))).
init(object(robot,1),value(at,(4,3))).
init(object(shelf,1),value(at,(2,2))). init(object(shelf,2),value(at,(3,2))).
init(object(product,1),value(on,(1,1))). init(object(product,2),value(on,(2,1))).
init(object(order,1),value(line,(1,1))). init(object(order,1),value(line,(2,1))).
init(object(order,1),value(pickingStation,1)).
"""


def test_registry():
    assert STYLES == {Domain.A: ["plain", "clingcon"], Domain.B: ["plain"], Domain.C: ["plain"]}


@pytest.mark.parametrize("name, domain, style, makespan", CASES,
                         ids=[f"{n[:5]}-{d.value}-{s}" for n, d, s, _ in CASES])
def test_minimal_makespan_and_none_below(name, domain, style, makespan):
    instance = read_instance(EXAMPLES / "encodings-repo" / name)
    outcome = solve(instance, domain, encoding=style)
    assert (outcome.status, outcome.horizon, outcome.minimal) == (SolveStatus.FOUND, makespan, True)
    assert outcome.check.valid and outcome.check.domain is domain
    below = solve(instance, domain, encoding=style, horizon=makespan - 1)
    assert below.status is SolveStatus.NONE


@pytest.mark.parametrize("domain", [Domain.A, Domain.B, Domain.C])
def test_a_two_trip_plan_starts_at_its_bound(write, domain):
    # one robot, two lines at one station: its second delivery comes a whole cycle after the
    # first (7 steps: put down next to the station, walk back, lift, carry, deliver), and the
    # first comes at 7 at the earliest, so the bound is 14 -- the minimal makespan (brute force)
    outcome = solve(write("two.lp", TWO_SHELVES), domain)
    assert [(a.horizon, a.result) for a in outcome.horizons_tried] == [(14, "sat")]
    assert (outcome.lower_bound, outcome.horizon, outcome.minimal, outcome.check.valid) == (14, 14, True, True)
    names = [a.name for a in outcome.plan.actions]
    assert (names.count("pickup"), names.count("putdown"), names.count("deliver")) == (2, 1, 2)


def test_clingcon_deliveries_carry_the_integer_amounts():
    instance = read_instance(EXAMPLES / "encodings-repo/x2_y2_n4_r2_s2_ps1_pr2_u4_o2_N1.lp")
    outcome = solve(instance, Domain.A, encoding="clingcon")
    deliveries = sorted(a.args for a in outcome.plan.actions if a.name == "deliver")
    assert deliveries == [(1, 1, 1), (2, 2, 3)]
    assert outcome.check.valid


@pytest.mark.parametrize("domain", [Domain.A, Domain.B, Domain.C])
def test_several_robots_deliver_in_the_same_step(write, domain):
    two_stations = """
    init(object(grid,1),value(xsize,3)). init(object(grid,1),value(ysize,2)).
    init(object(pickingStation,1),value(at,(1,1))). init(object(pickingStation,2),value(at,(3,1))).
    init(object(robot,1),value(at,(1,2))). init(object(robot,2),value(at,(3,2))).
    init(object(shelf,1),value(at,(1,2))). init(object(shelf,2),value(at,(3,2))).
    init(object(product,1),value(on,(1,1))). init(object(product,2),value(on,(2,1))).
    init(object(order,1),value(line,(1,1))). init(object(order,1),value(pickingStation,1)).
    init(object(order,2),value(line,(2,1))). init(object(order,2),value(pickingStation,2)).
    """
    outcome = solve(write("stations.lp", two_stations), domain)
    assert outcome.horizon == 3 and outcome.check.valid
    assert sorted((a.step, a.robot) for a in outcome.plan.actions if a.name == "deliver") == [(3, 1), (3, 2)]


def test_assignment_for_b_uses_fewest_shelves():
    instance = read_instance(SMALL_A)
    assignment = assign_tasks(instance, Domain.B)
    assert assignment.optimal
    shelves = sorted({fact.split("shelf(")[1].split(")")[0] for fact in assignment.facts})
    assert len(shelves) == 3 and "1" in shelves  # shelf 1 serves three lines at station 2
    assert assignment.cost[0] == 3


def test_a_robot_with_two_shelves_pays_for_putting_the_first_away(write):
    # 11x2, station (1,1), shelf 1 on (3,1) and shelf 2 on (2,2), every other cell a highway (no
    # free storage cell: a shelf goes back where it came from, 2 moves for both).  Robot 1 on
    # (3,2) is 1 move from each shelf, robot 2 on (11,1) 8 from shelf 1 and 10 from shelf 2.
    # Robot 1 with both: 1 + 1 fetch, 2 + 2 bring, 3 + 3 lift/deliver/set down, 2 to put the
    # first away = 14; robot 1 with shelf 2 and robot 2 with shelf 1: max(1+2+3, 8+2+3) = 13.
    # (Without the putting away, robot 1 with both would cost 12 and win.)
    cells = [(x, y) for x in range(1, 12) for y in (1, 2) if (x, y) not in {(1, 1), (3, 1), (2, 2)}]
    highways = " ".join(f"init(object(highway,{k}),value(at,({x},{y})))." for k, (x, y) in enumerate(cells, 1))
    instance = read_instance(write("chain.lp", f"""
    init(object(grid,1),value(xsize,11)). init(object(grid,1),value(ysize,2)). {highways}
    init(object(pickingStation,1),value(at,(1,1))).
    init(object(robot,1),value(at,(3,2))). init(object(robot,2),value(at,(11,1))).
    init(object(shelf,1),value(at,(3,1))). init(object(shelf,2),value(at,(2,2))).
    init(object(product,1),value(on,(1,1))). init(object(product,2),value(on,(2,1))).
    init(object(order,1),value(line,(1,1))). init(object(order,1),value(line,(2,1))).
    init(object(order,1),value(pickingStation,1)).
    """))
    assignment = assign_tasks(instance, Domain.B)
    # shelves, largest workload, squared workloads: robot 1 1 + 2 + 3 = 6, robot 2 13: 36 + 169
    assert assignment.optimal and assignment.cost == [2, 13, 205]
    assert sorted(assignment.facts) == ["assign(robot(1),shelf(2),pickingStation(1))",
                                        "assign(robot(2),shelf(1),pickingStation(1))"]


def pickup_cells(instance, plan: Plan) -> list[tuple[int, tuple[int, int]]]:
    """(robot, cell) of every pickup of ``plan``, in step order, following the robots' moves."""
    cells = {robot.id: robot.at for robot in instance.robots.values()}
    pickups = []
    for action in sorted(plan.actions):
        if action.name == "move":
            x, y = cells[action.robot]
            cells[action.robot] = (x + action.args[0], y + action.args[1])
        elif action.name == "pickup":
            pickups.append((action.robot, cells[action.robot]))
    return pickups


@pytest.fixture
def no_probe(monkeypatch):
    """Searches with assignment go straight to the optimised assignment (no probe without it)."""
    monkeypatch.setattr(assigned, "PROBE_CONFLICTS", 0)


def test_assigned_plans_follow_the_assignment(no_probe):
    instance = read_instance(SMALL_A)
    outcome = solve(instance, Domain.B, assign=True, time_limit=120)
    assert outcome.found and outcome.check.valid and outcome.horizon == 16
    # the plan along the assignment meets the lower bound (16), so it is minimal without more tries
    assert [(a.horizon, a.result, a.note) for a in outcome.horizons_tried] == [(16, "sat", "")]
    assert outcome.minimal and outcome.lower_bound == 16
    carriers = {}
    for fact in outcome.assignment.facts:  # assign(robot(R),shelf(S),pickingStation(P))
        robot = int(fact.split("robot(")[1].split(")")[0])
        carriers[int(fact.split("shelf(")[1].split(")")[0])] = robot
    picked = [(a.robot, a.step) for a in outcome.plan.actions if a.name == "pickup"]
    assert sorted(r for r, _ in picked) == sorted(carriers.values())


def test_a_given_assignment_is_followed_not_computed():
    # the small A example read as B: shelf 2 serves both stations (O1's products 2 and 4, O2's
    # 4 and 5), shelf 1 O3's product 3 and shelf 9 O3's product 1, each with another robot
    instance = read_instance(SMALL_A)
    given = ["assign(robot(2),shelf(2),pickingStation(1))", "assign(robot(2),shelf(2),pickingStation(2))",
             "assign(robot(3),shelf(1),pickingStation(2))", "assign(robot(1),shelf(9),pickingStation(2))"]
    outcome = solve(instance, Domain.B, assignment=given, tighten=False, time_limit=120)
    assert outcome.found and outcome.check.valid and outcome.assignment.facts == sorted(given)
    lifted = {}
    for robot, cell in pickup_cells(instance, outcome.plan):
        lifted.setdefault(robot, cell)
    assert lifted == {1: instance.shelves[9].at, 2: instance.shelves[2].at, 3: instance.shelves[1].at}


@pytest.mark.parametrize("facts, message", [
    (["assign(robot(7),shelf(1),pickingStation(1))"], "the assignment names robot 7, which the instance lacks"),
    (["assign(robot(1),shelf(1))"], "not an assignment fact of domain B: assign(robot(1),shelf(1))"),
    (["assign(robot(1"], "not an assignment fact: 'assign(robot(1'"),
    ([], "the given assignment is empty"),
])
def test_a_given_assignment_that_does_not_fit_is_bad_input(facts, message):
    with pytest.raises(InputError) as raised:
        solve(read_instance(SMALL_A), Domain.B, assignment=facts)
    assert str(raised.value) == message


def test_a_plan_along_the_assignment_is_tightened_without_it(no_probe):
    # read as C, the small A example's assignment leads to a plan of 15 steps, above a lower
    # bound of 14 (given: the strong bound is 15 since the trip relaxation counts the lifts
    # that clear a carry's way, which would leave nothing to tighten); one step shorter is
    # then tried without the assignment, and refuted.  The upward search without assignment,
    # a separate path, agrees: 14 refuted, 15 found; so 15 is the minimum and the strong
    # bound's search tries 15 alone.
    instance = read_instance(SMALL_A)
    plain = solve(instance, Domain.C, time_limit=120, bounds=LowerBounds(14))
    assert [(a.horizon, a.result) for a in plain.horizons_tried] == [(14, "unsat"), (15, "sat")]
    strong = solve(instance, Domain.C, time_limit=120)
    assert [(a.horizon, a.result) for a in strong.horizons_tried] == [(15, "sat")]
    outcome = solve(instance, Domain.C, assign=True, time_limit=120, bounds=LowerBounds(14))
    assert [(a.horizon, a.result, a.note) for a in outcome.horizons_tried] == [
        (15, "sat", ""), (14, "unsat", "without assignment")]
    assert (outcome.lower_bound, outcome.horizon, outcome.minimal, outcome.check.valid) == (14, 15, True, True)


def test_a_search_with_assignment_probes_without_one_first():
    # read as C, the small A example has no plan of 14 steps and one of 15 (the upward search
    # without assignment above); from a lower bound of 14 the probe finds both before any
    # assignment is computed, and the plan it returns follows the assignment read off it:
    # each robot lifts only its shelves
    outcome = solve(read_instance(SMALL_A), Domain.C, assign=True, time_limit=120, bounds=LowerBounds(14))
    assert [(a.horizon, a.result, a.note) for a in outcome.horizons_tried] == [
        (14, "unsat", "without assignment"), (15, "sat", "without assignment")]
    assert (outcome.horizon, outcome.minimal, outcome.check.valid, outcome.refuted) == (15, True, True, [14])
    assert outcome.assignment.origin == "read off a plan"
    carriers = {int(f.split("shelf(")[1].split(")")[0]): int(f.split("robot(")[1].split(")")[0])
                for f in outcome.assignment.facts}
    instance = read_instance(SMALL_A)
    shelves = {shelf.at: shelf.id for shelf in instance.shelves.values()}
    for robot, cell in pickup_cells(instance, outcome.plan):
        assert carriers[shelves[cell]] == robot


#: shelf 1 on (3,2) is walled in by shelves 2 (2,2) and 3 (3,1), which no order needs
WALLED = """
init(object(grid,1),value(xsize,3)). init(object(grid,1),value(ysize,2)).
init(object(pickingStation,1),value(at,(1,1))).
init(object(robot,1),value(at,(1,2))).
init(object(shelf,1),value(at,(3,2))). init(object(shelf,2),value(at,(2,2))).
init(object(shelf,3),value(at,(3,1))).
init(object(product,1),value(on,(1,1))). init(object(product,2),value(on,(2,1))).
init(object(product,2),value(on,(3,1))).
init(object(order,1),value(line,(1,1))). init(object(order,1),value(pickingStation,1)).
"""


def test_a_minimal_plan_that_no_assignment_allows_is_kept(write):
    # by hand: walk under shelf 2, lift it, set it down on (2,1) (or (1,2)), walk to shelf 1,
    # lift it, carry it past (2,2) and (1,2) (or (2,1)) to the station, deliver: 11 steps.
    # An assignment lets only shelf 1 move, so no plan follows one; the probe's plan stays.
    instance = read_instance(write("walled.lp", WALLED))
    assert brute_force(instance, "b") == 11
    outcome = solve(instance, Domain.B, assign=True, time_limit=120)
    assert (outcome.horizon, outcome.minimal, outcome.check.valid) == (11, True, True)
    assert outcome.minimal_along_assignment is False
    assert outcome.assignment.origin == "read off a plan that also moves other shelves"
    assert [(a.horizon, a.result) for a in outcome.horizons_tried[-2:]] == [(11, "sat"), (11, "unsat")]
    assert outcome.refuted == [7, 8, 9, 10]
    assert sorted(a.step for a in outcome.plan.actions if a.name == "pickup") == [2, 7]


def test_no_plan_follows_an_assignment_that_leaves_a_shelf_walled_in(write, no_probe):
    outcome = solve(read_instance(write("walled.lp", WALLED)), Domain.B, assign=True, time_limit=120)
    assert (outcome.status, outcome.plan, outcome.horizons_tried) == (SolveStatus.LIMIT, None, [])
    assert outcome.message == "no plan can follow the task assignment (a shelf cannot reach its station)"


ONE_SHELF = """
init(object(grid,1),value(xsize,3)). init(object(grid,1),value(ysize,2)).
init(object(pickingStation,1),value(at,(1,1))).
init(object(robot,1),value(at,(3,1))). init(object(robot,2),value(at,(1,2))).
init(object(shelf,1),value(at,(3,1))).
init(object(product,1),value(on,(1,1))).
init(object(order,1),value(line,(1,1))). init(object(order,1),value(pickingStation,1)).
"""


def test_the_assignment_read_off_a_plan(write):
    instance = read_instance(write("one.lp", ONE_SHELF))
    direct = Plan([Action(1, 1, "pickup"), Action(2, 1, "move", (-1, 0)), Action(3, 1, "move", (-1, 0)),
                   Action(4, 1, "deliver", (1, 1))])
    assignment, exact = assignment_of_plan(instance, Domain.B, direct)
    assert (assignment.facts, exact) == (["assign(robot(1),shelf(1),pickingStation(1))"], True)
    # robot 1 moves the shelf one cell and puts it down; robot 2 brings it: the deliveries'
    # assignment names robot 2 only, and the plan, in which robot 1 lifts it too, does not follow it
    relay = Plan([Action(1, 1, "pickup"), Action(2, 1, "move", (-1, 0)), Action(3, 1, "putdown"),
                  Action(4, 1, "move", (1, 0)), Action(4, 2, "move", (1, 0)), Action(5, 2, "move", (0, -1)),
                  Action(6, 2, "pickup"), Action(7, 2, "move", (-1, 0)), Action(8, 2, "deliver", (1, 1))])
    assert check(instance, relay, Domain.B).valid
    assignment, exact = assignment_of_plan(instance, Domain.B, relay)
    assert (assignment.facts, exact) == (["assign(robot(2),shelf(1),pickingStation(1))"], False)


def test_a_hinted_search_takes_the_same_path_every_time():
    # the paper's small N001 (11 robots) read as C at its minimal makespan 28 needs more
    # conflicts than the first hint turn (1,000): the turns are counted in conflicts, so two
    # searches switch hints on and off at the same points and agree conflict for conflict
    instance = read_instance(EXAMPLES / "paper-m/1x2x4/x11_y6_n66_r11_s16_ps1_pr16_u16_o11_N001.lp")
    first, second = (solve(instance, Domain.C, horizon=28, time_limit=120) for _ in range(2))
    assert first.found and first.stats["conflicts"] > program.FIRST_TURN
    assert (second.stats["conflicts"], second.plan) == (first.stats["conflicts"], first.plan)


def test_assignment_bound_chains_the_tasks_of_each_robot(write):
    from asprilo.encodings.bounds import assignment_bound
    two = read_instance(write("two.lp", TWO_SHELVES))
    facts = ["assign(robot(1),shelf(1),pickingStation(1))", "assign(robot(1),shelf(2),pickingStation(1))"]
    assert assignment_bound(two, facts) == 14  # the minimal makespan of this instance
    small = read_instance(SMALL_A)
    facts = ["assign(robot(1),shelf(2),pickingStation(1))", "assign(robot(1),shelf(2),pickingStation(2))",
             "assign(robot(2),shelf(3),pickingStation(1))", "assign(robot(3),shelf(1),pickingStation(2))",
             "assign(robot(3),shelf(9),pickingStation(2))"]
    assert assignment_bound(small, facts) == 23  # robot 3: shelf 1, put it down, shelf 9


def test_distance_facts_are_floor_distances():
    instance = read_instance(EXAMPLES / "encodings-repo/x3_y3_n9_r1_s1_ps1_pr1_u1_o1_N1.lp")
    # no highways: every cell but the station's (1,3) and the shelf's (3,1) is a free storage
    # cell, the nearest one a step from the station
    assert sorted(distance_facts(instance, Domain.B)) == [
        "distance((2,3),(3,1),3)", "distance((3,1),(1,3),4)", "set_down(1,1)"]


@pytest.mark.parametrize("domain, style", [(d, s) for d, styles in STYLES.items() for s in styles])
def test_a_robot_may_start_with_a_shelf(write, domain, style):
    carrying = """
    init(object(grid,1),value(xsize,3)). init(object(grid,1),value(ysize,1)).
    init(object(pickingStation,1),value(at,(1,1))).
    init(object(robot,1),value(at,(2,1))). init(object(robot,1),value(carries,1)).
    init(object(shelf,1),value(at,(2,1))). init(object(product,1),value(on,(1,2))).
    init(object(order,1),value(line,(1,2))). init(object(order,1),value(pickingStation,1)).
    """
    outcome = solve(write("carrying.lp", carrying), domain, encoding=style)
    deliver = (1, 1, 2) if domain is Domain.A else (1, 1)
    assert [(a.step, a.name, a.args) for a in outcome.plan.actions] == [(1, "move", (-1, 0)), (2, "deliver", deliver)]
    assert outcome.minimal and outcome.check.valid
