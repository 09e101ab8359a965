"""The solving package: one request, a table of methods, one stop-watch, the lower bounds
computed once per solve, and the exact search run on a user's own encoding."""

from __future__ import annotations

import threading
from dataclasses import replace

import pytest
from helpers import EXAMPLES

from asprilo.checker import report as checker_report
from asprilo.domain import Domain
from asprilo.encodings import Encoding, LowerBounds, SolveRequest, SolveStatus, find_encoding, solve
from asprilo.encodings import flow as flow_module
from asprilo.encodings.anytime import search as anytime_search
from asprilo.encodings.solving import Watch, bounds, find_method, method_names, request_for
from asprilo.errors import InputError
from asprilo.reader import read_instance

M5 = EXAMPLES / "paper-m/1x2x4/x11_y6_n66_r5_s16_ps1_pr16_u16_o5_N001.lp"
X3 = EXAMPLES / "encodings-repo/x3_y3_n9_r1_s1_ps1_pr1_u1_o1_N1.lp"


def test_a_request_and_the_keywords_solve_alike():
    instance = read_instance(M5)
    by_keywords = solve(instance, Domain.M, encoding="split", horizon=6)
    by_request = solve(SolveRequest(instance, Domain.M, encoding=find_encoding(Domain.M, "split"), horizon=6))
    assert (by_request.status, by_request.encoding, by_request.plan) == (
        SolveStatus.FOUND, "split", by_keywords.plan)
    assert request_for(instance, "m", encoding="split", horizon=6) == replace(
        SolveRequest(instance, Domain.M, horizon=6), encoding=find_encoding(Domain.M, "split"))
    with pytest.raises(TypeError):
        solve(SolveRequest(instance, Domain.M), horizon=3)


def test_methods_are_found_by_name_in_one_table():
    assert method_names() == ["auto", "asp", "flow", "anytime"]
    assert find_method("flow").name == "flow" and find_method("asp").encoded
    with pytest.raises(InputError) as unknown:
        find_method("sat")
    assert unknown.value.message == "unknown method 'sat' (choose auto, asp, flow or anytime)"


@pytest.mark.parametrize("path, options", [
    (M5, dict()), (M5, dict(method="flow")), (M5, dict(method="anytime", time_limit=5)),
    (X3, dict(domain="b")), (X3, dict(domain="c", assign=True)), (X3, dict(domain="b", method="anytime")),
])
def test_the_lower_bounds_are_computed_once_per_solve(monkeypatch, path, options):
    """Once at the start; the method, the anytime planner's reports and the check of the plan
    get them from the request."""
    calls = []

    def counted(function):
        def count(*args, **keywords):
            calls.append(function.__name__)
            return function(*args, **keywords)
        return count

    for module in (bounds, checker_report, flow_module, anytime_search):
        for name in ("makespan_bound", "mapf_bounds", "sum_of_costs_bound"):
            if hasattr(module, name):
                monkeypatch.setattr(module, name, counted(getattr(module, name)))
    outcome = solve(path, **options)
    assert outcome.found and outcome.check.valid
    assert len(calls) == 1, calls


def test_bounds_the_caller_knows_are_not_computed_again(monkeypatch):
    def refused(*_args, **_keywords):
        raise AssertionError("computed again")

    monkeypatch.setattr(bounds, "mapf_bounds", refused)
    monkeypatch.setattr(checker_report, "strong_bounds", refused)
    monkeypatch.setattr(checker_report, "cheap_bounds", refused)
    outcome = solve(M5, bounds=LowerBounds(6, 20))
    assert (outcome.horizon, outcome.lower_bound, outcome.check.metrics["sum_of_costs_bound"]) == (6, 6, 20)


@pytest.mark.parametrize("style, theory, incremental", [("plain", None, False), ("clingcon", "clingcon", False),
                                                        ("plain-inc", None, True)])
def test_the_exact_search_runs_a_users_own_encoding(write, style, theory, incremental):
    """A program of the user's (here one that includes a reference encoding), described by an
    :class:`Encoding` of its own: single-shot, with a theory, or incremental."""
    reference = find_encoding(Domain.M, style)
    mine = write("mine.lp", f'% my encoding\n#include "{reference.program}".\n')
    encoding = Encoding("mine", Domain.M, mine, theory, incremental, "my own", options=reference.options)
    outcome = solve(M5, encoding=encoding)
    assert (outcome.status, outcome.encoding, outcome.horizon, outcome.minimal) == (
        SolveStatus.FOUND, "mine", 6, True)
    assert outcome.check.valid


def test_one_watch_keeps_time_and_hears_cancel():
    ticks = iter(range(100))
    watch = Watch(time_limit=5, clock=lambda: float(next(ticks)))
    assert (watch.elapsed(), watch.remaining()) == (1.0, 3.0)
    assert not watch.out_of_time() and watch.out_of_time(keep=2) and watch.expired
    cancel = threading.Event()
    with Watch(cancel=cancel) as cancelled:
        assert not cancelled.out_of_time()
        cancel.set()
        assert cancelled.cancelled and cancelled.out_of_time() and cancelled.remaining() is None
