"""The solve front end: API outcome, limits, cancellation, and the `asprilo solve` command."""

from __future__ import annotations

import json
import threading

import pytest
from helpers import CORRIDOR, EXAMPLES, SMALL_A
from helpers.clocks import patient_solves

from asprilo.cli import main
from asprilo.domain import Domain
from asprilo.encodings import SolveStatus, solve
from asprilo.encodings.solving.bounds import lower_bounds
from asprilo.reader import read_instance, read_plan

M5 = EXAMPLES / "paper-m/1x2x4/x11_y6_n66_r5_s16_ps1_pr16_u16_o5_N001.lp"
X3 = EXAMPLES / "encodings-repo/x3_y3_n9_r1_s1_ps1_pr1_u1_o1_N1.lp"


def test_outcome_of_a_search():
    seen = []
    outcome = solve(str(M5), on_progress=seen.append)
    assert (outcome.status, outcome.domain, outcome.method, outcome.encoding) == (
        SolveStatus.FOUND, Domain.M, "asp", "plain")
    assert (outcome.horizon, outcome.minimal, outcome.lower_bound, outcome.plan.horizon) == (6, True, 6, 6)
    assert [(a.horizon, a.result) for a in seen] == [(6, "sat")] and seen == outcome.horizons_tried
    assert set(outcome.stats) == {"ground_time", "solve_time", "rules", "atoms", "choices", "conflicts"}
    assert outcome.stats["rules"] > 0 and outcome.stats["atoms"] > 0


@pytest.mark.parametrize("isolate", [False, True])
def test_the_time_limit_ends_a_search_that_has_no_end(write, isolate):
    outcome = solve(write("corridor.lp", CORRIDOR), Domain.B, time_limit=1.5, max_horizon=10**6, isolate=isolate)
    assert outcome.status is SolveStatus.LIMIT and outcome.plan is None
    # what it proved by then (how far it got depends on the machine; isolated, the child's
    # start-up counts too): every horizon from the lower bound up, one after the other
    lowest = int(outcome.lower_bound)
    assert outcome.refuted == list(range(lowest, lowest + len(outcome.refuted)))
    assert outcome.proven_bound == lowest + len(outcome.refuted)


def test_command_says_what_a_search_that_ran_out_of_time_proved(write, capsys, monkeypatch):
    corridor = write("corridor.lp", CORRIDOR)
    patient_solves(monkeypatch, 3)  # time runs out after three horizons tried, on any machine
    assert main(["solve", str(corridor), "--domain", "b", "--time-limit", "1.5", "--method", "asp"]) == 1
    summary = capsys.readouterr().err.splitlines()[-4:-1]
    assert summary[0] == "no plan within the limits"
    # the search starts at the lower bound; three horizons tried and refuted, then time ran out
    lowest = int(lower_bounds(read_instance(corridor), Domain.B).makespan)
    assert summary[1] == f"refuted horizons {lowest}-{lowest + 2}: no plan is shorter than {lowest + 3}"
    assert summary[2] == ("for a plan fast (not proven minimal), leave out --method asp: the default runs the "
                          "anytime planner beside the exact search")


def test_the_time_limit_holds_while_clingo_grounds(capsys):
    """At horizon 100,000 the small example grounds for minutes; the limit ends it anyway."""
    assert main(["solve", str(SMALL_A), "--domain", "b", "--horizon", "100000", "--time-limit", "2"]) == 1
    assert "no plan within the limits: stopped at the time limit (2 s) while grounding horizon 100000\n" \
        in capsys.readouterr().err


def test_cancel_from_another_thread():
    cancel, solving, result = threading.Event(), threading.Event(), {}

    def search():
        result["outcome"] = solve(SMALL_A, Domain.A, horizon=22, cancel=cancel,
                                  on_phase=lambda phase: phase.name == "solving" and solving.set())

    worker = threading.Thread(target=search, daemon=True)
    worker.start()
    assert solving.wait(120)  # grounded: clingo searches now (for minutes, uncancelled)
    cancel.set()
    worker.join(120)  # only against a hang
    assert not worker.is_alive()
    assert result["outcome"].status is SolveStatus.CANCELLED


def test_no_plan_when_an_ordered_product_cannot_reach_its_station(write):
    walled = """
    init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(3,1))).
    init(object(pickingStation,1),value(at,(1,1))). init(object(robot,1),value(at,(1,1))).
    init(object(shelf,1),value(at,(3,1))). init(object(product,1),value(on,(1,1))).
    init(object(order,1),value(line,(1,1))). init(object(order,1),value(pickingStation,1)).
    """
    outcome = solve(write("walled.lp", walled), Domain.B)
    assert (outcome.status, outcome.minimal, outcome.horizons_tried) == (SolveStatus.NONE, True, [])
    assert outcome.message == "some goal or order line can never be reached"


