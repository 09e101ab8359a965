"""The checker's API, its metrics, raw facts given to its programs, and the ``check`` command."""

from __future__ import annotations

import io
import json
import sys

import pytest
from helpers import EXAMPLES, OUTCOME, SMALL_A, WRONG_OUTCOME
from helpers.worlds import plan, walk, world

from asprilo.bounds import cheap_bounds, makespan_bound
from asprilo.checker import check
from asprilo.checker.programs import run_checker
from asprilo.cli import main
from asprilo.domain import Domain
from asprilo.reader import read_instance, read_plan

B_INSTANCE = EXAMPLES / "encodings-repo/x46_y15_n690_r10_s160_ps10_pr5_u10_o2_N1.lp"
B_PLAN = EXAMPLES / "encodings-repo/x46_y15_n690_r10_s160_ps10_pr5_u10_o2_N1.plan"


@pytest.fixture(scope="module")
def small_a():
    return read_instance(SMALL_A)


# --- acceptance --------------------------------------------------------------------------

def test_outcome_is_valid_for_a(small_a):
    report = check(small_a, read_plan(OUTCOME))
    assert (report.valid, report.domain, report.horizon, report.errors) == (True, Domain.A, 29, [])


def test_wrong_outcome_gives_the_three_errors_of_the_original_checker(small_a):
    report = check(small_a, read_plan(WRONG_OUTCOME))
    assert [e.atom for e in report.errors] == [
        "err(deliver,orderAmount,(1,23))", "err(deliver,shelfAmount,(1,23))", "err(goal,unfilledOrder,(1,2,1,29))"]
    first = report.errors[0]
    assert (first.module, first.check, first.params, first.step) == ("deliver", "orderAmount", (1, 23), 23)
    assert first.message == ("step 23: robot 1 delivers 6 units of product 5 for order 2, "
                             "but the order needs only 5 more")


def test_the_b_plan_puts_shelves_down_on_highways_three_times():
    report = check(read_instance(B_INSTANCE), read_plan(B_PLAN))
    assert report.domain is Domain.B
    assert [e.atom for e in report.errors] == [
        "err(putdown,onHighway,(9,44))", "err(putdown,onHighway,(8,45))", "err(putdown,onHighway,(10,45))"]


def test_packed_and_plain_facts_give_the_same_atoms(small_a):
    from asprilo.checker.programs import err_atoms
    wrong = read_plan(WRONG_OUTCOME)
    packed = sorted(map(str, err_atoms(small_a, wrong, Domain.A, packed=True)[0]))
    plain = sorted(map(str, err_atoms(small_a, wrong, Domain.A, packed=False)[0]))
    assert packed == plain and len(packed) == 3


# --- metrics -----------------------------------------------------------------------------

def test_metrics_of_the_outcome(small_a):
    report = check(small_a, read_plan(OUTCOME), bound="strong")
    bound = makespan_bound(small_a, Domain.A)  # its value is tested on hand-made cases in test_bounds.py
    assert report.metrics == {
        "horizon": 29, "actions": {"deliver": 11, "move": 58, "pickup": 5, "putdown": 5},
        "sum_of_costs": 87, "idle_steps": 8, "orders": 3, "orders_fulfilled": 3, "bounds": "strong",
        "makespan_bound": bound, "makespan_ratio": round(29 / bound, 3)}
    assert 0 < bound <= 29  # the outcome is a valid plan of 29 steps
    cheap = check(small_a, read_plan(OUTCOME)).metrics  # by default: the cheap bound
    assert (cheap["bounds"], cheap["makespan_bound"]) == ("cheap", cheap_bounds(small_a, Domain.A)[0]) == ("cheap", 17)
    assert check(small_a, read_plan(WRONG_OUTCOME)).metrics["orders_fulfilled"] == 2


