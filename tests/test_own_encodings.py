"""A user's own encoding through ``asprilo solve``: every style recognised and run as meant,
bad encodings answered in words.

The encodings are in tests/encodings/, written for these tests in the styles people use
with clingo.  Expected makespans are independent of them: the paper instance's minimum
comes from the max-flow method, the tiny instances' from their hand derivation (in the
files' comments).
"""

from __future__ import annotations

import json

import pytest
from helpers import EXAMPLES, ROOT

from asprilo.cli import main
from asprilo.domain import Domain
from asprilo.encodings import SolveStatus, solve
from asprilo.encodings.own import own_encoding
from asprilo.errors import InputError
from asprilo.reader import read_instance

OWN = ROOT / "tests" / "encodings"
PAPER_M = EXAMPLES / "paper-m/1x2x4/x11_y6_n66_r2_s16_ps1_pr16_u16_o2_N001.lp"
M_TINY, A_TINY = OWN / "m-tiny.lp", OWN / "a-tiny.lp"


@pytest.fixture(scope="module")
def minimum():
    """The paper instance's minimal makespan by max-flow."""
    outcome = solve(PAPER_M, method="flow")
    assert outcome.minimal
    return outcome.horizon


def _solve(capsys, *arguments):
    code = main(["solve", *map(str, arguments)])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


STYLES = {
    "m-single.lp": "single-shot with a horizon constant",
    "m-incmode.lp": "incremental (step(t)/check(t), query(t))",
    "m-split/main.ilp": "incremental (step(t)/check(t), query(t))",
    "m-clingcon.lp": "single-shot with a horizon constant, clingcon 5",
    "m-dl.lp": "single-shot with a horizon constant, clingo-dl",
}


@pytest.mark.parametrize("name", STYLES)
def test_every_style_finds_the_minimal_makespan(name, minimum, capsys):
    code, out, err = _solve(capsys, PAPER_M, "--encoding", OWN / name, "--json")
    report = json.loads(out)
    assert code == 0 and report["status"] == "found"
    assert report["horizon"] == minimum and report["minimal"]
    assert f"): {STYLES[name]}\n" in err
    assert report["encoding"] == name.split("/")[-1].rsplit(".", 1)[0]


def test_clingo4_incremental_files_are_run_as_their_author_meant(capsys):
    _code, _out, err = _solve(capsys, PAPER_M, "--encoding", OWN / "m-split/main.ilp", "-o", "-")
    assert [line for line in err.splitlines() if line.startswith("  assumed: ")] == [
        "  assumed: #program cumulative(t) read as step(t) (clingo 4's iclingo)",
        "  assumed: #program volatile(t) read as check(t) (clingo 4's iclingo)",
        "  assumed: query(t) declared #external in check(t), as clingo 4's incmode did"]


def test_clingcon4_programs_run_without_their_csp_include(capsys):
    code, _out, err = _solve(capsys, M_TINY, "--encoding", OWN / "m-clingcon4.clp", "-o", "-")
    assert code == 0
    assert ("  assumed: #include <csp>. left out: clingcon 5 reads &sum/&dom without it (clingcon 4's style)"
            in err.splitlines())


def test_clingo_warnings_on_the_encoding_are_said_with_their_file(tmp_path, capsys):
    typo = tmp_path / "typo.lp"
    typo.write_text(f'#include "{OWN / "m-single.lp"}".\n:- goal(C), not under(C).\n')
    outcome = solve(read_instance(M_TINY), encoding=own_encoding([typo]), max_horizon=5)
    assert outcome.status is SolveStatus.LIMIT and outcome.refuted == [4, 5]
    warning, = outcome.warnings
    assert warning.startswith(f"{typo}:2:17-") and "info: atom does not occur in any rule head" in warning


