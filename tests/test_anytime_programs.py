"""The anytime planner's logic programs on hand-made facts: routing (route.lp) and the two
assignment programs.  Expected routes and costs are derived by hand or by brute force."""

from __future__ import annotations

import itertools
import random
from pathlib import Path

import clingo
import pytest

import asprilo.encodings.anytime as anytime
from asprilo.encodings.anytime.assignment import Assigner

HERE = Path(anytime.__file__).resolve().parent


def route(facts: str) -> tuple[int | None, set[str]]:
    """The arrival step and the at/3 atoms of route.lp on ``facts``."""
    control = clingo.Control(["--warn=none"])
    control.load(str(HERE / "route.lp"))
    control.add("base", [], facts)
    control.ground([("base", [])])
    shown: list[clingo.Symbol] = []
    control.solve(on_model=lambda model: shown.extend(model.symbols(shown=True)))
    arrival = [s.arguments[0].number for s in shown if s.name == "arrival"]
    return (arrival[0] if arrival else None), {str(s) for s in shown if s.name == "at"}


def corridor(cells: list[str], stage: int = 1, first: int = 0, last: int = 20) -> str:
    return "".join(f"window({stage},{cell},{first},{last})." for cell in cells)


ROW = ["(1,1)", "(2,1)", "(3,1)", "(4,1)"]


def test_a_free_corridor_is_walked_at_once():
    arrival, at = route("begin((1,1),0). task(1,(4,1)). last(1)." + corridor(ROW))
    assert arrival == 3
    assert at == {"at(1,(1,1),0)", "at(1,(2,1),1)", "at(1,(3,1),2)", "at(1,(4,1),3)"}


def test_a_robot_in_the_way_makes_it_wait():
    # another robot stands on (2,1) after steps 1 and 2: the only way on is to wait until step 3
    arrival, at = route("begin((1,1),0). task(1,(4,1)). last(1). busy((2,1),1). busy((2,1),2)." + corridor(ROW))
    assert arrival == 5
    assert at == {"at(1,(1,1),0)", "at(1,(1,1),1)", "at(1,(1,1),2)", "at(1,(2,1),3)", "at(1,(3,1),4)",
                  "at(1,(4,1),5)"}


def test_robots_never_swap_cells():
    # the other robot moves (2,1) -> (1,1) at step 1: ours can neither stay nor pass it; it
    # steps aside to (1,2), comes back at step 2 and reaches (2,1) at step 3
    facts = ("begin((1,1),0). task(1,(2,1)). last(1). busy((2,1),0). busy((1,1),1). crossing((2,1),(1,1),1)."
             + corridor(["(1,1)", "(2,1)", "(1,2)"]))
    arrival, at = route(facts)
    assert arrival == 3
    assert at == {"at(1,(1,1),0)", "at(1,(1,2),1)", "at(1,(1,1),2)", "at(1,(2,1),3)"}


def test_an_action_takes_one_step_and_a_carrying_robot_waits_for_a_resting_shelf():
    # pick up on (2,1), then park on (3,1) with the shelf; another shelf rests on (3,1) until step 3
    facts = ("begin((1,1),0). task(1,(2,1)). acts(1). task(2,(3,1)). last(2). carrying(2). rests((3,1),0,3)."
             + corridor(["(1,1)", "(2,1)"], 1) + corridor(["(2,1)", "(3,1)"], 2))
    arrival, at = route(facts)
    assert arrival == 4
    assert at == {"at(1,(1,1),0)", "at(1,(2,1),1)", "at(2,(2,1),2)", "at(2,(2,1),3)", "at(2,(3,1),4)"}


def test_parking_waits_until_nobody_comes_any_more():
    # (2,1) is passed by another robot at step 5: parking there counts from step 6 on
    facts = "begin((1,1),0). task(1,(2,1)). last(1). busy((2,1),5). free_from((2,1),6)." + corridor(ROW[:3])
    arrival, _ = route(facts)
    assert arrival == 6


def test_no_route_means_no_arrival():
    facts = "begin((1,1),0). task(1,(3,1)). last(1). stays((2,1),0)." + corridor(ROW[:3])
    assert route(facts) == (None, set())


def _optimum(problem: Assigner):
    choice = problem.solve(budget=10)
    assert choice is not None and choice.optimal
    return choice


@pytest.mark.parametrize("seed", range(6))
def test_the_goal_assignment_is_lexicographically_optimal(seed):
    """Longest trip first, then the total: compared with all permutations."""
    rng = random.Random(seed)
    robots, goals = 4, 3
    distance = [[rng.randint(1, 9) for _ in range(goals)] for _ in range(robots)]
    facts = [f"goal({g})." for g in range(goals)]
    facts += [f"option({r},{g},{distance[r][g]})." for r in range(robots) for g in range(goals)]
    choice = _optimum(Assigner("assign_goals.lp", facts))
    trips = [distance[r][g] for r, g in choice.of("aim")]
    best = min((max(distance[r][g] for g, r in enumerate(pick)), sum(distance[r][g] for g, r in enumerate(pick)))
               for pick in itertools.permutations(range(robots), goals))
    assert (max(trips), sum(trips)) == best
    assert sorted(g for _, g in choice.of("aim")) == list(range(goals))


