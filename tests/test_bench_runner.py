"""The benchmark runner: checked plans, failures counted, resuming after a kill."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time

from helpers import EXAMPLES

from asprilo.bench import runner as runner_module
from asprilo.bench.limits import Outcome
from asprilo.bench.results import load_results
from asprilo.bench.runner import Runner
from asprilo.bench.suite import load_suite
from asprilo.cli import main

TINY = EXAMPLES / "encodings-repo/x2_y2_n4_r2_s2_ps1_pr2_u4_o2_N1.lp"
SMALL = EXAMPLES / "paper-m/1x2x4/x11_y6_n66_r2_s16_ps1_pr16_u16_o2_N001.lp"


def suite_file(write, files, runs="[{domain: m, encoding: [plain, split]}]"):
    listed = ", ".join(f'"{f}"' for f in files)
    return write("suite.yml", f"name: t\ntime_limit: 30\nmemory_limit: 2048\n"
                              f"instances: {{tiny: {{files: [{listed}]}}}}\nruns: {runs}\n")


def test_an_invalid_plan_is_a_failure(write, tmp_path, monkeypatch, capsys):
    """A solver that returns a plan breaking the rules: the runner's own check catches it."""

    def fake_run(job, time_limit, memory_mb):
        if job["kind"] == "makespan":
            return Outcome("done", 0.1, {"status": "found", "horizon": 1, "minimal": True})
        plan = "occurs(object(robot,1),action(move,(0,-1)),1)."  # off the 2x2 floor
        return Outcome("done", 0.2, {"status": "found", "time": 0.2, "plan": plan, "stats": {}})

    monkeypatch.setattr(runner_module, "run_limited", fake_run)
    suite = load_suite(suite_file(write, [TINY], "[{domain: m}]"))
    records = Runner(suite, tmp_path / "out").run()
    assert [(r["status"], r["horizon"]) for r in records] == [("invalid", 1)]
    assert "err(" in records[0]["error"]
    assert main(["bench", "report", str(tmp_path / "out")]) == 0
    assert "M       1         plain     30(1) !1" in capsys.readouterr().out


def test_a_killed_runner_resumes_without_repeating_runs(write, tmp_path):
    suite = suite_file(write, [TINY, SMALL], "[{domain: m, encoding: [plain, split, clingcon, dl]}]")
    out = tmp_path / "out"
    command = [sys.executable, "-m", "asprilo.cli", "bench", str(suite), "-o", str(out)]
    first = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                             start_new_session=True)
    deadline = time.time() + 120
    while time.time() < deadline and len(load_results(out)) < 2:
        time.sleep(0.2)
    os.killpg(first.pid, signal.SIGKILL)
    first.wait()
    done_before = {r["key"]: r for r in load_results(out)}
    assert 2 <= len(done_before) < 8
    result = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    assert f"resuming: {len(done_before)} runs already recorded" in result.stderr
    records = load_results(out)
    keys = [r["key"] for r in records]
    assert len(keys) == len(set(keys)) == 8
    assert all(records[i] == done_before[keys[i]] for i in range(len(done_before)))
    assert {r["status"] for r in records} == {"solved"}
    assert json.loads((out / "makespans.json").read_text()) == {
        str(TINY): {"M": 1}, str(SMALL): {"M": 6}}


def test_btool_export_and_its_results_read_back(write, tmp_path, capsys):
    """export-btool writes a runscript btool understands; report reads what such runs leave."""
    from asprilo.bench import single
    from asprilo.bench.btool import read_results
    suite = suite_file(write, [SMALL])
    folder = tmp_path / "cluster"
    assert main(["bench", "export-btool", str(suite), str(folder)]) == 0
    script = (folder / "runscripts/t.xml").read_text()
    assert '<setting name="M-plain" tag="all" cmdline="--domain m --encoding plain"/>' in script
    assert '<seqjob name="seq" timeout="30s" memout="2048"' in script
    assert '<folder path="benchmarks/tiny"/>' in script
    assert "{args} {files}" in (folder / "templates/asprilo.sh").read_text()
    copied = folder / "benchmarks/tiny" / SMALL.name
    assert json.loads((folder / "benchmarks/tiny/makespans.json").read_text()) == {SMALL.name: {"M": 6}}
    # what btool leaves behind: a finished run of M-plain and a run of M-split that runlim stopped
    runs = folder / "output/t-seq-tiny/cluster/results/tiny"
    solved = runs / "asprilo-0.1.0-M-plain/tiny" / SMALL.name / "run1"
    solved.mkdir(parents=True)
    capsys.readouterr()
    assert single.main([str(copied), "--domain", "m", "--encoding", "plain", "--time-limit", "30"]) == 0
    (solved / "runsolver.solver").write_text(capsys.readouterr().out)
    stopped = runs / "asprilo-0.1.0-M-split/tiny" / SMALL.name / "run1"
    stopped.mkdir(parents=True)
    (stopped / "runsolver.solver").write_text("")
    (stopped / "runsolver.watcher").write_text("[runlim] time limit:\t30 seconds\n[runlim] status:\tout of time\n")
    records = sorted(read_results(folder), key=lambda r: r["encoding"])
    assert [(r["label"], r["encoding"], r["status"], r["horizon"]) for r in records] == [
        ("M", "plain", "solved", 6), ("M", "split", "timeout", None)]
    assert records[1]["time"] == 30
    assert main(["bench", "report", str(folder)]) == 0
    assert "                  split     30(1)\n" in capsys.readouterr().out  # the time-out counts at the limit
