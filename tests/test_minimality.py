"""Minimal for the problem, or only the shortest plan an own encoding allows (issue 47, item 2):
solve's summary and --json, grade's lines and JSON, bench's failed runs; an invalid plan is
never minimal.

The weak encodings are the tests' own, each correct but for one restriction the domain does
not have: ``m-one-mover.lp`` moves one robot per step, ``a-one-unit.lp`` hands over one unit
per delivery.  The minima, by hand (in the instances' comments): on ``m-side-by-side.lp`` the
two robots move right twice at once, 2 steps (the lower bound), one at a time 4; on
``a-tiny.lp`` move, pick up, move, deliver both units: 4 (the lower bound), one unit at a
time 5; on the M ladder's ``02-x5_y2_r2.lp`` (stored minimum 4) robot 2 goes down and right
three times while robot 1 moves right four times, 4 steps, one at a time 4 + 4 = 8 (no
assignment of the two robots to the shelves at (5,1) and (5,2) needs fewer than 8 moves).
"""

from __future__ import annotations

import json

from helpers import ROOT

from asprilo.cli import main
from asprilo.encodings import solve
from asprilo.encodings.ladder import LADDERS
from asprilo.encodings.own import own_encoding
from asprilo.encodings.solving.minimality import problem_minimum, sentence

OWN = ROOT / "tests" / "encodings"
ONE_MOVER, ONE_UNIT = OWN / "m-one-mover.lp", OWN / "a-one-unit.lp"
SIDE_BY_SIDE, A_TINY, M_TINY = OWN / "m-side-by-side.lp", OWN / "a-tiny.lp", OWN / "m-tiny.lp"
M_LADDER_02 = LADDERS / "m" / "02-x5_y2_r2.lp"
ONLY = "(refuted for the encoding only, not for the problem)"


def _solve(capsys, *arguments) -> tuple[int, dict, list[str]]:
    """solve's exit status, its --json report (when asked for) and its summary lines (the
    progress lines left out)."""
    code = main(["solve", *map(str, arguments)])
    captured = capsys.readouterr()
    report = json.loads(captured.out) if captured.out.startswith("{") else {}
    lines = [line for line in captured.err.splitlines() if not line.startswith("horizon ")]
    return code, report, lines


def _minimality(report: dict) -> tuple:
    return tuple(report[key] for key in ("status", "horizon", "minimal", "encoding_minimal", "minimum", "minimum_by",
                                         "refuted", "proven_bound", "gap"))


def test_the_sentences():
    assert sentence(10, 8, 8, "by max-flow") == ("the shortest plan this encoding allows (10); the problem's minimum "
                                                 "is 8, by max-flow")
    assert sentence(10, None, 7) == ("the shortest plan this encoding allows (10); the problem's minimum is unknown: "
                                     "no plan is shorter than 7")
    assert problem_minimum(None, 0) == problem_minimum(None, float("inf")) == "the problem's minimum is unknown"


def test_a_weak_m_encoding_is_the_shortest_it_allows_and_max_flow_gives_the_minimum(capsys):
    code, report, lines = _solve(capsys, SIDE_BY_SIDE, "--encoding", ONE_MOVER, "--json")
    assert code == 0
    assert _minimality(report) == ("found", 4, False, True, 2, "by max-flow", [2, 3], 2, 2)
    assert lines[2:4] == [
        "plan: horizon 4 (the shortest plan this encoding allows (4); the problem's minimum is 2, by max-flow), "
        "4 actions, checked: valid",
        f"your encoding has no plan at horizons 2-3 {ONLY}"]
    assert not any("proven minimal" in line for line in lines)


def test_a_weak_a_encoding_leaves_the_minimum_unknown_with_the_bound(capsys):
    code, report, lines = _solve(capsys, A_TINY, "--encoding", ONE_UNIT, "--json")
    assert code == 0
    assert _minimality(report) == ("found", 5, False, True, None, None, [4], 4, 1)
    assert lines[2:4] == [
        "plan: horizon 5 (the shortest plan this encoding allows (5); the problem's minimum is unknown: no plan is "
        "shorter than 4), 5 actions, checked: valid",
        f"your encoding has no plan at horizon 4 {ONLY}"]
    # the hand-derived minimum 4, proven by the reference encoding (trusted: "proven minimal")
    reference = solve(A_TINY, "a", time_limit=60)
    assert (reference.horizon, reference.minimal, reference.encoding_minimal, reference.minimum) == (4, True, True, 4)


def test_the_ladder_s_stored_minimum_is_the_problem_s(capsys):
    code, report, lines = _solve(capsys, M_LADDER_02, "--encoding", ONE_MOVER, "--json")
    assert code == 0
    assert _minimality(report) == ("found", 8, False, True, 4, "as the M ladder stores it for 02-x5_y2_r2.lp",
                                   [4, 5, 6, 7], 4, 4)
    assert lines[2] == ("plan: horizon 8 (the shortest plan this encoding allows (8); the problem's minimum is 4, as "
                        "the M ladder stores it for 02-x5_y2_r2.lp), 8 actions, checked: valid")


def test_an_own_plan_at_the_lower_bound_or_at_the_known_minimum_is_minimal(capsys):
    code, report, lines = _solve(capsys, M_TINY, "--encoding", OWN / "m-single.lp", "--json")
    assert code == 0 and _minimality(report) == ("found", 4, True, True, 4, None, [], 4, 0)
    assert lines[2] == "plan: horizon 4 (proven minimal), 4 actions, checked: valid"
    # one robot on the A ladder's 02 (lower bound 11, stored minimum 15): the encoding is right
    code, report, lines = _solve(capsys, LADDERS / "a" / "02-x4_y2_r1.lp", "--encoding", OWN / "a-single.lp", "--json")
    assert code == 0
    assert _minimality(report) == ("found", 15, True, True, 15, "as the A ladder stores it for 02-x4_y2_r1.lp",
                                   [11, 12, 13, 14], 15, 0)
    assert lines[2] == ("plan: horizon 15 (proven minimal: the problem's minimum is 15, as the A ladder stores it for "
                        "02-x4_y2_r1.lp), 15 actions, checked: valid")


