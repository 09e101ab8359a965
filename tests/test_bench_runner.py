"""The benchmark runner: checked plans, failures counted, resuming after a kill."""

from __future__ import annotations

import io
import json
import os
import re
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import pytest
from helpers import EXAMPLES

from asprilo.bench import runner as runner_module
from asprilo.bench.btool import read_results
from asprilo.bench.limits import LimitedRun
from asprilo.bench.results import STATUSES, load_results
from asprilo.bench.runner import Runner
from asprilo.bench.suite import load_suite
from asprilo.cli import main

TINY = EXAMPLES / "encodings-repo/x2_y2_n4_r2_s2_ps1_pr2_u4_o2_N1.lp"
SMALL = EXAMPLES / "paper-m/1x2x4/x11_y6_n66_r2_s16_ps1_pr16_u16_o2_N001.lp"


def suite_file(write, files, runs="[{domain: m, encoding: [plain, split]}]"):
    listed = ", ".join(f'"{f}"' for f in files)
    return write("suite.yml", f"name: t\ntime_limit: 30\nmemory_limit: 2048\n"
                              f"instances: {{tiny: {{files: [{listed}]}}}}\nruns: {runs}\n")


def off_the_floor(job, time_limit, memory_mb):
    """A solver whose makespan is 1 and whose plan breaks the rules."""
    if job["kind"] == "makespan":
        return LimitedRun("done", 0.1, {"status": "found", "horizon": 1, "minimal": True})
    plan = "occurs(object(robot,1),action(move,(0,-1)),1)."  # off the 2x2 floor
    return LimitedRun("done", 0.2, {"status": "found", "time": 0.2, "plan": plan, "stats": {}})


def test_an_invalid_plan_is_a_failure(write, tmp_path, monkeypatch, capsys):
    """A solver that returns a plan breaking the rules: the runner's own check catches it."""
    monkeypatch.setattr(runner_module, "run_limited", off_the_floor)
    suite = load_suite(suite_file(write, [TINY], "[{domain: m}]"))
    records = Runner(suite, tmp_path / "out").run()
    assert [(r["status"], r["horizon"]) for r in records] == [("invalid", 1)]
    assert records[0]["violations"] == ["err(goal,unfilledOrder,(1,1,1,1))", "err(goal,unfilledOrder,(2,2,3,1))",
                                        "err(move,offFloor,(1,1))"]
    assert records[0]["error"] == (
        "the plan breaks the rules: step 1 (the horizon): order 1 is not fulfilled: no robot stands under a shelf "
        "holding product 1; step 1 (the horizon): order 2 is not fulfilled: no robot stands under a shelf holding "
        "product 2; step 1: robot 1 moves to (1,0), which is not a floor node")
    assert main(["bench", "report", str(tmp_path / "out"), "--plots", "none"]) == 0
    out = capsys.readouterr().out
    assert "M       1.0       plain     -(0) x1" in out  # not averaged in as a time
    assert f"Failed runs (1; not in the averages, not in PAR): domain encoding, set instance, why M plain: " \
           f"tiny {TINY}: invalid plan: {records[0]['error']}" in " ".join(out.split())


#: ``asprilo bench ARGS...`` that, once it has recorded its second run, says so and waits to
#: be killed (its next run may be under way meanwhile): a runner killed at the same point on
#: every machine
BENCH_UNTIL_TWO_RUNS = """
import sys, threading
from asprilo.bench import runner
from asprilo.cli import main

append, recorded = runner.append_result, []

def append_then_wait(folder, record):
    append(folder, record)
    recorded.append(record)
    if len(recorded) == 2:
        print("recorded 2 runs", flush=True)
        threading.Event().wait()

runner.append_result = append_then_wait
sys.exit(main(sys.argv[1:]))
"""


