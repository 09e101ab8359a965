"""Generate, Solve and Check from the window (offscreen): background jobs, results loaded,
cancel, a window that keeps working meanwhile."""

from __future__ import annotations

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import re  # noqa: E402
import threading  # noqa: E402
from itertools import pairwise  # noqa: E402

import pytest  # noqa: E402
from helpers import CORRIDOR, SMALL_A, WRONG_OUTCOME  # noqa: E402
from helpers.online import TINY, tiny  # noqa: E402
from helpers.viewer import shown_window  # noqa: E402
from PyQt5 import sip  # noqa: E402
from PyQt5.QtCore import QSettings, QTimer  # noqa: E402
from PyQt5.QtWidgets import QMessageBox  # noqa: E402

from asprilo import generator  # noqa: E402
from asprilo.bounds import makespan_bound  # noqa: E402
from asprilo.checker import check  # noqa: E402
from asprilo.domain import Domain  # noqa: E402
from asprilo.generator import populate  # noqa: E402
from asprilo.model import PickingStation  # noqa: E402
from asprilo.reader import read_instance  # noqa: E402
from asprilo.visualizer.jobs.job import wait_for_jobs  # noqa: E402
from asprilo.visualizer.state import edits  # noqa: E402
from asprilo.visualizer.window import MainWindow  # noqa: E402
from asprilo.writer import format_instance  # noqa: E402

pytestmark = pytest.mark.gui
WAIT_MS = 60_000  # no job may take longer here


@pytest.fixture
def window(qtbot, tmp_path_factory, monkeypatch):
    window = shown_window(qtbot, tmp_path_factory)
    monkeypatch.setattr(QMessageBox, "question", lambda *args: QMessageBox.Discard)
    yield window
    window.jobs.cancel()
    qtbot.waitUntil(lambda: window.jobs.job is None, timeout=WAIT_MS)


def finish(qtbot, window) -> None:
    qtbot.waitUntil(lambda: window.jobs.job is None, timeout=WAIT_MS)


def test_generate_fills_the_layout_as_one_undoable_edit(window, qtbot):
    window.editor.new_instance(6, 4)
    window.editor.add("station", (1, 1))
    template = edits.grid(6, 4)
    template.stations[1] = PickingStation(1, (1, 1))
    counts = {"robots": 2, "shelves": 4, "stations": 1, "products": 3, "units": 12, "orders": 2}
    assert window.jobs.generate(counts, seed=3) is not None
    assert not window.editor.palette.isEnabled() and not window.jobs.commands["solve"].isEnabled()
    assert not window.editor.commands["undo"].isEnabled()  # the generator works on this instance
    finish(qtbot, window)
    instance = window.editor.document.instance
    expected = populate(template, seed=3, **counts).instance
    assert format_instance(instance) == format_instance(expected)
    assert instance.stations == {1: PickingStation(1, (1, 1))}  # the layout's own objects stay
    assert len(window.stage.scene.robots) == 2 and len(window.stage.scene.shelves) == 4
    assert window.editor.document.history.undo_text == "generate (seed 3)"
    window.editor.commands["undo"].trigger()
    assert not window.stage.scene.robots and window.editor.document.instance == template
    assert window.editor.palette.isEnabled() and window.editor.commands["redo"].isEnabled()


def test_a_window_closed_after_cancelling_a_generation_leaves_it_to_run_out(qtbot, tmp_path_factory,
                                                                          monkeypatch):
    # the generator cannot be interrupted: here it runs until the test releases it
    release = threading.Event()
    monkeypatch.setattr(generator, "populate", lambda *args, **options: release.wait(WAIT_MS / 1000))
    monkeypatch.setattr(QMessageBox, "question", lambda *args: QMessageBox.Discard)
    window = MainWindow(QSettings(str(tmp_path_factory.mktemp("settings") / "viz.ini"), QSettings.IniFormat))
    window.editor.new_instance(6, 4)
    job = window.jobs.generate({"robots": 1}, seed=1)
    window.jobs.cancel()
    assert window.statusBar().currentMessage() == "Generate cancelled" and window.jobs.job is None
    window.close()
    sip.delete(window)  # with the window its thread went too: Qt aborted the process
    assert job.isRunning()
    threading.Timer(0.2, release.set).start()
    wait_for_jobs()  # what the application does last
    assert job.isFinished()