@pytest.mark.parametrize("arguments, message", [
    (dict(encoding="fast"), "no encoding 'fast' for domain M (choose one of plain, split, clingcon, dl, "
                            "plain-inc, split-inc, clingcon-inc)"),
    (dict(domain="b", encoding="dl"), "no encoding 'dl' for domain B (choose one of plain)"),
    (dict(domain="a", method="flow"), "the flow method solves domains M and Md only, not A"),
    (dict(method="sat"), "unknown method 'sat' (choose auto, asp, flow or anytime)"),
    (dict(horizon=-1), "the horizon must be at least 0, got -1"),
    (dict(domain="e"), "unknown domain 'e' (choose one of a, b, c, m, md)"),
])
def test_bad_requests(arguments, message):
    from asprilo.errors import InputError
    with pytest.raises(InputError) as error:
        solve(M5, **arguments)
    assert error.value.message == message


# --- the command ----------------------------------------------------------------------------

def test_command_prints_plan_and_summary(capsys):
    assert main(["solve", str(X3), "--domain", "b", "--method", "asp"]) == 0
    out, err = capsys.readouterr()
    assert out.splitlines()[3] == "occurs(object(robot,1),action(pickup,()),4)."
    assert read_plan(_source(out)).horizon == 9
    lines = err.splitlines()  # progress (standard error is no terminal here): a line per phase
    assert [line.split(" (")[0] for line in lines[:3]] == ["horizon 9: grounding", "horizon 9: solving",
                                                           "horizon 9: sat"]
    assert lines[3:5] == ["domain B, method asp, encoding plain, lower bound 9",
                          "plan: horizon 9 (proven minimal), 9 actions, checked: valid"]
    assert lines[5].startswith("ground ") and ", conflicts " in lines[5]


def test_command_writes_the_plan_file(tmp_path, capsys):
    target = tmp_path / "plans" / "plan.lp"
    assert main(["solve", str(M5), "-o", str(target), "--method", "flow"]) == 0
    out, err = capsys.readouterr()
    assert out == "" and "plan: horizon 6 (proven minimal)" in err
    assert read_plan(target).horizon == 6
    assert [p.name for p in target.parent.iterdir()] == ["plan.lp"]


def test_command_json(capsys):
    # the exact search alone: with the default (auto) the anytime planner may report a plan
    # first, whichever is faster on the machine (tests/test_solve_auto.py)
    assert main(["solve", str(X3), "--domain", "c", "--json", "--method", "asp"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert (report["status"], report["domain"], report["horizon"], report["minimal"]) == ("found", "c", 9, True)
    assert [a["horizon"] for a in report["horizons_tried"]] == [9]
    assert report["plan"][-1] == "occurs(object(robot,1),action(deliver,(1,1)),9)"


def test_command_exit_statuses(tmp_path, capsys):
    assert main(["solve", str(X3), "--domain", "b", "--horizon", "8"]) == 1
    assert "no plan exists" in capsys.readouterr().err
    assert main(["solve", str(tmp_path / "missing.lp")]) == 2
    assert capsys.readouterr().err == f"error: {tmp_path / 'missing.lp'}: no such file\n"
    assert main(["solve", str(X3), "--encoding", "nope"]) == 2
    assert capsys.readouterr().err.startswith("error: no encoding 'nope' for domain M")
    with pytest.raises(SystemExit) as stopped:  # argparse refuses the option itself
        main(["solve", str(X3), "--time-limit", "0"])
    assert stopped.value.code == 2
    assert capsys.readouterr().err.splitlines()[-1] == (
        "asprilo solve: error: argument --time-limit: must be a positive number of seconds, got 0")


def test_command_lists_the_encodings(capsys):
    assert main(["solve", "--list"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "a   plain         anonymous robots, named shelves in distance bands + the domain's deliveries"
    assert "m   plain         positions as cells (paper Listings 1-2)" in lines
    assert "a   clingcon      plain, with quantities as clingcon integer variables [clingcon]" in lines
    assert len(lines) == 7 * 2 + 3 + 1  # M and Md: 7 styles each; A, B, C: plain; A: clingcon


def _source(text):
    from asprilo.sources import Source
    return Source("<stdout>", text)
