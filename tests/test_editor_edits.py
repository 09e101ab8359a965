"""The editor's checked edits (no GUI): exact changes, exact refusals, undo restores."""

from __future__ import annotations

import copy

import pytest
from helpers import SMALL_A

from asprilo.model import Instance, Order, Product, Robot, Shelf
from asprilo.reader import read_instance
from asprilo.sources import Source
from asprilo.visualizer.state import edits, order_edits
from asprilo.visualizer.state.edits import EditRefused
from asprilo.writer import format_instance


def facts(instance: Instance) -> list[str]:
    """The instance's facts as saved (header left out)."""
    return [line for line in format_instance(instance, []).splitlines() if line.startswith("init(")]


def do(instance: Instance, edit: edits.Edit) -> edits.Edit:
    edits.apply(instance, edit)
    return edit


@pytest.fixture
def floor() -> Instance:
    return edits.grid(4, 3)


def test_grid_numbers_nodes_row_by_row(floor):
    assert facts(floor)[:5] == ["init(object(node,1),value(at,(1,1))).", "init(object(node,2),value(at,(2,1))).",
                                "init(object(node,3),value(at,(3,1))).", "init(object(node,4),value(at,(4,1))).",
                                "init(object(node,5),value(at,(1,2)))."]
    assert len(floor.nodes) == 12 and floor.size == (4, 3)
    with pytest.raises(EditRefused, match="at least one column and one row, not 0x3"):
        edits.grid(0, 3)


def test_objects_get_the_next_ids_and_refusals_say_why(floor):
    assert do(floor, edits.add_object(floor, "robot", (1, 1))).text == "add robot 1 at (1,1)"
    do(floor, edits.add_object(floor, "robot", (2, 1)))
    assert floor.robots == {1: Robot(1, (1, 1)), 2: Robot(2, (2, 1))}
    with pytest.raises(EditRefused) as refused:
        edits.add_object(floor, "robot", (2, 1))
    assert str(refused.value) == "robot 2 already stands on (2,1): two robots may not share a node"
    do(floor, edits.set_floor(floor, (3, 2), "highway"))
    with pytest.raises(EditRefused) as refused:
        edits.add_object(floor, "shelf", (3, 2))
    assert str(refused.value) == "(3,2) is a highway: shelves may not rest there"
    edits.add_object(floor, "station", (3, 2))  # allowed, as in the checker (the paper's instances do it)
    do(floor, edits.add_object(floor, "station", (4, 1)))
    with pytest.raises(EditRefused) as refused:
        edits.add_object(floor, "shelf", (4, 1))
    assert str(refused.value) == "picking station 1 is on (4,1): shelves may not rest there"
    do(floor, edits.set_floor(floor, (1, 3), "missing"))
    with pytest.raises(EditRefused) as refused:
        edits.add_object(floor, "robot", (1, 3))
    assert str(refused.value) == "(1,3) is not a floor node: a robot must stand on a node"
    do(floor, edits.add_object(floor, "shelf", (1, 1)))  # a robot may stand under a shelf
    with pytest.raises(EditRefused) as refused:
        edits.add_object(floor, "shelf", (1, 1))
    assert str(refused.value) == "shelf 1 already stands on (1,1): two shelves may not share a node"


def test_floor_edits_keep_node_ids_and_refuse_occupied_cells(floor):
    do(floor, edits.add_object(floor, "shelf", (2, 2)))
    edit = do(floor, edits.set_floor(floor, (3, 2), "highway"))
    assert edit.changes == [edits.Change("highways", 7, edits.MISSING, (3, 2))]
    with pytest.raises(EditRefused) as refused:
        edits.set_floor(floor, (2, 2), "highway")
    assert str(refused.value) == "shelf 1 rests on (2,2): a highway must stay free of shelves"
    with pytest.raises(EditRefused) as refused:
        edits.set_floor(floor, (2, 2), "missing")
    assert str(refused.value) == "shelf 1 stands on (2,2): remove it first"
    do(floor, edits.set_floor(floor, (3, 2), "missing"))   # a highway node goes with its highway
    assert 7 not in floor.nodes and not floor.highways
    do(floor, edits.set_floor(floor, (3, 2), "storage"))   # restored with its conventional id
    assert floor.nodes[7] == (3, 2)
    assert edits.set_floor(floor, (3, 2), "storage").changes == []


def test_removing_a_shelf_takes_its_stock_and_its_carrier_lets_go(floor):
    do(floor, edits.add_object(floor, "shelf", (2, 2)))
    do(floor, edits.add_object(floor, "shelf", (3, 2)))
    do(floor, edits.add_object(floor, "robot", (2, 2)))
    do(floor, edits.set_carries(floor, 1, 1))
    do(floor, order_edits.set_stock(floor, 1, {1: 4, 2: 1}))
    do(floor, order_edits.set_stock(floor, 2, {2: 3}))
    before = copy.deepcopy(floor)
    edit = do(floor, edits.remove_object(floor, "shelf", 1))
    assert floor.products == {2: Product(2, {2: 3})}
    assert floor.robots[1] == Robot(1, (2, 2), None)
    assert 1 not in floor.shelves
    edits.apply(floor, edit, undo=True)
    assert floor == before


