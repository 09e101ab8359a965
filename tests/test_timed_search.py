"""The Python routing engine (asprilo/encodings/anytime/timed_search.py) against ``route.lp``: the same
earliest arrival on every routing call of the anytime planner, and routes that keep every
rule of the space (checked here step by step, apart from both engines)."""

from __future__ import annotations

import pytest
from helpers.clocks import patient_anytime
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from test_anytime import _assert_sound, _instance

from asprilo.domain import Domain, domains
from asprilo.encodings.anytime import plan_anytime
from asprilo.encodings.anytime import router as router_module
from asprilo.encodings.anytime.errands import Task
from asprilo.encodings.anytime.space import Space
from asprilo.encodings.anytime.timed_search import search


def _legal(space: Space, cells: list, done: dict) -> None:
    """Every step of a route keeps the rules of ``route.lp`` (its docstring)."""
    number = 1
    for index, cell in enumerate(cells):
        step = space.step + index
        if index:
            before = cells[index - 1]
            assert abs(cell[0] - before[0]) + abs(cell[1] - before[1]) <= 1
            assert (cell, before, step) not in space.crossings
            if step in done:
                assert done[step] is space.tasks[number - 1] and cell == before
                assert before in space.task_cells[number - 1] and step >= space.settle.get(number, step)
                assert step <= space.due.get(number, step)
                number += 1
        first, last = space.windows[number - 1][cell]
        assert first <= step <= last and step not in space.busy.get(cell, ())
        assert step < space.stays.get(cell, step + 1)
        if space.carrying(number):
            assert not any(since <= step <= until for since, until in space.rests.get(cell, ()))
    assert number == space.last and cells[-1] in space.task_cells[-1]
    assert space.step + len(cells) - 1 >= space.free_from.get(cells[-1], 0)


@pytest.fixture
def compared(monkeypatch) -> list:
    """Route with both engines on every call; the calls as (python arrival, asp arrival)."""
    calls = []

    def both(space: Space):
        found, expected = search(space), router_module.asp_search(space)
        arrival = None if found is None else space.step + len(found[0]) - 1
        calls.append((arrival, None if expected is None else space.step + len(expected[0]) - 1))
        if found is not None:
            _legal(space, *found)
        return found

    monkeypatch.setitem(router_module.ENGINES, "python", both)
    return calls


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow,
                                                                  HealthCheck.function_scoped_fixture])
@given(domain=st.sampled_from(domains()), seed=st.integers(1, 10**6), robots=st.integers(1, 5),
       width=st.integers(4, 8), height=st.integers(3, 6))
def test_both_engines_find_the_same_earliest_arrival(compared, domain, seed, robots, width, height):
    compared.clear()
    instance = _instance(domain, seed, robots, width, height)
    result = plan_anytime(instance, domain, time_limit=0.5)  # the calls made by then agree
    _assert_sound(result, instance, domain)
    assert [python for python, _asp in compared] == [asp for _python, asp in compared]


def _corridor(busy: dict | None = None, crossings: set | None = None) -> Space:
    """A robot on (1,1) of a corridor (1,1)..(5,1) that is to park on (5,1), windows wide
    open (steps 0..20 everywhere)."""
    cells = [(x, 1) for x in range(1, 6)]
    space = Space((1, 1), 0, [Task("park", ((5, 1),))], [{cell: (0, 20) for cell in cells}])
    space.task_cells = [{(5, 1)}]
    space.busy.update(busy or {})
    space.crossings.update(crossings or set())
    space.estimate([20], [4])
    space.windows = [{cell: (0, 20 - (5 - cell[0])) for cell in cells}]  # as the router makes them
    return space


def test_a_free_corridor_is_walked_straight():
    cells, done = search(_corridor())
    assert cells == [(1, 1), (2, 1), (3, 1), (4, 1), (5, 1)] and done == {}


def test_the_robot_waits_for_a_robot_standing_in_its_way():
    # another robot is on (3,1) after steps 0..3: the robot can be there at step 4 at the
    # earliest, so it parks at step 6 (by hand: 2 steps to (3,1) + 2 waits + 2 steps on)
    cells, _done = search(_corridor(busy={(3, 1): {0, 1, 2, 3}}))
    assert len(cells) - 1 == 6 and cells[4] == (3, 1)


