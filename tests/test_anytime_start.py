"""A plan to start from (issue 45, ``asprilo solve --start PLAN``): the anytime planner reports
it first and only shorter plans after it, improves it where it can read its work out of it,
and takes a plan of a stronger reading (C relaxes B relaxes A).  Every plan derived by hand.

``siding()`` (from test_anytime_parking): station (1,1), highway (2..5,1), robot 1 on (6,1),
shelf 1 on (6,2) holding the product of the one order, one spare storage cell (2,2).  The
robot fetches the shelf: S (1), lift (2), N W W W W W (8), deliver (9): 9 is the minimum.
The planner's own first plan parks the shelf on (2,2) afterwards: E S, 11 (derived there).

``one_shelf()`` (from test_anytime_readings): station (1,1), highway (2,1), robot on (3,1),
shelf 1 on (2,2) holding products 1 and 2, order 1 asks both at the station: W S lift N W
(5), then B delivers line (1,1) at 6 and (1,2) at 7; as C the delivery at 6 closes both, so
the one at 7 closes nothing: the C plan ends at 6, the lower bound.
"""

from __future__ import annotations

import pytest
from helpers.clocks import patient_anytime
from helpers.worlds import md, plan, walk
from test_anytime_parking import siding
from test_anytime_readings import one_shelf

from asprilo.bounds import Floor
from asprilo.checker import check
from asprilo.cli import main
from asprilo.domain import Domain
from asprilo.encodings.anytime import plan_anytime
from asprilo.encodings.anytime.grid import Grid
from asprilo.encodings.anytime.readings import plan_readings, reading_plan, readings
from asprilo.encodings.anytime.start import rebuild, tracks_of
from asprilo.encodings.anytime.work import Work
from asprilo.errors import InputError
from asprilo.writer import format_instance, format_plan

FETCH = [*walk(1, "S"), (2, 1, "pickup"), *walk(1, "NWWWWW", 3), (9, 1, "deliver", (1, 1, 1))]
#: the siding's plan that steps off the station with the shelf at the end: 10, one above the minimum
STEP_OFF = plan(*FETCH, (10, 1, "E"))
#: the one-shelf floor's plan under B: both lines delivered one by one (7)
B_PLAN = plan(*walk(1, "WS"), (3, 1, "pickup"), *walk(1, "NW", 4), (6, 1, "deliver", (1, 1)),
              (7, 1, "deliver", (1, 2)))


def _actions(some_plan) -> list[tuple]:
    return sorted((a.step, a.robot, a.name, a.args) for a in some_plan.actions)


def test_a_start_plan_shorter_than_the_first_plan_is_reported_first_and_improved(monkeypatch):
    instance = siding()
    assert check(instance, STEP_OFF, Domain.A).valid
    clock = patient_anytime(monkeypatch, stop_after=None)  # it stops at the lower bound, 9
    result = plan_anytime(instance, Domain.A, time_limit=120, on_improvement=clock.reported, start=STEP_OFF)
    assert _actions(result.history[0].plan) == _actions(STEP_OFF)
    assert [better.makespan for better in result.history] == [10, 9]
    assert _actions(result.plan) == _actions(plan(*FETCH))
    assert result.minimal and result.stats["start"] == "the search started from the plan given"


def test_the_work_of_a_plan_is_read_out_of_its_tracks():
    instance = siding()
    tracks = tracks_of(STEP_OFF, instance)
    assert tracks[1].cells == [(6, 1), (6, 2), (6, 2), (6, 1), (5, 1), (4, 1), (3, 1), (2, 1), (1, 1), (1, 1), (2, 1)]
    assert [(step, task.name, task.shelf) for step, task in sorted(tracks[1].done.items())] == \
        [(2, "pickup", 1), (9, "deliver", 1)]
    work = Work(instance, Domain.A, Grid(Floor(instance.cells)), 9)
    assert rebuild(work, tracks) is None
    assert [(trip.shelf, trip.deliveries) for trip in work.trips[1]] == [(1, [((1, 1), ((1, 1),), (1, 1, 1))])]
    assert work.choice.of("carry") == [(1, 1)] and work.choice.of("give") == [(1, 1, 1, 1)]


def test_a_plan_whose_work_cannot_be_read_is_kept_as_given(monkeypatch):
    # the robot lifts the shelf, puts it down and lifts it again before it goes: 11, as long as
    # the planner's own first plan, which the search improves to 9 instead
    instance = siding()
    lifts = plan(*walk(1, "S"), (2, 1, "pickup"), (3, 1, "putdown"), (4, 1, "pickup"), *walk(1, "NWWWWW", 5),
                 (11, 1, "deliver", (1, 1, 1)))
    assert check(instance, lifts, Domain.A).valid
    clock = patient_anytime(monkeypatch, stop_after=None)
    result = plan_anytime(instance, Domain.A, time_limit=120, on_improvement=clock.reported, start=lifts)
    assert [better.makespan for better in result.history] == [11, 9]
    assert _actions(result.history[0].plan) == _actions(lifts)
    assert result.stats["start"] == ("the plan given was kept as given (robot 1 carries shelf 1 without "
                                     "delivering from it): the search started from its own first plan")


def test_a_start_plan_longer_than_the_first_plan_only_bounds_the_answer(monkeypatch):
    instance = siding()
    late = plan(*FETCH, *walk(1, "EEE", 10))  # 12: the planner's first plan (11) is shorter
    clock = patient_anytime(monkeypatch, stop_after=None)
    result = plan_anytime(instance, Domain.A, time_limit=120, on_improvement=clock.reported, start=late)
    assert [better.makespan for better in result.history] == [12, 11, 9]
    assert result.stats["start"] == "the planner's own first plan was shorter than the plan given"


