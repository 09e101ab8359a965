"""Rule variants (docs/VARIANTS.md): the built-in ones through ``check``, on tiny instances
whose plans and violations are derived by hand (tests/variants/*.lp say what they hold).

- corner.lp: a 3x3 floor, robot 1 at (1,1), the ordered product's shelf at (3,3).  Two
  diagonal moves (1,1) reach it at step 2; in M each is an ill-formed move.
- square.lp: a 2x2 floor, robots 1 at (1,1) and 2 at (2,1), the ordered shelves at (2,2) and
  (1,2).  Robot 1 moving (1,1) and robot 2 moving (-1,1) at step 1 use both diagonals of the
  square: their paths cross (both midpoints are (1.5,1.5)).
- corridor.lp: a 4x1 floor, robot 1 at (2,1) with energy 2, the ordered shelf at (4,1).  The
  middle is (4 + 1) // 2 = 2: the robot starts in the left half.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from asprilo.cli import main

HERE = Path(__file__).parent / "variants"
CORNER, SQUARE, CORRIDOR = HERE / "corner.lp", HERE / "square.lp", HERE / "corridor.lp"


def _plan(tmp_path: Path, *moves: tuple[int, tuple[int, int], int]) -> Path:
    path = tmp_path / "plan.lp"
    path.write_text("".join(f"occurs(object(robot,{robot}),action(move,({dx},{dy})),{step}).\n"
                            for robot, (dx, dy), step in moves))
    return path


def _check(capsys, *args) -> tuple[int, dict]:
    code = main(["check", *map(str, args), "--json"])
    return code, json.loads(capsys.readouterr().out)


def _messages(answer: dict) -> list[str]:
    return [error["message"] for error in answer["errors"]]


def test_diagonal_moves_are_refused_in_m_and_taken_under_the_variant(capsys, tmp_path):
    plan = _plan(tmp_path, (1, (1, 1), 1), (1, (1, 1), 2))
    code, answer = _check(capsys, CORNER, plan)
    assert code == 1 and [error["atom"] for error in answer["errors"]] == [
        "err(action,badArguments,(1,move,1))", "err(action,badArguments,(1,move,2))",
        "err(goal,unfilledOrder,(1,1,1,2))"]
    code, answer = _check(capsys, CORNER, plan, "--variant", "diagonal")
    assert (code, answer["valid"], answer["domain"]) == (0, True, "m+diagonal")
    assert answer["metrics"]["orders_fulfilled"] == 1 and answer["metrics"]["bounds"] == "none"


def test_a_move_the_variant_lacks_is_named_with_the_variants_moves(capsys, tmp_path):
    code, answer = _check(capsys, CORNER, _plan(tmp_path, (1, (2, 0), 1)), "--variant", "diagonal")
    assert code == 1 and _messages(answer)[0] == (
        "step 1: robot 1 does move with (2,0), but move takes (1,0), (-1,0), (0,1), (0,-1), (1,1), (1,-1), (-1,1) "
        "or (-1,-1)")


def test_two_robots_crossing_diagonally_are_reported_at_their_step(capsys, tmp_path):
    code, answer = _check(capsys, SQUARE, _plan(tmp_path, (1, (1, 1), 1), (2, (-1, 1), 1)), "--variant", "diagonal")
    assert code == 1
    assert [error["atom"] for error in answer["errors"]] == ["err(diagonal,crossing,(1,2,1))"]
    assert _messages(answer) == ["step 1: robots 1 and 2 cross each other's diagonal paths"]


def test_robots_swapping_on_a_diagonal_are_a_swap_not_a_crossing(capsys, tmp_path):
    """Robot 1 (1,1) -> (2,2) and a robot at (2,2) -> (1,1): the base's swap alone."""
    square = tmp_path / "swap.lp"
    square.write_text(SQUARE.read_text().replace("init(object(robot,2),value(at,(2,1))).",
                                                 "init(object(robot,2),value(at,(2,2)))."))
    code, answer = _check(capsys, square, _plan(tmp_path, (1, (1, 1), 1), (2, (-1, -1), 1)), "--variant", "diagonal")
    assert code == 1 and [error["atom"] for error in answer["errors"]][0] == "err(collision,swap,(1,2,1))"
    assert not [error for error in answer["errors"] if error["module"] == "diagonal"]


