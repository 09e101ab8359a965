"""MovingAI maps, scenarios and LaCAM results <-> asprilo; M <-> Md."""

from __future__ import annotations

import re

import pytest
from helpers import EXAMPLES

from asprilo.cli import main
from asprilo.interop.convert import m_to_md, md_to_m, result_to_plan
from asprilo.interop.movingai import octile_lengths, parse_map, parse_result, parse_scenario
from asprilo.model import Action, Destination, Instance, Plan, Robot
from asprilo.reader import read_instance, read_plan
from asprilo.sources import Source

MAPS = sorted((EXAMPLES / "movingai").glob("*.map"))
SCEN = EXAMPLES / "movingai/random-32-32-20-random-1.scen"


def convert(*args) -> int:
    return main(["convert", *map(str, args)])


@pytest.mark.parametrize("path", MAPS, ids=lambda p: p.name)
def test_map_round_trip_is_byte_identical(tmp_path, path):
    assert convert(path, tmp_path / "floor.lp") == 0
    assert convert(tmp_path / "floor.lp", tmp_path / "back.map") == 0
    assert (tmp_path / "back.map").read_bytes() == path.read_bytes()


def test_map_cells_become_nodes(tmp_path):
    convert(EXAMPLES / "movingai/warehouse-10-20-10-2-1.map", tmp_path / "w.lp")
    instance = read_instance(tmp_path / "w.lp")
    assert len(instance.nodes) == 5699
    assert instance.size == (160, 62)  # the map's border row/column are blocked
    assert (2, 2) in instance.cells and (1, 1) not in instance.cells
    assert instance.nodes[1 * 161 + 1 + 1] == (2, 2)  # id = y * width + x + 1, 0-based (x, y)


def test_octile_lengths_agree_with_the_scenario():
    grid = parse_map(Source.from_path(EXAMPLES / "movingai/random-32-32-20.map"))
    tasks = parse_scenario(Source.from_path(SCEN))
    lengths = octile_lengths(grid, [(t.start, t.goal) for t in tasks])
    assert len(tasks) == 409
    assert max(abs(length - t.optimal) for length, t in zip(lengths, tasks, strict=True)) < 2e-8


def test_scenario_to_md_and_back(tmp_path):
    assert convert(SCEN, tmp_path / "a.lp", "--agents", 50) == 0
    instance = read_instance(tmp_path / "a.lp")
    assert (len(instance.robots), len(instance.destinations)) == (50, 50)
    assert instance.robots[1] == Robot(1, (6, 17)) and instance.destinations[1] == Destination(1, (32, 25))
    assert convert(tmp_path / "a.lp", tmp_path / "a.scen") == 0
    original = SCEN.read_text().splitlines()[1:51]
    written = (tmp_path / "a.scen").read_text().splitlines()
    assert written[0] == "version 1" and len(written) == 51
    for mine, theirs in zip(written[1:], original, strict=True):
        assert mine.split("\t")[:8] == theirs.split("\t")[:8]
        assert abs(float(mine.split("\t")[8]) - float(theirs.split("\t")[8])) < 2e-8


def test_scenario_to_m(tmp_path):
    assert convert(SCEN, tmp_path / "m.lp", "--agents", 3, "--goals", "m") == 0
    instance = read_instance(tmp_path / "m.lp")
    assert instance.shelves[2].at == (25, 23)
    assert instance.orders[2].lines == {2: 1} and instance.products[2].stock == {2: 1}
    assert list(instance.stations) == [1]
    assert instance.stations[1].at not in {s.at for s in instance.shelves.values()}


def test_m_and_md_convert_both_ways_without_loss():
    m = read_instance(EXAMPLES / "paper-m/2x3x5/x19_y9_n171_r5_s60_ps3_pr60_u60_o5_N001.lp")
    md = m_to_md(m)
    assert len(md.destinations) == 5 and all(not order.lines for order in md.orders.values())
    assert {d.at for d in md.destinations.values()} == {
        m.shelves[next(iter(m.products[next(iter(o.lines))].stock))].at for o in m.orders.values()}
    assert md_to_m(md) == m
    pure = Instance(nodes={1: (1, 1), 2: (2, 1), 3: (3, 1)}, robots={1: Robot(1, (1, 1))},
                    destinations={4: Destination(4, (3, 1))})
    as_m = md_to_m(pure)
    assert (as_m.orders[4].lines, as_m.stations[1].at, as_m.shelves[1].at) == ({1: 1}, (1, 1), (3, 1))
    assert m_to_md(as_m).destinations == pure.destinations