def test_m_metrics_have_assignment_bounds():
    # robot 1 at (1,1) and robot 2 at (2,2); shelf 1 at (4,1) and shelf 2 at (1,2): each
    # assignment has a robot 3 steps away, the cheapest costs 3 + 1
    instance = world("R..S/SR..", products={1: {1: 1}, 2: {2: 1}}, orders={1: ({1: 1}, None), 2: ({2: 1}, None)})
    steps = plan(*walk(1, "EEE"), (1, 2, "W"))
    report = check(instance, steps, bound="strong")
    assert report.valid and report.domain is Domain.M
    assert report.metrics == {
        "horizon": 3, "actions": {"move": 4}, "sum_of_costs": 4, "idle_steps": 2, "orders": 2,
        "orders_fulfilled": 2, "bounds": "strong", "makespan_bound": 3, "sum_of_costs_bound": 4,
        "sum_of_costs_ratio": 1.0, "makespan_ratio": 1.0}
    # the cheap pair gives each shelf its nearest robot: 3 steps to shelf 1, 1 to shelf 2
    cheap = check(instance, steps).metrics
    assert (cheap["bounds"], cheap["makespan_bound"], cheap["sum_of_costs_bound"]) == ("cheap", 3, 4)


def test_md_metrics_count_destinations():
    report = check(world("R.D/D.."), plan(*walk(1, "EE")))
    assert report.domain is Domain.MD
    assert (report.metrics["destinations"], report.metrics["destinations_reached"]) == (2, 1)
    assert [e.atom for e in report.errors] == ["err(goal,unoccupiedDestination,(2,2))"]


# --- raw facts ---------------------------------------------------------------------------

def _raw(text: str, domain: Domain = Domain.M) -> list[str]:
    return sorted(str(atom) for atom in run_checker(text, domain)[0])


def test_a_grid_instance_gives_all_nodes_of_the_rectangle():
    grid = "init(object(grid,1),value(xsize,3)). init(object(grid,1),value(ysize,2)). " \
           "init(object(robot,1),value(at,(1,1))). "
    assert _raw(grid + "occurs(object(robot,1),action(move,(1,0)),1). "
                       "occurs(object(robot,1),action(move,(0,1)),2).") == []
    assert _raw(grid + "occurs(object(robot,1),action(move,(0,-1)),1).") == ["err(move,offFloor,(1,1))"]


def test_raw_facts_the_reader_would_reject_are_reported():
    floor = "init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))). "
    assert _raw(floor + "init(object(robot,1),value(at,(1,1))). init(object(robot,1),value(at,(2,1))).") == [
        "err(instance,manyPositions,(robot,1,0))"]
    orders = (floor + "init(object(node,3),value(at,(3,1))). init(object(pickingStation,1),value(at,(2,1))). "
              "init(object(pickingStation,2),value(at,(3,1))). "
              "init(object(robot,1),value(at,(1,1))). init(object(shelf,1),value(at,(1,1))). "
              "init(object(product,1),value(on,(1,0))). init(object(order,1),value(line,(1,0))). "
              "init(object(order,1),value(pickingStation,1)). init(object(order,1),value(pickingStation,2)). ")
    assert _raw(orders, Domain.A) == ["err(instance,orderStation,(1,0))"]
    assert _raw(floor + "init(object(robot,1),value(at,(1,1))). occurs(object(robot,1),action(move,(1,0)),a).") == [
        "err(action,badStep,(1,a))"]


def test_quantity_free_facts_count_one_unit_in_a():
    facts = ("init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))). "
             "init(object(pickingStation,1),value(at,(2,1))). init(object(robot,1),value(at,(1,1))). "
             "init(object(shelf,1),value(at,(1,1))). init(object(product,1),value(on,1)). "
             "init(object(order,1),value(line,1)). init(object(order,1),value(pickingStation,1)). "
             "occurs(object(robot,1),action(pickup,()),1). occurs(object(robot,1),action(move,(1,0)),2). ")
    assert _raw(facts + "occurs(object(robot,1),action(deliver,(1,1,1)),3).", Domain.A) == []
    assert _raw(facts + "occurs(object(robot,1),action(deliver,(1,1,2)),3).", Domain.A) == [
        "err(deliver,orderAmount,(1,3))", "err(deliver,shelfAmount,(1,3))"]


# --- the command -------------------------------------------------------------------------

def _run(capsys, *argv, stdin: str | None = None) -> tuple[int, str, str]:
    if stdin is not None:
        sys.stdin = io.StringIO(stdin)
    try:
        code = main(["check", *map(str, argv)])
    finally:
        sys.stdin = sys.__stdin__
    out, err = capsys.readouterr()
    return code, out, err


BOUND = int(cheap_bounds(read_instance(SMALL_A), Domain.A)[0])


