"""``asprilo grade``: an encoding graded on a ladder -- valid? minimal? -- and every wrong
answer a graded line, never a crash.

The encodings are those of tests/encodings/ (written for the tests, in the styles people use
with clingo).  The ladders' minima are tested in test_grade_ladders.py; here the grades.
Expected violations are computed apart from the grader: by checking the graded plan with
``asprilo.checker.check``, and for the first M instance by hand.
"""

from __future__ import annotations

import json
import multiprocessing
import os
import signal

import pytest
from helpers import ROOT

from asprilo.checker import check
from asprilo.cli import main
from asprilo.domain import Domain
from asprilo.encodings.grading import grade_ladder
from asprilo.encodings.ladder import bundled_ladder
from asprilo.encodings.own import own_encoding
from asprilo.errors import InputError

OWN = ROOT / "tests" / "encodings"
M_LADDER = bundled_ladder(Domain.M)


def _grade(capsys, *arguments):
    code = main(["grade", *map(str, arguments)])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def _lines(out: str) -> list[str]:
    """The instance lines of a text report (between the header and the summary)."""
    return out.splitlines()[1:-1]


def test_a_correct_encoding_is_valid_and_minimal_on_every_instance(capsys):
    code, out, err = _grade(capsys, OWN / "m-single.lp", "--domain", "m")
    assert code == 0
    header, *lines, summary = out.splitlines()
    assert header == (f"grading your encoding ({OWN / 'm-single.lp'}: single-shot with a horizon constant) on the "
                      f"M ladder: {len(M_LADDER.rungs)} instances, time limit 20 s each")
    lines, probes = lines[:len(M_LADDER.rungs)], lines[len(M_LADDER.rungs):]  # the ladder's probes after (test_probes)
    assert probes == [f"kept: {probe.rule} ({probe.name} probe refused)" for probe in M_LADDER.probes]
    assert summary.endswith(f"; probes: {len(probes)}/{len(probes)} refused")
    for line, rung in zip(lines, M_LADDER.rungs, strict=True):
        assert f" {rung.name} " in line and line.endswith(f"  valid    minimal (makespan {rung.minimum})")
    assert summary.startswith(f"{len(lines)}/{len(lines)} valid, {len(lines)}/{len(lines)} minimal; ")
    assert err.splitlines()[0] == f"grading [1/{len(lines)}] 01-x3_y2_r1 (minimum 3)"  # progress on stderr


def test_a_sign_error_makes_every_plan_invalid_with_its_first_violation():
    graded = list(grade_ladder(own_encoding([OWN / "m-wrong.lp"]), M_LADDER, time_limit=20))
    assert [g.result for g in graded] == ["invalid"] * len(M_LADDER.rungs)
    for item in graded:
        errors = check(item.instance, item.plan, Domain.M).errors  # the checker, apart from the grader
        assert item.violation.message == errors[0].message and item.violations == len(errors)
        assert item.makespan == item.plan.horizon and not item.minimal
    # by hand: on the first instance the robot at (3,2) must go up once to (1,1); the wrong
    # encoding shows that move as (0,1), which leaves the floor, so the shelf is never reached
    first = check(graded[0].instance, graded[0].plan, Domain.M).errors
    assert {(error.module, error.check) for error in first} == {("move", "offFloor"), ("goal", "unfilledOrder")}


#: a fixed plan for the first M instance (robot 1 at (3,2), the ordered shelf at (1,1)): two
#: steps left, then "up" as (0,1), which leaves the floor -- by hand, the goal is missed at
#: step 3 and the robot is off the floor there (two violations, the goal's sorted first)
UPSIDE_DOWN = """occurs(object(robot,1),action(move,(-1,0)),1).
occurs(object(robot,1),action(move,(-1,0)),2).
occurs(object(robot,1),action(move,(0,1)),3).
"""


@pytest.fixture
def upside_down(tmp_path):
    path = tmp_path / "upside-down.lp"
    path.write_text(UPSIDE_DOWN)
    return path


