"""Reading instances and plans: every example, every accepted form, exact objects."""

from __future__ import annotations

import io
import sys

import pytest
from helpers import EXAMPLES, OUTCOME, SMALL_A, WRONG_OUTCOME

from asprilo.domain import Domain, detect_domain
from asprilo.errors import InputError
from asprilo.limits import Limits
from asprilo.model import Action, Order, PickingStation, Product, Robot, Shelf
from asprilo.reader import read_instance, read_plan
from asprilo.sources import Source
from asprilo.writer import format_instance, format_plan

ALL_FILES = sorted(p for p in EXAMPLES.rglob("*") if p.suffix in (".lp", ".txt", ".plan"))


def test_small_a_instance_objects():
    instance = read_instance(SMALL_A)
    assert instance.counts() == {"x": 11, "y": 6, "nodes": 66, "highways": 45, "robots": 3,
                                 "shelves": 12, "stations": 2, "products": 5, "units": 50,
                                 "orders": 3, "destinations": 0}
    assert instance.robots[1] == Robot(1, (1, 6))
    assert instance.shelves[12] == Shelf(12, (10, 4))
    assert instance.stations[2] == PickingStation(2, (8, 1))
    assert instance.products[1] == Product(1, {9: 4, 12: 4})
    assert instance.orders[1] == Order(1, {2: 11, 4: 2}, 1)
    assert instance.nodes[12] == (1, 2)
    assert instance.file_name() == SMALL_A.name
    assert detect_domain(instance) is Domain.A


def test_outcome_holds_instance_and_plan():
    plan = read_plan(OUTCOME)
    assert plan.horizon == 29
    assert len(plan) == 79
    assert plan.actions[0] == Action(1, 1, "move", (1, 0))
    assert Action(8, 3, "deliver", (1, 4, 1)) in plan.actions
    assert Action(29, 3, "putdown", ()) in plan.actions
    assert read_instance(OUTCOME) == read_instance(SMALL_A)
    wrong = read_plan(WRONG_OUTCOME)
    assert set(wrong.actions) - set(plan.actions) == {
        Action(23, 1, "deliver", (2, 5, 6)), Action(26, 2, "deliver", (1, 2, 3))}
    assert set(plan.actions) - set(wrong.actions) == {
        Action(23, 1, "deliver", (2, 5, 5)), Action(26, 2, "deliver", (1, 2, 4))}


@pytest.mark.parametrize("path", ALL_FILES, ids=lambda p: str(p.relative_to(EXAMPLES)))
def test_every_example_reads_and_round_trips(path):
    if path.suffix in (".lp", ".txt") and "init(" in path.read_text():
        instance = read_instance(path)
        assert instance.robots or instance.nodes
        text = format_instance(instance)
        assert read_instance(Source("written", text)) == instance
        assert format_instance(read_instance(Source("again", text))) == text
    plan = read_plan(path)
    assert read_plan(Source("written", format_plan(plan))) == plan


def test_example_plan_counts():
    b_plan = read_plan(EXAMPLES / "encodings-repo/x46_y15_n690_r10_s160_ps10_pr5_u10_o2_N1.plan")
    assert (b_plan.horizon, len(b_plan)) == (45, 129)
    instance = read_instance(EXAMPLES / "encodings-repo/x46_y15_n690_r10_s160_ps10_pr5_u10_o2_N1.plan")
    assert detect_domain(instance, b_plan) is Domain.B


def test_spaces_inside_facts():
    instance = read_instance(EXAMPLES / "encodings-repo/barricade.lp")
    assert instance.nodes[5] == (1, 2)
    assert instance.robots[4] == Robot(4, (3, 3))


def test_grid_form_and_quantity_free_forms():
    text = """
    % a 3x2 grid given by its size
    init(object(grid,1),value(xsize,3)).  init(object(grid,1),value(ysize,2)).
    init(object(robot,1),value(at,(1,1))). init(object(shelf,7),value(at,(3,2))).
    init(object(pickingStation,1),value(at,(2,1))).
    init(object(product,4),value(on,7)).
    init(object(order,1),value(line,4)). init(object(order,1),value(pickingStation,1)).
    """
    instance = read_instance(Source("grid.lp", text))
    assert instance.nodes == {1: (1, 1), 2: (2, 1), 3: (3, 1), 4: (1, 2), 5: (2, 2), 6: (3, 2)}
    assert instance.products[4].stock == {7: None}
    assert instance.orders[1] == Order(1, {4: None}, 1)
    assert detect_domain(instance) is Domain.M
    written = format_instance(instance)
    assert "init(object(product,4),value(on,7))." in written
    assert "init(object(order,1),value(line,4))." in written
    assert read_instance(Source("w", written)) == instance


