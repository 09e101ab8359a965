"""The default method (auto): the exact search and the anytime planner side by side, a plan
never lost, what is proven said as such, the bounds computed once, and the heartbeat.

No test here asserts a speed: where a test needs a plan first, it waits for the event that
reports it (and cancels then), or makes the child hang after the report (so that a time limit
strikes after the plan, whatever the machine)."""

from __future__ import annotations

import json
import multiprocessing
import os
import pty
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
from helpers import CORRIDOR, EXAMPLES, SMALL_A
from helpers.streams import Terminal

from asprilo import isolation
from asprilo.checker import check
from asprilo.checker import report as checker_report
from asprilo.cli import main
from asprilo.domain import Domain
from asprilo.encodings import SolveStatus, solve
from asprilo.encodings.cli import SearchProgress, _verdict, report
from asprilo.encodings.solving import (
    Attempt,
    Listeners,
    LowerBounds,
    Outcome,
    Phase,
    SolveRequest,
    Watch,
    bounds,
    request_for,
    solve_request,
)
from asprilo.encodings.solving.methods import auto, exact
from asprilo.encodings.solving.status import WITHOUT_ASSIGNMENT
from asprilo.reader import read_instance

X3 = EXAMPLES / "encodings-repo/x3_y3_n9_r1_s1_ps1_pr1_u1_o1_N1.lp"
M5 = EXAMPLES / "paper-m/1x2x4/x11_y6_n66_r5_s16_ps1_pr16_u16_o5_N001.lp"
#: read as A, the exact search neither solves nor refutes its lower bound 23 for many minutes
#: (benchmarks/RESULTS.md): it cannot finish, the anytime planner has a plan in seconds
SMALL_A_BOUND = 23


@pytest.fixture
def forked(monkeypatch):
    """Children are forked (they inherit this process's patches), whatever threads run here."""
    monkeypatch.setattr(isolation, "_context", lambda: multiprocessing.get_context("fork"))


def cancel_on_first_plan(cancel: threading.Event):
    """A progress listener that cancels the solve once a plan was reported."""
    def heard(attempt: Attempt) -> None:
        if attempt.plan is not None:
            cancel.set()
    return heard


def solve_until_a_plan(path, domain: Domain, **options) -> Outcome:
    """Solve with the default method until a plan and the lower bounds are known (then cancel)."""
    cancel, plans, known = threading.Event(), [], []

    def heard(message) -> None:
        (plans if isinstance(message, Attempt) and message.plan is not None else known).append(message)
        if plans and any(isinstance(m, LowerBounds) for m in known):
            cancel.set()

    request = request_for(path, domain, method="auto", time_limit=600, **options)
    return solve_request(request, Listeners(progress=heard, bounds=heard), cancel)


# --- a plan once found is never lost -----------------------------------------------------------


@pytest.mark.parametrize("assign", [False, True])
def test_the_default_answers_with_a_plan_where_the_exact_search_cannot_finish(assign):
    outcome = solve_until_a_plan(SMALL_A, Domain.A, assign=assign)
    assert outcome.status is SolveStatus.FOUND and outcome.method == "auto"
    assert outcome.check.valid and check(read_instance(SMALL_A), outcome.plan, Domain.A).valid
    # not proven: the plan is longer than the bound, which is given with the gap
    assert not outcome.minimal and outcome.lower_bound == SMALL_A_BOUND
    assert outcome.horizon > outcome.proven_bound >= SMALL_A_BOUND
    assert outcome.gap == outcome.horizon - outcome.proven_bound
    assert outcome.history and outcome.history[-1]["makespan"] == outcome.horizon


def test_the_corridor_has_no_plan_and_the_default_says_what_it_proved(write):
    """The corridor of tests/helpers has no plan at any horizon: neither part finds one, and
    the answer says which horizons the exact search refuted."""
    outcome = solve(write("corridor.lp", CORRIDOR), Domain.B, method="auto", time_limit=3)
    assert outcome.status is SolveStatus.LIMIT and outcome.plan is None and not outcome.minimal
    lowest = int(outcome.lower_bound)
    assert outcome.refuted == list(range(lowest, lowest + len(outcome.refuted)))