def test_visit_anytime_takes_a_visit_before_the_horizon_that_m_refuses(capsys, tmp_path):
    """Robot 1 reaches (4,1) at step 2 and steps back at step 3: served at step 2, not at the end."""
    plan = _plan(tmp_path, (1, (1, 0), 1), (1, (1, 0), 2), (1, (-1, 0), 3))
    code, answer = _check(capsys, CORRIDOR, plan)
    assert code == 1 and _messages(answer) == [
        "step 3 (the horizon): order 1 is not fulfilled: no robot stands under a shelf holding product 1"]
    code, answer = _check(capsys, CORRIDOR, plan, "--variant", "visit-anytime")
    assert (code, answer["valid"], answer["metrics"]["orders_fulfilled"]) == (0, True, 1)


def test_visit_anytime_names_the_order_never_visited(capsys, tmp_path):
    code, answer = _check(capsys, CORRIDOR, _plan(tmp_path, (1, (1, 0), 1)), "--variant", "visit-anytime")
    assert code == 1 and [error["atom"] for error in answer["errors"]] == ["err(visit,neverVisited,(1,1,1))"]
    assert _messages(answer) == ["step 1: order 1 is not served: no robot stands under a shelf holding product 1 "
                                 "at any step"]
    assert answer["metrics"]["orders_fulfilled"] == 0


def test_energy_below_zero_names_robot_step_and_level(capsys, tmp_path):
    """Energy 2, four moves: 1 after step 1, 0 after step 2, -1 after step 3 (reported once)."""
    plan = _plan(tmp_path, (1, (-1, 0), 1), (1, (1, 0), 2), (1, (1, 0), 3), (1, (1, 0), 4))
    code, answer = _check(capsys, CORRIDOR, plan, "--variant", "energy")
    assert code == 1 and [error["atom"] for error in answer["errors"]] == ["err(energy,exhausted,(1,-1,3))"]
    assert _messages(answer) == ["step 3: robot 1 runs out of energy: its level would be -1"]
    code, answer = _check(capsys, CORRIDOR, _plan(tmp_path, (1, (1, 0), 1), (1, (1, 0), 2)), "--variant", "energy")
    assert code == 0 and answer["valid"]


def test_a_robot_leaving_its_side_is_reported_where_it_crosses(capsys, tmp_path):
    plan = _plan(tmp_path, (1, (1, 0), 1), (1, (1, 0), 2))
    code, answer = _check(capsys, CORRIDOR, plan, "--variant", "sides")
    assert code == 1 and [error["atom"] for error in answer["errors"]] == ["err(sides,crossed,(1,left,1))"]
    assert _messages(answer) == ["step 1: robot 1 leaves the left half of the floor, where it started"]


def test_variants_compose_in_the_order_given(capsys, tmp_path):
    plan = _plan(tmp_path, (1, (-1, 0), 1), (1, (1, 0), 2), (1, (1, 0), 3), (1, (1, 0), 4))
    code, answer = _check(capsys, CORRIDOR, plan, "--variant", "energy", "--variant", "sides")
    assert (code, answer["domain"]) == (1, "m+energy+sides")
    assert [error["atom"] for error in answer["errors"]] == ["err(energy,exhausted,(1,-1,3))",
                                                             "err(sides,crossed,(1,left,3))"]


def test_the_energy_attribute_is_data_under_the_variant_and_warned_about_without(capsys, tmp_path):
    plan = _plan(tmp_path, (1, (1, 0), 1))
    main(["check", str(CORRIDOR), str(plan)])
    assert "warning: " in capsys.readouterr().err
    main(["check", str(CORRIDOR), str(plan), "--variant", "energy"])
    assert "warning" not in capsys.readouterr().err


@pytest.mark.parametrize("text, message", [
    ("variant: x\n", "'summary:' is missing"),
    ("variant: x\nsummary: y\nmoves: [[2, 0]]\n", "a move is [DX, DY], each -1, 0 or 1 and not both 0, got [2, 0]"),
    ("variant: x\nsummary: y\nrules: [nowhere.lp]\n", "'rules:' names nowhere.lp, which is not a file beside v.yml"),
    ("variant: x\nsummary: y\nmessages: {a/b: {params: {R: robot}, text: 'robot {S}'}}\n",
     "message a/b says {S}, which 'params:' does not name"),
    ("variant: x\nsummary: y\ncolour: red\n", "unknown key 'colour' (the keys: variant, summary, domains, moves, "
     "rules, replace, restricts, constants, kinds, attributes, generate, resource, encodings, messages)"),
])
def test_a_bad_variant_file_is_one_line(capsys, tmp_path, text, message):
    variant = tmp_path / "v.yml"
    variant.write_text(text)
    code = main(["check", str(CORRIDOR), str(_plan(tmp_path, (1, (1, 0), 1))), "--variant", str(variant)])
    err = capsys.readouterr().err
    assert code == 2 and err.startswith(f"error: {variant}") and err.rstrip().endswith(message)


