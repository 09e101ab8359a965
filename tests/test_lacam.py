"""LaCAM's first plans for M and Md (asprilo/encodings/anytime/lacam.py over the PIBT steps of
pibt.py): tracks that keep the rules, checked here apart from the planner, plans where robots
must take turns in a dead end, and no tracks where no plan exists."""

from __future__ import annotations

import pytest
from helpers import EXAMPLES
from helpers.clocks import patient_anytime

from asprilo.bounds import Floor
from asprilo.encodings.anytime.lacam import lacam_tracks
from asprilo.encodings.anytime.pibt import Pibt
from asprilo.encodings.anytime.roadmap import Roadmap


def _keeps_the_rules(tracks, starts, goals) -> None:
    """One cell per robot per step, moves to neighbours, no swaps, all at their goals at the end."""
    steps = max(track.parked for track in tracks.values())
    for robot, track in tracks.items():
        assert track.cells[0] == starts[robot] and track.cells[-1] == goals.get(robot, starts[robot])
    for step in range(1, steps + 1):
        before = {robot: track.at(step - 1) for robot, track in tracks.items()}
        now = {robot: track.at(step) for robot, track in tracks.items()}
        assert len(set(now.values())) == len(now)
        for robot in now:
            (x, y), (u, v) = before[robot], now[robot]
            assert abs(x - u) + abs(y - v) <= 1
            assert not any(now[robot] == before[other] and now[other] == before[robot]
                           for other in now if other != robot)


def test_two_robots_pass_each_other_on_a_ring():
    # a 3x2 block: the robots swap the ends of row 1; both cannot go straight (they would
    # swap cells), so by hand one of them goes round by row 2: 2 steps more, makespan >= 4
    floor = Floor([(x, y) for x in (1, 2, 3) for y in (1, 2)])
    starts, goals = {1: (1, 1), 2: (3, 1)}, {1: (3, 1), 2: (1, 1)}
    tracks = lacam_tracks(floor, starts, goals, lambda: False)
    _keeps_the_rules(tracks, starts, goals)
    assert max(track.finish for track in tracks.values()) >= 4


def test_robots_take_turns_in_a_dead_end():
    # a corridor (1,1)..(4,1) with a pocket (2,2): one robot must wait in the pocket while the
    # other passes; plain PIBT steps push the two back and forth for ever (checked first)
    floor = Floor([(1, 1), (2, 1), (3, 1), (4, 1), (2, 2)])
    starts, goals = {1: (1, 1), 2: (4, 1)}, {1: (4, 1), 2: (1, 1)}
    roadmap = Roadmap(floor)
    robots = sorted(starts)
    aims = [roadmap.vertex(goals[robot]) for robot in robots]
    pibt, at = Pibt(roadmap, aims, swap=False), [roadmap.vertex(starts[robot]) for robot in robots]
    for _ in range(50):
        at = pibt.step(at, [0, 1])
    assert at != aims
    tracks = lacam_tracks(floor, starts, goals, lambda: False)
    _keeps_the_rules(tracks, starts, goals)


def test_the_swap_move_backs_away_and_pulls_the_other_robot_to_the_branch():
    # the same corridor: robot 1 on (2,1) wants (3,1), where robot 2 stands, which wants to
    # come back past it; ahead lies the dead end (4,1), behind the branch (2,1) with two ways
    # on: so robot 1 backs away from its goal, to (1,1) or (2,2), and pulls robot 2 after it
    floor = Floor([(1, 1), (2, 1), (3, 1), (4, 1), (2, 2)])
    roadmap = Roadmap(floor)
    aims = [roadmap.vertex((4, 1)), roadmap.vertex((1, 1))]
    for seed in range(10):
        pibt = Pibt(roadmap, aims, seed)
        after = pibt.step([roadmap.vertex((2, 1)), roadmap.vertex((3, 1))], [0, 1])
        assert roadmap.cells[after[1]] == (2, 1) and roadmap.cells[after[0]] in {(1, 1), (2, 2)}
        at = after
        for _ in range(30):
            at = pibt.step(at, [0, 1])
        assert at == aims


def test_a_robot_without_a_goal_steps_aside_and_comes_back():
    floor = Floor([(1, 1), (2, 1), (3, 1), (2, 2)])
    starts, goals = {1: (1, 1), 2: (2, 1)}, {1: (3, 1)}
    tracks = lacam_tracks(floor, starts, goals, lambda: False)
    _keeps_the_rules(tracks, starts, goals)
    # robot 1 can only reach (3,1) through (2,1): robot 2 must leave it, and come back
    assert tracks[2].cells[-1] == (2, 1) and len(set(tracks[2].cells)) >= 2


def test_no_tracks_where_the_robots_cannot_pass_each_other():
    floor = Floor([(1, 1), (2, 1), (3, 1)])
    assert lacam_tracks(floor, {1: (1, 1), 2: (3, 1)}, {1: (3, 1), 2: (1, 1)}, lambda: False) is None


def test_no_tracks_when_a_goal_cannot_be_reached():
    floor = Floor([(1, 1), (2, 1), (5, 5)])
    assert lacam_tracks(floor, {1: (1, 1)}, {1: (5, 5)}, lambda: False) is None


def test_the_planner_falls_back_on_prioritized_planning_when_lacam_finds_nothing(monkeypatch):
    from test_anytime import PAPER, _assert_sound

    from asprilo.domain import Domain
    from asprilo.encodings.anytime import plan_anytime
    from asprilo.encodings.anytime import search as anytime_search
    from asprilo.interop.convert import m_to_md
    from asprilo.reader import read_instance

    asked = []
    monkeypatch.setattr(anytime_search, "lacam_tracks", lambda *args: asked.append(args) or None)
    instance = m_to_md(read_instance(PAPER / "1x2x4/x11_y6_n66_r8_s16_ps1_pr16_u16_o8_N001.lp"))
    clock = patient_anytime(monkeypatch)  # time runs out after the first plan, on any machine
    result = plan_anytime(instance, Domain.MD, time_limit=3, on_improvement=clock.reported)
    assert len(asked) == 1 and result.status == "found"
    _assert_sound(result, instance, Domain.MD)


def test_labelled_agents_get_lacams_plan_then_refined_ones(monkeypatch):
    # every robot has a goal of its own (MovingAI, labelled): LaCAM's plan goes straight to the
    # refinement (no prioritized planning), whose plans pass the checker and only get better.
    # The clock moves on only when the search reads it: the same run on every machine.
    from test_anytime import ReadClock, _assert_sound

    from asprilo.domain import Domain
    from asprilo.encodings.anytime import plan_anytime
    from asprilo.encodings.anytime import search as anytime_search
    from asprilo.interop.convert import scenario_to_instance
    from asprilo.interop.movingai import parse_map, parse_scenario
    from asprilo.sources import Source

    movingai = EXAMPLES / "movingai"
    grid = parse_map(Source.from_path(movingai / "random-32-32-20.map"))
    tasks = parse_scenario(Source.from_path(movingai / "random-32-32-20-random-1.scen"))
    instance = scenario_to_instance(grid, tasks, 100, labelled=True)
    monkeypatch.setattr(anytime_search, "first_tracks", lambda *args: pytest.fail("prioritized planning ran"))
    monkeypatch.setattr(anytime_search, "time", ReadClock(tick=4.0 / 4000))
    result = plan_anytime(instance, Domain.MD, time_limit=4.0)
    _assert_sound(result, instance, Domain.MD)
    assert result.status == "found" and len(result.history) >= 2 and result.stats["neighbourhoods"] > 0