def test_removing_a_robot_or_its_goal_drops_the_labelled_goal(floor):
    for kind, cell in (("robot", (1, 1)), ("robot", (2, 1)), ("destination", (4, 3)), ("destination", (3, 3))):
        do(floor, edits.add_object(floor, kind, cell))
    floor.assignment = {1: ("destination", 1), 2: ("destination", 2)}
    before = copy.deepcopy(floor)
    first = do(floor, edits.remove_object(floor, "destination", 1))
    assert floor.assignment == {2: ("destination", 2)}
    second = do(floor, edits.remove_object(floor, "robot", 2))
    assert floor.assignment == {}
    edits.apply(floor, second, undo=True)
    edits.apply(floor, first, undo=True)
    assert floor == before


def test_a_robot_takes_its_shelf_along_but_not_under_another(floor):
    do(floor, edits.add_object(floor, "robot", (1, 1)))
    do(floor, edits.add_object(floor, "shelf", (1, 1)))
    do(floor, edits.add_object(floor, "shelf", (3, 3)))
    do(floor, edits.set_carries(floor, 1, 1))
    do(floor, edits.move_object(floor, "robot", 1, (2, 3)))
    assert floor.robots[1] == Robot(1, (2, 3), 1) and floor.shelves[1] == Shelf(1, (2, 3))
    with pytest.raises(EditRefused) as refused:
        edits.move_object(floor, "robot", 1, (3, 3))
    assert str(refused.value) == "shelf 2 rests on (3,3): a robot carrying shelf 1 cannot go under it"
    do(floor, edits.move_object(floor, "shelf", 1, (4, 3)))  # dragging a carried shelf moves its robot
    assert floor.robots[1].at == (4, 3) and floor.shelves[1].at == (4, 3)
    with pytest.raises(EditRefused) as refused:
        edits.set_carries(floor, 1, 2)
    assert str(refused.value) == "shelf 2 does not stand on robot 1's node (4,3)"


def test_resize_removes_what_lies_beyond_and_adds_storage_nodes(floor):
    do(floor, edits.add_object(floor, "shelf", (4, 3)))
    do(floor, order_edits.set_stock(floor, 1, {1: 2}))
    before = copy.deepcopy(floor)
    edit = do(floor, edits.resize(floor, 3, 4))
    assert floor.size == (3, 4) and len(floor.nodes) == 12
    assert not floor.shelves and not floor.products
    assert sorted(cell for cell in floor.nodes.values() if cell[1] == 4) == [(1, 4), (2, 4), (3, 4)]
    edits.apply(floor, edit, undo=True)
    assert floor == before


def test_orders_and_stock(floor):
    do(floor, edits.add_object(floor, "shelf", (1, 1)))
    do(floor, edits.add_object(floor, "station", (4, 1)))
    do(floor, order_edits.set_stock(floor, 1, {3: 5}))
    do(floor, order_edits.add_order(floor, 3, 2, 1))
    do(floor, order_edits.set_order_line(floor, 1, 4, None))
    do(floor, order_edits.set_order_line(floor, 1, 5, 1, replaces=4))
    assert floor.orders == {1: Order(1, {3: 2, 5: 1}, 1)}
    with pytest.raises(EditRefused) as refused:
        order_edits.set_order_line(floor, 1, 3, 1, replaces=5)
    assert str(refused.value) == "order 1 already has a line for product 3"
    with pytest.raises(EditRefused) as refused:
        order_edits.set_stock(floor, 1, {3: 0})
    assert str(refused.value) == "product 3: a shelf holds at least 1 unit (or no quantity)"
    do(floor, order_edits.remove_order_line(floor, 1, 5))
    do(floor, order_edits.set_order_station(floor, 1, None))
    assert floor.orders == {1: Order(1, {3: 2}, None)}
    assert facts(floor)[-2:] == ["init(object(product,3),value(on,(1,5))).",
                                 "init(object(order,1),value(line,(3,2)))."]


def test_every_edit_undone_gives_back_the_example_instance():
    instance = read_instance(SMALL_A)
    original = format_instance(instance)
    done = [do(instance, make(instance)) for make in (
        lambda i: edits.add_object(i, "robot", (11, 6)),
        lambda i: edits.remove_object(i, "shelf", 3),
        lambda i: edits.move_object(i, "robot", 1, (1, 5)),
        lambda i: edits.set_floor(i, (5, 5), "missing"),
        lambda i: edits.resize(i, 8, 7),
        lambda i: order_edits.remove_order(i, 2),
    )]
    assert format_instance(instance) != original
    for edit in reversed(done):
        edits.apply(instance, edit, undo=True)
    assert format_instance(instance) == original


def test_saved_text_reads_back_as_the_same_instance(floor):
    do(floor, edits.set_floor(floor, (2, 1), "highway"))
    do(floor, edits.add_object(floor, "shelf", (1, 2)))
    do(floor, order_edits.set_stock(floor, 1, {1: None}))
    do(floor, order_edits.add_order(floor, 1, None, None))
    assert read_instance(Source("saved.lp", format_instance(floor))) == floor


def test_template_keeps_the_layout_only(floor):
    do(floor, edits.add_object(floor, "shelf", (1, 2)))
    do(floor, order_edits.set_stock(floor, 1, {1: 2}))
    do(floor, order_edits.add_order(floor, 1, 1, None))
    template = edits.template_of(floor)
    assert template.shelves == floor.shelves and not template.products and not template.orders
