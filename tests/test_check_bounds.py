"""``check`` answers at once: the bound it shows (cheap by default, the strongest on request),
the verdict that does not depend on it, the bound computed once per check and per solve, and
the command that does not import numpy for a valid plan."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest
from helpers import EXAMPLES, OUTCOME, SMALL_A, WRONG_OUTCOME
from helpers.worlds import md, plan, walk, world

from asprilo.bounds import Floor, cheap_bounds, makespan, mapf, strong_bounds
from asprilo.checker import check
from asprilo.checker import report as checker_report
from asprilo.cli import main
from asprilo.domain import Domain, detect_domain
from asprilo.model import Instance
from asprilo.reader import read_instance, read_plan
from asprilo.sources import Source

B_INSTANCE = EXAMPLES / "encodings-repo/x46_y15_n690_r10_s160_ps10_pr5_u10_o2_N1.lp"
B_PLAN = EXAMPLES / "encodings-repo/x46_y15_n690_r10_s160_ps10_pr5_u10_o2_N1.plan"
BUNDLED = sorted(EXAMPLES.glob("**/*.lp"))
BOUND_KEYS = {"bounds", "makespan_bound", "makespan_ratio", "sum_of_costs_bound", "sum_of_costs_ratio"}


def _row(width: int, height: int, robots: dict, shelves: dict, station: tuple, lines: dict) -> Instance:
    """A full grid; shelf k holds one unit of product k; order o asks for one unit of product ``lines[o]``."""
    facts = [f"init(object(grid,1),value(xsize,{width})). init(object(grid,1),value(ysize,{height})).",
             f"init(object(pickingStation,1),value(at,{station}))."]
    facts += [f"init(object(robot,{r}),value(at,{cell}))." for r, cell in robots.items()]
    facts += [f"init(object(shelf,{s}),value(at,{cell})). init(object(product,{s}),value(on,({s},1)))."
              for s, cell in shelves.items()]
    facts += [f"init(object(order,{o}),value(line,({p},1))). init(object(order,{o}),value(pickingStation,1))."
              for o, p in lines.items()]
    return read_instance(Source("<world>", "\n".join(facts)))


# --- the verdict does not depend on the bound --------------------------------------------------

def _m_world() -> tuple[Instance, object]:
    instance = world("R..S/SR..", products={1: {1: 1}, 2: {2: 1}}, orders={1: ({1: 1}, None), 2: ({2: 1}, None)})
    return instance, plan(*walk(1, "EE"), (1, 2, "W"))  # robot 1 stops one cell short: invalid


CASES = {
    "outcome": lambda: (read_instance(SMALL_A), read_plan(OUTCOME)),
    "wrong outcome": lambda: (read_instance(SMALL_A), read_plan(WRONG_OUTCOME)),
    "b plan": lambda: (read_instance(B_INSTANCE), read_plan(B_PLAN)),
    "m world": _m_world,
}


@pytest.mark.parametrize("case", CASES)
def test_the_verdict_and_the_violations_are_the_same_whatever_the_bound(case):
    instance, steps = CASES[case]()
    reports = [check(instance, steps, bound="cheap"), check(instance, steps, bound="strong"),
               check(instance, steps, bound=None), check(instance, steps, makespan_bound=0, sum_of_costs_bound=0)]
    seen = {(r.valid, r.domain, r.horizon, tuple((e.atom, e.message) for e in r.errors),
             tuple(sorted((k, json.dumps(v)) for k, v in r.metrics.items() if k not in BOUND_KEYS)))
            for r in reports}
    assert len(seen) == 1
    assert [r.metrics.get("bounds") for r in reports] == ["cheap", "strong", None, "given"]
    assert not BOUND_KEYS & set(reports[2].metrics)  # bound=None: no bounds at all
    checker_report.add_bounds(reports[2], instance, "strong")
    assert reports[2].metrics == reports[1].metrics


@pytest.mark.parametrize("plan_path", [OUTCOME, WRONG_OUTCOME])
def test_the_command_says_the_same_whatever_the_bound(plan_path, capsys):
    outputs = {}
    for strength in ("cheap", "strong"):
        code = main(["check", str(SMALL_A), str(plan_path), "--bound", strength])
        text = capsys.readouterr().out.splitlines()
        assert main(["check", str(SMALL_A), str(plan_path), "--bound", strength, "--json"]) == code
        report = json.loads(capsys.readouterr().out)
        outputs[strength] = (code, text[:-1], report["valid"], report["errors"],
                             {k: v for k, v in report["metrics"].items() if k not in BOUND_KEYS})
        assert report["metrics"]["bounds"] == strength
        bound = report["metrics"]["makespan_bound"]
        which = "cheap; --bound strong for the strongest" if strength == "cheap" else "the strongest"
        assert text[-1] == f"lower bounds ({which}): makespan {bound} (plan/bound {29 / bound:.2f})"
    assert outputs["cheap"] == outputs["strong"]
    assert outputs["cheap"][0] == (0 if plan_path == OUTCOME else 1)


# --- the cheap bound: hand-derived values, and never above the strong one ----------------------

def test_the_cheap_a_b_c_bound_is_the_stations_bound():
    # 8x2, station (1,1), shelves (3,1) and (4,1), robot 1 at (4,2), robot 2 at (8,2).  Line 1
    # (shelf 1): robot 1 walks 2 moves, lifts at 3, carries 2 moves, delivers at 6.  Line 2
    # (shelf 2): lifted at 2 (robot 1, 1 move), but (3,1) holds shelf 1 until it is lifted at 3,
    # so shelf 2 is on (3,1) at 4, on the station at 5, delivered at 7 at the earliest.  One
    # station serves them in turn, a step between two shelves: 6, then 8.  The strong bound
    # also sees that robot 2 is far and robot 1 cannot deliver both by 8: 10.
    instance = _row(8, 2, {1: (4, 2), 2: (8, 2)}, {1: (3, 1), 2: (4, 1)}, (1, 1), {1: 1, 2: 2})
    assert cheap_bounds(instance, Domain.B) == (8, None)
    assert strong_bounds(instance, Domain.B) == (10, None)


def test_the_cheap_bound_sees_shelves_in_the_way_within_its_budget(monkeypatch):
    # R.SSP: shelf 2 on (4,1) blocks the way of shelf 1 to the station (5,1).  Robot 1 lifts
    # shelf 1 at 3 and could carry it there by 5, delivering at 6; but (4,1) is free only once
    # shelf 2 could have been lifted (at 4) and carried away: on (4,1) at 5, delivered at 7
    instance = _row(5, 1, {1: (1, 1)}, {1: (3, 1), 2: (4, 1)}, (5, 1), {1: 1})
    assert cheap_bounds(instance, Domain.B) == strong_bounds(instance, Domain.B) == (7, None)
    monkeypatch.setattr(makespan, "CHEAP_VISITS", 0)  # beyond the budget: walking distances alone
    assert cheap_bounds(instance, Domain.B) == (6, None)


def test_the_cheap_bound_knows_when_there_is_no_plan():
    # A: two orders want one unit each of product 1, which one shelf holds once.  B: the shelf
    # is delivered from at 6 at the earliest, and once for each order: 6 and 7
    short = _row(5, 1, {1: (1, 1)}, {1: (3, 1)}, (5, 1), {1: 1, 2: 1})
    assert cheap_bounds(short, Domain.A) == (math.inf, None) and cheap_bounds(short, Domain.B) == (7, None)
    assert cheap_bounds(_row(5, 1, {1: (1, 1)}, {1: (3, 1)}, (5, 1), {}), Domain.B) == (0, None)


def test_the_cheap_m_bound_gives_each_goal_its_nearest_robot():
    # SSR.R: goals (the shelves) on (1,1) and (2,1), robots on (3,1) and (5,1).  Robot 1 is
    # nearest to both (2 and 1 steps): cheap makespan 2, sum 3.  A robot each: robot 1 to
    # (1,1) and robot 2 to (2,1), 2 + 3 steps (or 1 + 4): makespan 3, sum 5
    instance = world("SSR.R", products={1: {1: 1}, 2: {2: 1}}, orders={1: ({1: 1}, None), 2: ({2: 1}, None)})
    assert cheap_bounds(instance, Domain.M) == (2, 3)
    assert strong_bounds(instance, Domain.M) == (3, 5)
    instance.robots.pop(2)  # fewer robots than goals: no plan
    assert cheap_bounds(instance, Domain.M) == strong_bounds(instance, Domain.M) == (math.inf, math.inf)


def test_the_cheap_md_bound_walks_a_labelled_robot_around_a_wall(monkeypatch):
    # 3x3 without its centre: robot 1 on (1,2) must reach destination 1 on (3,2), 4 steps around
    # the hole (Manhattan: 2); robot 2 on (1,1) and destination 2 on (1,3) are anonymous: 2 steps
    cells = [(x, y) for x in range(1, 4) for y in range(1, 4) if (x, y) != (2, 2)]
    instance = md(cells, [(1, 2), (1, 1)], [(3, 2), (1, 3)])
    instance.assignment = {1: ("destination", 1)}
    assert cheap_bounds(instance, Domain.MD) == strong_bounds(instance, Domain.MD) == (4, 6)
    monkeypatch.setattr(mapf, "CHEAP_VISITS", 0)  # beyond the budget: Manhattan, which no path undercuts
    assert cheap_bounds(instance, Domain.MD) == (2, 4)


def test_the_python_search_and_the_numpy_search_agree():
    cells = {(x, y) for x in range(1, 9) for y in range(1, 6)} - {(3, y) for y in range(1, 5)} - {(6, 3)}
    floor = Floor(cells | {(12, 12)})  # a node nothing reaches
    ordered = sorted(floor.cells)
    for source in [(1, 1), (8, 5), (12, 12)]:
        steps = floor.steps_from([source])
        assert [steps.get(cell, math.inf) for cell in ordered] == floor.distances([source], ordered)[0].tolist()
    nearest = floor.steps_from([(1, 1), (8, 5), (20, 20)])  # the nearest of several; not a node: left out
    assert [nearest.get(cell, math.inf) for cell in ordered] == \
        floor.distances([(1, 1), (8, 5)], ordered).min(axis=0).tolist()


@pytest.mark.parametrize("path", BUNDLED, ids=lambda path: path.stem)
def test_the_strong_m_bounds_are_the_same_without_numpy(path, monkeypatch):
    """Small instances are matched in plain Python (no numpy to import), the others with numpy:
    the same bounds (here with labelled goals too: robot k bound to goal k, where there are as many)."""
    instance = read_instance(path)
    if not instance.orders and not instance.destinations:
        return
    variants = [instance]
    if instance.destinations and len(instance.robots) >= len(instance.destinations):
        labelled = read_instance(path)
        labelled.assignment = {r: ("destination", d) for r, d in zip(sorted(labelled.robots),
                                                                     sorted(labelled.destinations), strict=False)}
        variants.append(labelled)
    python = [mapf.mapf_bounds(variant) for variant in variants]
    monkeypatch.setattr(mapf, "CHEAP_VISITS", -1)  # every search with numpy
    assert [mapf.mapf_bounds(variant) for variant in variants] == python


def test_the_strong_md_bound_of_labelled_robots_on_a_floor_with_holes(monkeypatch):
    cells = [(x, y) for x in range(1, 4) for y in range(1, 4) if (x, y) != (2, 2)]
    instance = md(cells, [(1, 2), (1, 1), (3, 3)], [(3, 2), (1, 3), (2, 1)])
    instance.assignment = {1: ("destination", 1), 3: ("destination", 3)}
    # robot 1: 4 steps around the hole; robot 3: (3,3) -> (2,1) 3 steps; robot 2: 2 steps
    assert mapf.mapf_bounds(instance) == (4, 9)
    monkeypatch.setattr(mapf, "CHEAP_VISITS", -1)
    assert mapf.mapf_bounds(instance) == (4, 9)


def _domains(instance: Instance, every: bool) -> list[Domain]:
    detected = detect_domain(instance)
    if every and instance.orders and instance.stations:
        return [Domain.A, Domain.B, Domain.C, Domain.M]
    return [detected, *([Domain.M] if detected.delivers and instance.orders else [])]


def _cheap_no_more_than_strong(path: Path, every: bool) -> None:
    instance = read_instance(path)
    for domain in _domains(instance, every):
        (cheap, cheap_total), (strong, strong_total) = cheap_bounds(instance, domain), strong_bounds(instance, domain)
        assert cheap <= strong, (path.name, domain)
        assert (cheap_total is None) == (strong_total is None) and (cheap_total or 0) <= (strong_total or 0)


@pytest.mark.parametrize("path", BUNDLED, ids=lambda path: path.stem)
def test_the_cheap_bound_is_no_more_than_the_strong_one_on_every_bundled_instance(path):
    _cheap_no_more_than_strong(path, every=False)  # in its own domain (and M where it has orders)


@pytest.mark.slow
@pytest.mark.parametrize("path", BUNDLED, ids=lambda path: path.stem)
def test_the_cheap_bound_is_no_more_than_the_strong_one_in_every_domain(path):
    _cheap_no_more_than_strong(path, every=True)


# --- the bound is computed once -----------------------------------------------------------------

@pytest.fixture
def counted(monkeypatch):
    """Calls of the checker's bounds and of solve's (by name)."""
    from asprilo.encodings import flow
    from asprilo.encodings.solving import bounds as solving_bounds
    calls: list[str] = []

    def counting(module, name, label):
        function = getattr(module, name)

        def count(*args, **keywords):
            calls.append(f"{label}.{name}")
            return function(*args, **keywords)
        monkeypatch.setattr(module, name, count)

    for module, label in ((checker_report, "report"), (solving_bounds, "solve"), (flow, "flow")):
        for name in ("cheap_bounds", "strong_bounds", "makespan_bound", "mapf_bounds"):
            if hasattr(module, name):
                counting(module, name, label)
    return calls


@pytest.mark.parametrize("argv, expected", [
    ([], ["report.cheap_bounds"]), (["--bound", "strong"], ["report.strong_bounds"]),
    (["--json"], ["report.cheap_bounds"]), (["--json", "--bound", "strong"], ["report.strong_bounds"])])
def test_a_check_computes_its_bound_once(counted, capsys, argv, expected):
    assert main(["check", str(SMALL_A), str(WRONG_OUTCOME), *argv]) == 1
    assert counted == expected


def test_a_check_handed_the_bounds_computes_none(counted):
    instance, steps = _m_world()
    report = check(instance, steps, makespan_bound=3, sum_of_costs_bound=4, bound="strong")
    assert (report.metrics["bounds"], report.metrics["makespan_bound"], counted) == ("given", 3, [])


@pytest.mark.parametrize("domain, method, expected", [
    (Domain.B, "asp", ["solve.makespan_bound"]),
    (Domain.M, "flow", ["solve.mapf_bounds"]),
    (Domain.M, "asp", ["solve.mapf_bounds"])])
def test_a_solve_computes_the_bound_once_and_hands_it_to_its_check(counted, domain, method, expected):
    from asprilo.encodings import solve
    instance = _row(5, 2, {1: (1, 1)}, {1: (3, 1)}, (5, 2), {1: 1})
    if domain is Domain.M:
        instance = world("R..S/SR..", products={1: {1: 1}, 2: {2: 1}}, orders={1: ({1: 1}, None), 2: ({2: 1}, None)})
    outcome = solve(instance, domain, method=method)
    assert outcome.found and outcome.check.valid and outcome.check.metrics["bounds"] == "given"
    assert counted == expected
    assert outcome.check.metrics["makespan_bound"] == outcome.lower_bound


# --- no numpy for a valid plan --------------------------------------------------------------------

def _imports_after(argv: list[str]) -> tuple[int, list[str]]:
    """The exit status of the command ``argv`` in a fresh interpreter, and the heavy modules it imported."""
    program = ("import sys\nfrom asprilo.cli import main\ncode = main(sys.argv[1:])\n"
               "print(sorted(name for name in sys.modules if name.split('.')[0] in ('numpy', 'scipy', 'PyQt5')))\n"
               "sys.exit(code)\n")
    done = subprocess.run([sys.executable, "-c", program, *argv], capture_output=True, text=True, timeout=120)
    return done.returncode, json.loads(done.stdout.splitlines()[-1].replace("'", '"'))


def test_the_check_command_does_not_import_numpy(write):
    assert _imports_after(["check", str(SMALL_A), str(OUTCOME)]) == (0, [])
    assert _imports_after(["check", str(SMALL_A), str(OUTCOME), "--json"]) == (0, [])
    m = write("m.lp", "".join(f"init(object(node,{k}),value(at,({k},1))). " for k in range(1, 4))
              + "init(object(robot,1),value(at,(1,1))). init(object(shelf,1),value(at,(3,1))). "
              "init(object(product,1),value(on,(1,1))). init(object(order,1),value(line,(1,1))).")
    steps = write("p.lp", "occurs(object(robot,1),action(move,(1,0)),1). occurs(object(robot,1),action(move,(1,0)),2).")
    assert _imports_after(["check", str(m), str(steps)]) == (0, [])
