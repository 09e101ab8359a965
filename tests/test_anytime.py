"""The anytime planner (``solve --method anytime``): every plan it returns passes the ASP
checker, its improvements only ever get better, it keeps its time limit, and on tiny
instances it reaches the minimal makespan known from an independent source (the exact
encodings' figures in asprilo/encodings/README.md, the max-flow solver for M and Md)."""

from __future__ import annotations

import json
import threading

import pytest
from helpers import EXAMPLES
from helpers.clocks import patient_anytime, patient_solves
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from asprilo.checker import check
from asprilo.cli import main
from asprilo.domain import Domain, domains
from asprilo.encodings import SolveStatus, solve
from asprilo.encodings.anytime import plan_anytime
from asprilo.encodings.anytime import search as anytime_search
from asprilo.encodings.anytime.router import Router
from asprilo.generator import GeneratorConfig, generate
from asprilo.interop.convert import m_to_md
from asprilo.reader import read_instance

REPO = EXAMPLES / "encodings-repo"
PAPER = EXAMPLES / "paper-m"


def _instance(domain: Domain, seed: int, robots: int, width: int, height: int):
    """A small generated instance of ``domain`` (Md: an M instance with destinations)."""
    assume(width * height >= 2 * robots + 4)  # room for the robots, their shelves and a station
    options = {"-x": width, "-y": height, "-r": robots, "-p": 1}
    if domain in (Domain.M, Domain.MD):
        options.update({"-s": robots + 1, "-P": robots + 1, "-u": robots + 1, "-o": robots, "--domain": "m"})
    else:
        options.update({"-s": robots + 2, "-P": 3, "-u": 8, "-o": 2, "--ol": 2})
    instance = generate(GeneratorConfig.from_options(options), count=1, seed=seed)[0].instance
    return m_to_md(instance) if domain is Domain.MD else instance


def _assert_sound(result, instance, domain: Domain) -> None:
    """The plan passes the checker (asked again here), and the history only improves."""
    history = [(better.makespan, better.sum_of_costs) for better in result.history]
    assert history == sorted(set(history), reverse=True)
    if result.plan is None:
        assert result.status != "found"
        return
    assert check(instance, result.plan, domain).valid
    assert result.history[-1].makespan == result.plan.horizon
    assert result.minimal == (result.plan.horizon <= result.bound)


SMALL = dict(domain=st.sampled_from(domains()), seed=st.integers(1, 10**6), robots=st.integers(1, 4),
             width=st.integers(4, 7), height=st.integers(3, 5))


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(**SMALL)
def test_every_plan_passes_the_checker_and_improvements_only_get_better(domain, seed, robots, width, height):
    instance = _instance(domain, seed, robots, width, height)
    result = plan_anytime(instance, domain, time_limit=0.5)  # what it found by then: sound
    _assert_sound(result, instance, domain)


@pytest.mark.slow
@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(**{**SMALL, "robots": st.integers(1, 8), "width": st.integers(4, 12), "height": st.integers(3, 9)})
def test_many_more_random_instances(domain, seed, robots, width, height):
    instance = _instance(domain, seed, robots, width, height)
    result = plan_anytime(instance, domain, time_limit=2.0)
    _assert_sound(result, instance, domain)


@pytest.mark.parametrize(("name", "minimal"), [
    ("x2_y2_n4_r2_s2_ps1_pr2_u4_o2_N1", {"c": 4, "b": 5, "a": 5}),
    ("x3_y3_n9_r1_s1_ps1_pr1_u1_o1_N1", {"c": 9, "b": 9, "a": 9}),
    ("x4_y4_n16_r2_s3_ps1_pr2_u4_o2_N1", {"c": 7, "b": 8, "a": 8}),
])
def test_tiny_delivery_instances_reach_their_minimal_makespan(name, minimal, monkeypatch):
    patient_anytime(monkeypatch, stop_after=None)  # each search stops at its lower bound
    instance = read_instance(REPO / f"{name}.lp")
    for domain, makespan in minimal.items():
        result = plan_anytime(instance, Domain.parse(domain), time_limit=10)
        assert (result.status, result.plan.horizon, result.minimal) == ("found", makespan, True)


@pytest.mark.parametrize("path", sorted(PAPER.glob("1x2x4/*.lp")))
def test_m_and_md_reach_the_flow_optimum(path, monkeypatch):
    patient_anytime(monkeypatch, stop_after=None)  # each search stops at its lower bound
    instance = read_instance(path)
    for domain, goals in ((Domain.M, instance), (Domain.MD, m_to_md(instance))):
        optimum = solve(goals, domain, method="flow").horizon
        result = plan_anytime(goals, domain, time_limit=10)
        assert result.plan.horizon == optimum
        _assert_sound(result, goals, domain)