def test_an_encoding_without_a_plan_at_a_horizon_proves_nothing_for_the_problem(capsys):
    code, report, lines = _solve(capsys, M_LADDER_02, "--encoding", ONE_MOVER, "--horizon", "4", "--json")
    assert (code, report["status"], report["refuted"], report["proven_bound"]) == (1, "none", [4], 4)
    assert lines[2] == f"your encoding has no plan at horizon 4 {ONLY}"
    assert not any("no plan exists" in line for line in lines)


def test_an_invalid_plan_is_never_minimal(capsys):
    """mapf-upside-down.lp plans "down" as up: on down.lp its plan at the lower bound 2 breaks
    the rules."""
    code, report, lines = _solve(capsys, ROOT / "docs/own-encoding/down.lp", "--encoding",
                                 ROOT / "docs/own-encoding/mapf-upside-down.lp", "--json")
    assert code == 1
    assert (report["status"], report["horizon"], report["minimal"], report["encoding_minimal"], report["minimum"],
            report["plan"]) == ("invalid", 2, False, False, None, None)
    assert not any("minimal" in line for line in lines)


def test_grade_says_the_same_sentence(capsys):
    code = main(["grade", str(ONE_MOVER), "--domain", "m", "--first", "2", "-q"])
    lines = capsys.readouterr().out.splitlines()
    assert code == 0
    assert lines[1].endswith("  valid    minimal (makespan 3)")
    assert lines[2].endswith("  valid    the shortest plan this encoding allows (8); the problem's minimum is 4 "
                             "(horizons 4-7 refuted, yet plans exist from makespan 4 on: a constraint is too strong)")
    assert lines[3].startswith("2/2 valid, 1/2 minimal; ")
    main(["grade", str(ONE_MOVER), "--domain", "m", "--first", "2", "-q", "--json"])
    entries = json.loads(capsys.readouterr().out)["instances"]
    assert [(e["minimum"], e["makespan"], e["valid"], e["minimal"], e["encoding_minimal"]) for e in entries] == [
        (3, 3, True, True, True), (4, 8, True, False, True)]


def test_bench_says_a_run_has_no_plan_at_the_problem_s_minimum(tmp_path, capsys):
    suite = tmp_path / "suite.yml"
    suite.write_text(f"encodings:\n  weak: {{files: [\"{ONE_MOVER}\"]}}\ninstances:\n  small: {{files: "
                     f"[\"{M_LADDER_02}\"]}}\nruns:\n  - {{domain: m, encoding: [plain, weak]}}\n")
    assert main(["bench", str(suite), "-o", str(tmp_path / "out"), "--plots", "none"]) == 0
    out = capsys.readouterr().out
    assert f"M weak: small {M_LADDER_02}: error: the encoding has no plan at horizon 4, the problem's minimum" \
        in " ".join(out.split())  # (the line wraps)
    rows = [line.split() for line in out.splitlines() if line.split()[:1] in (["M"], ["weak"])]
    assert rows[0][:3] == ["M", "4.0", "plain"] and rows[1][0] == "weak" and rows[1][-2:] == ["-(0)", "!1"]


def test_the_teacher_s_reference_stays_trusted():
    """A reference given as a file is an own encoding: grade trusts it all the same (its
    minimum is the one its search proves: m-single.lp on the M ladder's 02 proves 4)."""
    from asprilo.encodings.reference import found
    from asprilo.reader import read_instance

    outcome = solve(read_instance(M_LADDER_02), "m", encoding=own_encoding([OWN / "m-single.lp"]), time_limit=60)
    assert (outcome.horizon, outcome.minimal, outcome.trusted) == (4, True, False)
    said = found(outcome, 1.0, 60)
    assert (said.minimum, said.makespan, said.at_least) == (4, 4, 4)


def test_the_page_shows_what_solve_says(capsys, monkeypatch):
    """docs/OWN_ENCODINGS.md's example of a weak encoding: its command, run from the root of
    the checkout, says the two lines the page shows."""
    page = (ROOT / "docs" / "OWN_ENCODINGS.md").read_text(encoding="utf-8").splitlines()
    start = page.index("    asprilo solve tests/encodings/m-side-by-side.lp --encoding tests/encodings/m-one-mover.lp")
    shown = [line.strip() for line in page[start + 1:start + 3]]
    monkeypatch.chdir(ROOT)
    _code, _report, lines = _solve(capsys, "tests/encodings/m-side-by-side.lp", "--encoding",
                                   "tests/encodings/m-one-mover.lp")
    assert lines[2:4] == shown


def test_the_heartbeat_claims_nothing_from_an_own_encoding_s_refutations():
    from helpers.streams import Terminal

    from asprilo.encodings import Attempt
    from asprilo.encodings.cli import SearchProgress

    for own, said in ((False, "best plan: makespan 4 (proven minimal) | no plan shorter than 4 | "),
                      (True, "best plan: makespan 4 | ")):
        progress = SearchProgress(Terminal(), time_limit=300, own=own)
        for horizon in (2, 3):
            progress.attempt(Attempt(horizon, "unsat", 0.1))
        progress.attempt(Attempt(4, "sat", 0.1, plan=object()))
        line = progress.heartbeat(progress.started + 1.2)
        progress.close()
        assert line == f"{said}elapsed 1 s, 299 s left"