def test_includes_are_found_next_to_the_including_file(tmp_path, monkeypatch, capsys):
    (tmp_path / "m-moves.lp").write_text("this is not the file the encoding means\n")
    monkeypatch.chdir(tmp_path)
    code, _out, _err = _solve(capsys, M_TINY, "--encoding", OWN / "m-clingcon.lp", "-o", tmp_path / "plan.lp")
    assert code == 0


def test_several_files_are_loaded_in_order(tmp_path, capsys):
    moves = tmp_path / "moves.lp"
    moves.write_text(f'#const horizon = 1.\n#include "{OWN / "m-moves.lp"}".\n')
    show = tmp_path / "show.lp"
    show.write_text("occurs(object(robot,R),action(move,D),T) :- move(R,D,T).\n#show occurs/3.\n")
    code, out, err = _solve(capsys, M_TINY, "--encoding", moves, "--encoding", show, "--json")
    assert code == 0 and json.loads(out)["horizon"] == 4
    assert f"your encoding ({moves}, {show}): single-shot with a horizon constant" in err


def test_a_fixed_program_is_solved_once(capsys):
    code, out, err = _solve(capsys, M_TINY, "--encoding", OWN / "m-fixed.lp", "--json")
    report = json.loads(out)
    assert code == 0 and report["horizon"] == 4 and report["minimal"]
    assert [attempt["horizon"] for attempt in report["horizons_tried"]] == [4]
    assert "fixed (no horizon constant: solved once)" in err


def test_a_constant_horizon_solves_at_that_horizon_only(minimum, capsys):
    code, out, _err = _solve(capsys, PAPER_M, "--encoding", OWN / "m-single.lp", "-c", f"horizon={minimum + 2}",
                             "--json")
    report = json.loads(out)
    assert code == 0 and [a["horizon"] for a in report["horizons_tried"]] == [minimum + 2]
    assert report["horizon"] <= minimum + 2


def test_clingo_options_pass_and_refusals_say_why(capsys):
    code, _out, _err = _solve(capsys, M_TINY, "--encoding", OWN / "m-single.lp", "--configuration=crafty",
                              "-o", "-")
    assert code == 0
    code, _out, err = _solve(capsys, M_TINY, "--encoding", OWN / "m-single.lp", "--frobnicate=3")
    assert code == 2
    assert err == "error: clingo refuses the option --frobnicate=3: unknown option: 'frobnicate'\n"


def test_an_invalid_plan_lists_its_violations_and_exits_1(capsys):
    code, out, err = _solve(capsys, A_TINY, "--encoding", OWN / "a-wrong.lp", "--horizon", "3")
    assert code == 1 and out == ""
    assert "no valid plan: the plan of makespan 3 breaks the rules (2 violations)" in err
    outcome = solve(read_instance(A_TINY), encoding=own_encoding([OWN / "a-wrong.lp"]), horizon=3)
    assert outcome.status is SolveStatus.INVALID
    assert [error.atom for error in outcome.check.errors] == ["err(deliver,wrongStation,(1,3))",
                                                              "err(goal,unfilledOrder,(1,1,2,3))"]


def test_a_sign_error_is_caught_by_the_checker():
    outcome = solve(read_instance(M_TINY), encoding=own_encoding([OWN / "m-wrong.lp"]))
    assert outcome.status is SolveStatus.INVALID
    assert {(error.module, error.check) for error in outcome.check.errors} == {("move", "offFloor"),
                                                                              ("goal", "unfilledOrder")}


def test_a_domain_a_encoding_of_ones_own_meets_the_hand_derived_minimum(capsys):
    code, out, err = _solve(capsys, A_TINY, "--encoding", OWN / "a-single.lp", "--json")
    report = json.loads(out)
    assert code == 0 and report["domain"] == "a" and report["horizon"] == 4 and report["minimal"]
    assert report["plan"] == ["occurs(object(robot,1),action(move,(1,0)),1)",
                              "occurs(object(robot,1),action(pickup,()),2)",
                              "occurs(object(robot,1),action(move,(1,0)),3)",
                              "occurs(object(robot,1),action(deliver,(1,1,2)),4)"]


