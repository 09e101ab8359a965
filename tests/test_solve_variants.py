"""``asprilo solve`` under rule variants (docs/VARIANTS.md) and under domains registered with
rules of their own (docs/EXTENDING.md): which methods honour the rules, which encoding the
search runs, where it starts, and what it may claim.

Expected values by hand (tests/variants/*.lp say what they hold):

- corner.lp (3x3, robot 1 at (1,1), the ordered shelf at (3,3)): in M the robot needs the
  Manhattan distance, 4 moves; with diagonal moves the Chebyshev distance, 2 ((1,1) twice),
  and no plan of 0 or 1 step reaches (3,3).
- corridor.lp (4x1, robot 1 at (2,1) with energy 2, the shelf at (4,1)): 2 moves right; each
  costs 1, so energy 2 pays for them: makespan 2 under energy.  Under sides the middle is
  (4 + 1) // 2 = 2: the robot starts in the left half and may never reach x = 4: no plan.
  M's lower bound (the distance, 2) holds under both (they only restrict M), so the search
  starts at 2; it stops after horizon 2 + 4 cells + 1 robot + 2 x 1 order line = 9.
- docs/extending/corridor.lp (Mc, tests/test_extending.py): 4 with the charger, 2 without.
"""

from __future__ import annotations

import dataclasses
import json

import pytest
from helpers import ROOT

from asprilo.cli import main
from asprilo.domain import Domain, ReferenceEncoding, register, unregister
from asprilo.domain.variants import with_variants
from asprilo.encodings import SolveRequest, SolveStatus, solve
from asprilo.encodings.solving import find_method, request_for
from asprilo.encodings.solving.method import spec_rules
from asprilo.encodings.solving.methods import methods_words, resolve
from asprilo.errors import InputError
from asprilo.reader import read_instance

HERE = ROOT / "tests" / "variants"
CORNER, CORRIDOR = HERE / "corner.lp", HERE / "corridor.lp"
EXTENDING = ROOT / "docs" / "extending"


def _solve(capsys, *arguments) -> tuple[int, dict, str]:
    code = main(["solve", *map(str, arguments), "--json"])
    captured = capsys.readouterr()
    return code, json.loads(captured.out) if captured.out.strip() else {}, captured.err


# --- the variants through the command ------------------------------------------------------------

def test_diagonal_moves_make_the_corner_two_steps_and_the_summary_says_how_that_was_proven(capsys):
    code, report, err = _solve(capsys, CORNER, "--variant", "diagonal")
    assert (code, report["status"], report["horizon"], report["minimal"]) == (0, "found", 2, True)
    assert (report["domain"], report["method"], report["encoding"], report["variants"]) == (
        "m+diagonal", "asp", "diagonal", ["diagonal"])
    assert (report["lower_bound"], report["refuted"]) == (0, [0, 1])
    assert report["plan"] == ["occurs(object(robot,1),action(move,(1,1)),1)",
                              "occurs(object(robot,1),action(move,(1,1)),2)"]
    lines = err.splitlines()
    assert lines[0] == ("M+diagonal: max-flow and the anytime planner know only SPEC.md's rules, not the rules of "
                        "variant 'diagonal'; the exact search serves it, with the model solution of variant 'diagonal'")
    assert ("no lower bound under M+diagonal: variant 'diagonal' may allow shorter plans than M's rules, so the "
            "search starts at horizon 0") in lines
    assert ("proven minimal under M+diagonal's rules: the encoding 'diagonal' (the model solution of variant "
            "'diagonal') has no plan at horizons 0-1") in lines


def test_without_the_variant_the_corner_takes_four_moves_by_max_flow(capsys):
    code, report, err = _solve(capsys, CORNER)
    assert (code, report["horizon"], report["minimal"], report["method"], report["variants"]) == (
        0, 4, True, "flow", [])
    assert "know only SPEC.md's rules" not in err


def test_energy_restricts_m_so_the_search_starts_at_m_s_bound_and_meets_it(capsys):
    code, report, err = _solve(capsys, CORRIDOR, "--variant", "energy")
    assert (code, report["horizon"], report["minimal"], report["lower_bound"], report["encoding"]) == (
        0, 2, True, 2, "energy")
    assert [attempt["horizon"] for attempt in report["horizons_tried"]] == [2]
    assert "lower bound 2: M's, which holds under M+energy (variant 'energy' only restricts its rules)" in err
    assert "proven minimal under M+energy's rules: the plan meets the lower bound" in err