def test_invalid_lines_say_the_first_violation_in_words(upside_down, capsys):
    code, out, _err = _grade(capsys, upside_down, "--domain", "m", "--first", "1")
    assert code == 1
    assert _lines(out)[0].endswith("  INVALID  makespan 3: step 3 (the horizon): order 1 is not fulfilled: no robot "
                                   "stands under a shelf holding product 1 (and 1 more violation)")
    assert out.splitlines()[-1].startswith("0/1 valid, 0/1 minimal, 1 invalid; ")


def test_a_model_without_occurs_says_what_the_interface_is(capsys):
    code, out, _err = _grade(capsys, OWN / "m-none.lp", "--domain", "m", "--first", "2")
    assert code == 1
    for line in _lines(out):
        assert line.endswith("  no plan  its model has no occurs(object(robot,R),action(Name,Args),T) atoms: an "
                             "encoding reads the instance's init/2 facts and shows the plan as occurs/3 "
                             "(e.g. #show occurs/3.)")
    assert out.splitlines()[-1].startswith("0/2 valid, 0/2 minimal, 2 without a plan; ")


def test_a_domain_a_encoding_is_minimal_on_the_first_instances(capsys):
    ladder = bundled_ladder(Domain.A)
    code, out, _err = _grade(capsys, OWN / "a-single.lp", "--domain", "a", "--first", "3")
    assert code == 0
    for line, rung in zip(_lines(out), ladder.rungs[:3], strict=True):
        assert line.endswith(f"  valid    minimal (makespan {rung.minimum})")


def test_the_json_shape(upside_down, capsys):
    code, out, _err = _grade(capsys, upside_down, "--domain", "m", "--first", "2", "--json",
                             "-c", "unused=1", "--configuration=crafty")
    assert code == 1
    report = json.loads(out)
    seconds = [entry.pop("seconds") for entry in report["instances"]] + [report["summary"].pop("seconds")]
    assert all(isinstance(value, float) and value >= 0 for value in seconds)
    first, second = report["instances"]
    assert report == {
        "version": 1,
        "domain": "m",
        "ladder": "m",
        "encoding": {"name": "upside-down", "own": True, "files": [str(upside_down)],
                     "style": "fixed (no horizon constant: solved once)", "assumed": [], "constants": {"unused": "1"},
                     "horizon": None, "options": ["--configuration=crafty"]},
        "time_limit": 20.0,
        "instances": [first, second],
        "summary": {"instances": 2, "valid": 0, "minimal": 0, "invalid": 2, "no_plan": 0, "time_outs": 0},
    }
    assert first == {
        "step": 1, "name": "01-x3_y2_r1", "file": "01-x3_y2_r1.lp", "size": "3x2", "robots": 1, "minimum": 3,
        "result": "invalid", "valid": False, "minimal": False, "encoding_minimal": False, "makespan": 3,
        "violation": {"atom": "err(goal,unfilledOrder,(1,1,1,3))", "module": "goal", "check": "unfilledOrder",
                      "step": 3, "message": "step 3 (the horizon): order 1 is not fulfilled: no robot stands under "
                                            "a shelf holding product 1"},
        "violations": 2, "reason": None, "refuted": [], "warnings": []}
    assert set(second) == set(first) and second["result"] == "invalid" and second["step"] == 2


def test_the_json_of_a_valid_and_a_missing_plan(capsys):
    _code, out, _err = _grade(capsys, OWN / "m-single.lp", "--domain", "m", "--first", "1", "--json")
    entry = json.loads(out)["instances"][0]
    assert {key: entry[key] for key in ("result", "valid", "minimal", "makespan", "violation", "violations",
                                        "reason", "refuted")} == {
        "result": "valid", "valid": True, "minimal": True, "makespan": 3, "violation": None, "violations": 0,
        "reason": None, "refuted": []}
    _code, out, _err = _grade(capsys, OWN / "m-none.lp", "--domain", "m", "--first", "1", "--json")
    entry = json.loads(out)["instances"][0]
    assert entry["result"] == "no-plan" and entry["makespan"] is None and entry["violation"] is None
    assert entry["reason"].startswith("its model has no occurs(object(robot,R),action(Name,Args),T) atoms")