def test_a_model_without_a_plan_says_what_the_interface_is(capsys):
    code, _out, err = _solve(capsys, M_TINY, "--encoding", OWN / "m-none.lp")
    assert code == 1
    assert ("no valid plan: its model has no occurs(object(robot,R),action(Name,Args),T) atoms: an encoding "
            "reads the instance's init/2 facts and shows the plan as occurs/3 (e.g. #show occurs/3.)") in err


def test_a_reference_encoding_s_anonymous_model_is_no_plan_of_its_own():
    outcome = solve(read_instance(A_TINY), encoding=own_encoding([ROOT / "asprilo/encodings/abc/a.lp"]))
    assert outcome.status is SolveStatus.INVALID and "no occurs(object(robot,R)" in outcome.message


def test_clingcon3_programs_are_refused_naming_why(capsys):
    code, _out, err = _solve(capsys, M_TINY, "--encoding", OWN / "m-clingcon3.clp")
    assert code == 2
    assert err == (f"error: {OWN / 'm-clingcon3.clp'}:4: written for clingcon 3 ('#include <csp>.' and "
                   "$-constraints such as $<=), which clingcon 5 cannot read: state the constraints with "
                   "&sum{...} and &dom{...} (docs/OWN_ENCODINGS.md)\n")


def test_a_syntax_error_is_located(tmp_path, capsys):
    broken = tmp_path / "broken.lp"
    broken.write_text("#const horizon = 1.\nstep(1..horizon)\nrobot(R) :- init(object(robot,R),_).\n")
    code, _out, err = _solve(capsys, M_TINY, "--encoding", broken)
    assert code == 2
    assert err.startswith(f"error: {broken}:3: column ")
    assert "syntax error" in err


def test_a_program_that_grounds_for_ever_is_stopped_by_the_time_limit(tmp_path, capsys):
    endless = tmp_path / "endless.lp"
    endless.write_text("#const horizon = 1.\np(0).\np(X+1) :- p(X).\n")
    code, _out, err = _solve(capsys, M_TINY, "--encoding", endless, "--time-limit", "2")
    assert code == 1
    assert "no plan within the limits: stopped at the time limit (2 s)" in err


def test_unsatisfiable_horizons_are_said(tmp_path):
    never = tmp_path / "never.lp"
    never.write_text(f'#include "{OWN / "m-single.lp"}".\n:- step(1).\n')
    outcome = solve(read_instance(M_TINY), encoding=own_encoding([never]), max_horizon=6)
    assert outcome.status is SolveStatus.LIMIT
    # refuted by the encoding only: for the problem the lower bound stands (m-tiny.lp: 4 moves)
    assert outcome.refuted == [4, 5, 6] and outcome.proven_bound == 4 and not outcome.trusted


def test_bad_choices_of_encoding_are_refused(tmp_path, capsys):
    code, _out, err = _solve(capsys, M_TINY, "--encoding", "plain", "--encoding", "split")
    assert code == 2 and err == "error: name one reference encoding, not 2: plain, split\n"
    code, _out, err = _solve(capsys, M_TINY, "--encoding", "plain", "-c", "lanes=2")
    assert code == 2 and err == "error: -c sets constants of your own encoding; the reference encodings take none\n"
    code, _out, err = _solve(capsys, M_TINY, "--encoding", tmp_path / "missing.lp")
    assert code == 2 and err == f"error: {tmp_path / 'missing.lp'}: no such file\n"
    with pytest.raises(InputError, match="-c horizon=H is for single-shot encodings"):
        own_encoding([OWN / "m-incmode.lp"], [("horizon", "5")])


def test_the_domain_comes_from_the_instance_or_the_option():
    encoding = own_encoding([OWN / "m-single.lp"])
    assert encoding.domain is None and encoding.own
    outcome = solve(read_instance(M_TINY), Domain.M, encoding=encoding)
    assert outcome.found and outcome.domain is Domain.M