@pytest.mark.parametrize("assign", [False, True])
def test_a_time_limit_after_the_exact_search_found_a_plan_keeps_it(monkeypatch, forked, assign):
    """The exact search reports each plan as it finds it: a child stopped later (here: it
    hangs after the report, as a long try of a shorter horizon would) still answers with it."""
    record = exact.HorizonSearch.record

    def record_then_hang(search, attempt):
        record(search, attempt)
        if attempt.plan is not None:
            threading.Event().wait()

    monkeypatch.setattr(exact.HorizonSearch, "record", record_then_hang)
    outcome = solve(X3, Domain.C, method="asp", assign=assign, isolate=True, time_limit=3)
    assert outcome.status is SolveStatus.FOUND and outcome.horizon == 9 and outcome.check.valid
    assert outcome.message == "stopped at the time limit (3 s); the answer is the best plan found before"
    assert outcome.minimal  # 9 is the lower bound


def test_a_cancel_after_a_plan_keeps_it_and_says_what_is_proven(forked):
    cancel = threading.Event()
    outcome = solve(SMALL_A, Domain.A, method="anytime", isolate=True, time_limit=600, cancel=cancel,
                    on_progress=cancel_on_first_plan(cancel))
    assert outcome.status is SolveStatus.FOUND and outcome.check.valid
    assert not outcome.minimal and outcome.proven_bound == SMALL_A_BOUND
    assert outcome.message == "cancelled; the answer is the best plan found before"


def test_a_plan_proven_minimal_says_so(capsys):
    assert main(["solve", str(X3), "--domain", "b", "--json"]) == 0
    answer = json.loads(capsys.readouterr().out)
    assert (answer["method"], answer["status"], answer["minimal"], answer["horizon"]) == ("auto", "found", True, 9)
    assert answer["proven_bound"] == 9 and answer["gap"] == 0 and answer["found_by"] in ("asp", "anytime")
    assert main(["solve", str(X3), "--domain", "b"]) == 0
    assert "plan: horizon 9 (proven minimal), 9 actions, checked: valid; found by the " \
        in capsys.readouterr().err


def test_m_with_anonymous_goals_is_max_flow(capsys):
    assert main(["solve", str(M5), "--json"]) == 0
    answer = json.loads(capsys.readouterr().out)
    assert (answer["method"], answer["horizon"], answer["minimal"]) == ("flow", 6, True)


def test_the_command_answers_with_a_plan_not_proven_minimal_exit_130(tmp_path):
    """Ctrl-C (SIGINT) once the anytime planner reported a plan: the answer is that plan, not
    proven minimal, with the bound and the gap; exit status 130, interrupted (README: Exit status)."""
    plan = tmp_path / "plan.lp"
    process = subprocess.Popen([sys.executable, "-m", "asprilo.cli", "solve", str(SMALL_A), "--domain", "a",
                                "--json", "-o", str(plan)], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True)
    lines = []
    for line in process.stderr:  # standard error is a pipe: a line per phase and per plan
        lines.append(line)
        # a plan, and the bound known (the exact search grounds its first horizon)
        if any(seen.startswith("plan: makespan ") for seen in lines) and \
                any(seen.startswith("horizon ") for seen in lines):
            process.send_signal(signal.SIGINT)
            break
    out, err = process.communicate(timeout=120)
    assert process.returncode == 130, "".join(lines) + err
    answer = json.loads(out)
    assert (answer["status"], answer["minimal"], answer["lower_bound"]) == ("found", False, SMALL_A_BOUND)
    assert answer["gap"] == answer["horizon"] - answer["proven_bound"] > 0
    assert answer["message"] == "cancelled"
    assert "not proven minimal: no plan is shorter than" in err and plan.exists()


# --- refuted for the problem, or only along the assignment -------------------------------------


def test_a_horizon_refuted_along_the_assignment_is_no_bound():
    along = [Attempt(29, "unsat", 1.0, along=True), Attempt(30, "unsat", 1.0, along=True)]
    without = [Attempt(27, "unsat", 1.0, WITHOUT_ASSIGNMENT)]
    outcome = Outcome(SolveStatus.LIMIT, Domain.A, "asp", "plain", lower_bound=27,
                      horizons_tried=without + along + [Attempt(31, "unknown", 2.0, along=True)])
    assert outcome.refuted == [27] and outcome.refuted_along == [29, 30] and outcome.proven_bound == 28
    assert _verdict(outcome) == [
        "no plan within the limits",
        "refuted horizons 27: no plan is shorter than 28",
        "no plan along the task assignment at horizons 29-30 (refuted along the assignment only, not for the problem)",
        "undecided: horizon 31"]
    assert report(outcome)["refuted_along_assignment"] == [29, 30]