def test_a_plan_longer_than_the_minimum_and_the_horizons_refuted(tmp_path, capsys):
    late = tmp_path / "late.lp"  # a robot must move at step 4: horizon 3 is refuted although a plan exists
    late.write_text(f'#include "{OWN / "m-single.lp"}".\n:- not move(_,_,4).\n')
    code, out, _err = _grade(capsys, late, "--domain", "m", "--first", "1")
    assert code == 0
    assert _lines(out)[0].endswith("  valid    the shortest plan this encoding allows (4); the problem's minimum "
                                   "is 3 (horizon 3 refuted, yet plans exist from makespan 3 on: a constraint is too "
                                   "strong)")
    assert out.splitlines()[-1].startswith("1/1 valid, 0/1 minimal; ")


def test_an_encoding_without_answer_sets_says_which_horizons_it_refuted(tmp_path, capsys):
    never = tmp_path / "never.lp"
    never.write_text(f'#include "{OWN / "m-single.lp"}".\n:- step(1).\n')
    code, out, _err = _grade(capsys, never, "--domain", "m", "--first", "1")
    assert code == 1
    # the search gives up after the lower bound 3 plus 6 cells, 1 robot and 2 per order line
    assert _lines(out)[0].endswith("  no plan  no answer set up to horizon 12; horizons 3-12 refuted, yet plans "
                                   "exist from makespan 3 on: a constraint is too strong")


def test_a_constant_horizon_solves_there_only(capsys):
    code, out, _err = _grade(capsys, OWN / "m-single.lp", "--domain", "m", "-c", "horizon=5", "--first", "5")
    lines = _lines(out)
    assert code == 1
    assert lines[3].endswith("  valid    minimal (makespan 4)")  # a plan of horizon 5 that ends at step 4
    assert lines[4].endswith("  no plan  no answer set; horizon 5 refuted")  # the minimum is 6


def test_an_encoding_that_grounds_for_ever_is_a_time_out_said_where(tmp_path, capsys):
    endless = tmp_path / "endless.lp"
    endless.write_text("#const horizon = 1.\np(0).\np(X+1) :- p(X).\n")
    code, out, _err = _grade(capsys, endless, "--domain", "m", "--first", "1", "--time-limit", "2")
    assert code == 1
    # the search starts at the lower bound 3 (the robot at (3,2) is 3 steps from the shelf at (1,1))
    assert _lines(out)[0].endswith("  time-out time limit (2 s) while grounding horizon 3")
    assert out.splitlines()[-1].startswith("0/1 valid, 0/1 minimal, 1 time-out; ")


def test_a_crash_of_the_child_process_is_a_grade():
    def kill_the_child(phase):
        for child in multiprocessing.active_children():
            os.kill(child.pid, signal.SIGKILL)

    ladder = bundled_ladder(Domain.M)
    graded = list(grade_ladder(own_encoding([OWN / "m-single.lp"]), ladder, time_limit=20, first=2,
                               on_phase=kill_the_child))
    assert [(g.result, g.reason) for g in graded] == [
        ("no-plan", "the solver process died (killed by signal 9)")] * 2


def test_a_reference_encoding_is_graded_by_name(capsys):
    code, out, _err = _grade(capsys, "plain", "--domain", "md", "--first", "2")
    assert code == 0
    assert out.splitlines()[0] == ("grading the reference encoding plain on the Md ladder: 2 instances, "
                                   "time limit 20 s each")


def test_encodings_clingo_refuses_are_graded_and_bad_command_lines_refused(tmp_path, capsys):
    broken = tmp_path / "broken.lp"  # the '.' after step(1..horizon) is missing: clingo stops on line 3
    broken.write_text("#const horizon = 1.\nstep(1..horizon)\nrobot(R) :- init(object(robot,R),_).\n")
    code, out, err = _grade(capsys, broken, "--domain", "m", "--first", "2")
    assert code == 1 and out.splitlines()[0].startswith(f"grading your encoding ({broken}: refused by clingo) ")
    for line in _lines(out):
        assert f"  0.0 s  no plan  clingo refused the encoding: {broken}:3: column 1: syntax error" in line
    assert out.splitlines()[-1].startswith("0/2 valid, 0/2 minimal, 2 without a plan; ")
    unsafe = tmp_path / "unsafe.lp"  # found by clingo when it grounds each instance
    unsafe.write_text("#const horizon = 1.\np(X) :- q.\n")
    code, out, err = _grade(capsys, unsafe, "--domain", "m", "--quiet", "--first", "2", "--json")
    assert code == 1
    assert [(entry["result"], entry["reason"]) for entry in json.loads(out)["instances"]] == [
        ("no-plan", f"clingo refused the encoding: {unsafe}:2: unsafe variables in: p(X):-[#inc_base];q. 'X' is "
                    "unsafe")] * 2
    code, out, err = _grade(capsys, OWN / "m-single.lp", "--domain", "m", "--frobnicate=3")
    assert (code, out) == (2, "")
    assert err == "error: clingo refuses the option --frobnicate=3: unknown option: 'frobnicate'\n"
    code, out, err = _grade(capsys, tmp_path / "missing.lp", "--domain", "m")
    assert (code, err) == (2, f"error: {tmp_path / 'missing.lp'}: no such file\n")