def test_rules_constants_and_program_parts_go_through_clingo_when_rules_are_allowed():
    text = """
    #const width=4.
    #program base.
    init(object(node,X),value(at,(X,1))) :- X=1..width.
    init(object(robot,1),value(at,(width,1))).
    #program other.
    init(object(robot,2),value(at,(1,1))).
    """
    with pytest.raises(InputError) as refused:
        read_instance(Source("rules.lp", text))
    assert str(refused.value) == ("rules.lp:4: 'init(object(node,X),value(at,(X,1))) :- X=1..width.' is a rule; "
                                  "data holds only facts, #const and '#program base.' (rules need --allow-rules)")
    instance = read_instance(Source("rules.lp", text), Limits(allow_rules=True))
    assert instance.nodes == {1: (1, 1), 2: (2, 1), 3: (3, 1), 4: (4, 1)}
    assert list(instance.robots) == [1]


def test_several_files_make_one_instance(write):
    floor = write("floor.lp", "init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))).")
    robots = write("robots.lp", "init(object(robot,1),value(at,(2,1))).")
    instance = read_instance([floor, robots])
    assert instance.cells == {(1, 1), (2, 1)} and instance.robots[1].at == (2, 1)


def test_clingo_printed_output_is_a_plan():
    output = """clingo version 5.8.3
Reading from instance.lp ...
Solving...
Answer: 1
occurs(object(robot,1),action(move,(1,0)),1) occurs(object(robot,1),action(pickup,()),2)
Answer: 2
occurs(object(robot,2),action(move,(0,-1)),1) occurs(object(robot,2),action(deliver,(1,3,2)),2) other(atom)
SATISFIABLE

Models       : 2
Calls        : 1
Time         : 0.002s (Solving: 0.00s 1st Model: 0.00s Unsat: 0.00s)
CPU Time     : 0.002s
"""
    plan = read_plan(Source("<stdin>", output))
    assert plan.actions == [Action(1, 2, "move", (0, -1)), Action(2, 2, "deliver", (1, 3, 2))]


def test_clingo_quiet_output_with_atom_format():
    output = ("occurs(object(robot,1),action(move,(1,0)),1). occurs(object(robot,1),action(move,(0,1)),2).\n"
              "SATISFIABLE\n")
    assert read_plan(Source("out", output)).horizon == 2


def test_unusual_action_terms_are_kept():
    text = """occurs(object(robot,1),action(jump,up),1).
occurs(object(shelf,2),action(move,(1,0)),2).
occurs(object(robot,1),action(move,(1,0,0)),0).
occurs(object(robot,1),action(move,"far"),3)."""
    plan = read_plan(Source("odd.lp", text))
    assert plan.actions == [Action(0, 1, "move", (1, 0, 0)), Action(1, 1, "jump", "up"),
                            Action(2, 2, "move", (1, 0), kind="shelf"),
                            Action(3, 1, "move", '"far"')]
    assert read_plan(Source("again", format_plan(plan))) == plan


def test_stdin(monkeypatch):
    monkeypatch.setattr(sys, "stdin", io.StringIO("init(object(robot,1),value(at,(1,1)))."))
    assert read_instance("-").robots[1].at == (1, 1)


def test_m_aligned_instances_are_m_and_plans_refine_the_guess():
    instance = read_instance(EXAMPLES / "paper-m/1x2x4/x11_y6_n66_r2_s16_ps1_pr16_u16_o2_N001.lp")
    assert detect_domain(instance) is Domain.M
    moves = read_plan(Source("p", "occurs(object(robot,1),action(move,(1,0)),1)."))
    assert detect_domain(instance, moves) is Domain.M
    pickup = read_plan(Source("p", "occurs(object(robot,1),action(pickup,()),1)."))
    assert detect_domain(instance, pickup) is Domain.A
    no_orders = read_instance(EXAMPLES / "encodings-repo/x4_y4_n16_r8_s8_ps0_pr0_u0_o0_N1.lp")
    assert detect_domain(no_orders) is Domain.M
    md = read_instance(Source("md", "init(object(node,1),value(at,(1,1))). "
                                    "init(object(destination,1),value(at,(1,1)))."))
    assert detect_domain(md) is Domain.MD
