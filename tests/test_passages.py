"""The ways a carried shelf can take past resting shelves (asprilo/bounds/passages.py), and
the bound that needs every shelf on such a way lifted (asprilo/bounds/trip.lp), derived by hand."""

from __future__ import annotations

from asprilo.bounds import Floor, makespan_bound, trip
from asprilo.bounds.delivery import Deliveries
from asprilo.bounds.passages import passages
from asprilo.bounds.trip import blocker_facts
from asprilo.domain import Domain
from asprilo.reader import read_instance
from asprilo.sources import Source


def grid(width: int, height: int) -> set:
    return {(x, y) for x in range(1, width + 1) for y in range(1, height + 1)}


def manhattan(cells: set, station) -> dict:
    return {(x, y): abs(x - station[0]) + abs(y - station[1]) for x, y in cells}


def test_two_ways_through_one_shelf_each_and_none_through_both():
    """A 3x2 floor, the shelf on (3,2), the station on (1,1), shelves 7 on (2,2) and 8 on (2,1):
    the three ways of 3 moves pass {7} (over (1,2)), {7, 8} (over (2,1)) and {8} (over (3,1));
    the second is beaten by either other; every longer way crosses column 2, so passes 7 or 8
    with more moves."""
    cells = grid(3, 2)
    found = passages(cells, {(2, 2): 7, (2, 1): 8}, (3, 2), (1, 1), manhattan(cells, (1, 1)), 10**6)[0]
    assert found == [(3, frozenset({7})), (3, frozenset({8}))]
    assert passages(cells, {(2, 2): 7, (2, 1): 8}, (3, 2), (1, 1), manhattan(cells, (1, 1)), 3)[0] == []


def test_a_way_around_the_shelves_bounds_the_ways_listed():
    """The same floor with a row (y=3) below: around column 2's shelves over (2,3) is 5 moves,
    so only ways of fewer than 5 moves count: the two of 3 (4 is the wrong parity)."""
    cells = grid(3, 3)
    resting = {(2, 2): 7, (2, 1): 8}
    found = passages(cells, resting, (3, 2), (1, 1), manhattan(cells, (1, 1)), 5)[0]
    assert found == [(3, frozenset({7})), (3, frozenset({8}))]
    # a third shelf on (2,3) closes the way around: the way that went around now passes it
    # alone, in 5 moves; a way over two of the three shelves is beaten by one over either alone
    resting[(2, 3)] = 9
    assert passages(cells, resting, (3, 2), (1, 1), manhattan(cells, (1, 1)), 10**6)[0] == [*found, (5, frozenset({9}))]


def test_a_corridor_needs_both_shelves_in_it():
    """A corridor (1,1)..(5,1) with pockets (2,2) and (3,2): the shelf on (4,1) reaches (1,1) in 3
    moves over shelves 2 on (3,1) and 3 on (2,1); through the pockets it is 5 moves over both."""
    cells = grid(5, 1) | {(2, 2), (3, 2)}
    found = passages(cells, {(3, 1): 2, (2, 1): 3}, (4, 1), (1, 1), manhattan(cells, (1, 1)), 10**6)[0]
    assert found == [(3, frozenset({2, 3}))]


def test_too_many_states_to_list_says_so():
    """On the first floor above the listing starts from one state, (3,2) with no shelves, and its
    first move adds (2,2) with {7} and (3,1) with none: the third state passes a limit of 2."""
    cells = grid(3, 2)
    near = manhattan(cells, (1, 1))
    assert passages(cells, {(2, 2): 7, (2, 1): 8}, (3, 2), (1, 1), near, 10**6, limit=2) == (None, 3)


CORRIDOR = """
    init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))).
    init(object(node,3),value(at,(3,1))). init(object(node,4),value(at,(4,1))).
    init(object(node,5),value(at,(5,1))). init(object(node,6),value(at,(2,2))).
    init(object(node,7),value(at,(3,2))). init(object(pickingStation,1),value(at,(1,1))).
    init(object(robot,1),value(at,(5,1))).
    init(object(shelf,1),value(at,(4,1))). init(object(shelf,2),value(at,(3,1))).
    init(object(shelf,3),value(at,(2,1))).
    init(object(product,1),value(on,(1,2))). init(object(product,2),value(on,(2,1))).
    init(object(order,1),value(line,(1,1))). init(object(order,1),value(pickingStation,1)).
    init(object(order,2),value(line,(1,1))). init(object(order,2),value(pickingStation,1)).
"""


def test_a_shelf_behind_two_others_waits_for_both_lifts():
    """The corridor above with one robot on (5,1); shelf 1 holds the two units both orders ask
    for.  By hand the minimum is 19: walk 2, lift shelf 2 at 3, into pocket (3,2), put down at 5,
    back and on to (2,1) at 7, lift shelf 3 at 8, into pocket (2,2), put down at 10, walk to (4,1)
    at 13, lift at 14, carry 3, deliver at 18 and 19 (``asprilo solve --method asp`` proves it).
    Needing one of the two shelves in the way lifted (the rule before the passages), the bound
    was 11: shelf 2 lifted at 3, lift_gap(2,1) = 3 more steps (put back on its own cell, walk 1,
    lift shelf 1) to 6, carry 3, deliveries at 10 and 11.  Needing both: shelf 2 at 3 and shelf 3
    lift_gap(2,3) = 3 later at 6 (or shelf 3 at 4 and shelf 2 at 7), then lift_gap(3,1) = 4 (put
    down, walk 2, lift) or lift_gap(2,1) = 3 to lift shelf 1 at 10, carry 3, deliveries at 14 and
    15: the bound is 15."""
    instance = read_instance(Source("<corridor>", CORRIDOR))
    facts = Deliveries(instance, Domain.A, Floor(instance.cells))
    said = blocker_facts(facts, [1], [(1, 1)])
    assert [fact for fact in said if fact.startswith(("clear", "passage", "passes"))] == [
        "clear(1,0,1000000).", "passage(1,0,0,3).", "passes(1,0,0,2,2).", "passes(1,0,0,3,1)."]
    assert {"lift_gap(2,3,3).", "lift_gap(3,2,3).", "lift_gap(3,1,4).", "lift_gap(2,1,3)."} <= set(said)
    assert makespan_bound(instance, Domain.A) == 15