class ReadClock:
    """Stands in for the clock of the anytime search (``time`` in its module): time moves on
    only when the search reads it, ``tick`` seconds a reading.  A time limit then runs out at
    the same point of the search on every machine, however fast or loaded."""

    def __init__(self, tick: float):
        self.tick, self.readings = tick, []

    def perf_counter(self) -> float:
        self.readings.append(len(self.readings) * self.tick)
        return self.readings[-1]

    def now(self) -> float:
        """The time the search saw last (without a reading)."""
        return self.readings[-1] if self.readings else 0.0


class CountedCancel(threading.Event):
    """A cancel event that counts how often the search asks it and, given ``at``, sets itself
    when asked the ``at``-th time: a cancel at the same point of the search on every machine."""

    def __init__(self, at: int | None = None):
        super().__init__()
        self.at, self.asked = at, 0

    def is_set(self) -> bool:
        self.asked += 1
        if self.asked == self.at:
            self.set()
        return self.raised

    @property
    def raised(self) -> bool:
        """Whether it is set (without counting a question)."""
        return threading.Event.is_set(self)


def routes_started(monkeypatch, now) -> list:
    """``now()`` each time the anytime search starts to route a robot (first plan or improvement)."""
    seen = []
    route = Router.route

    def recorded(self, *args, **options):
        seen.append(now())
        return route(self, *args, **options)

    monkeypatch.setattr(Router, "route", recorded)
    return seen


def test_the_time_limit_is_kept_when_no_plan_is_found_by_then(monkeypatch):
    """A limit far below what the search would like (a first plan takes some 100 readings of
    the clock, the limit runs out at the 32nd): the search stops at its first look at the
    clock past the limit, routes no robot after it, and says that time ran out."""
    instance = read_instance(PAPER / "4x5x8/x46_y15_n690_r46_s320_ps10_pr320_u320_o46_N001.lp")
    clock = ReadClock(tick=2.0 / 32)
    monkeypatch.setattr(anytime_search, "time", clock)
    routed = routes_started(monkeypatch, clock.now)
    result = plan_anytime(instance, Domain.B, time_limit=2.0)
    assert (result.status, result.plan, result.history) == ("limit", None, [])
    assert "first_plan_seconds" not in result.stats  # no first plan: no time of one
    assert clock.now() >= 2.0  # the clock said the time was up: that stopped it
    assert all(seen < 2.0 for seen in routed)  # no robot routed after


def test_the_time_limit_is_kept_with_the_best_plan_found_by_then(monkeypatch, write):
    """The bound out of reach (TWO_TRIPS: 19, every plan takes 21 steps or more): the search
    improves until its limit (but the time it keeps for the last check) and answers with its
    best checked plan."""
    instance = read_instance(write("two-trips.lp", TWO_TRIPS))
    clock = ReadClock(tick=2.0 / 1024)
    monkeypatch.setattr(anytime_search, "time", clock)
    routed = routes_started(monkeypatch, clock.now)
    result = plan_anytime(instance, Domain.B, time_limit=2.0)
    assert (result.status, result.minimal) == ("found", False)
    assert clock.now() > 0.9 * 2.0 and routed and all(seen < 2.0 for seen in routed)
    _assert_sound(result, instance, Domain.B)


def test_cancelling_stops_the_search_before_a_first_plan(monkeypatch):
    """Cancelled while the first plan is under way (the search asks the event about 100 times
    before it has one; here it is set the 10th time): no robot is routed after, no plan."""
    instance = read_instance(PAPER / "4x5x8/x46_y15_n690_r35_s320_ps10_pr320_u320_o35_N001.lp")
    cancel = CountedCancel(at=10)
    routed = routes_started(monkeypatch, lambda: cancel.raised)
    result = plan_anytime(instance, Domain.C, time_limit=600, cancel=cancel)
    assert (result.status, result.plan, result.history) == ("cancelled", None, [])
    assert cancel.raised and not any(routed)


def test_cancelling_after_the_first_plan_keeps_it(monkeypatch, write):
    """Cancelled as soon as the first plan is reported: the search, which would improve on it
    for up to 600 s (it is not minimal), stops there and answers with it."""
    instance = read_instance(write("two-trips.lp", TWO_TRIPS))
    cancel = CountedCancel()
    routed = routes_started(monkeypatch, lambda: cancel.raised)
    result = plan_anytime(instance, Domain.B, time_limit=600, cancel=cancel,
                          on_improvement=lambda _better: cancel.set())
    assert (result.status, len(result.history), result.minimal) == ("found", 1, False)
    assert result.stats["neighbourhoods"] == 0 and routed and not any(routed)
    _assert_sound(result, instance, Domain.B)


def test_a_line_that_cannot_be_served_means_no_plan(write):
    path = write("unserved.lp", "init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))).\n"
                 "init(object(robot,1),value(at,(1,1))). init(object(pickingStation,1),value(at,(2,1))).\n"
                 "init(object(product,1),value(on,(1,1))).\n"
                 "init(object(order,1),value(line,(1,1))). init(object(order,1),value(pickingStation,1)).\n")
    result = plan_anytime(read_instance(path), Domain.A, time_limit=5)
    assert (result.status, result.plan, result.minimal) == ("none", None, True)