def test_solve_loads_and_plays_a_plan_of_minimal_makespan(window, qtbot, write):
    window.open_files([str(write("tiny.lp", TINY))])
    window.jobs.solve()
    finish(qtbot, window)
    outcome = window.jobs.last_outcome
    assert outcome.found and outcome.minimal and outcome.horizon == 6
    assert window.scenario.plan == outcome.plan and window.track.horizon == 6
    assert not window.track.violations
    assert window.player.playing
    assert "minimal makespan 6" in window.statusBar().currentMessage()


def test_a_solve_out_of_time_points_to_the_default_method(window, qtbot, write):
    window.open_files([str(write("corridor.lp", CORRIDOR))])
    window.settings.setValue("tools/method", "asp")  # the exact search alone, chosen in the Run menu
    assert window.jobs.solve(time_limit=1.0) is not None, window.state.last_error
    finish(qtbot, window)
    assert window.state.last_error == ("No plan: limit. For a plan fast (not proven minimal), "
                                       "choose Run > Solve method > Best plan fast.")


def test_solving_keeps_the_window_alive_and_can_be_cancelled(window, qtbot):
    window.open_files([str(SMALL_A)])  # its minimal makespan takes minutes to prove
    ticks = []  # the progress line at each tick of a timer of the window
    timer = QTimer(window)
    timer.timeout.connect(lambda: ticks.append(window.jobs.bar.label.text()))
    timer.start(50)
    window.jobs.solve(method="asp")  # the exact search alone (the default answers with a plan: test_solve_auto)
    assert window.jobs.bar.isVisible() and window.jobs.bar.label.text() == "Solve…"
    # A on the small example: the search starts at the lower bound, and no horizon from there
    # on is settled within minutes; the progress line says what it works on meanwhile
    first = f"Solve: horizon {int(makespan_bound(read_instance(SMALL_A), Domain.A))}: solving…"
    # the window's own events go on while clingo searches in the job's thread: its timer ticks
    # again and again after the progress line said so
    qtbot.waitUntil(lambda: ticks.count(first) >= 10, timeout=WAIT_MS)
    assert window.jobs.job is not None and window.jobs.job.isRunning()  # still searching
    window.jobs.cancel()
    finish(qtbot, window)  # within WAIT_MS, below the solve's own limit: the cancel stopped it
    assert window.statusBar().currentMessage() == "Solve cancelled"
    assert len(window.scenario.plan) == 0 and not window.jobs.bar.isVisible()
    assert window.editor.palette.isEnabled()
    timer.stop()


def watch_plans(window) -> list[tuple[bool, str, object]]:
    """Each plan shown from now on: whether a job ran then, the progress line, the plan."""
    seen = []
    window.editor.document.changed.connect(lambda change: change.plan and seen.append(
        (window.jobs.job is not None, window.jobs.bar.label.text(), window.scenario.plan)))
    return seen


