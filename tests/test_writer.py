"""Canonical instance and plan files, written atomically."""

from __future__ import annotations

import os

import pytest

from asprilo import writer
from asprilo.errors import InputError
from asprilo.model import Action, Instance, Order, PickingStation, Plan, Product, Robot, Shelf
from asprilo.reader import read_instance, read_plan


def tiny() -> Instance:
    return Instance(
        nodes={1: (1, 1), 2: (2, 1), 3: (1, 2), 4: (2, 2)}, highways={1: (1, 1)},
        robots={1: Robot(1, (2, 2), carries=1)}, shelves={1: Shelf(1, (2, 2))},
        stations={1: PickingStation(1, (2, 1))}, products={3: Product(3, {1: 2})},
        orders={1: Order(1, {3: 1}, 1)})


def test_canonical_instance_text():
    text = writer.format_instance(tiny(), header=["made by a test"])
    assert text == """\
############################################################
% made by a test
############################################################

#program base.

% nodes
init(object(node,1),value(at,(1,1))).
init(object(node,2),value(at,(2,1))).
init(object(node,3),value(at,(1,2))).
init(object(node,4),value(at,(2,2))).

% highways
init(object(highway,1),value(at,(1,1))).

% picking stations
init(object(pickingStation,1),value(at,(2,1))).

% robots
init(object(robot,1),value(at,(2,2))).
init(object(robot,1),value(carries,1)).

% shelves
init(object(shelf,1),value(at,(2,2))).

% products on shelves
init(object(product,3),value(on,(1,2))).

% orders
init(object(order,1),value(line,(3,1))).
init(object(order,1),value(pickingStation,1)).
""".replace("#" * 60, "%" * 60)


def test_default_header_has_tool_and_counts():
    lines = writer.header_lines(tiny(), command="gen -x 2 -y 2", seed=7)
    assert lines[:3] == ["asprilo 0.1.0", "command: gen -x 2 -y 2", "seed: 7"]
    assert "Number of Robots:                  1" in lines
    assert "Number of Product Units in Total:  2" in lines


def test_write_and_read_back(tmp_path):
    path = tmp_path / "sub" / "instance.lp"
    writer.write_instance(path, tiny())
    assert read_instance(path) == tiny()
    assert oct(path.stat().st_mode & 0o777) == oct(0o666 & ~writer._UMASK)
    plan = Plan([Action(2, 1, "deliver", (1, 3, 1)), Action(1, 1, "move", (0, -1))])
    writer.write_plan(tmp_path / "plan.lp", plan)
    assert (tmp_path / "plan.lp").read_text() == (
        "occurs(object(robot,1),action(move,(0,-1)),1).\n"
        "occurs(object(robot,1),action(deliver,(1,3,1)),2).\n")
    assert read_plan(tmp_path / "plan.lp") == plan


def test_failed_write_leaves_old_file_and_no_debris(tmp_path, monkeypatch):
    path = tmp_path / "instance.lp"
    path.write_text("old")

    def broken(*_args):
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", broken)
    with pytest.raises(InputError) as error:
        writer.write_text(path, "new")
    assert str(error.value) == f"{path}: cannot be written (disk full)"
    assert path.read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["instance.lp"]


def test_plan_horizon_and_steps():
    plan = Plan([Action(3, 2, "move", (1, 0)), Action(1, 1, "move", (1, 0)), Action(3, 1, "pickup", ())])
    assert plan.horizon == 3
    assert [a.robot for a in plan.at_step(3)] == [1, 2]
    assert sorted(plan.by_step()) == [1, 3]
    assert Plan().horizon == 0
