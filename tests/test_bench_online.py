"""Online suites (``asprilo bench online``, asprilo/bench/online.py): read and checked, run,
reported; the figures are those of test_online_run.py's corridor, derived there by hand."""

from __future__ import annotations

import json

import pytest
from test_online_scenarios import SCENARIO

from asprilo.bench.online import load_online_suite
from asprilo.cli import main
from asprilo.errors import InputError


def _suite(folder, text: str):
    (folder / "corridor.lp").write_text(SCENARIO)
    path = folder / "suite.yml"
    path.write_text(text)
    return path


def test_a_suite_runs_every_scenario_planner_and_budget_and_reports_them(tmp_path, capsys):
    """Order 2 released at step 4 (the scenario's own); 6 steps: order 1 done at 3, order 2 at 5."""
    suite = _suite(tmp_path, "name: corridor\nscenarios: {files: [corridor.lp]}\nsteps: 6\nplanners: [asp]\n"
                             "budgets: [30, 60]\n")
    out = tmp_path / "out"
    assert main(["bench", "online", str(suite), "-o", str(out), "--plots", "png"]) == 0
    records = [json.loads(line) for line in (out / "online.jsonl").read_text().splitlines()]
    assert [(r["scenario"], r["method"], r["budget"], r["lines_done"], r["units_done"], r["ceiling_lines"],
             r["latency"]) for r in records] == [
        ("corridor.lp", "asp", budget, 2, 3, 2, {"orders": 2, "mean": 2.0, "p95": 3, "max": 3}) for budget in (30, 60)]
    assert all(r["lines_per_100"] == 100 * 2 / 6 for r in records)
    err = capsys.readouterr().err
    assert "[1/2] corridor.lp asp 30 s: 33.3 lines per 100 steps, 0 waiting steps" in err
    table = (out / "report" / "online.txt").read_text().splitlines()
    assert table[2].split() == ["planner", "budget", "(s)", "lines/100", "steps", "%", "of", "ceiling", "latency",
                                "p95", "s/call", "max", "s", "waiting"]
    assert table[4].split()[:6] == ["asp", "30", "33.3", "100", "2.0", "3"]
    assert (out / "report" / "online.csv").read_text().splitlines()[0] == (
        "scenario,method,budget,ended,steps,lines,lines_done,units_done,lines_per_100,ceiling_lines,waiting_steps")
    assert (out / "report" / "throughput.png").read_bytes()[:4] == b"\x89PNG"
    assert "\\begin{tabular}" in (out / "report" / "online.tex").read_text()


@pytest.mark.parametrize(("text", "words"), [
    ("name: x\nscenarios: {files: [corridor.lp]}\nplanners: [fast]\n",
     "planners: choose among anytime, asp, multishot"),
    ("name: x\nscenarios: {files: [corridor.lp]}\nbudgets: [0]\n", "budgets: seconds a planner call may take, above 0"),
    ("name: x\nscenarios: {files: [corridor.lp]}\nsteps: 0\n", "steps: a whole number of at least 1, got 0"),
    ("name: x\nscenarios: [corridor.lp]\n", "scenarios: give {files: [PATTERN, ...]}"),
    ("name: x\nscenarios: {files: [nothing*.lp]}\n", "scenarios: no file matches 'nothing*.lp'"),
    ("name: x\nscenario: {files: [corridor.lp]}\n",
     "unknown key 'scenario' (an online suite has budgets, every, name, planners, scenarios, step_seconds, steps)"),
])
def test_a_bad_suite_is_refused_in_words(tmp_path, text, words):
    path = _suite(tmp_path, text)
    with pytest.raises(InputError) as refused:
        load_online_suite(path)
    assert (refused.value.message, refused.value.file) == (words, str(path))