def test_the_shelf_assignment_takes_the_nearest_shelf_and_robot():
    # one line of product 1 at station 1; shelf 1 is 5 steps from it, shelf 2 2 steps; robot 2
    # is 1 step from shelf 2: trip 1 + 2 + 2 = 5, every other pair is longer
    facts = ["line(1,1,1).", "order(1,1).", "holds(1,1,1).", "holds(2,1,1).", "haul(1,1,5).", "haul(2,1,2).",
             "option(1,1,1).", "option(1,2,6).", "option(2,2,1).", "option(2,1,7).", "cap(1)."]
    choice = _optimum(Assigner("assign_shelves.lp", facts, {"domain": "b"}))
    assert choice.of("give") == [(2, 1, 1, 1)]
    assert choice.of("carry") == [(2, 2)]


def test_domain_a_splits_a_line_over_shelves_without_taking_more_than_they_hold():
    facts = ["line(1,1,3).", "order(1,1).", "holds(1,1,2).", "holds(2,1,2).", "haul(1,1,3).", "haul(2,1,3).",
             "option(1,1,2).", "option(2,2,2).", "cap(1)."]
    choice = _optimum(Assigner("assign_shelves.lp", facts, {"domain": "a"}))
    gives = choice.of("give")
    assert sum(units for *_, units in gives) == 3
    assert all(units <= 2 for *_, units in gives) and len(gives) == 2
    assert choice.of("carry") == [(1, 1), (2, 2)]


def test_kept_choices_hold_when_a_neighbourhood_is_assigned_again():
    facts = ["goal(0).", "goal(1).", "option(1,0,1).", "option(1,1,5).", "option(2,0,5).", "option(2,1,1)."]
    assigner = Assigner("assign_goals.lp", facts)
    assert _optimum(assigner).of("aim") == [(1, 0), (2, 1)]
    forced = assigner.solve(keep=[clingo.parse_term("aim(1,1)")], budget=10)
    assert forced.of("aim") == [(1, 1), (2, 0)]


def test_the_greedy_start_serves_lines_from_the_nearest_shelves_and_gives_each_robot_its_cap():
    from asprilo.encodings.anytime.assignment import _greedy

    # A: 3 units of product 10 at station 4; shelves by hauling steps: 3 (2 steps, holds 1),
    # 1 (5 steps, holds 2), 2 (9 steps, holds 5): 3 gives 1, 1 gives 2, and 2 is not needed.
    # Robot 8 is nearest to both shelves used; with a cap of 1 shelf, shelf 1 goes to robot 9
    stock = {1: {10: 2}, 2: {10: 5}, 3: {10: 1}}
    haul = {(1, 4): 5, (2, 4): 9, (3, 4): 2}
    options = [(7, 3, 4), (8, 3, 1), (8, 1, 2), (9, 1, 6)]
    assert _greedy({(1, 10): 3}, stock, haul, {1: 4}, options, 1, True) == [
        "hint_give(3,1,10,1).", "hint_give(1,1,10,2).", "hint_carry(8,3).", "hint_carry(9,1)."]
    # B: one shelf per line, the nearest
    assert _greedy({(1, 10): 1}, stock, haul, {1: 4}, options, 1, False) == [
        "hint_give(3,1,10,1).", "hint_carry(8,3)."]


def test_the_shelves_a_greedy_start_uses_get_robots_of_their_own_first():
    import numpy as np

    from asprilo.encodings.anytime.assignment import _greedy, _matching

    # two robots (rows), three shelves (columns), one shelf each; shelf 0 is nearest to both.
    # Nearest first: shelf 0 takes robot 0, shelf 1 robot 1 (5 steps), none is left for shelf 2
    distance = np.array([[1.0, 2.0, 5.0], [1.0, 5.0, 3.0]])
    assert _matching(distance, 1) == {(0, 0), (1, 1)}
    # shelves 1 and 2 are those the start uses: matched first, robot 0 to 1 (2), robot 1 to 2 (3)
    assert _matching(distance, 1, [1, 2]) == {(0, 1), (1, 2)}
    # the start's shelves go to the robots matched to them, not to the nearest with room
    stock, haul = {1: {10: 2}, 3: {10: 1}}, {(1, 4): 5, (3, 4): 2}
    options = [(7, 3, 4), (8, 3, 1), (8, 1, 2), (9, 1, 6)]
    assert _greedy({(1, 10): 3}, stock, haul, {1: 4}, options, 1, True, {3: 7, 1: 8}) == [
        "hint_give(3,1,10,1).", "hint_give(1,1,10,2).", "hint_carry(7,3).", "hint_carry(8,1)."]


def test_a_greedy_start_changes_where_the_search_begins_not_the_optimum():
    # the facts of the nearest-shelf test, with hints for the worse shelf and robot
    facts = ["line(1,1,1).", "order(1,1).", "holds(1,1,1).", "holds(2,1,1).", "haul(1,1,5).", "haul(2,1,2).",
             "option(1,1,1).", "option(1,2,6).", "option(2,2,1).", "option(2,1,7).", "cap(1).",
             "hint_give(1,1,1,1).", "hint_carry(2,1)."]
    choice = _optimum(Assigner("assign_shelves.lp", facts, {"domain": "b"}, ["--heuristic=Domain"]))
    assert choice.of("give") == [(2, 1, 1, 1)]
    assert choice.of("carry") == [(2, 2)]