def test_bad_input_exits_2(capsys):
    assert _grade(capsys, OWN / "m-single.lp")[::2] == (
        2, "error: name the domain (--domain a|b|c|m|md) or a ladder (--ladder FILE)\n")
    assert _grade(capsys, "--domain", "m")[::2] == (2, "error: no encoding given (asprilo grade ENCODING... "
                                                       "--domain D)\n")
    with pytest.raises(SystemExit) as stopped:
        main(["grade", str(OWN / "m-single.lp"), "--domain", "m", "--first", "0"])
    assert stopped.value.code == 2


def test_a_ladder_of_ones_own(tmp_path, capsys):
    for rung in M_LADDER.rungs[:2]:
        (tmp_path / rung.file.name).write_text(rung.file.read_text())
    ladder = tmp_path / "ladder.yml"
    ladder.write_text("domain: m\ninstances:\n"
                      "  - {file: 01-x3_y2_r1.lp, minimum: 3, established: by hand}\n"
                      "  - {file: 02-x5_y2_r2.lp, minimum: 5, established: a mistake}\n")
    code, out, _err = _grade(capsys, OWN / "m-single.lp", "--ladder", ladder)
    assert code == 0
    assert out.splitlines()[0].endswith(f"on the ladder {ladder}: 2 instances, time limit 20 s each")
    assert _lines(out)[1].endswith("  valid    makespan 4, below the stored minimum 5: the ladder is wrong, "
                                   "please report it")
    code, _out, err = _grade(capsys, OWN / "m-single.lp", "--ladder", ladder, "--domain", "a")
    assert (code, err) == (2, f"error: {ladder}: the ladder is of domain M, not A\n")


@pytest.mark.parametrize("text, message", [
    ("domain: m\ninstances: []\n", ":2: 'instances' is a list of instances (file, minimum, established)"),
    ("domain: q\ninstances: [{file: a.lp}]\n", ":1: "),
    ("domain: m\ninstances:\n  - {file: a.lp, minimum: 3}\n", ":3: the instance has no 'established'"),
    ("domain: m\ninstances:\n  - {file: none.lp, minimum: 3, established: x}\n", ":3: no such instance file: "),
    ("domain: m\ninstances:\n  - {file: a.lp, minimum: -1, established: x}\n",
     ":3: the minimum is a makespan (a whole number >= 0), got -1"),
    ("domain: m\ninstances:\n  - {file: a.lp, minimum: 3, established: x, seed: 3}\n", ":3: unknown key 'seed'"),
    ("domains: m\n", ":1: unknown key 'domains'"),
])
def test_bad_ladders_are_refused_with_their_line(tmp_path, text, message):
    (tmp_path / "a.lp").write_text(M_LADDER.rungs[0].file.read_text())
    ladder = tmp_path / "ladder.yml"
    ladder.write_text(text)
    from asprilo.encodings.ladder import read_ladder
    with pytest.raises(InputError) as refused:
        read_ladder(ladder)
    assert message in str(refused.value) and str(refused.value).startswith(str(ladder))


def test_the_list_shows_the_ladder_with_its_minima(capsys):
    code, out, _err = _grade(capsys, "--list", "--domain", "c")
    ladder = bundled_ladder(Domain.C)
    assert code == 0
    lines = out.splitlines()
    assert lines[0] == f"the C ladder: {len(ladder.rungs)} instances ({ladder.manifest})"
    assert lines[1].startswith(" 1  01-x3_y2_r1   3x2, 1 robot     minimum 5")
