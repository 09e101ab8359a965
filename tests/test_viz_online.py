"""The viewer on an online run (issue 43, item 4): orders appear at their release in the Orders
panel, the Online panel gives the figures after the step shown (from a run record too), and a
live run is followed through the plan file it rewrites (``asprilo online --live``).

The scenario is the corridor of test_online_run.py with order 2 released at step 4; its plan
delivers order 1 at step 3 and order 2 at step 5 (derived there by hand)."""

from __future__ import annotations

import json
import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pytest  # noqa: E402
from helpers.viewer import shown_window  # noqa: E402
from test_online_run import CORRIDOR  # noqa: E402

from asprilo.cli import main  # noqa: E402
from asprilo.errors import InputError  # noqa: E402
from asprilo.online.record import read_record  # noqa: E402
from asprilo.reader import read_instance, read_plan  # noqa: E402
from asprilo.sources import Source  # noqa: E402
from asprilo.visualizer.panels.online_figures import OnlineFigures  # noqa: E402
from asprilo.visualizer.panels.orders import TO_COME, OrdersModel  # noqa: E402
from asprilo.visualizer.panels.tables import TablePanel  # noqa: E402
from asprilo.visualizer.state.track import Track  # noqa: E402

pytestmark = pytest.mark.gui

SCENARIO = CORRIDOR + "init(object(order,2),value(release,4)).\n"
PLAN = ("occurs(object(robot,1),action(move,(-1,0)),1). occurs(object(robot,1),action(move,(-1,0)),2).\n"
        "occurs(object(robot,1),action(deliver,(1,1,1)),3). occurs(object(robot,1),action(deliver,(2,1,2)),5).\n")
#: a run record as asprilo online writes it: planner calls after steps 0 and 4, one waiting step (5)
RECORD = {"version": 1, "steps": 5, "calls": [{"step": 0, "seconds": 0.5, "found": True},
                                              {"step": 4, "seconds": 1.5, "found": True}], "waiting": [5]}


@pytest.fixture
def track():
    return Track(read_instance(Source("scenario.lp", SCENARIO)), read_plan(Source("plan.lp", PLAN)))


def test_an_order_not_yet_released_says_when_it_comes(qapp, track):
    panel = TablePanel(OrdersModel())
    panel.set_track(track)
    panel.show_step(3)  # columns: order, station, product, requested, delivered, open, status
    assert panel.texts() == [["1 ✓", "PS1", "1", "1", "1", "0", "done"],
                             ["2", "PS1", "1", "2", "0", "2", "released at 4"]]
    assert panel.model.background(panel.model.rows[1]) == TO_COME
    panel.show_step(4)  # known after step 4
    assert panel.texts()[1] == ["2", "PS1", "1", "2", "0", "2", "open"]


def test_the_online_panel_gives_the_figures_after_the_step_shown(qapp, track):
    figures = OnlineFigures()
    figures.set_record(RECORD)
    figures.set_track(track)
    figures.show_step(3)
    # after step 3: order 1 done (latency 3 - 0); order 2 not known; one call (after step 0);
    # the ceiling: order 1's line at step 3 at the earliest (2 moves, the delivery): 1 line in 3 steps
    assert figures.text().split("<br>") == [
        "2 orders released over steps 0–4: 1 known after step 3",
        "done by step 3: 1 of 1 line released, 1 unit; 33.3 lines per 100 steps (ceiling 33.3)",
        "latency of 1 order done: mean 3.0, p95 3, max 3 steps",
        "planner: 1 call by step 3, 0.50 s on average, 0.50 s at most; 0 waiting steps"]
    figures.show_step(5)  # order 2 done at 5, released at 4: latency 1; both calls, the waiting step 5
    assert figures.text().split("<br>") == [
        "2 orders released over steps 0–4: 2 known after step 5",
        "done by step 5: 2 of 2 lines released, 3 units; 40.0 lines per 100 steps (ceiling 40.0)",
        "latency of 2 orders done: mean 2.0, p95 3, max 3 steps",
        "planner: 2 calls by step 5, 1.00 s on average, 1.50 s at most; 1 waiting step"]


def test_the_window_has_the_online_panel_and_the_command_line_its_record(qtbot, tmp_path_factory, tmp_path):
    scenario, plan, record = tmp_path / "scenario.lp", tmp_path / "plan.lp", tmp_path / "run.json"
    scenario.write_text(SCENARIO)
    plan.write_text(PLAN)
    record.write_text(json.dumps(RECORD))
    window = shown_window(qtbot, tmp_path_factory)
    window.panels.online.set_record(read_record(str(record)))
    window.open_files([str(scenario), str(plan)])
    window.go_to(5)
    assert window.panels.online.text().split("<br>")[1].startswith("done by step 5: 2 of 2 lines released")
    assert window.panels.docks["online"].windowTitle() == "Online"


@pytest.mark.parametrize(("text", "words"), [
    ("[1, 2]", 'not a run record of asprilo online (no "version": 1)'),
    ('{"version": 1, "calls": [{"step": "x"}], "waiting": []}',
     'a run record needs "calls" ({step, seconds, found} each) and "waiting" (steps)'),
    ("[" * 100_000, "not a run record of asprilo online (RecursionError: maximum recursion depth exceeded"),
])
def test_a_bad_run_record_is_refused_in_words(tmp_path, text, words):
    path = tmp_path / "run.json"
    path.write_text(text)
    with pytest.raises(InputError) as refused:
        read_record(str(path))
    assert refused.value.message.startswith(f"{path}: {words}")


def test_a_live_run_rewrites_its_plan_file_as_it_goes(tmp_path, capsys):
    """--live: the scenario written first, the plan every 5 steps and at the end; the run of
    test_online_run's first test takes 5 steps, so the plan file is written at step 5 and at the end."""
    scenario, plan, written = tmp_path / "scenario.lp", tmp_path / "plan.lp", tmp_path / "written.lp"
    scenario.write_text(SCENARIO)
    assert main(["online", str(scenario), "--planner", "asp", "--budget", "60", "-o", str(plan), "--live",
                 "--scenario", str(written)]) == 0
    capsys.readouterr()
    assert main(["check", str(written), str(plan)]) == 0
    assert main(["online", str(scenario), "--live"]) == 2
    assert capsys.readouterr().err == "error: --live writes the plan as the run goes: give it a file with -o PLAN\n"