def test_a_variant_for_other_domains_is_refused_naming_them(capsys, tmp_path):
    code = main(["check", str(CORRIDOR), str(_plan(tmp_path, (1, (1, 0), 1))), "--domain", "md", "--variant",
                 "visit-anytime"])
    assert code == 2 and capsys.readouterr().err.endswith("variant 'visit-anytime' changes domain M, not Md\n")


@pytest.mark.parametrize("variant, instance, minimum", [
    ("diagonal", CORNER, 2),       # two diagonal steps to (3,3), one is too few
    ("diagonal", SQUARE, 1),       # both robots straight down at once
    ("visit-anytime", CORRIDOR, 2),  # (2,1) -> (4,1)
    ("energy", CORRIDOR, 2),       # two moves, energy 2: just enough
])
def test_the_model_solutions_reach_the_minimum_by_hand_with_plain_clingo(capsys, tmp_path, variant, instance, minimum):
    """python -m clingo INSTANCE asprilo/variants/V-plan.lp -c horizon=H: no plan at H-1, a
    plan at H that the checker accepts under the variant."""
    import subprocess
    import sys

    encoding = Path(__file__).parent.parent / "asprilo" / "variants" / f"{variant}-plan.lp"
    answers = []
    for horizon in (minimum - 1, minimum):
        run = subprocess.run([sys.executable, "-m", "clingo", str(instance), str(encoding), "-c", f"horizon={horizon}"],
                             capture_output=True, text=True)
        answers.append(run.stdout)
    assert "UNSATISFIABLE" in answers[0].splitlines() and "SATISFIABLE" in answers[1].splitlines()
    plan = tmp_path / "plan.txt"
    plan.write_text(answers[1])
    code, answer = _check(capsys, instance, plan, "--variant", variant)
    assert (code, answer["valid"], answer["horizon"]) == (0, True, minimum)


def test_no_robot_of_the_corridor_can_serve_its_order_without_leaving_its_side():
    """corridor.lp under sides: the robot starts left of the middle (x = 2), the shelf is at x = 4."""
    import subprocess
    import sys

    encoding = Path(__file__).parent.parent / "asprilo" / "variants" / "sides-plan.lp"
    run = subprocess.run([sys.executable, "-m", "clingo", str(CORRIDOR), str(encoding), "-c", "horizon=6"],
                         capture_output=True, text=True)
    assert "UNSATISFIABLE" in run.stdout.splitlines()


GEN = ["gen", "-x", "11", "-y", "6", "-H", "-r", "3", "-s", "8", "-p", "1", "--domain", "m", "-C", "-q"]


def _energies(text: str) -> dict[int, int]:
    import re

    facts = re.findall(r"init\(object\(robot,(\d+)\),value\(energy,(-?\d+)\)\)", text)
    return {int(robot): int(level) for robot, level in facts}


def test_gen_draws_the_variants_attributes_within_their_range(capsys):
    """energy.yml draws every robot's energy from 30..50; --energy 7-7 leaves one value."""
    assert main([*GEN, "--variant", "energy", "--seed", "5"]) == 0
    drawn = _energies(capsys.readouterr().out)
    assert set(drawn) == {1, 2, 3} and all(30 <= level <= 50 for level in drawn.values())
    assert main([*GEN, "--variant", "energy", "--seed", "5"]) == 0
    assert _energies(capsys.readouterr().out) == drawn  # the seed decides
    assert main([*GEN, "--energy", "7-7", "--seed", "5"]) == 0
    assert _energies(capsys.readouterr().out) == {1: 7, 2: 7, 3: 7}


def test_gen_refuses_a_variant_that_does_not_change_its_domain(capsys):
    code = main([*GEN[:-4], "--domain", "a", "-P", "2", "-u", "4", "-o", "1", "--variant", "visit-anytime", "-C"])
    assert code == 2 and capsys.readouterr().err.endswith("variant 'visit-anytime' changes domain M, not A\n")
