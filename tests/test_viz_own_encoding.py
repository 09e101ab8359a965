"""Run > Solve with encoding file… (offscreen): a user's own encoding chosen in the file dialog,
its style said while it runs, its plan checked and shown (a wrong one with the checker's
violations), bad files in the error dialog, cancel, and the recent encodings in the settings."""

from __future__ import annotations

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import re  # noqa: E402
import shutil  # noqa: E402
from pathlib import Path  # noqa: E402

import pytest  # noqa: E402
from helpers.viewer import shown_window  # noqa: E402
from PyQt5.QtWidgets import QFileDialog, QMessageBox  # noqa: E402

from asprilo.checker import check  # noqa: E402
from asprilo.reader import read_instance  # noqa: E402
from asprilo.visualizer.panels.commands import shortcut_rows  # noqa: E402
from asprilo.visualizer.panels.violation_list import sentence  # noqa: E402

pytestmark = pytest.mark.gui
WAIT_MS = 60_000  # a hang guard: no job may take longer here
ENCODINGS = Path(__file__).parent / "encodings"
M_TINY = ENCODINGS / "m-tiny.lp"
SINGLE = "single-shot with a horizon constant"


@pytest.fixture
def window(qtbot, tmp_path_factory, monkeypatch):
    window = shown_window(qtbot, tmp_path_factory)
    monkeypatch.setattr(QMessageBox, "question", lambda *args: QMessageBox.Discard)
    window.open_files([str(M_TINY)])
    yield window
    window.jobs.cancel()
    qtbot.waitUntil(lambda: window.jobs.job is None, timeout=WAIT_MS)


@pytest.fixture
def choose(monkeypatch):
    """Let the file dialog answer ``files`` (set ``choose.files``); ``choose.calls`` counts it."""

    class Dialog:
        files: list[str] = []
        calls: list[tuple] = []

    def answer(*args):
        Dialog.calls.append(args)
        return [str(file) for file in Dialog.files], "ASP programs (*.lp *.ilp *.clp *.dlp *.asp)"

    monkeypatch.setattr(QFileDialog, "getOpenFileNames", answer)
    return Dialog


def finish(qtbot, window) -> None:
    qtbot.waitUntil(lambda: window.jobs.job is None, timeout=WAIT_MS)


def recent_entries(window) -> list[tuple[str, bool, str]]:
    """Run > Recent encoding files as the menu shows it: text, enabled, tooltip."""
    window.jobs.fill_recent_encodings()  # what the menu does when it opens
    return [(a.text(), a.isEnabled(), a.toolTip()) for a in window.jobs.recent_menu.actions()]


def error_dialogs(window) -> list[str]:
    return [box.text() for box in window.findChildren(QMessageBox) if box.isVisible()]


def test_the_command_is_in_the_run_menu_with_its_shortcut(window):
    run = window.menus["run"]
    texts = [action.text() for action in run.actions()]
    solve = texts.index("&Solve")
    assert texts[solve:solve + 5] == ["&Solve", "Solve &method", "Solve &with encoding", "Solve with encoding &file…",
                                      "&Recent encoding files"]
    assert ("Solve with encoding file", "Shift+F9") in shortcut_rows(window)  # the F1 list
    assert recent_entries(window) == [("(none yet)", False, "(none yet)")]


def test_a_file_chosen_in_the_dialog_solves_and_the_recent_menu_runs_it_again(window, qtbot, choose):
    choose.files = [ENCODINGS / "m-single.lp"]
    window.jobs.commands["solve_file"].trigger()
    assert window.jobs.job is not None and window.jobs.bar.isVisible()
    assert not window.jobs.commands["solve_file"].isEnabled() and not window.editor.palette.isEnabled()
    finish(qtbot, window)
    assert len(choose.calls) == 1
    outcome = window.jobs.last_outcome
    assert outcome.found and outcome.minimal and outcome.horizon == 4
    # the plan shown is the job's, makespan 4, valid (by the viewer's replay and by the checker)
    assert window.scenario.plan == outcome.plan and window.track.horizon == 4
    assert not window.track.violations and check(read_instance(M_TINY), window.scenario.plan).valid
    assert "valid plan" in window.status_line.verdict.text()
    assert window.player.playing
    # the progress line said the style, then the horizons as for the reference encodings
    assert re.fullmatch(rf"Solve: m-single.lp, {SINGLE} — horizon 4: sat \(\d+\.\d s\)", window.jobs.bar.label.text())
    assert re.fullmatch(rf"plan found in \d+\.\d s: minimal makespan 4, 4 actions \(M, m-single: {SINGLE}\)",
                        window.statusBar().currentMessage())
    history = window.editor.document.history
    assert history.count == 1 and history.undo_text == "solve (m-single, makespan 4)"

    assert recent_entries(window) == [("m-single.lp", True, str((ENCODINGS / "m-single.lp").resolve()))]
    window.editor.commands["undo"].trigger()
    assert len(window.scenario.plan) == 0
    window.jobs.recent_menu.actions()[0].trigger()  # again, without the dialog
    assert window.jobs.job is not None
    finish(qtbot, window)
    assert len(choose.calls) == 1
    assert window.jobs.last_outcome.found and window.scenario.plan == window.jobs.last_outcome.plan
    assert window.track.horizon == 4 and not window.track.violations


