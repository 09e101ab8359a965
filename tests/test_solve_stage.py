"""Two-stage encodings (``asprilo solve --encoding plan.lp --stage assign.lp``) and encodings
of several files after one ``--encoding``, as clingo users type them.

The encodings are the tests' own (tests/encodings/); expected values by hand, in the files'
comments: on m-pass.lp the minimal makespan is 1, and 4 along the first stage's answer
"robot 1 under shelf 1 at (3,1), robot 2 under shelf 2 at (2,1)" (stage-assign.lp, which has
exactly that one answer); on m-tiny.lp it is 4 (three moves right, one down).
"""

from __future__ import annotations

import argparse
import json

import clingo
import pytest
from helpers import ROOT

from asprilo.cli import main
from asprilo.encodings import SolveRequest, SolveStatus, solve
from asprilo.encodings.choice import stage_encoding
from asprilo.encodings.own import own_encoding
from asprilo.errors import InputError
from asprilo.solver import Solver

OWN = ROOT / "tests" / "encodings"
M_PASS, M_TINY = OWN / "m-pass.lp", OWN / "m-tiny.lp"
PLAN, ASSIGN = OWN / "stage-plan.lp", OWN / "stage-assign.lp"
TARGETS = ["target(1,(3,1))", "target(2,(2,1))"]


def _solve(capsys, *arguments) -> tuple[int, dict, str]:
    code = main(["solve", *map(str, arguments)])
    captured = capsys.readouterr()
    return code, json.loads(captured.out) if captured.out.startswith("{") else {}, captured.err


# --- two stages ----------------------------------------------------------------------------------

def test_the_first_answer_of_the_stage_becomes_facts_of_the_plan(capsys):
    code, report, err = _solve(capsys, M_PASS, "--encoding", PLAN, "--stage", ASSIGN, "--json")
    assert (code, report["status"], report["horizon"], report["stage"]) == (0, "found", 4, TARGETS)
    # refuted along the stage's answer only: nothing is proven for the problem beyond its bound
    assert (report["minimal"], report["refuted"], report["refuted_along_assignment"], report["proven_bound"]) == (
        False, [], [1, 2, 3], 1)
    assert f"first stage ({ASSIGN}): its first answer, 2 atoms: target(1,(3,1)) target(2,(2,1))" in err
    # the problem's minimum 1 (by hand, m-pass.lp) is max-flow's: the plan is said to be 3 steps longer
    assert (report["encoding_minimal"], report["minimum"], report["minimum_by"]) == (False, 1, "by max-flow")
    assert ("plan: horizon 4 (minimal along the first stage's answer; not minimal: the problem's minimum is 1, by "
            "max-flow, gap 3 steps), 6 actions, checked: valid") in err
    assert "no plan along the first stage's answer at horizons 1-3 (refuted along that answer only, not for the " \
           "problem)" in err


def test_a_horizon_without_a_plan_along_the_stage_is_not_said_to_have_none(capsys):
    code, report, err = _solve(capsys, M_PASS, "--encoding", PLAN, "--stage", ASSIGN, "--horizon", "2", "--json")
    assert (code, report["status"], report["refuted"], report["refuted_along_assignment"]) == (1, "none", [], [2])
    assert "no plan: no plan at horizon 2 along the first stage's answer (not refuted for the problem)" in err
    assert "no plan exists" not in err


def test_without_the_stage_the_same_encoding_plans_one_step():
    outcome = solve(M_PASS, encoding=own_encoding([PLAN]), time_limit=60)
    assert (outcome.horizon, outcome.minimal, outcome.stage, outcome.staged) == (1, True, "", None)


def test_the_request_carries_the_stage_for_any_caller():
    """``stage`` is a field of the request (files or an Encoding), as ``grade`` may use it."""
    encoding = own_encoding([PLAN])
    outcome = solve(M_PASS, encoding=encoding, stage=[ASSIGN], time_limit=60)
    assert (outcome.horizon, outcome.staged, outcome.minimal_along_assignment) == (4, TARGETS, True)
    from asprilo.reader import read_instance
    request = SolveRequest(read_instance(M_PASS), outcome.domain, encoding=encoding, stage=stage_encoding([ASSIGN]),
                           time_limit=60)
    assert solve(request).staged == TARGETS


def test_the_stage_gets_the_same_constants(tmp_path):
    """The stage has an answer only with -c need=2, which the encoding is given."""
    stage = tmp_path / "needy.lp"
    stage.write_text(f'#include "{ASSIGN}".\n:- need != 2.\n')
    planned = solve(M_PASS, encoding=own_encoding([PLAN], [("need", "2")]), stage=[stage], time_limit=60)
    assert (planned.horizon, planned.staged) == (4, TARGETS)
    other = solve(M_PASS, encoding=own_encoding([PLAN], [("need", "1")]), stage=[stage], time_limit=60)
    assert (other.status, other.staged, other.horizons_tried) == (SolveStatus.NONE, None, [])


def test_a_stage_without_an_answer_is_said_in_words(capsys, tmp_path):
    none = tmp_path / "none.lp"
    none.write_text("a.\n:- a.\n")
    code, _report, err = _solve(capsys, M_PASS, "--encoding", PLAN, "--stage", none)
    assert code == 1
    assert f"first stage ({none}): no answer" in err
    assert (f"no plan: the first stage ({none}) has no answer set on this instance: there are no facts to plan "
            "with") in err


