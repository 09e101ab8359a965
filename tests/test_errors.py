"""Bad input: one line `error: FILE[:LINE]: what is wrong`, exit status 2, no traceback."""

from __future__ import annotations

import subprocess
import sys

import pytest
from helpers import SMALL_A

from asprilo.cli import main

PLAN_FOR_ROBOT_9 = "occurs(object(robot,1),action(move,(1,0)),1).\noccurs(object(robot,9),action(move,(1,0)),2).\n"


def run(capsys, *args):
    code = main(["info", *map(str, args)])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("name, text, message", [
    ("syntax.lp", "init(object(robot,1),value(at,(1,1))).\ninit(object(robot,2),value(at,(1,2)).\n",
     "syntax.lp:2: syntax error, unexpected ., expecting , or )"),
    ("empty.lp", "% nothing but a comment\n",
     "empty.lp: no instance facts (expected init(object(..),value(..)) facts) found"),
    ("shape.lp", "init(object(node,1),value(at,(1,1))).\n\ninit(object(robot,1),value(at,5)).\n",
     "shape.lp:3: robot 1: value of 'at' must be a cell (X,Y), got 5"),
    ("arity.lp", "init(object(shelf,1),value(at,(1,1,2))).\n",
     "arity.lp:1: shelf 1: value of 'at' must be a cell (X,Y), got (1,1,2)"),
    ("line.lp", "init(object(order,1),value(line,(a,b))).\n",
     "line.lp:1: order 1: value of 'line' must be (Product,Units) or Product, got (a,b)"),
    ("twice.lp", "init(object(robot,1),value(at,(1,1))).\ninit(object(robot,1),value(at,(2,1))).\n",
     "twice.lp:2: robot 1 is at two places: (1,1) and (2,1)"),
    ("ids.lp", "init(object(robot,r1),value(at,(1,1))).\n",
     "ids.lp:1: robot id must be an integer, got r1"),
    ("unsafe.lp", "init(object(robot,1),value(at,(X,1))).\n",
     "unsafe.lp:1: 'init(object(robot,1),value(at,(X,1))).' holds a variable; data holds only facts, #const and "
     "'#program base.' (rules need --allow-rules)"),
    ("contradiction.lp", "init(object(robot,1),value(at,(1,1))).\n:- init(object(robot,1),_).\n",
     "contradiction.lp:2: ':- init(object(robot,1),_).' is a rule; data holds only facts, #const and "
     "'#program base.' (rules need --allow-rules)"),
])
def test_bad_instances(capsys, write, name, text, message):
    path = write(name, text)
    code, out, err = run(capsys, path)
    assert (code, out) == (2, "")
    assert err == f"error: {path.parent}/{message}\n"


def test_rules_are_read_when_allowed(capsys, write):
    path = write("contradiction.lp", "init(object(robot,1),value(at,(1,1))).\n:- init(object(robot,1),_).\n")
    assert run(capsys, path, "--allow-rules") == (
        2, "", f"error: {path}: the program has no answer set (its rules contradict each other)\n")


@pytest.mark.parametrize("name, text, warning", [
    ("type.lp", "init(object(node,1),value(at,(1,1))).\ninit(object(robott,1),value(at,(1,1))).\n",
     "type.lp:2: ignored (and kept when written): object type 'robott'"),
    ("attribute.lp", "init(object(node,1),value(at,(1,1))).\ninit(object(robot,1),value(at,(1,1))).\n"
     "init(object(robot,1),value(colour,red)).\ninit(object(robot,1),value(energy,(1,2))).\n",
     "attribute.lp:3: ignored (and kept when written): attribute 'colour' of robot, attribute 'energy' of robot"),
])
def test_unknown_types_and_attributes_are_named_once_and_ignored(capsys, write, name, text, warning):
    path = write(name, text)
    code, out, err = run(capsys, path)
    assert (code, err) == (0, f"warning: {path.parent}/{warning}\n")
    assert out.startswith("instance: 1x1 grid, 1 nodes")


def test_missing_file(capsys, tmp_path):
    assert run(capsys, tmp_path / "nope.lp") == (2, "", f"error: {tmp_path}/nope.lp: no such file\n")