def test_several_files_load_in_order_and_a_set_whose_file_is_gone_is_shown_disabled(window, qtbot, choose,
                                                                                     tmp_path):
    show = tmp_path / "show.lp"
    show.write_text("#const horizon = 1.\noccurs(object(robot,R),action(move,D),T) :- move(R,D,T).\n"
                    "#show occurs/3.\n")
    moves = Path(shutil.copy(ENCODINGS / "m-moves.lp", tmp_path / "moves.lp"))
    choose.files = [show, moves]
    window.jobs.ask_solve_file()
    finish(qtbot, window)
    outcome = window.jobs.last_outcome
    assert outcome.found and outcome.horizon == 4 and outcome.encoding == "show+moves"
    choose.files = [ENCODINGS / "m-single.lp"]
    window.jobs.ask_solve_file()
    finish(qtbot, window)
    assert [(text, enabled) for text, enabled, _tip in recent_entries(window)] == [
        ("m-single.lp", True), ("show.lp + moves.lp", True)]
    moves.unlink()
    entries = recent_entries(window)
    assert entries[1] == ("show.lp + moves.lp  (missing)", False,
                          f"{show.resolve()}\n{moves.resolve()}\nmissing: {moves.resolve()}")
    assert entries[0][1]  # the other set stays usable


def test_an_invalid_plan_opens_with_the_checkers_violations(window, qtbot, choose):
    choose.files = [ENCODINGS / "m-wrong.lp"]
    window.jobs.commands["solve_file"].trigger()
    finish(qtbot, window)
    outcome = window.jobs.last_outcome
    assert outcome.status.value == "invalid" and outcome.plan is not None
    assert window.scenario.plan == outcome.plan and window.track.horizon == 4  # the job's plan, shown
    expected = check(read_instance(M_TINY), window.scenario.plan).errors
    assert expected  # the sign error breaks the rules
    rows = window.panels["violations"].texts()
    assert len(rows) == len(expected)
    assert rows[0] == [str(expected[0].step), f"{expected[0].module}/{expected[0].check}", sentence(expected[0])]
    assert [row[2] for row in rows] == [sentence(error) for error in expected]
    assert window.docks["violations"].windowTitle() == f"Violations — ASP checker ({len(expected)})"
    assert any(row[1] == "move/offFloor" and "robot 1" in row[2] for row in rows)  # rule, step, robot
    message = window.statusBar().currentMessage()
    assert re.fullmatch(rf"the plan found in \d+\.\d s breaks {len(expected)} rules: makespan 4, 4 actions "
                        rf"\(M, m-wrong: {SINGLE}\); the checker's violations are in the Violations panel", message)
    assert f"{len(expected)} rule violations" in window.status_line.verdict.text()
    # the state of the first violation is shown, not played past
    assert not window.player.playing and window.player.step == min(error.step for error in expected)
    assert window.editor.document.history.undo_text == "solve (m-wrong, makespan 4, invalid)"
    assert not error_dialogs(window)


def test_a_model_without_occurs_says_what_the_interface_is(window, qtbot, choose):
    choose.files = [ENCODINGS / "m-none.lp"]
    window.jobs.commands["solve_file"].trigger()
    finish(qtbot, window)
    outcome = window.jobs.last_outcome
    assert outcome.status.value == "invalid" and outcome.plan is None
    assert window.state.last_error == f"m-none.lp: no plan: {outcome.message}"
    assert "occurs(object(robot,R),action(Name,Args),T)" in window.state.last_error
    assert error_dialogs(window) == [window.state.last_error]
    assert len(window.scenario.plan) == 0


def test_no_plan_within_the_time_limit_says_which_horizons_were_refuted(window, qtbot, tmp_path):
    never = tmp_path / "never.lp"  # no plan below horizon 1000: the search refutes one horizon after another
    never.write_text("#const horizon = 1.\n:- horizon < 1000.\n")
    assert window.jobs.solve_files([never], time_limit=2.0) is not None
    finish(qtbot, window)
    outcome = window.jobs.last_outcome
    assert outcome.status.value == "limit"
    refuted = outcome.refuted  # by the user's encoding: nothing is proven for the problem
    only = "(refuted for the encoding only, not for the problem)"
    words = "" if not refuted else (
        f" (your encoding has no plan at horizon {refuted[0]} {only})" if len(refuted) == 1 else
        f" (your encoding has no plan at horizons {refuted[0]}–{refuted[-1]} {only})")
    assert window.state.last_error == f"never.lp: no plan within the time limit{words}"
    assert error_dialogs(window) == [window.state.last_error] and len(window.scenario.plan) == 0