def test_lacam_result_to_plan_and_back(tmp_path, write):
    instance = write("i.lp", "init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))). "
                             "init(object(node,3),value(at,(2,2))). init(object(robot,1),value(at,(1,1))). "
                             "init(object(robot,2),value(at,(2,2))). init(object(destination,1),value(at,(2,1))). "
                             "init(object(destination,2),value(at,(2,2))).")
    result = write("result.txt", "agents=2\nsolved=1\nsolution=\n0:(0,0),(1,1),\n1:(1,0),(1,1),\n")
    assert convert(result, tmp_path / "plan.lp", "--instance", instance) == 0
    assert read_plan(tmp_path / "plan.lp").actions == [Action(1, 1, "move", (1, 0))]
    assert convert(tmp_path / "plan.lp", tmp_path / "back.txt", "--instance", instance) == 0
    back = parse_result(Source.from_path(tmp_path / "back.txt"))
    assert back.configurations == [[(0, 0), (1, 1)], [(1, 0), (1, 1)]]
    assert (back.fields["soc"], back.fields["makespan"], back.fields["goals"]) == ("1", "1", "(1,0),(1,1),")


def test_result_with_a_jump_is_rejected():
    result = parse_result(Source("r.txt", "0:(0,0),\n1:(1,1),\n"))
    with pytest.raises(Exception, match=r"agent 0 jumps from \(0, 0\) to \(1, 1\) at step 1"):
        result_to_plan(result)


@pytest.mark.parametrize("text, message", [
    ("type octile\nheight 2\nwidth 2\nmap\n..\n.\n", "bad.map:6: row of 1 cells, the header says width 2"),
    ("type octile\nheight x\nwidth 2\nmap\n", "bad.map:2: the header needs integer 'height' and 'width'"),
    ("height 1\n", "bad.map: the MovingAI header ends without a 'map' line"),
])
def test_bad_maps(capsys, write, text, message):
    path = write("bad.map", text)
    assert convert(path, path.with_suffix(".lp")) == 2
    assert capsys.readouterr().err == f"error: {path.parent}/{message}\n"
    assert not path.with_suffix(".lp").exists()


@pytest.mark.parametrize("agents", [500, 0])
def test_agents_out_of_range(capsys, tmp_path, agents):
    assert convert(SCEN, tmp_path / "x.lp", "--agents", agents) == 2
    assert capsys.readouterr().err == f"error: --agents must be between 1 and 409 (the scenario's rows), got {agents}\n"
    assert not (tmp_path / "x.lp").exists()


def test_labelled_scenario_metrics(tmp_path):
    """The first 50 agents of random-32-32-20-random-1, each bound to its own goal."""
    from asprilo.checker import check
    assert convert(SCEN, tmp_path / "l.lp", "--agents", 50, "--labelled") == 0
    instance = read_instance(tmp_path / "l.lp")
    assert instance.assignment == {k: ("destination", k) for k in range(1, 51)}
    report = check(instance, Plan([]))
    assert (report.metrics["makespan_bound"], report.metrics["sum_of_costs_bound"]) == (48, 1082)
    missed = [v for v in report.errors if v.check == "missedAssignedGoal"]
    assert len(missed) == 50 and missed[0].params == (1, (32, 25), 0)
    # the same scenario rows come back, in the same pairing
    assert convert(tmp_path / "l.lp", tmp_path / "l.scen") == 0
    original = [line.split("\t")[:8] for line in SCEN.read_text().splitlines()[1:51]]
    assert [line.split("\t")[:8] for line in (tmp_path / "l.scen").read_text().splitlines()[1:]] == original