def test_directory_instead_of_file(capsys, tmp_path):
    assert run(capsys, tmp_path) == (2, "", f"error: {tmp_path}: is a directory, not a file\n")


def test_plan_for_a_robot_the_instance_lacks(capsys, write):
    plan = write("plan.lp", PLAN_FOR_ROBOT_9)
    assert run(capsys, SMALL_A, plan) == (
        2, "", f"error: {plan}:2: the plan moves robot 9, but the instance has robots 1..3 "
               "(plan and instance do not fit)\n")


def test_bad_plan_step(capsys, write):
    plan = write("plan.lp", "occurs(object(robot,1),action(move,(1,0)),soon).\n")
    assert run(capsys, SMALL_A, plan) == (
        2, "", f"error: {plan}:1: the time step of occurs(object(robot,1),action(move,(1,0)),soon) "
               "must be an integer\n")


def test_clingo_output_without_answer(capsys, write):
    plan = write("out.txt", "clingo version 5.8.3\nSolving...\nUNSATISFIABLE\n")
    assert run(capsys, SMALL_A, plan) == (
        2, "", f"error: {plan}: the clingo output holds no answer (clingo reported UNSATISFIABLE)\n")


def test_unknown_domain_is_a_usage_error(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["info", str(SMALL_A), "--domain", "z"])
    assert exit_.value.code == 2
    assert "unknown domain 'z' (choose one of a, b, c, m, md)" in capsys.readouterr().err


def test_console_script_prints_no_traceback(tmp_path):
    result = subprocess.run([sys.executable, "-m", "asprilo.cli", "info", str(tmp_path / "x.lp")],
                            capture_output=True, text=True)
    assert (result.returncode, result.stdout) == (2, "")
    assert result.stderr == f"error: {tmp_path}/x.lp: no such file\n"


def _json_answer(capsys, *args) -> tuple[int, dict, str]:
    import json

    try:
        code = main(list(map(str, args)))
    except SystemExit as exit_:  # a usage error, as argparse ends it
        code = exit_.code
    out, err = capsys.readouterr()
    return code, json.loads(out), err


@pytest.mark.parametrize("command", ["check", "info"])
def test_a_refusal_with_json_is_a_json_object_too(capsys, write, command):
    plan = write("plan.lp", PLAN_FOR_ROBOT_9)
    code, answer, err = _json_answer(capsys, command, "--json", SMALL_A, plan)
    message = f"{plan}:2: the plan moves robot 9, but the instance has robots 1..3 (plan and instance do not fit)"
    assert (code, err) == (2, f"error: {message}\n")
    assert answer == {"error": message, "file": str(plan), "line": 2, "exit": 2}


def test_a_missing_file_with_json_is_a_json_object(capsys, tmp_path):
    code, answer, _err = _json_answer(capsys, "solve", "--json", tmp_path / "x.lp")
    assert (code, answer) == (2, {"error": f"{tmp_path}/x.lp: no such file", "file": f"{tmp_path}/x.lp",
                                  "line": None, "exit": 2})


def test_an_option_clingo_refuses_is_said_before_solving_also_in_json(capsys):
    """An option for clingo that clingo does not know, with a reference encoding: refused in
    clingo's words before any search starts (it was a traceback from the search's child)."""
    code, answer, err = _json_answer(capsys, "solve", "--json", SMALL_A, "--no-such-option=3")
    message = "clingo refuses the option --no-such-option=3: unknown option: 'no-such-option'"
    assert (code, err, answer) == (2, f"error: {message}\n", {"error": message, "exit": 2})


@pytest.mark.parametrize("argv, usage", [
    (["check", "--json"], "asprilo check: error: the following arguments are required: INSTANCE"),
    (["info", SMALL_A, "--json", "--domain", "z"],
     "asprilo info: error: argument --domain: unknown domain 'z' (choose one of a, b, c, m, md)"),
    (["grade", "--json", "--time-limit", "soon"],
     "asprilo grade: error: argument --time-limit: not a number of seconds: 'soon'"),
])
def test_a_usage_error_with_json_is_a_json_object(capsys, argv, usage):
    code, answer, err = _json_answer(capsys, *argv)
    assert code == 2 and err.startswith("usage: ") and err.endswith(f"\n{usage}\n")
    assert answer == {"error": usage, "exit": 2}