def test_solve_reports_each_plan_and_the_best_one(capsys, monkeypatch):
    patient_solves(monkeypatch, 3)  # three plans (or fewer, the last at the lower bound)
    instance = read_instance(PAPER / "1x2x4/x11_y6_n66_r8_s16_ps1_pr16_u16_o8_N001.lp")
    heard = []
    outcome = solve(instance, "b", method="anytime", time_limit=1.5, on_progress=heard.append)
    assert outcome.found and outcome.check.valid and outcome.method == "anytime"
    assert [a.horizon for a in heard] == [h["makespan"] for h in outcome.history]
    assert all(a.result == "improved" for a in heard)
    assert outcome.horizon == outcome.history[-1]["makespan"]


def test_cli_json_reports_bound_minimal_and_history(capsys, monkeypatch):
    patient_solves(monkeypatch, None)  # the search stops at its lower bound
    path = REPO / "x4_y4_n16_r2_s3_ps1_pr2_u4_o2_N1.lp"
    assert main(["solve", str(path), "--domain", "b", "--method", "anytime", "--time-limit", "5", "--json"]) == 0
    captured = capsys.readouterr()
    report = json.loads(captured.out)
    assert (report["status"], report["method"], report["horizon"], report["minimal"]) == ("found", "anytime", 8, True)
    assert report["lower_bound"] == 8 and report["history"][-1]["makespan"] == 8
    assert report["history"][-1]["gap"] == 0.0
    assert "plan: makespan 8, sum of costs" in captured.err


#: one robot, two shelves, two lines at one station (domain B): the robot must bring one shelf,
#: put it down and fetch the other, while the lower bound (10) counts one trip per line
TWO_TRIPS = ("init(object(grid,1),value(xsize,5)). init(object(grid,1),value(ysize,2)).\n"
             "init(object(robot,1),value(at,(3,1))). init(object(pickingStation,1),value(at,(1,1))).\n"
             "init(object(shelf,1),value(at,(4,2))). init(object(shelf,2),value(at,(5,2))).\n"
             "init(object(product,1),value(on,1)). init(object(product,2),value(on,2)).\n"
             "init(object(order,1),value(line,1)). init(object(order,1),value(line,2)).\n"
             "init(object(order,1),value(pickingStation,1)).\n")


def test_cli_answers_a_time_out_with_the_best_plan(write, capsys, monkeypatch):
    path = write("two-trips.lp", TWO_TRIPS)
    patient_solves(monkeypatch, 2)  # time runs out after two plans, on any machine
    # the bound is out of reach: the search runs till its limit (the time limit tests above)
    assert main(["solve", str(path), "--domain", "b", "--method", "anytime", "--time-limit", "2"]) == 0
    captured = capsys.readouterr()
    assert captured.out.startswith("occurs(")
    assert "not proven minimal" in captured.err  # the bound (19) is below the minimal makespan (21)


def test_cli_refuses_a_horizon_with_the_anytime_method(capsys):
    path = REPO / "x4_y4_n16_r2_s3_ps1_pr2_u4_o2_N1.lp"
    assert main(["solve", str(path), "--method", "anytime", "--horizon", "5"]) == 2
    assert capsys.readouterr().err == "error: the anytime method searches the makespan itself; leave out --horizon\n"


@pytest.mark.parametrize("steps", [8, 12])
def test_it_plans_from_a_state_in_the_middle_of_a_plan(steps, monkeypatch):
    """What the online link asks after new orders: robots carrying shelves (some from the
    start, some standing on a station), shelves away from their cells, lines done."""
    from asprilo.model import Plan
    from asprilo.online.planner import world_at
    from asprilo.simulate import simulate

    instance = read_instance(PAPER / "1x2x4/x11_y6_n66_r8_s16_ps1_pr16_u16_o8_N001.lp")
    found = threading.Event()  # the first plan, whatever the machine's speed
    first = plan_anytime(instance, Domain.B, time_limit=60, cancel=found, on_improvement=lambda _: found.set())
    done = Plan([action for action in first.plan.actions if action.step <= steps])
    now = world_at(instance, simulate(instance, done, Domain.B).state(steps))
    assert any(robot.carries is not None for robot in now.robots.values())
    clock = patient_anytime(monkeypatch)  # time runs out after the first plan, on any machine
    result = plan_anytime(now, Domain.B, time_limit=5, on_improvement=clock.reported)
    assert result.status == "found"
    _assert_sound(result, now, Domain.B)


def test_the_summary_of_an_anytime_run_without_a_plan_says_so(capsys):
    """It said 'first plan 0.00 s, 0 plans reported' (the issue on planners' pace)."""
    from asprilo.encodings.solving.outcome import Outcome
    from asprilo.encodings.summary import summary

    summary(Outcome(SolveStatus.LIMIT, Domain.B, "anytime", "anytime"))
    assert capsys.readouterr().err.splitlines()[-2:] == ["no plan within the limits",
                                                         "the anytime planner: no plan reported"]
