"""The exact max-flow solver of domains M and Md (asprilo/encodings/flow.py)."""

from __future__ import annotations

import threading

import pytest
from helpers import EXAMPLES
from helpers.worlds import WALLED, md

from asprilo.bounds import Floor
from asprilo.checker import check
from asprilo.domain import Domain
from asprilo.encodings import SolveStatus
from asprilo.encodings.flow import TimeExpandedNetwork, flow_plan
from asprilo.encodings.solving import Watch
from asprilo.reader import read_instance

#: minimal makespans of the paper's domain-M instances (bottleneck bound = flow optimum)
PAPER_M = {
    "1x2x4/x11_y6_n66_r2_s16_ps1_pr16_u16_o2_N001.lp": 6,
    "1x2x4/x11_y6_n66_r5_s16_ps1_pr16_u16_o5_N001.lp": 6,
    "1x2x4/x11_y6_n66_r8_s16_ps1_pr16_u16_o8_N001.lp": 5,
    "1x2x4/x11_y6_n66_r11_s16_ps1_pr16_u16_o11_N001.lp": 4,
    "2x3x5/x19_y9_n171_r5_s60_ps3_pr60_u60_o5_N001.lp": 7,
    "2x3x5/x19_y9_n171_r10_s60_ps3_pr60_u60_o10_N001.lp": 11,
    "2x3x5/x19_y9_n171_r15_s60_ps3_pr60_u60_o15_N001.lp": 6,
    "2x3x5/x19_y9_n171_r19_s60_ps3_pr60_u60_o19_N001.lp": 6,
    "4x5x8/x46_y15_n690_r12_s320_ps10_pr320_u320_o12_N001.lp": 38,
    "4x5x8/x46_y15_n690_r23_s320_ps10_pr320_u320_o23_N001.lp": 39,
    "4x5x8/x46_y15_n690_r35_s320_ps10_pr320_u320_o35_N001.lp": 24,
    "4x5x8/x46_y15_n690_r46_s320_ps10_pr320_u320_o46_N001.lp": 17,
}


@pytest.mark.parametrize("name, makespan", PAPER_M.items())
def test_paper_instances_at_their_minimal_makespan(name, makespan):
    instance = read_instance(EXAMPLES / "paper-m" / name)
    search = flow_plan(instance)
    assert (search.horizon, search.plan.horizon, search.minimal) == (makespan, makespan, True)


@pytest.mark.parametrize("engine", ["python", "scipy"])
@pytest.mark.parametrize("name, makespan", [(name, makespan) for name, makespan in PAPER_M.items()
                                            if not name.startswith("4x5x8")])
def test_both_maximum_flows_find_the_minimal_makespan(monkeypatch, engine, name, makespan):
    from asprilo.encodings import flow

    monkeypatch.setattr(flow, "PYTHON_FLOW", 10**12 if engine == "python" else 0)
    instance = read_instance(EXAMPLES / "paper-m" / name)
    search = flow_plan(instance)
    assert (search.horizon, search.minimal) == (makespan, True)
    assert check(instance, search.plan, Domain.M).valid
    assert [(a.horizon, a.feasible) for a in search.attempts] == [(makespan, True)]
    assert check(instance, search.plan, Domain.M).valid


def test_search_goes_up_from_the_bound_on_a_walled_floor():
    search = flow_plan(WALLED)
    assert (search.lower_bound, search.horizon, search.minimal) == (3, 4, True)
    assert [(a.horizon, a.feasible) for a in search.attempts] == [(3, False), (4, True)]
    assert check(WALLED, search.plan, Domain.MD).valid


def test_fixed_horizon():
    assert flow_plan(WALLED, horizon=3).plan is None
    search = flow_plan(WALLED, horizon=6)
    assert (search.horizon, search.minimal) == (6, False) and search.plan.horizon <= 6
    assert check(WALLED, search.plan, Domain.MD).valid


def test_more_robots_than_goals_the_others_end_anywhere():
    corridor = [(x, 1) for x in range(1, 6)]
    instance = md(corridor, [(1, 1), (2, 1), (3, 1)], [(5, 1)])
    search = flow_plan(instance)
    assert (search.horizon, search.minimal) == (2, True)
    assert check(instance, search.plan, Domain.MD).valid


def test_no_swaps_through_the_edge_gadget():
    # two robots on a two-cell floor, each goal under the other: anonymous robots stay put
    instance = md([(1, 1), (2, 1)], [(1, 1), (2, 1)], [(2, 1), (1, 1)])
    search = flow_plan(instance)
    assert (search.horizon, len(search.plan)) == (0, 0)
    network = TimeExpandedNetwork(Floor([(1, 1), (2, 1)]), [(1, 1)], [(2, 1)], 1)
    # in, out per cell and step; one gadget pair per edge and step; source, sink, idle
    assert (network.size, network.arcs) == (2 * (2 * 2 + 2) + 3, 13)


def test_unreachable_goal_means_no_plan_at_any_horizon():
    instance = md([(1, 1), (3, 1)], [(1, 1)], [(3, 1)])
    search = flow_plan(instance)
    assert (search.plan, search.minimal, search.attempts) == (None, True, [])


def test_time_limit_and_cancellation_stop_the_search():
    assert (flow_plan(WALLED, watch=Watch(time_limit=0)).status, flow_plan(WALLED).status) == (
        SolveStatus.LIMIT, SolveStatus.FOUND)
    cancel = threading.Event()
    cancel.set()
    with Watch(cancel=cancel) as watch:
        assert flow_plan(WALLED, watch=watch).status is SolveStatus.CANCELLED


@pytest.mark.parametrize("name, memory_limit, in_child", [
    ("1x2x4/x11_y6_n66_r11_s16_ps1_pr16_u16_o11_N001.lp", None, False),  # 11 x 66 = 726 robot-cells
    ("1x2x4/x11_y6_n66_r11_s16_ps1_pr16_u16_o11_N001.lp", 2000, True),  # a memory limit asks for a child
    ("2x3x5/x19_y9_n171_r15_s60_ps3_pr60_u60_o15_N001.lp", None, True),  # 15 x 171 = 2,565 > 2,000
])
def test_a_quick_flow_runs_in_this_process_even_when_isolation_is_asked(monkeypatch, name, memory_limit, in_child):
    from asprilo.encodings.solving import solve
    from asprilo.isolation import run_isolated

    children = []
    monkeypatch.setattr("asprilo.isolation.run_isolated",
                        lambda *args, **options: children.append(args) or run_isolated(*args, **options))
    outcome = solve(EXAMPLES / "paper-m" / name, Domain.M, method="flow", isolate=True, memory_limit=memory_limit,
                    time_limit=60)
    assert (outcome.status, outcome.horizon, outcome.minimal) == (SolveStatus.FOUND, PAPER_M[name], True)
    assert len(children) == in_child