def test_labelled_goals_are_checked_and_followed(write):
    from asprilo.checker import check
    from asprilo.encodings import solve
    # two robots on a corridor, each labelled with the destination the other one is closer to
    path = write("swap.lp", """
        init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))).
        init(object(node,3),value(at,(3,1))). init(object(node,4),value(at,(2,2))).
        init(object(robot,1),value(at,(1,1))). init(object(robot,2),value(at,(3,1))).
        init(object(destination,1),value(at,(1,1))). init(object(destination,2),value(at,(3,1))).
        assign(robot(1),destination(2)). assign(robot(2),destination(1)).""")
    instance = read_instance(path)
    anonymous = check(instance, Plan([]))
    assert [(v.check, v.params) for v in anonymous.errors] == [
        ("missedAssignedGoal", (1, (3, 1), 0)), ("missedAssignedGoal", (2, (1, 1), 0))]
    assert [v.message for v in anonymous.errors][0] == (
        "step 0 (the horizon): robot 1 does not end on its assigned goal, destination 2 at (3,1)")
    outcome = solve(instance)
    assert outcome.found and outcome.check.valid and outcome.minimal
    assert outcome.horizon == 4  # one robot steps aside into (2,2) to let the other pass
    assert (outcome.lower_bound, outcome.check.metrics["sum_of_costs_bound"]) == (2, 4)


def test_labelled_m_and_md_convert_both_ways():
    m = read_instance(EXAMPLES / "paper-m/2x3x5/x19_y9_n171_r5_s60_ps3_pr60_u60_o5_N001.lp")
    ordered = [next(iter(m.products[next(iter(o.lines))].stock)) for _id, o in sorted(m.orders.items())]
    m.assignment = {robot: ("shelf", shelf) for robot, shelf in zip(sorted(m.robots), ordered, strict=True)}
    md = m_to_md(m)
    assert md.assigned_cells() == m.assigned_cells()
    assert set(kind for kind, _ in md.assignment.values()) == {"destination"}
    assert md_to_m(md) == m


@pytest.mark.parametrize("text, message", [
    ("assign(robot(1),destination(1)). assign(robot(1),destination(2)).",
     "robot 1 is assigned two goals: destination(1) and destination(2)"),
    ("assign(robot(3),destination(1)).", "assign names robot 3, which the instance lacks"),
    ("assign(robot(1),destination(9)).", "assign names destination 9, which the instance lacks"),
    ("assign(robot(1),node(1)).", "expected assign(robot(R),shelf(S)) or assign(robot(R),destination(D)), "
                                  "got assign(robot(1),node(1))"),
])
def test_bad_assignments(write, text, message):
    path = write("bad.lp", "init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))). "
                           "init(object(robot,1),value(at,(1,1))). init(object(destination,1),value(at,(2,1))). "
                           "init(object(destination,2),value(at,(1,1))).\n" + text)
    with pytest.raises(Exception, match=re.escape(f"{path}:2: {message}")):
        read_instance(path)


def test_unknown_facts_are_carried_through_m_and_md(tmp_path, write, capsys):
    """A robot's energy (later asprilo work) is ignored with a warning and written back."""
    path = write("energy.lp", "init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))).\n"
                              "init(object(robot,1),value(at,(1,1))). init(object(destination,1),value(at,(2,1))).\n"
                              "init(object(robot,1),value(energy,80)). init(object(robot,1),value(max_energy,100)).\n")
    kept = ["init(object(robot,1),value(energy,80)).", "init(object(robot,1),value(max_energy,100))."]
    assert main(["convert", str(path), str(tmp_path / "m.lp"), "--to", "m"]) == 0
    assert main(["convert", str(tmp_path / "m.lp"), str(tmp_path / "md.lp"), "--to", "md"]) == 0
    heading = "% facts asprilo does not use (kept as they were read)"
    for name in ("m.lp", "md.lp"):
        assert (tmp_path / name).read_text().splitlines()[-3:] == [heading, *kept]
    warnings = capsys.readouterr().err.splitlines()
    assert warnings == [f"warning: {path}:3: ignored (and kept when written): attribute 'energy' of robot, "
                        "attribute 'max_energy' of robot",
                        f"warning: {tmp_path / 'm.lp'}:{_line_of(tmp_path / 'm.lp', kept[0])}: ignored (and kept "
                        "when written): attribute 'energy' of robot, attribute 'max_energy' of robot"]


def _line_of(path, text: str) -> int:
    return path.read_text().splitlines().index(text) + 1