def test_energy_too_low_for_the_way_is_no_plan_where_m_has_one(capsys, tmp_path):
    """Energy 1 pays for one move of the two: the model solution refutes every horizon."""
    weak = tmp_path / "weak.lp"
    weak.write_text(CORRIDOR.read_text().replace("value(energy,2)", "value(energy,1)"))
    code, report, _err = _solve(capsys, weak, "--variant", "energy")
    assert (code, report["status"], report["refuted"]) == (1, "limit", list(range(2, 10)))


def test_sides_leave_no_plan_and_the_search_says_where_it_stopped(capsys):
    code, report, err = _solve(capsys, CORRIDOR, "--variant", "sides", "--time-limit", "60")
    assert (code, report["status"], report["horizon"], report["minimal"]) == (1, "limit", None, False)
    assert report["refuted"] == list(range(2, 10)) and report["proven_bound"] == 10
    assert report["message"].startswith("the encoding 'sides' has no plan up to horizon 9, where the search stops")
    assert "refuted horizons 2-9: no plan is shorter than 10" in err
    assert "proven minimal" not in err


def test_composed_variants_refute_with_the_last_model_solution_only_where_that_is_sound(capsys):
    """diagonal, then sides: sides' solution knows four moves, so what it refutes is not refuted
    under M+diagonal+sides (nothing is claimed; it stops after 0 + 9 cells + 1 robot + 2 = 12).
    sides, then diagonal: sides only restricts, so diagonal's refutations of 0 and 1 hold; its
    plan of 2 leaves the left half (x <= 2) at step 2 and is rejected."""
    code, report, err = _solve(capsys, CORNER, "--variant", "diagonal", "--variant", "sides")
    assert (code, report["status"], report["encoding"], report["refuted"]) == (1, "limit", "sides", [])
    assert report["refuted_along_assignment"] == list(range(13)) and report["proven_bound"] == 0
    assert "no plan for the encoding 'sides' at horizons 0-12 (it states the rules of its variant alone: not " \
           "refuted under M+diagonal+sides)" in err
    code, report, err = _solve(capsys, CORNER, "--variant", "sides", "--variant", "diagonal")
    assert (code, report["status"], report["refuted"]) == (1, "invalid", [0, 1])
    assert "step 2: robot 1 leaves the left half of the floor, where it started" in err


def test_a_method_written_for_spec_s_rules_is_refused_under_a_variant(capsys):
    for method, said in (("flow", "the flow method knows only SPEC.md's rules of M and Md, not the rules of "
                                  "variant 'diagonal'"),
                         ("anytime", "the anytime planner knows only SPEC.md's rules, not the rules of variant "
                                     "'diagonal'")):
        assert main(["solve", str(CORNER), "--variant", "diagonal", "--method", method]) == 2
        assert said in capsys.readouterr().err