def test_a_b_plan_given_to_c_is_a_c_plan_no_longer(monkeypatch):
    instance = one_shelf()
    assert check(instance, B_PLAN, Domain.B).valid and not check(instance, B_PLAN, Domain.C).valid
    as_c = reading_plan(instance, Domain.C, B_PLAN)
    assert _actions(as_c) == _actions(plan(*walk(1, "WS"), (3, 1, "pickup"), *walk(1, "NW", 4),
                                           (6, 1, "deliver", (1, 1))))
    clock = patient_anytime(monkeypatch, stop_after=None)
    result = plan_anytime(instance, Domain.C, time_limit=120, on_improvement=clock.reported, start=as_c)
    assert [better.makespan for better in result.history] == [6]
    assert result.minimal


def test_the_readings_in_one_call_never_grow(monkeypatch):
    # A and B deliver the two lines one by one, at 6 and 7 (their lower bounds, 7); C's delivery
    # at 6 closes both: B's plan as C ends at 6 (its bound).  Each search stops at its bound.
    instance = one_shelf()
    assert [domain.label for domain in readings(Domain.C)] == ["C", "B", "A"]
    patient_anytime(monkeypatch, stop_after=None)
    found = plan_readings(instance, Domain.C, time_limit=120)
    assert {label: result.makespan for label, result in found.items()} == {"A": 7, "B": 7, "C": 6}
    assert [found[label].history[0].makespan for label in "BC"] == [7, 6]  # each starts from the plan before
    assert all(result.minimal for result in found.values())


def test_an_md_plan_is_a_start_too(monkeypatch):
    # corridor (1..4,1): robot 1 on (1,1) to destination 1 on (3,1), robot 2 on (2,1) to 2 on
    # (4,1); one after the other (2 goes at 1-2, 1 at 3-4) takes 4 steps, side by side 2
    instance = md([(x, 1) for x in range(1, 5)], [(1, 1), (2, 1)], [(3, 1), (4, 1)])
    queued = plan(*walk(2, "EE"), *walk(1, "EE", 3))
    assert check(instance, queued, Domain.MD).valid
    work = Work(instance, Domain.MD, Grid(Floor(instance.cells)), 2)
    assert rebuild(work, tracks_of(queued, instance)) is None
    assert work.goals == {1: (3, 1), 2: (4, 1)} and work.choice.of("aim") == [(1, 0), (2, 1)]
    instance.assignment = {1: ("destination", 1), 2: ("destination", 2)}  # labelled: refined
    clock = patient_anytime(monkeypatch, stop_after=None)
    result = plan_anytime(instance, Domain.MD, time_limit=120, on_improvement=clock.reported, start=queued)
    assert result.history[0].makespan == 4 and result.makespan == 2 and result.minimal


# --- the command -----------------------------------------------------------------------------

@pytest.fixture
def floor(write):
    return write("floor.lp", format_instance(one_shelf()))


def test_the_command_turns_a_b_plan_into_a_c_plan(floor, write, capsys):
    given = write("b.lp", format_plan(B_PLAN))
    assert main(["solve", str(floor), "--domain", "c", "--method", "anytime", "--start", str(given)]) == 0
    out, err = capsys.readouterr()
    assert out.splitlines()[-1] == "occurs(object(robot,1),action(deliver,(1,1)),6)."
    assert "plan: horizon 6 (proven minimal)" in err
    assert err.splitlines()[-1].endswith("; the search started from the plan given")


@pytest.mark.parametrize(("name", "text", "said"), [
    ("short.lp", format_plan(plan(*walk(1, "WS"), (3, 1, "pickup"), *walk(1, "NW", 4), (6, 1, "deliver", (1, 1))))
     , "short.lp: not a valid plan of this instance as B (nor as A): step 6 (the horizon): order 1 still waits for "
       "product 2"),
    ("other.lp", format_plan(plan(*walk(2, "W"))),
     "other.lp:1: the plan moves robot 2, but the instance has robot 1 (plan and instance do not fit)"),
    ("broken.lp", "occurs(object(robot,1),action(move,(1,0)),1", "broken.lp:1: syntax error, unexpected EOF"),
    ("missing.lp", None, "missing.lp: no such file"),
])
def test_a_bad_start_plan_is_one_sentence(floor, write, tmp_path, capsys, monkeypatch, name, text, said):
    monkeypatch.chdir(tmp_path)
    if text is not None:
        write(name, text)
    assert main(["solve", str(floor), "--domain", "b", "--method", "anytime", "--start", name]) == 2
    assert capsys.readouterr().err.strip() == f"error: {said}"


def test_the_exact_search_takes_no_start_plan(floor, write, capsys):
    given = write("b.lp", format_plan(B_PLAN))
    assert main(["solve", str(floor), "--domain", "b", "--method", "asp", "--start", str(given)]) == 2
    assert capsys.readouterr().err.strip() == ("error: --start goes with the anytime planner (--method auto or "
                                               "anytime): the exact search starts from no plan")


def test_reading_plan_names_the_file():
    with pytest.raises(InputError, match="^given.lp: not a valid plan of this instance as A: "):
        reading_plan(one_shelf(), Domain.A, B_PLAN, "given.lp")