def test_it_never_swaps_cells_with_another_robot():
    # another robot comes from (2,1) to (1,1) at step 1: ours cannot stay on (1,1), and its
    # only move, to (2,1), would swap the two robots
    swapping = _corridor(busy={(2, 1): {0}, (1, 1): {1}})
    assert search(swapping)[0][:2] == [(1, 1), (2, 1)]  # the move, were it not a swap
    swapping.crossings.add(((2, 1), (1, 1), 1))
    assert search(swapping) is None


def test_a_robot_that_cannot_get_through_gets_no_route():
    space = _corridor()
    space.stays[(3, 1)] = 0  # another robot parked in the middle for good
    assert search(space) is None


@pytest.mark.parametrize("domain", [Domain.A, Domain.MD])
def test_both_engines_agree_on_a_paper_instance(compared, domain, monkeypatch):
    from test_anytime import PAPER

    from asprilo.interop.convert import m_to_md
    from asprilo.reader import read_instance

    instance = read_instance(PAPER / "2x3x5/x19_y9_n171_r10_s60_ps3_pr60_u60_o10_N001.lp")
    instance = m_to_md(instance) if domain is Domain.MD else instance
    # the search stops once it has a plan and both engines routed 10 times
    clock = patient_anytime(monkeypatch, enough=lambda: len(compared) >= 10)
    _assert_sound(plan_anytime(instance, domain, time_limit=3, on_improvement=clock.reported), instance, domain)
    assert len(compared) >= 10
    assert [python for python, _asp in compared] == [asp for _python, asp in compared]


def test_a_space_looked_up_cell_by_cell_routes_as_one_gathered_whole(monkeypatch):
    # every routing call of a first plan on a paper instance: the lazy space the Python
    # engine gets (Space.gather(lazy=True), cells looked up as the search comes near) and
    # the space gathered in full give the same route
    from test_anytime import PAPER

    from asprilo.reader import read_instance

    instance = read_instance(PAPER / "2x3x5/x19_y9_n171_r10_s60_ps3_pr60_u60_o10_N001.lp")
    routes = []
    gather = Space.gather

    def both(robot, table, tasks, windows, begin, step, lazy=False):
        routes.append((gather(robot, table, tasks, windows, begin, step, lazy=True),
                       gather(robot, table, tasks, windows, begin, step)))
        return routes[-1][0]

    def compare(space: Space):
        whole = routes[-1][1]
        whole.deadlines, whole.tails = space.deadlines, space.tails  # as Space.estimate set them
        found = search(space)
        assert found == search(whole)
        return found

    monkeypatch.setattr(Space, "gather", staticmethod(both))
    monkeypatch.setitem(router_module.ENGINES, "python", compare)
    clock = patient_anytime(monkeypatch)
    _assert_sound(plan_anytime(instance, Domain.A, time_limit=3, on_improvement=clock.reported), instance, Domain.A)
    assert len(routes) >= 10


def test_a_long_way_across_an_open_floor_is_routed_in_a_corridor_when_the_wide_level_is_too_big(monkeypatch):
    # a 40x40 floor without walls, from one corner to the other: every cell lies on a
    # shortest way, so the first level's windows cover the whole floor (1,600 cells); with
    # room for 30,000 (cell, step) pairs only a corridor of radius 3 around one way fits
    # (at most 7 cells across 79 cells of the way, each a window of at most 31 steps:
    # about 17,000); on a free floor the robot parks after 78 steps (39 + 39, by hand)
    from helpers.worlds import md

    from asprilo.bounds import Floor
    from asprilo.encodings.anytime.errands import goal_errand
    from asprilo.encodings.anytime.grid import Grid
    from asprilo.encodings.anytime.reservations import Reservations
    from asprilo.encodings.anytime.router import Router

    instance = md([(x, y) for x in range(1, 41) for y in range(1, 41)], [(1, 1)], [(40, 40)])
    router = Router(Grid(Floor(instance.cells)), Reservations(instance, {}))
    sizes = []
    monkeypatch.setitem(router_module.ENGINES, "python", lambda space: sizes.append(len(space.windows[0])) or
                        search(space))
    monkeypatch.setitem(router_module.MAX_SLOTS, "python", 30_000)
    cells, _done = router.route(1, goal_errand((40, 40)), (1, 1))
    assert len(cells) - 1 == 78 and cells[-1] == (40, 40)
    assert len(sizes) == 1 and sizes[0] < 7 * 79
    monkeypatch.setitem(router_module.MAX_SLOTS, "python", 1_000)  # not even the corridor fits
    assert router.route(1, goal_errand((40, 40)), (1, 1)) is None and len(sizes) == 1