def test_a_child_killed_after_refuting_along_the_assignment_proves_no_more(monkeypatch, forked):
    """The attempts say themselves whether they followed the assignment: a child stopped from
    outside (whose outcome is made here) claims no bound from them."""
    record = exact.HorizonSearch.record

    def record_then_hang(search, attempt):
        record(search, attempt)
        if attempt.along:
            threading.Event().wait()

    monkeypatch.setattr(exact.HorizonSearch, "record", record_then_hang)
    assignment = ["assign(robot(1),shelf(1),pickingStation(1))"]
    outcome = solve(X3, Domain.C, method="asp", assignment=assignment, horizon=8, isolate=True, time_limit=3)
    assert outcome.status is SolveStatus.LIMIT and outcome.refuted_along == [8] and outcome.refuted == []
    assert outcome.proven_bound == 9  # the lower bound, not raised


# --- the parent's bookkeeping --------------------------------------------------------------------


class Heard:
    """A watch whose listeners keep what they hear."""

    def __init__(self):
        self.attempts, self.phases = [], []

    def watch(self) -> Watch:
        return Watch(listeners=Listeners(self.attempts.append, self.phases.append))


def test_the_parent_stops_when_the_exact_search_refuted_every_horizon_below_the_best_plan():
    instance = read_instance(X3)
    plan = solve(instance, Domain.B, method="asp").plan  # makespan 9
    heard = Heard()
    portfolio = auto.Portfolio(SolveRequest(instance, Domain.B, method="auto"), heard.watch())
    portfolio._heard(auto.EXACT, LowerBounds(7))
    portfolio._heard(auto.ANYTIME, Attempt(9, "improved", 0.5, "sum of costs 9", plan))
    portfolio._heard(auto.EXACT, Attempt(7, "unsat", 0.1))
    assert not portfolio.stop.is_set()  # 8 is open
    portfolio._heard(auto.EXACT, Phase("solving", 8, 5000))
    portfolio._heard(auto.EXACT, Attempt(8, "unsat", 0.1))
    assert portfolio.stop.is_set()
    answer = portfolio._answer()
    assert (answer.status, answer.horizon, answer.minimal, answer.found_by) == (SolveStatus.FOUND, 9, True, "anytime")
    assert answer.check.valid and answer.proven_bound == 9
    assert [a.horizon for a in heard.attempts] == [9, 7, 8] and heard.phases[0].conflicts == 5000


def test_an_exact_plan_that_fails_the_check_is_not_kept():
    instance = read_instance(X3)
    plan = solve(instance, Domain.B, method="asp").plan
    broken = type(plan)(plan.actions[1:])
    portfolio = auto.Portfolio(SolveRequest(instance, Domain.B, method="auto"), Heard().watch())
    portfolio._heard(auto.EXACT, LowerBounds(9))
    portfolio._heard(auto.EXACT, Attempt(9, "sat", 0.1, plan=broken))
    assert portfolio.best is None and portfolio.outcome.message.startswith("the plan failed the check")


# --- the bounds are computed once ------------------------------------------------------------------


@pytest.mark.parametrize("path, domain", [(X3, Domain.B), (SMALL_A, Domain.A)])
def test_the_bounds_are_computed_once_by_the_exact_search_and_handed_over(monkeypatch, forked, tmp_path,
                                                                          path, domain):
    """Counted in every process (children are forked with the counters): once, in the exact
    search's child; the parent and the anytime planner get them handed over."""
    from asprilo.encodings.anytime import search as anytime_search

    log = tmp_path / "calls.txt"

    def counted(function):
        def count(*args, **keywords):
            with open(log, "a") as calls:
                calls.write(f"{os.getpid()} {function.__name__}\n")
            return function(*args, **keywords)
        return count

    for module in (bounds, checker_report, anytime_search):
        for name in ("makespan_bound", "mapf_bounds", "sum_of_costs_bound", "strong_bounds", "cheap_bounds"):
            if hasattr(module, name):
                monkeypatch.setattr(module, name, counted(getattr(module, name)))
    outcome = solve_until_a_plan(path, domain)
    assert outcome.found and outcome.check.valid
    calls = log.read_text().splitlines()
    assert len(calls) == 1 and calls[0].split()[1] == "makespan_bound", calls
    assert int(calls[0].split()[0]) != os.getpid()  # in a child: the exact search's
    assert outcome.lower_bound == outcome.check.metrics["makespan_bound"] > 0


