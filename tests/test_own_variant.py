"""A variant written only in YAML + ASP, not one of the built-ins (docs/exercise/tired.yml: a
robot moves at most three steps in a row), reaches every tool: check, viz --export, solve with
an own encoding, grade against a reference, a bench suite.

By hand, on docs/exercise/corridor.lp (8x1, the robot seven moves from the shelf): seven moves
in a row break the rule at step 4; with a rest after every third move the plan takes 9 steps
(3 + rest + 3 + rest + 1), and 7 or 8 steps leave no room for two rests.  Without the rule 7.
"""

from __future__ import annotations

import json

from helpers import ROOT

from asprilo.bench.results import load_results
from asprilo.cli import main

EXERCISE = ROOT / "docs" / "exercise"
TIRED, CORRIDOR = EXERCISE / "tired.yml", EXERCISE / "corridor.lp"
ANN, BOB = EXERCISE / "students" / "ann.lp", EXERCISE / "students" / "bob.lp"


def test_check_says_the_rule_in_its_words(capsys):
    assert main(["check", str(CORRIDOR), str(EXERCISE / "rushed.lp"), "--variant", str(TIRED)]) == 1
    assert capsys.readouterr().out.splitlines()[0] == "step 4: robot 1 moves a fourth step in a row without resting"


def test_viz_exports_with_the_checkers_verdict(capsys, tmp_path):
    out = tmp_path / "rushed.png"
    code = main(["viz", str(CORRIDOR), str(EXERCISE / "rushed.lp"), "--variant", str(TIRED), "--export", str(out)])
    assert code == 1 and out.stat().st_size > 0
    assert "invalid plan: 1 violation (domain M+tired (detected), horizon 7)" in capsys.readouterr().err


def test_solve_with_an_own_encoding_checks_under_the_rule(capsys):
    assert main(["solve", str(CORRIDOR), "--variant", str(TIRED), "--encoding", str(ANN), "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert (report["status"], report["horizon"]) == ("found", 9)
    assert main(["solve", str(CORRIDOR), "--variant", str(TIRED), "--encoding", str(BOB), "--json"]) == 1
    report = json.loads(capsys.readouterr().out)
    assert report["status"] == "invalid" and report["horizon"] == 7


def test_grade_against_the_reference(capsys):
    code = main(["grade", str(BOB), "--variant", str(TIRED), "--reference", str(EXERCISE / "tired-plan.lp"),
                 "--instances", str(CORRIDOR), "--json"])
    entry = json.loads(capsys.readouterr().out)["instances"][0]
    assert (code, entry["result"], entry["minimum"], entry["makespan"]) == (1, "invalid", 9, 7)
    assert entry["violation"]["message"] == "step 4: robot 1 moves a fourth step in a row without resting"


def test_a_bench_suite_runs_under_the_rule(tmp_path):
    suite = tmp_path / "suite.yml"
    suite.write_text("name: tired\ntime_limit: 60\nmemory_limit: 2048\nmakespan_time_limit: 60\n"
                     f"encodings: {{ann: {{files: [{ANN}]}}}}\n"
                     f"instances: {{corridor: {{files: [{CORRIDOR}]}}}}\n"
                     f"runs:\n  - {{domain: m, variant: {TIRED}, encoding: [tired, ann]}}\n")
    assert main(["bench", str(suite), "-o", str(tmp_path / "out"), "--plots", "none"]) == 0
    records = sorted(load_results(tmp_path / "out"), key=lambda record: record["encoding"])
    assert [(r["encoding"], r["status"], r["horizon"]) for r in records] == [("ann", "solved", 9),
                                                                            ("tired", "solved", 9)]
    assert {record["domain"] for record in records} == {"m+tired"}
