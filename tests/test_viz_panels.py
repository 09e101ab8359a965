"""The viewer's side panels: exact numbers for the example plans at several steps."""

from __future__ import annotations

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pytest  # noqa: E402
from helpers import OUTCOME, WRONG_OUTCOME  # noqa: E402

from asprilo.reader import read_instance, read_plan  # noqa: E402
from asprilo.visualizer.panels.inventory import InventoryModel  # noqa: E402
from asprilo.visualizer.panels.orders import OrdersModel  # noqa: E402
from asprilo.visualizer.panels.plan_list import PlanModel  # noqa: E402
from asprilo.visualizer.panels.robot_list import RobotsModel  # noqa: E402
from asprilo.visualizer.panels.tables import CURRENT, DONE, TablePanel  # noqa: E402
from asprilo.visualizer.panels.violation_list import ViolationsModel, sentence  # noqa: E402
from asprilo.visualizer.state.describe import action_text, actions_text, tooltip  # noqa: E402
from asprilo.visualizer.state.track import Track  # noqa: E402

pytestmark = pytest.mark.gui


@pytest.fixture(scope="module")
def outcome():
    return Track(read_instance(OUTCOME), read_plan(OUTCOME))


def panel(model, track, step, qtbot=None):
    widget = TablePanel(model)
    widget.set_track(track)
    widget.show_step(step)
    return widget


# Orders of outcome.txt; deliveries: step 8 (1,4,1), 12 (1,2,7), 13 (3,3,1), 14 (2,5,10),
# 18 (2,5,1), 19 (2,5,4), 22 (2,4,1), 23 (2,5,5), 24 (1,4,1), 25 (3,1,2), 26 (1,2,4).
# Columns: order, station, product, requested, delivered, open, status.
ORDERS = {
    0: [["1", "PS1", "2", "11", "0", "11", "open"], ["1", "PS1", "4", "2", "0", "2", "open"],
        ["2", "PS2", "4", "1", "0", "1", "open"], ["2", "PS2", "5", "20", "0", "20", "open"],
        ["3", "PS2", "1", "2", "0", "2", "open"], ["3", "PS2", "3", "1", "0", "1", "open"]],
    14: [["1", "PS1", "2", "11", "7", "4", "open"], ["1", "PS1", "4", "2", "1", "1", "open"],
         ["2", "PS2", "4", "1", "0", "1", "open"], ["2", "PS2", "5", "20", "10", "10", "open"],
         ["3", "PS2", "1", "2", "0", "2", "open"], ["3", "PS2", "3", "1", "1", "0", "done"]],
    23: [["1", "PS1", "2", "11", "7", "4", "open"], ["1", "PS1", "4", "2", "1", "1", "open"],
         ["2 ✓", "PS2", "4", "1", "1", "0", "done"], ["2 ✓", "PS2", "5", "20", "20", "0", "done"],
         ["3", "PS2", "1", "2", "0", "2", "open"], ["3", "PS2", "3", "1", "1", "0", "done"]],
    29: [["1 ✓", "PS1", "2", "11", "11", "0", "done"], ["1 ✓", "PS1", "4", "2", "2", "0", "done"],
         ["2 ✓", "PS2", "4", "1", "1", "0", "done"], ["2 ✓", "PS2", "5", "20", "20", "0", "done"],
         ["3 ✓", "PS2", "1", "2", "2", "0", "done"], ["3 ✓", "PS2", "3", "1", "1", "0", "done"]],
}


@pytest.mark.parametrize("step", sorted(ORDERS))
def test_orders_panel(qapp, outcome, step):
    widget = panel(OrdersModel(), outcome, step)
    assert widget.texts() == ORDERS[step]


def test_finished_orders_are_marked(qapp, outcome):
    model = OrdersModel()
    model.set_track(outcome)
    model.show_step(23)
    backgrounds = [model.data(model.index(row, 0), 8) for row in range(len(model.rows))]  # BackgroundRole
    assert [colour == DONE for colour in backgrounds] == [False, False, True, True, False, False]
    assert [model.bold(row) for row in model.rows] == [False, False, True, True, False, False]


# Inventory of outcome.txt: shelf, product, now, initially.  Robot 3 carries shelf 1 (steps 4-17)
# and shelf 9 (from 20), robot 1 shelf 2 (from 8), robot 2 shelf 4 (12-14) and shelf 3 (from 18).
INVENTORY = {
    0: [["1", "3", "8", "8"], ["1", "4", "1", "1"], ["1", "5", "10", "10"], ["2", "2", "7", "7"],
        ["2", "4", "1", "1"], ["2", "5", "10", "10"], ["3", "2", "4", "4"], ["3", "4", "1", "1"],
        ["9", "1", "4", "4"], ["12", "1", "4", "4"]],
    14: [["1", "3", "7", "8"], ["1", "4", "0", "1"], ["1", "5", "0", "10"], ["2", "2", "0", "7"],
         ["2", "4", "1", "1"], ["2", "5", "10", "10"], ["3", "2", "4", "4"], ["3", "4", "1", "1"],
         ["9", "1", "4", "4"], ["12", "1", "4", "4"]],
    29: [["1", "3", "7", "8"], ["1", "4", "0", "1"], ["1", "5", "0", "10"], ["2", "2", "0", "7"],
         ["2", "4", "0", "1"], ["2", "5", "0", "10"], ["3", "2", "0", "4"], ["3", "4", "0", "1"],
         ["9", "1", "2", "4"], ["12", "1", "4", "4"]],
}