# --- the heartbeat ---------------------------------------------------------------------------------


def _stderr_of(command: list[str], terminal: bool, seconds: float) -> str:
    """What ``command`` writes on standard error within ``seconds`` (then it is interrupted):
    on a pseudo-terminal or into a pipe."""
    if terminal:
        master, slave = pty.openpty()
        process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=slave, stdin=subprocess.DEVNULL)
        os.close(slave)
        reading = master
    else:
        process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                   stdin=subprocess.DEVNULL)
        reading = process.stderr.fileno()
    chunks, end = [], time.monotonic() + seconds
    os.set_blocking(reading, False)
    while time.monotonic() < end and process.poll() is None:
        try:
            chunk = os.read(reading, 65536)
        except BlockingIOError:
            time.sleep(0.05)
            continue
        except OSError:  # the pseudo-terminal's other side has gone
            break
        if chunk:
            chunks.append(chunk)
    process.send_signal(signal.SIGINT)
    process.wait(60)
    os.set_blocking(reading, True)
    try:
        while chunk := os.read(reading, 65536):
            chunks.append(chunk)
    except OSError:
        pass
    if terminal:
        os.close(master)
    return b"".join(chunks).decode(errors="replace")


def test_the_heartbeat_beats_on_a_terminal_and_not_in_a_pipe():
    command = [sys.executable, "-m", "asprilo.cli", "solve", str(SMALL_A), "--domain", "a", "--time-limit", "600"]
    on_terminal = _stderr_of(command, terminal=True, seconds=4)
    assert "\r\x1b[K" in on_terminal and " s left" in on_terminal and "elapsed " in on_terminal
    assert "horizon 23: " in on_terminal or "lower bound: computing" in on_terminal
    in_pipe = _stderr_of(command, terminal=False, seconds=4)
    assert "\r" not in in_pipe and " s left" not in in_pipe


def test_the_heartbeat_line_says_what_runs_and_what_is_known():
    progress = SearchProgress(Terminal(), time_limit=300)
    progress.phase(Phase("solving", 23))
    progress.phase(Phase("solving", 23, 12_000))
    progress.attempt(Attempt(22, "unsat", 1.0))
    progress.phase(Phase("solving", 23, 15_000))
    progress.attempt(Attempt(30, "improved", 3.0, "sum of costs 80", plan=object()))
    line = progress.heartbeat(progress.started + 12.2)
    progress.close()
    assert line == ("horizon 23: solving 12 s, 15,000 conflicts | best plan: makespan 30 | "
                    "no plan shorter than 23 | elapsed 12 s, 288 s left")


def test_gen_says_which_instance_it_makes_while_one_takes_long():
    from asprilo.generator.output import WriteProgress

    for total in (1, 3):
        terminal = Terminal()
        progress = WriteProgress(total, terminal)
        progress.working("out: N001")
        progress._since -= 4.2  # as if making it took 4.2 s so far
        progress.beat()
        assert terminal.text.endswith("making out: N001... 4 s")
        progress.advance("out/N001.lp")
        progress.close()
        assert terminal.text.endswith("\r\033[K" if total == 1 else "1/3 out/N001.lp" + " " * 49)
    quiet = Terminal()
    progress = WriteProgress(0, quiet, beats=False)
    progress.working("N001")
    progress._since -= 4.2
    progress.beat()
    progress.close()
    assert quiet.text == ""


def test_bench_redraws_its_line_while_runs_take_long():
    from asprilo.bench.runner import BenchProgress

    terminal = Terminal()
    progress = BenchProgress(4, "runs", terminal)
    progress.update("solved")
    progress.started -= 75
    progress.beat()
    progress.close()
    assert terminal.text.splitlines()[-1].split("\r")[-1].startswith(
        "runs [1/4] solved 1, time-outs 0, failures 0 | elapsed 0:01:15, left ~0:03:4")


def test_the_request_of_the_default_keeps_the_callers_options():
    instance = read_instance(X3)
    request = SolveRequest(instance, Domain.M, method="auto", horizon=9)
    assert auto.resolve(request).method == "asp"
    assert auto.resolve(SolveRequest(instance, Domain.M, method="auto")).method == "flow"
    assert auto.resolve(SolveRequest(instance, Domain.B, method="auto")).method == "auto"
    assert Path(auto.__file__).name == "auto.py"
