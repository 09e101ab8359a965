"""The domain-M encodings: every style agrees with the max-flow oracle, plans pass the checker."""

from __future__ import annotations

import clingo
import pytest
from helpers import EXAMPLES
from helpers.worlds import WALLED

from asprilo.domain import Domain
from asprilo.encodings import SolveStatus, reference_encodings, solve
from asprilo.encodings.flow import flow_plan
from asprilo.reader import read_instance
from asprilo.writer import format_instance

M_STYLES = [e.name for e in reference_encodings(Domain.M)]
SMALL_PAPER = sorted((EXAMPLES / "paper-m/1x2x4").glob("*.lp"))
TINY = {  # instance -> minimal makespan in domain M (one robot per shelf holding an ordered product)
    "x2_y2_n4_r2_s2_ps1_pr2_u4_o2_N1.lp": 1,
    "x3_y3_n9_r1_s1_ps1_pr1_u1_o1_N1.lp": 3,
    "x4_y4_n16_r2_s3_ps1_pr2_u4_o2_N1.lp": 3,
}


def test_the_registry_holds_four_styles_and_three_incremental_versions():
    assert M_STYLES == ["plain", "split", "clingcon", "dl", "plain-inc", "split-inc", "clingcon-inc"]


@pytest.mark.parametrize("style", M_STYLES)
@pytest.mark.parametrize("path", SMALL_PAPER, ids=lambda p: p.name[:16])
def test_every_style_finds_the_flow_optimum_on_the_small_paper_instances(style, path):
    instance = read_instance(path)
    optimum = flow_plan(instance).horizon
    outcome = solve(instance, encoding=style)
    assert (outcome.status, outcome.horizon, outcome.minimal) == (SolveStatus.FOUND, optimum, True)
    assert outcome.check.valid
    below = solve(instance, encoding=style, horizon=optimum - 1)
    assert (below.status, below.plan) == (SolveStatus.NONE, None)


@pytest.mark.parametrize("style", M_STYLES)
@pytest.mark.parametrize("name, makespan", TINY.items())
def test_tiny_instances_satisfiable_at_the_minimum_and_not_below(style, name, makespan):
    instance = read_instance(EXAMPLES / "encodings-repo" / name)
    at = solve(instance, Domain.M, encoding=style, horizon=makespan)
    below = solve(instance, Domain.M, encoding=style, horizon=makespan - 1)
    assert (at.status, at.horizon, at.check.valid, below.status) == (
        SolveStatus.FOUND, makespan, True, SolveStatus.NONE)


@pytest.mark.parametrize("style", M_STYLES)
def test_search_climbs_from_the_bound_on_a_floor_with_walls(style):
    outcome = solve(WALLED, encoding=style)
    assert outcome.domain is Domain.MD
    assert [(a.horizon, a.result) for a in outcome.horizons_tried] == [(3, "unsat"), (4, "sat")]
    assert (outcome.horizon, outcome.minimal, outcome.lower_bound) == (4, True, 3)
    assert outcome.check.valid


def test_plain_clingo_runs_the_main_files(tmp_path):
    """A student's command line: python -m clingo instance.lp asprilo/encodings/m/plain.lp -c horizon=N."""
    import subprocess
    import sys

    from asprilo.checker import check
    from asprilo.reader import read_plan
    instance_file = tmp_path / "walled.lp"
    instance_file.write_text(format_instance(WALLED))
    program = EXAMPLES.parent / "asprilo/encodings/m/plain.lp"
    for horizon, expected in ((3, "UNSATISFIABLE"), (4, "SATISFIABLE")):
        run = subprocess.run([sys.executable, "-m", "clingo", str(instance_file), str(program),
                              "-c", f"horizon={horizon}"], capture_output=True, text=True)
        assert expected in run.stdout.splitlines()
    plan = read_plan(_source(run.stdout))
    assert plan.horizon == 4 and check(WALLED, plan, Domain.MD).valid


def _source(text):
    from asprilo.sources import Source
    return Source("<clingo>", text)


def test_assignment_ties_robots_to_their_shelves():
    instance = read_instance(SMALL_PAPER[2])  # 5 robots, 5 orders
    outcome = solve(instance, assign=True)
    assert outcome.found and outcome.check.valid and outcome.assignment.optimal
    assert len(outcome.assignment.facts) == 5
    ends = {}
    for fact in outcome.assignment.facts:  # assign(robot(R),shelf(S))
        robot, shelf = (term.arguments[0].number for term in clingo.parse_term(fact).arguments)
        ends[robot] = instance.shelves[shelf].at
    final = {r: robot.at for r, robot in instance.robots.items()}
    for action in outcome.plan.actions:
        x, y = final[action.robot]
        final[action.robot] = (x + action.args[0], y + action.args[1])
    assert final == ends