def test_a_killed_runner_resumes_without_repeating_runs(write, tmp_path):
    suite = suite_file(write, [TINY, SMALL], "[{domain: m, encoding: [plain, split, clingcon, dl]}]")
    out = tmp_path / "out"
    arguments = ["bench", str(suite), "-o", str(out)]
    first = subprocess.Popen([sys.executable, "-c", BENCH_UNTIL_TWO_RUNS, *arguments], stdout=subprocess.PIPE,
                             stderr=subprocess.DEVNULL, text=True, start_new_session=True)
    try:
        assert first.stdout.readline() == "recorded 2 runs\n"  # (an empty line: it ended before)
    finally:
        os.killpg(first.pid, signal.SIGKILL)
        first.wait()
        first.stdout.close()
    done_before = {r["key"]: r for r in load_results(out)}
    assert len(done_before) == 2
    result = subprocess.run([sys.executable, "-m", "asprilo.cli", *arguments], capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 0, result.stderr
    assert f"resuming: {len(done_before)} runs already recorded" in result.stderr
    records = load_results(out)
    keys = [r["key"] for r in records]
    assert len(keys) == len(set(keys)) == 8
    assert all(records[i] == done_before[keys[i]] for i in range(len(done_before)))
    assert {r["status"] for r in records} == {"solved"}
    assert json.loads((out / "makespans.json").read_text()) == {
        str(TINY): {"M": 1}, str(SMALL): {"M": 6}}


BTOOL = shutil.which("btool", path=f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}")


def masked(summary: str) -> str:
    """A report with the run times (and so the best-encoding marks, which follow them, the
    PAR columns and the column widths) left out."""
    summary = re.sub(r"(?m)^(.* \d+/\d+ +\d+ +\d+ +\d+ +)\S+ +\S+$", r"\1P P", summary)
    return re.sub(r" +", " ", re.sub(r"-{2,}", "-", re.sub(r"\b\d+(\.\d)?\((\d+)\)( !\d+)?( x\d+)?\*?",
                                                           r"T(\2)\3\4", summary)))


needs_runlim = pytest.mark.skipif(
    shutil.which("runlim") is None,
    reason="runlim is not installed (Debian/Ubuntu: apt-get install runlim); btool's runs need it")
needs_btool = pytest.mark.skipif(
    BTOOL is None, reason="btool is not installed (pip install -e '.[test]' brings potassco-benchmark-tool)")


def btool_round_trip(cluster: Path) -> list[dict]:
    """btool gen, the sequential job, btool eval (into results.xml) in an export folder; the records."""
    for command in ([BTOOL, "gen", "runscripts/t.xml"], [sys.executable, "output/t-seq/cluster/start.py"]):
        done = subprocess.run(command, cwd=cluster, capture_output=True, text=True, timeout=300)
        assert done.returncode == 0, done.stderr
    evaluated = subprocess.run([BTOOL, "eval", "runscripts/t.xml"], cwd=cluster, capture_output=True, text=True,
                               timeout=300)
    assert evaluated.returncode == 0, evaluated.stderr
    (cluster / "results.xml").write_text(evaluated.stdout)
    records = read_results(cluster / "results.xml")
    assert {r["status"] for r in records} <= set(STATUSES)
    return records


@needs_runlim
@needs_btool
def test_the_btool_round_trip_gives_the_local_summary(write, tmp_path, capsys):
    """export-btool -> btool gen -> the sequential job -> btool eval -> bench report, against a local run."""
    suite = write("suite.yml", f"name: t\ntime_limit: 60\nmemory_limit: 2048\nmakespan_time_limit: 60\n"
                               f"instances: {{tiny: {{files: ['{TINY}']}}, small: {{files: ['{SMALL}']}}}}\n"
                               f"runs: [{{domain: m, encoding: [plain, split]}}, {{domain: a, sets: [tiny]}}]\n")
    cluster = tmp_path / "cluster"
    assert main(["bench", "export-btool", str(suite), str(cluster)]) == 0
    assert not list(cluster.glob("benchmarks/*/*.makespans.json"))  # the runs find them, not the export
    records = btool_round_trip(cluster)
    capsys.readouterr()
    assert main(["bench", "report", str(cluster / "results.xml")]) == 0
    from_btool = capsys.readouterr().out
    assert main(["bench", str(suite), "-o", str(tmp_path / "local")]) == 0
    local = capsys.readouterr().out
    assert masked(from_btool) == masked(local)
    assert masked(local).splitlines()[2:6] == [  # M's makespans: 1 (2x2) and 6 (the paper's r02 instance)
        "domain makespan encoding tiny small", "- - - - -", "M 1.0/6.0 plain T(0) T(0)", " split T(0) T(0)"]
    assert sorted((r["set"], r["label"], r["encoding"], r["status"]) for r in records) == [
        ("small", "M", "plain", "solved"), ("small", "M", "split", "solved"), ("tiny", "A", "plain", "solved"),
        ("tiny", "M", "plain", "solved"), ("tiny", "M", "split", "solved")]
    local_spans = json.loads((tmp_path / "local/makespans.json").read_text())
    for instance in (TINY, SMALL):  # the runs cached the minimal makespans they found beside the instances
        cached = json.loads((cluster / "benchmarks" / ("tiny" if instance == TINY else "small")
                             / f"{instance.name}.makespans.json").read_text())
        assert cached == local_spans[str(instance)]


@needs_runlim
@needs_btool
def test_a_run_that_runlim_stops_counts_as_a_memout(write, tmp_path, capsys):
    """12 MB are less than Python with clingo needs to start: runlim stops the run, whatever the
    machine (40 MB no longer do: the tiny M instance solves within them since the max-flow of a
    small floor imports neither numpy nor scipy)."""
    suite = write("suite.yml", f"name: t\ntime_limit: 60\nmemory_limit: 12\n"
                               f"instances: {{tiny: {{files: ['{TINY}']}}}}\nruns: [{{domain: m}}]\n")
    cluster = tmp_path / "cluster"
    assert main(["bench", "export-btool", str(suite), str(cluster)]) == 0
    records = btool_round_trip(cluster)
    assert [(r["label"], r["status"], r["time"], r["time_limit"], r["robots"]) for r in records] == [
        ("M", "memout", 60.0, 60.0, 2)]
    capsys.readouterr()
    assert main(["bench", "report", str(cluster / "results.xml")]) == 0
    assert "M       -         plain     60(1)\n" in capsys.readouterr().out  # out of limits, at the limit


def test_a_rerun_with_other_limits_is_refused_or_restarted(write, tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(runner_module, "run_limited", off_the_floor)
    suite, out = suite_file(write, [TINY], "[{domain: m}]"), tmp_path / "out"
    assert main(["bench", str(suite), "-o", str(out)]) == 0
    before = (out / "results.jsonl").read_text()
    capsys.readouterr()
    assert main(["bench", str(suite), "-o", str(out), "--time-limit", "5", "--memory-limit", "1000"]) == 2
    assert capsys.readouterr().err == (
        f"error: {out}: its results were run with --time-limit 30.0 (this run: 5.0), --memory-limit 2048 "
        f"(this run: 1000); give --restart to discard them and run again, or -o ANOTHER_FOLDER\n")
    assert (out / "results.jsonl").read_text() == before
    assert main(["bench", str(suite), "-o", str(out)]) == 0  # the same limits: resumes
    assert (out / "results.jsonl").read_text() == before
    assert main(["bench", str(suite), "-o", str(out), "--time-limit", "5", "--restart"]) == 0
    assert f"{out}: earlier results discarded (--restart)\n" in capsys.readouterr().err
    assert [(r["time_limit"], r["status"]) for r in load_results(out)] == [(5.0, "invalid")]


def test_a_folder_of_an_older_version_is_checked_by_its_records(write, tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(runner_module, "run_limited", off_the_floor)
    suite, out = suite_file(write, [TINY], "[{domain: m}]"), tmp_path / "out"
    assert main(["bench", str(suite), "-o", str(out)]) == 0
    (out / "suite.json").write_text('{"name": "t", "sets": ["tiny"]}\n')  # no limits recorded
    assert main(["bench", str(suite), "-o", str(out), "--time-limit", "5"]) == 2
    assert "its results were run with --time-limit 30.0 (this run: 5.0);" in capsys.readouterr().err


def test_a_corrupt_makespans_file_is_reported_and_recomputed(write, tmp_path, monkeypatch):
    monkeypatch.setattr(runner_module, "run_limited", off_the_floor)
    out = tmp_path / "out"
    out.mkdir()
    (out / "makespans.json").write_text('{"a.lp": {"M": 3')  # cut off
    stream = io.StringIO()
    records = Runner(load_suite(suite_file(write, [TINY], "[{domain: m}]")), out, stream=stream).run()
    assert stream.getvalue().splitlines()[0] == (
        f"warning: {out}/makespans.json: not a makespans file (Expecting ',' delimiter: line 1 column 17 "
        f"(char 16)); finding the minimal makespans again")
    assert json.loads((out / "makespans.json").read_text()) == {str(TINY): {"M": 1}}
    assert [r["horizon"] for r in records] == [1]
    (out / "makespans.json").write_text('{"a.lp": [1, 2]}')  # valid JSON, wrong shape
    stream = io.StringIO()
    Runner(load_suite(suite_file(write, [TINY], "[{domain: m}]")), out, stream=stream).run()
    assert "not a makespans file (not a mapping of instances to makespans by domain)" in stream.getvalue()


def test_an_output_folder_that_is_a_file_is_bad_input(write, tmp_path, capsys):
    suite, taken = suite_file(write, [TINY], "[{domain: m}]"), write("taken", "")
    assert main(["bench", str(suite), "-o", str(taken)]) == 2
    assert capsys.readouterr().err == f"error: {taken}: is a file, not a folder (-o names the output folder)\n"
    assert main(["bench", str(suite), "-o", str(taken / "sub")]) == 2
    assert capsys.readouterr().err == \
        f"error: {taken / 'sub'}: cannot make the output folder (-o): {taken} is a file\n"



def test_the_runs_with_assignment_follow_the_one_of_their_makespan_search(write, tmp_path, monkeypatch):
    """As in the paper, the assignment is computed once (with the makespan) and every run
    follows it; it is kept in assignments.json for resumed runs."""
    from asprilo.encodings import solve

    jobs = []
    real = runner_module.run_limited
    monkeypatch.setattr(runner_module, "run_limited", lambda job, *limits: jobs.append(job) or real(job, *limits))
    suite = load_suite(suite_file(write, [SMALL], "[{domain: c, assign: true}]"))
    records = Runner(suite, tmp_path / "out").run()
    facts = solve(SMALL, "c", assign=True, tighten=False).assignment.facts
    assert len(facts) == 2  # two robots, two order lines
    assert json.loads((tmp_path / "out/assignments.json").read_text()) == {str(SMALL): {"C_a": facts}}
    assert [(job["kind"], job.get("assignment")) for job in jobs] == [("makespan", None), ("run", facts)]
    assert [(r["status"], r["label"]) for r in records] == [("solved", "C_a")]


def test_a_makespan_with_assignment_is_known_only_with_its_assignment():
    from asprilo.bench.runner import needs_search
    from asprilo.bench.suite import RunSpec
    from asprilo.domain import Domain

    plain, assigned = RunSpec(Domain.C, "plain", False), RunSpec(Domain.C, "plain", True)
    facts = {"C_a": ["assign(robot(1),shelf(1),pickingStation(1))"]}
    assert needs_search({}, {}, plain) and needs_search({}, facts, assigned)
    assert not needs_search({"C": 14}, {}, plain)
    assert needs_search({"C_a": 14}, {}, assigned)  # its runs could not follow the same assignment
    assert not needs_search({"C_a": 14}, facts, assigned)
    assert not needs_search({"C_a": None}, {}, assigned)  # not found: nothing to follow


def test_a_resumed_run_finds_its_records_however_the_suite_path_is_spelled(tmp_path, monkeypatch):
    """The suite names its instance relative to itself; run once as ``suite.yml`` from its folder
    and once by its absolute path from elsewhere, the one run is recorded once (it was run again:
    the keys held the instance's path as spelled through the suite's path)."""
    monkeypatch.setattr(runner_module, "run_limited", off_the_floor)
    folder = tmp_path / "course"
    folder.mkdir()
    shutil.copy(TINY, folder / "tiny.lp")
    (folder / "suite.yml").write_text("name: t\ntime_limit: 30\nmemory_limit: 2048\n"
                                      "instances: {tiny: {files: [tiny.lp]}}\nruns: [{domain: m}]\n")
    monkeypatch.chdir(folder)
    first = Runner(load_suite("suite.yml"), tmp_path / "out").run()
    monkeypatch.chdir(tmp_path)
    again = Runner(load_suite(str(folder / "suite.yml")), tmp_path / "out").run()
    assert [record["instance"] for record in first] == ["tiny.lp"]
    assert [record["key"] for record in again] == [first[0]["key"]]
    assert len((tmp_path / "out" / "results.jsonl").read_text().splitlines()) == 1