def test_a_weak_encoding_is_said_to_be_the_shortest_it_allows_not_minimal(qtbot, tmp_path_factory, monkeypatch):
    """m-one-mover.lp moves one robot at a time: on m-side-by-side.lp its shortest plan is 4
    steps where both robots move at once in 2 (by hand; max-flow proves it too)."""
    window = shown_window(qtbot, tmp_path_factory)
    monkeypatch.setattr(QMessageBox, "question", lambda *args: QMessageBox.Discard)
    window.open_files([str(ENCODINGS / "m-side-by-side.lp")])
    assert window.jobs.solve_files([ENCODINGS / "m-one-mover.lp"]) is not None
    finish(qtbot, window)
    outcome = window.jobs.last_outcome
    assert (outcome.found, outcome.horizon, outcome.minimal, outcome.encoding_minimal, outcome.minimum) == (
        True, 4, False, True, 2)
    assert re.fullmatch(rf"plan found in \d+\.\d s: makespan 4 \(the shortest plan this encoding allows \(4\); the "
                        rf"problem's minimum is 2, by max-flow\), 4 actions \(M, m-one-mover: {SINGLE}\)",
                        window.statusBar().currentMessage())


@pytest.mark.parametrize("name", ["encoding-check.ilp", "encoding-clingcon.iclp"])
def test_an_incremental_encoding_that_shows_its_plan_in_check_plays_every_step(window, qtbot, name):
    """The public collection's style (tests/encodings/m-parts): the moves shown from
    ``#program check(t)``; rung 3 of the M ladder, whose stored minimum is 5."""
    from asprilo.domain import Domain
    from asprilo.encodings.ladder import bundled_ladder

    rung = bundled_ladder(Domain.M).rungs[2]
    window.open_files([str(rung.file)])
    assert window.jobs.solve_files([ENCODINGS / "m-parts" / name]) is not None
    finish(qtbot, window)
    outcome = window.jobs.last_outcome
    assert (outcome.found, outcome.horizon, outcome.minimal) == (True, rung.minimum, True)
    assert window.scenario.plan == outcome.plan and check(read_instance(rung.file), window.scenario.plan).valid


def test_a_syntax_error_opens_the_error_dialog_located_and_the_warehouse_stays(window, qtbot, choose, tmp_path):
    choose.files = [ENCODINGS / "m-single.lp"]
    window.jobs.ask_solve_file()
    finish(qtbot, window)
    plan, history = window.scenario.plan, window.editor.document.history.count
    scenario = window.scenario
    bad = tmp_path / "bad.lp"
    bad.write_text("#const horizon = 1.\noccurs(object(robot,R),action(move,D),T) :- move(R,D,T\n")
    choose.files = [bad]
    window.jobs.ask_solve_file()
    finish(qtbot, window)
    dialogs = error_dialogs(window)
    assert len(dialogs) == 1 and re.match(rf"{re.escape(str(bad))}:\d+:", dialogs[0]), dialogs
    assert "syntax error" in dialogs[0]
    assert window.scenario is scenario and window.scenario.plan == plan
    assert window.editor.document.history.count == history
    assert recent_entries(window)[0][0] == "bad.lp"  # to run again once it is mended


def test_cancel_stops_an_encoding_that_grounds_for_ever_and_keeps_the_plan(window, qtbot, choose, tmp_path):
    choose.files = [ENCODINGS / "m-single.lp"]
    window.jobs.ask_solve_file()
    finish(qtbot, window)
    plan = window.scenario.plan
    assert len(plan) == 4
    forever = tmp_path / "forever.lp"
    forever.write_text("#const horizon=1. p(0). p(X+1) :- p(X).\n")
    choose.files = [forever]
    window.jobs.ask_solve_file()
    label = window.jobs.bar.label
    qtbot.waitUntil(lambda: label.text() == f"Solve: forever.lp, {SINGLE} — horizon 4: grounding…",
                    timeout=WAIT_MS)
    assert window.jobs.job is not None and window.jobs.job.isRunning()
    window.jobs.cancel()
    finish(qtbot, window)  # within WAIT_MS, far below the solve's own limit: the cancel stopped it
    assert window.statusBar().currentMessage() == "Solve cancelled"
    assert window.scenario.plan == plan and window.track.horizon == 4
    assert window.editor.document.history.count == 1 and not error_dialogs(window)
    assert window.editor.palette.isEnabled() and window.jobs.commands["solve_file"].isEnabled()