def test_the_atoms_go_in_as_symbols_never_as_text():
    """A string with quotes, a full stop and a newline comes through as the same symbol (read
    back as text, '"a). b(' would be a fact and a half)."""
    from asprilo.encodings.solving.stage import add_symbols

    odd = clingo.Function("s", [clingo.String('x"). bad(1). t("\n')])
    solver = Solver()
    solver.add("seen(X) :- s(X). #show seen/1. #show bad/1.")
    add_symbols(solver, [odd, clingo.Function("p", [clingo.Number(1)], False)])
    solver.ground()
    assert solver.solve().symbols == [clingo.Function("seen", odd.arguments)]


@pytest.mark.parametrize("arguments, said", [
    (["--method", "flow"], "--stage goes with an encoding: the flow method runs none"),
    (["--encoding", str(PLAN), "--assign"], "--stage and --assign each give the plan an assignment: give one of "
                                            "them"),
])
def test_a_stage_with_what_cannot_take_it_is_refused(capsys, arguments, said):
    assert main(["solve", str(M_PASS), "--stage", str(ASSIGN), *arguments]) == 2
    assert said in capsys.readouterr().err


def test_an_incremental_stage_is_refused(capsys):
    assert main(["solve", str(M_PASS), "--encoding", str(PLAN), "--stage", str(OWN / "m-incmode.lp")]) == 2
    assert "is solved once, with the instance: it has step(t)/check(t) parts" in capsys.readouterr().err


# --- several files after one --encoding -------------------------------------------------------------

@pytest.fixture
def three(tmp_path):
    """An M encoding in three files: the moves with a horizon constant, what is shown, a comment."""
    moves, show, note = tmp_path / "moves.lp", tmp_path / "show.lp", tmp_path / "note.lp"
    moves.write_text(f'#const horizon = 1.\n#include "{OWN / "m-moves.lp"}".\n')
    show.write_text("occurs(object(robot,R),action(move,D),T) :- move(R,D,T).\n#show occurs/3.\n")
    note.write_text("% nothing but a comment\n")
    return moves, show, note


def test_one_flag_takes_several_files(capsys, three):
    code, report, err = _solve(capsys, M_TINY, "--encoding", *three, "--json")
    assert (code, report["horizon"], report["minimal"]) == (0, 4, True)
    assert f"your encoding ({', '.join(map(str, three))}): single-shot with a horizon constant" in err


def test_the_flag_repeated_still_works(capsys, three):
    moves, show, note = three
    code, report, _err = _solve(capsys, M_TINY, "--encoding", moves, show, "--encoding", note, "--json")
    assert (code, report["horizon"]) == (0, 4)


def test_an_instance_taken_by_the_flag_is_said_so(capsys, three):
    moves, show, _note = three
    code, _report, err = _solve(capsys, "--encoding", moves, show, M_TINY)
    assert code == 2
    assert err == (f"error: no instance given: --encoding took {moves}, {show}, {M_TINY}, every file after the flag "
                   f"({M_TINY} looks like an instance: it has init/2 facts); give the instance first: asprilo solve "
                   "INSTANCE --encoding FILE...\n")


def test_a_reference_name_before_the_instance_leaves_the_instance(capsys):
    code, report, _err = _solve(capsys, "--encoding", "plain", M_TINY, "--json")
    assert (code, report["encoding"], report["horizon"]) == (0, "plain", 4)


def test_check_watch_takes_several_files_after_one_flag(three):
    from asprilo.cli import check

    parser = argparse.ArgumentParser()
    check.configure(parser)
    args = parser.parse_args([str(M_TINY), "--watch", "--encoding", *map(str, three)])
    assert (args.instance, args.plan, args.encoding) == (str(M_TINY), None, list(map(str, three)))


def test_the_stage_file_must_exist(capsys, tmp_path):
    assert main(["solve", str(M_PASS), "--encoding", str(PLAN), "--stage", str(tmp_path / "missing.lp")]) == 2
    assert capsys.readouterr().err == f"error: {tmp_path / 'missing.lp'}: no such file\n"
    with pytest.raises(InputError, match="--stage names the files of the first stage"):
        stage_encoding([])


def test_grade_runs_a_two_stage_encoding_with_its_first_stage(capsys):
    """The grader hands the stage on as solve does: along the stage's answer the plan has
    makespan 4, the instance's minimum (plain M, by the reference) is 1."""
    code = main(["grade", str(PLAN), "--stage", str(ASSIGN), "--domain", "m", "--instances", str(M_PASS), "--json"])
    entry = json.loads(capsys.readouterr().out)["instances"][0]
    assert (code, entry["result"], entry["makespan"], entry["minimum"], entry["minimal"]) == (0, "valid", 4, 1, False)
    code = main(["grade", str(PLAN), "--domain", "m", "--instances", str(M_PASS), "--json"])
    entry = json.loads(capsys.readouterr().out)["instances"][0]
    assert (entry["makespan"], entry["minimal"]) == (1, True)  # without the stage nothing ties the robots