@pytest.mark.parametrize("step", sorted(INVENTORY))
def test_inventory_panel(qapp, outcome, step):
    assert panel(InventoryModel(), outcome, step).texts() == INVENTORY[step]


def test_inventory_filter_and_numeric_sort(qapp, outcome):
    widget = panel(InventoryModel(), outcome, 29)
    widget.filter.setText("12")
    assert widget.texts() == [["12", "1", "4", "4"]]
    widget.filter.setText("")
    widget.table.sortByColumn(2, 1)  # "Now", descending: numbers, not strings
    assert [row[2] for row in widget.texts()][:3] == ["7", "4", "2"]


def test_plan_panel_highlights_the_step_shown(qapp, outcome):
    model = PlanModel()
    model.set_track(outcome)
    model.show_step(8)
    assert len(model.rows) == 79
    first = model.first_row(8)
    assert [(a.step, a.robot, a.name) for a in model.rows[first:first + 3]] == [
        (8, 1, "pickup"), (8, 2, "move"), (8, 3, "deliver")]
    assert model.data(model.index(first, 0), 8) == CURRENT
    assert model.data(model.index(first + 3, 0), 8) is None
    assert model.data(model.index(first, 2)) == "pick up"
    assert model.data(model.index(first + 2, 2), 3) == "occurs(object(robot,3),action(deliver,(1,4,1)),8)."


def test_robots_panel(qapp, outcome):
    assert panel(RobotsModel(), outcome, 0).texts() == [
        ["1", "(1,6)", "", "", "move right", "0"],
        ["2", "(2,6)", "", "", "move up", "0"],
        ["3", "(3,6)", "", "", "move up", "0"]]
    assert panel(RobotsModel(), outcome, 8).texts() == [
        ["1", "(5,3)", "2", "pick up", "move up", "0"],
        ["2", "(6,4)", "", "move right", "move right", "2"],   # waited at steps 3 and 5
        ["3", "(4,1)", "1", "deliver 1 × product 4 to order 1", "move right", "0"]]


def test_violations_panel_lists_every_broken_rule(qapp):
    track = Track(read_instance(WRONG_OUTCOME), read_plan(WRONG_OUTCOME))
    widget = panel(ViolationsModel(), track, 0)
    rows = widget.texts()
    assert [row[:2] for row in rows] == [["23", "deliver/orderAmount"], ["23", "deliver/shelfAmount"],
                                         ["29", "goal/unfilledOrder"]]
    assert [v.atom for v in track.violations] == [
        "err(deliver,orderAmount,(1,23))", "err(deliver,shelfAmount,(1,23))",
        "err(goal,unfilledOrder,(1,2,1,29))"]
    # the sentence without the step its column shows
    assert [row[2] for row in rows] == [sentence(v) for v in track.violations]
    assert [v.message.removeprefix(f"step {v.step}: ") for v in track.violations[:2]] == [r[2] for r in rows[:2]]
    assert rows[2][2].startswith("at the horizon: order 1 still lacks 1 unit of product 2")


def test_valid_plan_has_no_violations(qapp, outcome):
    assert panel(ViolationsModel(), outcome, 0).texts() == []


def test_tooltips_describe_objects_and_cell(qapp, outcome):
    text = tooltip(outcome, 8, (5, 3), [("robot", 1), ("shelf", 2)])
    assert "<b>Robot 1</b><br>at (5,3)<br>carries shelf 2<br>step 8: pick up<br>next (step 9): move up" in text
    assert "<b>Shelf 2</b><br>at (5,3), carried by robot 1<br>stock now / initially:" in text
    assert "product 2: 7 / 7" in text
    assert text.endswith("<b>Cell (5,3): storage node</b><br>holds robot 1, shelf 2")
    station = tooltip(outcome, 14, (8, 1), [("station", 2)])
    assert ("order 2: product 4 1 of 1 open, product 5 10 of 20 open<br>"
            "order 3: product 1 2 of 2 open, product 3 done") in station
    assert tooltip(outcome, 0, (6, 1), []) == "<b>Cell (6,1): highway</b><br>empty"


def test_tooltips_name_labelled_goals(qapp, write):
    from asprilo.model import Plan
    path = write("labelled.lp", "init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))). "
                                "init(object(robot,1),value(at,(1,1))). init(object(destination,4),value(at,(2,1))). "
                                "assign(robot(1),destination(4)).")
    track = Track(read_instance(path), Plan([]))
    assert "<br>assigned goal: destination 4 at (2,1)" in tooltip(track, 0, (1, 1), [("robot", 1)])
    assert tooltip(track, 0, (2, 1), [("destination", 4)]).startswith(
        "<b>Destination 4</b><br>assigned to robot 1<hr>")


def test_action_texts():
    from asprilo.model import Action
    assert action_text(None) == "wait"
    assert action_text(Action(1, 1, "move", (0, -1))) == "move up"
    assert action_text(Action(1, 1, "deliver", (2, 5))) == "deliver product 5 to order 2"
    assert action_text(Action(1, 1, "jump", (1, 2))) == "jump(1,2)"
    assert actions_text([]) == "wait"
    assert actions_text([Action(1, 1, "move", (1, 0)), Action(1, 1, "pickup")]) == "move right + pick up"