#: trip.lp's facts, written by hand: one robot, one station (0); shelf 1 (line 0) is delivered
#: at 3 at the earliest, carried 1 move; shelf 2 (line 1) at 4, carried 2 moves through the
#: cell of shelf 3, which no robot can lift (no reach_shelf), or 6 moves around it; both
#: shelves are lifted where they stand (handled/3 at 100: never moved first); after a delivery
#: the robot lifts either shelf 3 steps later (fetch/3: put down, walk, lift).
SECOND_TRIP = """
robot(1). #const delivery = line.
line(0). station_of(0,0). holder(0,1). product_of(0,1).
line(1). station_of(1,0). holder(1,2). product_of(1,2).
earliest(1,1,0,3). own(1,1,0,3). reach_shelf(1,1,1). carry(1,0,1). handled(1,0,100).
earliest(1,2,0,4). own(1,2,0,4). reach_shelf(1,2,1). carry(2,0,2). handled(2,0,100).
clear(2,0,6). passage(2,0,0,2). passes(2,0,0,3,1).
fetch(0,1,3). fetch(0,2,3). gap_fresh(0,1,0,5). gap_fresh(0,2,0,6). gap_any(0,0,5).
gap_hand(0,0,4). apart(0,0,0).
"""


def refuted(program: str, horizon: int) -> bool:
    import clingo
    control = clingo.Control(["--warn=none", "-c", f"horizon={horizon}"])
    control.add("base", [], program + SECOND_TRIP)
    control.ground([("base", [])])
    return control.solve().unsatisfiable


def test_a_second_shelf_s_way_counts_from_the_robot_s_previous_delivery():
    """By hand, with the facts above: shelf 2 first takes the way around (lift at 1, 6 moves,
    delivery at 8), then shelf 1 gap_fresh = 5 later, at 13.  Shelf 1 first (at 3): shelf 2 is
    lifted fetch = 3 steps later at the earliest (6), so its way has U - 1 - 6 moves at most; the
    way around needs U >= 13.  The bound is 13.  Counting shelf 2's way from the robot's start
    (lifted at 1, as before the rule), a delivery at 9 (gap_fresh after 3) left it 7 >= 6 moves,
    so 9 passed (and 8 was refuted: shelf 2 at 3 + gap_fresh 6 at the earliest)."""
    from asprilo.bounds.trip import _PROGRAM
    program = _PROGRAM.read_text()
    assert refuted(program, 12) and not refuted(program, 13)
    rule = next(line for line in program.splitlines() if line.startswith("way(S,P,U,U-1-T-G)"))
    assert refuted(program.replace(rule, ""), 8) and not refuted(program.replace(rule, ""), 9)


def test_too_many_ways_to_list_fall_back_to_one_shelf_each(monkeypatch):
    """The corridor when the ways cannot be listed: each shelf in the way is a passage alone (3
    moves over shelf 2's cell, 3 over shelf 3's), and the bound is the one-shelf bound of 11
    derived above."""
    monkeypatch.setattr(trip, "PASSAGE_STATES", 0)
    instance = read_instance(Source("<corridor>", CORRIDOR))
    facts = Deliveries(instance, Domain.A, Floor(instance.cells))
    said = blocker_facts(facts, [1], [(1, 1)])
    assert [fact for fact in said if fact.startswith(("passage", "passes"))] == [
        "passage(1,0,0,3).", "passes(1,0,0,2,2).", "passage(1,0,1,3).", "passes(1,0,1,3,1)."]
    assert makespan_bound(instance, Domain.A) == 11


def test_an_exercise_floor_s_bound_meets_its_minimum(tmp_path, capsys):
    """The exercise-size call with two orders, seed 4601 (benchmarks/RESULTS.md): the exact
    encoding refutes horizon 16 and finds a plan of 17 (28 s here, so not run), and the bound,
    16 before the passages and later trips' ways, is now 17."""
    from helpers.generated import one

    from asprilo.cli import main
    from asprilo.writer import format_instance
    options = {"-x": 11, "-y": 6, "-X": 4, "-Y": 2, "-p": 2, "-s": 16, "-P": 8, "-u": 40, "-r": 4, "-H": True,
               "--prsmin": 1, "--prsmax": 3, "--olmin": 1, "--olmax": 3, "-o": 2}
    instance = one(options, 4601)
    assert makespan_bound(instance, Domain.A) == 17
    path = tmp_path / "4601.lp"
    path.write_text(format_instance(instance))
    assert main(["solve", str(path), "--domain", "a", "--method", "asp", "--horizon", "16"]) == 1
    assert "no plan exists" in capsys.readouterr().err