def test_check_prints_one_line_per_violation_then_a_summary(capsys):
    code, out, _ = _run(capsys, SMALL_A, WRONG_OUTCOME)
    assert code == 1
    assert out.splitlines() == [
        "step 23: robot 1 delivers 6 units of product 5 for order 2, but the order needs only 5 more",
        "step 23: robot 1 delivers 6 units of product 5 for order 2, but shelf 2 holds only 5",
        "step 29 (the horizon): order 1 still lacks 1 unit of product 2",
        "invalid plan: 3 violations (domain A (detected), horizon 29)",
        "actions: 79 (11 deliver, 58 move, 5 pickup, 5 putdown); sum of costs 87, idle steps 8",
        "orders fulfilled: 2 of 3",
        f"lower bounds (cheap; --bound strong for the strongest): makespan {BOUND} (plan/bound {29 / BOUND:.2f})",
    ]


def test_check_and_solve_report_the_same_bound(small_a):
    from asprilo.encodings import solve
    for domain in (Domain.A, Domain.B, Domain.C):
        checked = check(small_a, read_plan(OUTCOME), domain, bound="strong").metrics["makespan_bound"]
        assert solve(small_a, domain, horizon=1).lower_bound == checked


def test_check_valid_plan_exits_0_and_reads_clingo_output_from_stdin(capsys):
    facts = OUTCOME.read_text().split("\n")
    printed = "clingo version 5.8.3\nReading from stdin\nSolving...\nAnswer: 1\n" + " ".join(
        line.rstrip(".") for line in facts if line.startswith("occurs")) + "\nSATISFIABLE\n"
    code, out, _ = _run(capsys, SMALL_A, "-", stdin=printed)
    assert code == 0
    assert out.splitlines()[0] == "valid plan (domain A (detected), horizon 29)"


def test_check_json(capsys):
    code, out, _ = _run(capsys, SMALL_A, WRONG_OUTCOME, "--json", "--domain", "b")
    report = json.loads(out)
    assert code == 1
    assert set(report) == {"valid", "domain", "horizon", "errors", "metrics"}
    assert (report["valid"], report["domain"], report["horizon"]) == (False, "b", 29)
    assert report["errors"][0] == {
        "atom": "err(deliver,lineClosed,(1,18))", "module": "deliver", "check": "lineClosed", "params": [1, 18],
        "step": 18, "message": "step 18: robot 1 delivers product 5 for order 2, but order 2 has no open line "
                               "for product 5"}
    assert [e["atom"] for e in report["errors"]] == [
        "err(deliver,lineClosed,(1,18))", "err(deliver,lineClosed,(1,19))", "err(deliver,lineClosed,(1,23))",
        "err(deliver,lineClosed,(2,24))", "err(deliver,lineClosed,(2,26))"]
    assert report["metrics"]["orders_fulfilled"] == 3


def test_a_plan_for_robots_the_instance_lacks_is_refused_in_one_sentence_as_viz_refuses_it(write, capsys):
    instance = write("i.lp", "init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))). "
                             "init(object(robot,1),value(at,(1,1))).")
    steps = write("p.lp", "occurs(object(robot,4),action(move,(1,0)),1). occurs(object(robot,1),action(fly,()),2).")
    assert _run(capsys, instance, steps) == (
        2, "", f"warning: {steps}:1: there is no action 'fly' (the actions: deliver, move, pickup, putdown)\n"
               f"error: {steps}:1: the plan moves robot 4, but the instance has robot 1 "
               "(plan and instance do not fit)\n")
    # the checker itself (the API) still reports both as violations
    report = check(read_instance(instance), read_plan(steps))
    assert [error.message for error in report.errors][:2] == [
        "step 1: the plan moves robot 4, but the instance has no robot 4",
        "step 2: robot 1 does 'fly', which is not an action of domain M"]


@pytest.mark.parametrize("plan_text, message", [
    (None, "no such file"),
    ("occurs(object(robot,1),action(move,(1,0)),1", "syntax error"),
])
def test_bad_input_exits_2_with_one_message(write, capsys, plan_text, message):
    path = write("p.lp", plan_text) if plan_text is not None else "missing.lp"
    code, out, err = _run(capsys, SMALL_A, path)
    assert code == 2 and out == ""
    assert err.startswith("error: ") and message in err and "Traceback" not in err