def test_anytime_solve_shows_each_better_plan_then_plays_the_best(window, qtbot, write):
    window.open_files([str(write("tiny.lp", TINY))])
    anytime = next(a for a in window.jobs.methods.actions() if a.data() == "anytime")
    anytime.trigger()
    assert window.settings.value("tools/method") == "anytime"
    window.jobs._show_method()  # what the menu shows when it opens
    assert [a.isChecked() for a in window.jobs.methods.actions()] == [False, False, True]
    seen = watch_plans(window)
    window.jobs.solve()
    finish(qtbot, window)
    outcome = window.jobs.last_outcome
    # the tiny world: robot 1 carries shelf 1 three cells to the station and delivers (4 steps);
    # robot 2 moves onto shelf 2, picks it up, carries it 3 cells to the station, delivers: 6 steps
    assert outcome.method == "anytime" and outcome.found and outcome.minimal and outcome.horizon == 6
    assert check(tiny(), window.scenario.plan).valid and window.scenario.plan == outcome.plan
    drafts = [(label, plan) for running, label, plan in seen if running]
    makespans = [entry["makespan"] for entry in outcome.history]
    assert [plan.horizon for _label, plan in drafts] == makespans and makespans[-1] == 6
    assert all(a > b for a, b in pairwise(makespans))
    assert [label for label, _plan in drafts] == [
        f"Solve: makespan {e['makespan']}, sum of costs {e['sum_of_costs']}, {100 * e['gap']:.1f}% above "
        f"the lower bound ({e['seconds']:.1f} s)" for e in outcome.history]
    plans = len(makespans)
    assert re.fullmatch(rf"plan found in \d+\.\d s: minimal makespan 6, {len(outcome.plan)} actions, "
                        rf"{plans} plans? reported \(A, anytime\)", window.statusBar().currentMessage())
    assert window.player.playing
    history = window.editor.document.history
    assert history.count == 1 and history.undo_text == "solve (anytime, makespan 6)"
    window.editor.commands["undo"].trigger()
    assert len(window.scenario.plan) == 0


def test_cancelling_an_anytime_solve_keeps_its_best_plan(window, qtbot):
    window.open_files([str(SMALL_A)])
    window.jobs.solve(method="anytime", time_limit=600)
    # no plan the anytime search finds meets the lower bound, so it searches on; the progress
    # line and the plan arrive as two events (the line first): wait for both
    qtbot.waitUntil(lambda: window.jobs.bar.label.text().startswith("Solve: makespan ")
                    and len(window.scenario.plan) > 0, timeout=WAIT_MS)
    assert window.editor.document.history.count == 0  # a draft
    window.jobs.cancel()
    finish(qtbot, window)  # within WAIT_MS, far below the 600 s limit: the cancel stopped it
    outcome = window.jobs.last_outcome
    assert outcome.found and window.scenario.plan == outcome.plan
    assert check(read_instance(SMALL_A), window.scenario.plan).valid
    makespan, bound = outcome.horizon, int(makespan_bound(read_instance(SMALL_A), Domain.A))
    gap = 100 * (makespan - bound) / bound
    assert re.fullmatch(rf"Solve stopped after \d+\.\d s, best plan: makespan {makespan}, {gap:.1f}% above the "
                        rf"lower bound {bound}, {len(outcome.plan)} actions, \d+ plans? reported \(A, anytime\)",
                        window.statusBar().currentMessage())
    assert window.editor.document.history.undo_text == f"solve (anytime, makespan {makespan})"
    window.editor.commands["undo"].trigger()
    assert len(window.scenario.plan) == 0


def test_a_plan_found_for_an_instance_no_longer_shown_is_dropped(window, qtbot, write):
    window.open_files([str(SMALL_A)])
    window.jobs.solve(method="anytime", time_limit=1.0)
    window.open_files([str(write("tiny.lp", TINY))])  # before any plan of the search can come
    finish(qtbot, window)
    assert len(window.scenario.plan) == 0 and window.editor.document.history.count == 0
    assert window.statusBar().currentMessage() == "Solve: another instance is open now; the plan found is dropped"


def test_check_shows_the_asp_checkers_diagnostics(window, qtbot):
    window.open_files([str(WRONG_OUTCOME)])
    replay = [row for row in window.panels["violations"].texts()]
    window.jobs.check()
    finish(qtbot, window)
    report = window.jobs.last_outcome
    assert not report.valid
    assert window.docks["violations"].windowTitle() == f"Violations — ASP checker ({len(report.errors)})"
    assert sorted(window.panels["violations"].texts()) == sorted(replay)
    assert window.statusBar().currentMessage().endswith("it agrees with the viewer's replay")


def test_check_without_a_plan_reports_the_open_orders(window, qtbot):
    window.open_files([str(SMALL_A)])
    assert window.panels["violations"].texts() == []  # no plan: the goal is no problem yet
    window.jobs.check()
    finish(qtbot, window)
    rows = window.panels["violations"].texts()
    assert rows and {row[1] for row in rows} == {"goal/unfilledOrder"}
    assert window.statusBar().currentMessage().endswith("it agrees with the viewer's replay")