def test_a_variant_without_a_model_solution_for_the_domain_is_refused_naming_it(capsys):
    assert main(["solve", str(CORRIDOR), "--domain", "a", "--variant", "energy"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: no method of solve serves A+energy: max-flow and the anytime planner know only "
                          "SPEC.md's rules, not the rules of variant 'energy', and variant 'energy' names no model "
                          "solution for A")
    assert err.rstrip().endswith("give your own encoding to solve under its rules: --encoding FILE")


def test_your_own_encoding_is_checked_with_the_variant_s_rules(capsys, tmp_path):
    """M's encoding of the tests moves in four directions: its plan of 4 passes M's checker and,
    under diagonal, the variant's too (its four moves are moves of the eight)."""
    own = ROOT / "tests" / "encodings" / "m-single.lp"
    code, report, _err = _solve(capsys, CORNER, "--variant", "diagonal", "--encoding", own)
    assert (code, report["domain"], report["horizon"]) == (0, "m+diagonal", 4)
    assert report["refuted"] == [0, 1, 2, 3]  # from 0: the variant allows shorter plans than M's bound


# --- which methods honour which rules -----------------------------------------------------------

def test_max_flow_and_anytime_honour_the_built_in_rules_only():
    flow, anytime, exact = find_method("flow"), find_method("anytime"), find_method("asp")
    m = Domain.parse("m")
    diagonal = with_variants(m, ["diagonal"])
    assert (flow.honours(m), anytime.honours(m), exact.honours(m)) == (True, True, True)
    assert (flow.honours(diagonal), anytime.honours(diagonal), exact.honours(diagonal)) == (False, False, True)
    assert not flow.honours(Domain.parse("a")) and anytime.honours(Domain.parse("a"))
    assert methods_words(m) == ""


@pytest.fixture
def renamed_m():
    """M under another name, with M's rules: a domain registered at run time that changes nothing."""
    domain = register(dataclasses.replace(Domain.parse("m"), value="m-again", label="M again"))
    yield domain
    unregister(domain)


@pytest.fixture
def no_waiting(tmp_path):
    """'M, no waiting': M with one checker concern more, registered at run time and keeping
    M's encodings (which know nothing of the rule)."""
    concern = tmp_path / "nowait.lp"
    concern.write_text("% no robot stands still before the horizon\n"
                       "err(nowait,waited,(R,T)) :- position(R,C,T-1), position(R,C,T), horizon(H), T <= H, T > 0.\n")
    m = Domain.parse("m")
    domain = register(dataclasses.replace(m, value="mnw", label="Mnw", checker=(*m.checker[:-1], str(concern), "goal")))
    yield domain
    unregister(domain)


def test_rules_are_compared_not_names(renamed_m, no_waiting):
    assert spec_rules(renamed_m) and not spec_rules(no_waiting)
    assert find_method("flow").honours(renamed_m) and not find_method("flow").honours(no_waiting)
    instance = read_instance(CORNER)
    assert resolve(SolveRequest(instance, renamed_m, method="auto")).method == "flow"
    assert resolve(SolveRequest(instance, no_waiting, method="auto")).method == "asp"


def test_a_domain_with_a_concern_more_is_not_routed_to_max_flow(no_waiting):
    """The default solve of corner.lp runs M's plain encoding (the domain's own): robot 1 has
    four moves to make in four steps, so its plan never waits and passes the rule."""
    outcome = solve(CORNER, no_waiting, method="auto", time_limit=60)
    assert (outcome.status, outcome.method, outcome.encoding, outcome.horizon) == (SolveStatus.FOUND, "asp", "plain", 4)
    assert outcome.check.valid


def test_a_domain_with_a_concern_more_and_no_encoding_is_refused_in_words(no_waiting):
    bare = register(dataclasses.replace(no_waiting, value="mnw-bare", label="Mnw bare", encodings=()))
    try:
        with pytest.raises(InputError, match=r"no method of solve serves Mnw bare: max-flow and the anytime planner "
                                             r"know only SPEC.md's rules, not the rules of domain Mnw bare"):
            request_for(CORNER, bare, method="auto")
    finally:
        unregister(bare)


@pytest.fixture
def mc():
    """docs/EXTENDING.md's Mc: Md, and every robot passes over a charger (its own encoding)."""
    from asprilo.objects import CELL, ObjectKind, register_kind, unregister_kind

    register_kind(ObjectKind("charger", "charger", "chargers", {"at": CELL}))
    md = Domain.parse("md")
    domain = register(dataclasses.replace(
        md, value="mc", label="Mc", reads=md.reads | {"charger"},
        checker=(*md.checker[:-1], str(EXTENDING / "charged.lp"), "goal"),
        encodings=(ReferenceEncoding("charge", str(EXTENDING / "charge.lp")),), generation=None))
    yield domain
    unregister(domain)
    unregister_kind("charger")


def test_the_default_solve_of_mc_runs_its_own_encoding_not_max_flow(mc, capsys):
    code, report, err = _solve(capsys, EXTENDING / "corridor.lp", "--domain", "mc")
    assert (code, report["method"], report["encoding"], report["horizon"], report["minimal"]) == (
        0, "asp", "charge", 4, True)
    assert err.splitlines()[0] == (
        "Mc: max-flow and the anytime planner know only SPEC.md's rules, not the rules of domain Mc (its checker "
        "concerns are not those of a built-in domain); the exact search serves it, with the encoding 'charge'")


def test_the_bench_worker_asks_the_method_not_the_domain_s_name(mc):
    """A makespan job of Mc: max-flow would plan 2 steps, which the charger rule rejects."""
    from asprilo.bench.worker import run

    report = run({"kind": "makespan", "instance": str(EXTENDING / "corridor.lp"), "domain": "mc", "time_limit": 60})
    assert (report["status"], report["horizon"], report["minimal"]) == ("found", 4, True)
