"""The viewer under rule variants (``viz --variant``, docs/VARIANTS.md), offscreen: the
variant's moves animate, its verdict and violations are the checker's, its resource is shown
per robot and step, the export and the Run menu's jobs follow it.

The instances are tests/variants/*.lp (tests/test_variants.py's docstring says what they
hold); the plans and everything expected of them are derived by hand:

- corner.lp, two moves (1,1): robot 1 goes (1,1) -> (2,2) -> (3,3), under the shelf of order
  1 at step 2: valid under ``diagonal``; in M both moves are ill-formed (they do not take
  effect: the robot stays at (1,1)) and the order is not served.
- square.lp, robot 1 moves (1,1) and robot 2 (-1,1) at step 1: both diagonals of the square,
  ``err(diagonal,crossing,(1,2,1))``, the one violation.
- corridor.lp, robot 1 with energy 2 moves left, then right three times: its level is 2, 1,
  0, -1, -2 after steps 0..4; it falls below 0 at step 3 (``err(energy,exhausted,(1,-1,3))``).
- corridor.lp, right, right, left: the robot is under the shelf at (4,1) after step 2 only:
  served under ``visit-anytime`` (from step 2 on), not in M (at the horizon, step 3).
"""

from __future__ import annotations

import dataclasses
import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from pathlib import Path  # noqa: E402

import pytest  # noqa: E402
from helpers.viewer import shown_window  # noqa: E402
from PIL import Image  # noqa: E402
from PyQt5.QtCore import Qt  # noqa: E402
from PyQt5.QtWidgets import QApplication, QMessageBox  # noqa: E402

from asprilo.cli import main  # noqa: E402
from asprilo.domain import Domain, register, unregister  # noqa: E402
from asprilo.domain.variants import BUILTIN, load_variant  # noqa: E402
from asprilo.model import Action, Plan  # noqa: E402
from asprilo.reader import read_instance  # noqa: E402
from asprilo.visualizer.panels.tables import PROBLEM  # noqa: E402
from asprilo.visualizer.scene import style  # noqa: E402
from asprilo.visualizer.state.narrate import narrate  # noqa: E402
from asprilo.visualizer.state.rules import varied  # noqa: E402
from asprilo.visualizer.state.track import Track  # noqa: E402
from asprilo.visualizer.window import MainWindow  # noqa: E402

pytestmark = [pytest.mark.gui, pytest.mark.filterwarnings("ignore:.*attribute .energy. of robot")]
HERE = Path(__file__).parent / "variants"
CORNER, SQUARE, CORRIDOR = HERE / "corner.lp", HERE / "square.lp", HERE / "corridor.lp"
WAIT_MS = 60_000  # a hang guard for the jobs
DIAGONAL = ((1, (1, 1), 1), (1, (1, 1), 2))
CROSSING = ((1, (1, 1), 1), (2, (-1, 1), 1))
DETOUR = ((1, (-1, 0), 1), (1, (1, 0), 2), (1, (1, 0), 3), (1, (1, 0), 4))
VISIT = ((1, (1, 0), 1), (1, (1, 0), 2), (1, (-1, 0), 3))


@pytest.fixture
def window(qtbot, tmp_path_factory, monkeypatch):
    window = shown_window(qtbot, tmp_path_factory, (1366, 768))
    monkeypatch.setattr(QMessageBox, "question", lambda *args: QMessageBox.Discard)
    yield window
    window.jobs.cancel()
    qtbot.waitUntil(lambda: window.jobs.job is None, timeout=WAIT_MS)


def plan_file(tmp_path: Path, moves, name: str = "plan.lp") -> Path:
    path = tmp_path / name
    path.write_text("".join(f"occurs(object(robot,{robot}),action(move,({dx},{dy})),{step}).\n"
                            for robot, (dx, dy), step in moves))
    return path


def plan_of(moves) -> Plan:
    return Plan([Action(step, robot, "move", move) for robot, move, step in moves])


def show(window, instance: Path, plan: Path, *variants: str) -> None:
    window.state.document.follow_variants([load_variant(name) for name in variants])
    assert window.open_files([str(instance)], [str(plan)]), window.last_error


def robot_cell(window, robot: int) -> tuple[float, float]:
    item = window.stage.scene.robots[robot]
    return item.pos().x() / style.CELL + 0.5, item.pos().y() / style.CELL + 0.5


def panel_rows(window, name: str, step: int) -> list[list[str]]:
    window.go_to(step)
    return window.panels[name].texts()


# --- moves and verdicts ----------------------------------------------------------------------

def test_a_diagonal_plan_animates_to_its_cells_and_is_valid_under_the_variant(window, tmp_path):
    show(window, CORNER, plan_file(tmp_path, DIAGONAL), "diagonal")
    assert window.track.domain.label == "M+diagonal" and window.track.checked
    assert "domain M+diagonal" in window.status_line.summary.text()
    for step, cell in ((0, (1, 1)), (1, (2, 2)), (2, (3, 3))):
        window.go_to(step)
        assert robot_cell(window, 1) == cell
    window.stage.animator.show(1.5)  # half-way through step 2: on the diagonal
    assert robot_cell(window, 1) == (2.5, 2.5)
    assert "valid plan" in window.status_line.verdict.text()
    assert window.panels["violations"].texts() == []
    assert window.docks["violations"].windowTitle() == "Violations (0)"
    assert window.status_line.verdict.toolTip() == (
        "the ASP checker's verdict: domain M+diagonal has rules the viewer's simulator does not know")
    assert panel_rows(window, "orders", 2)[0][0] == "1 \u2713"
    assert panel_rows(window, "robots", 1)[0][:4] == ["1", "(2,2)", "", "move down-right"]
    assert narrate(window.track, 1) == "step 1: robot 1 moves down-right to (2,2)"


def test_without_a_variant_the_same_plan_is_refused_as_today(window, tmp_path):
    show(window, CORNER, plan_file(tmp_path, DIAGONAL))
    assert window.track.domain is Domain.M and not window.track.checked
    window.go_to(2)
    assert robot_cell(window, 1) == (1, 1)  # ill-formed moves take no effect
    rows = window.panels["violations"].texts()
    assert [row[1] for row in rows] == ["action/badArguments", "action/badArguments", "goal/unfilledOrder"]
    assert window.docks["violations"].windowTitle() == "Violations (3)"
    assert "3 rule violations" in window.status_line.verdict.text() and not window.status_line.verdict.toolTip()


def test_robots_crossing_diagonally_are_in_the_panel_in_the_variants_words_and_marked(window, tmp_path):
    show(window, SQUARE, plan_file(tmp_path, CROSSING), "diagonal")
    assert panel_rows(window, "violations", 1) == [
        ["1", "diagonal/crossing", "robots 1 and 2 cross each other's diagonal paths"]]
    assert window.docks["violations"].windowTitle() == "Violations (1)"
    assert "1 rule violation, 1 at step 1" in window.status_line.verdict.text()
    assert window.transport.slider.marks == [1]  # a red tick on the time slider
    scene = window.stage.scene
    assert scene.robots[1].flagged and scene.robots[2].flagged  # red rings at step 1
    window.go_to(0)
    assert not scene.robots[1].flagged
    violation = window.track.violations[0]
    assert (violation.atom, violation.robots) == ("err(diagonal,crossing,(1,2,1))", (1, 2))
    window.panels["violations"].row_activated.emit(violation)  # a click: the variant's rule below the list
    assert f"found by <b>{BUILTIN / 'diagonal.lp'}:12</b>" in window.rule_note.text()


def test_the_checkers_verdict_where_the_simulator_has_no_such_rule(window, tmp_path):
    """Robot 1 leaves its half at step 1: only the variant's checker module knows the rule."""
    show(window, CORRIDOR, plan_file(tmp_path, ((1, (1, 0), 1), (1, (1, 0), 2))), "sides")
    assert window.track.timeline.valid  # the simulator finds nothing
    assert panel_rows(window, "violations", 1) == [
        ["1", "sides/crossed", "robot 1 leaves the left half of the floor, where it started"]]
    assert "1 rule violation" in window.status_line.verdict.text()


# --- the goal of a variant ---------------------------------------------------------------------

def test_a_visit_before_the_horizon_serves_the_order_under_visit_anytime(window, tmp_path):
    show(window, CORRIDOR, plan_file(tmp_path, VISIT), "visit-anytime")
    assert window.track.goal_checked and "valid plan" in window.status_line.verdict.text()
    assert [panel_rows(window, "orders", step)[0][-1] for step in range(4)] == ["open", "open", "done", "done"]
    assert panel_rows(window, "orders", 3)[0][0] == "1 \u2713"
    goal = window.stage.animator.goals.goals[("shelf", 1)]
    assert goal.reached and goal.by is None  # served at step 2, though no robot stands there now


def test_the_same_visit_leaves_the_order_open_in_m(window, tmp_path):
    show(window, CORRIDOR, plan_file(tmp_path, VISIT))
    assert [panel_rows(window, "orders", step)[0][-1] for step in range(4)] == ["open", "open", "done", "open"]
    assert [row[1] for row in window.panels["violations"].texts()] == ["goal/unfilledOrder"]


def test_an_order_never_visited_is_open_and_named_in_the_variants_words(window, tmp_path):
    show(window, CORRIDOR, plan_file(tmp_path, ((1, (1, 0), 1),)), "visit-anytime")
    assert panel_rows(window, "violations", 1) == [
        ["1", "visit/neverVisited", "order 1 is not served: no robot stands under a shelf holding product 1 at "
                                    "any step"]]
    assert panel_rows(window, "orders", 1)[0][-1] == "open"


def test_without_a_plan_the_variants_goal_is_not_held_against_the_instance(window):
    window.state.document.follow_variants([load_variant("visit-anytime")])
    assert window.open_files([str(CORRIDOR)])
    assert window.track.violations == [] and window.track.checker_violations  # (the goal at horizon 0)
    assert window.status_line.verdict.text() == ""


# --- resources -------------------------------------------------------------------------------------

def test_energy_levels_per_step_and_the_step_it_runs_out(window, tmp_path):
    show(window, CORRIDOR, plan_file(tmp_path, DETOUR), "energy")
    panel = window.panels["robots"]
    assert panel.model.columns == ("Robot", "Position", "Carries", "Energy", "Action", "Next", "Idle")
    rows = [panel_rows(window, "robots", step)[0] for step in range(5)]
    assert [row[3] for row in rows] == ["2", "1", "0", "-1 \u26a0", "-2"]
    assert rows[1][4:] == ["move left", "move right", "0"]  # the columns after it as without a variant
    model, column = panel.model, 3
    for step, red in ((2, False), (3, True), (4, True)):
        window.go_to(step)
        assert (model.data(model.index(0, column), Qt.BackgroundRole) == PROBLEM) is red
    window.go_to(3)
    assert model.tooltip(1, column) == ("energy -1 after step 3 (2 at the start); below 0 since step 3: out of "
                                        "energy \u26a0")
    assert [row[1:] for row in window.panels["violations"].texts()] == [
        ["energy/exhausted", "robot 1 runs out of energy: its level would be -1"]]
    gauge = window.stage.scene.robots[1].gauge
    assert gauge is not None and gauge.shown == (-0.5, True)  # an empty red bar under the robot
    window.go_to(1)
    assert gauge.shown == (0.5, False)


def test_the_levels_follow_the_resources_costs_as_the_checker_counts_them(tmp_path):
    """A: robot 1 (energy 3) moves to the shelf (1), picks it up (1), carries it one cell
    (carrying move: 2): 3, 2, 1, -1; the checker reports step 3 with level -1 as well."""
    instance = tmp_path / "a.lp"
    instance.write_text("".join(f"init(object(node,{i}),value(at,({i},1))).\n" for i in (1, 2, 3)) + (
        "init(object(robot,1),value(at,(1,1))).\ninit(object(robot,1),value(energy,3)).\n"
        "init(object(shelf,1),value(at,(2,1))).\ninit(object(pickingStation,1),value(at,(3,1))).\n"
        "init(object(product,1),value(on,(1,2))).\ninit(object(order,1),value(pickingStation,1)).\n"
        "init(object(order,1),value(line,(1,1))).\n"))
    energy = load_variant("energy")
    plan = Plan([Action(1, 1, "move", (1, 0)), Action(2, 1, "pickup", ()), Action(3, 1, "move", (1, 0)),
                 Action(4, 1, "deliver", (1, 1, 1))])
    track = Track(read_instance(instance), plan, varied(Domain.A, [energy]))
    gauge, = track.gauges
    assert gauge.levels[:, 0].tolist() == [3, 2, 1, -1, -1] and gauge.drops == {1: [3]}
    assert [v.atom for v in track.violations] == ["err(energy,exhausted,(1,-1,3))"]


def test_a_robot_without_a_level_shows_none_and_the_checker_says_so(window):
    """No plan: the variant's own check of the instance (energy/missing) is shown all the same."""
    window.state.document.follow_variants([load_variant("energy")])
    assert window.open_files([str(SQUARE)])
    assert [row[3] for row in window.panels["robots"].texts()] == ["\u2013", "\u2013"]
    assert [row[1] for row in window.panels["violations"].texts()] == ["energy/missing", "energy/missing"]
    assert window.stage.scene.robots[1].gauge is None


# --- the viz command: export and window ----------------------------------------------------------

def viz(*args) -> int:
    return main(["viz", *map(str, args)])


def test_export_marks_a_plan_valid_or_invalid_as_the_checker_does(qapp, tmp_path, capsys):
    diagonal, out = plan_file(tmp_path, DIAGONAL), tmp_path / "end.png"
    assert viz(CORNER, diagonal, "--variant", "diagonal", "--export", out, "--step", 1, "--cell", 48) == 0
    assert capsys.readouterr().err == f"wrote {out}: 168x192\n"
    image = Image.open(out).convert("RGB")
    colour = style.robot_colour(0)  # robot 1 on (2,2) after step 1, a little left of the centre
    x, y = int((2 - 0.5 + 0.25) * 48) - 9, int((2 - 0.5 + 0.25) * 48)
    assert image.getpixel((x, y)) == pytest.approx((colour.red(), colour.green(), colour.blue()), abs=3)
    assert viz(CORNER, diagonal, "--export", out) == 1
    assert capsys.readouterr().err.splitlines()[-1] == (
        "invalid plan: 3 violations (domain M (detected), horizon 2); check INSTANCE PLAN lists them")
    assert viz(SQUARE, plan_file(tmp_path, CROSSING), "--variant", "diagonal", "--export", out) == 1
    assert capsys.readouterr().err.splitlines()[-1] == (
        "invalid plan: 1 violation (domain M+diagonal (detected), horizon 1); check INSTANCE PLAN lists them")
    visit = plan_file(tmp_path, VISIT, "visit.lp")
    assert viz(CORRIDOR, visit, "--variant", "visit-anytime", "--export", tmp_path / "visit.gif") == 0
    assert viz(CORRIDOR, visit, "--export", tmp_path / "visit.gif") == 1
    assert viz(CORRIDOR, plan_file(tmp_path, DETOUR), "--variant", "energy", "--export", out) == 1
    assert "invalid plan: 1 violation (domain M+energy (detected)" in capsys.readouterr().err


def test_an_animation_under_the_variant_moves_diagonally(qapp, tmp_path, capsys):
    out = tmp_path / "corner.gif"
    assert viz(CORNER, plan_file(tmp_path, DIAGONAL), "--variant", "diagonal", "--export", out, "--frames", 2) == 0
    assert Image.open(out).n_frames == 5  # states 0, 1, 2 and one frame between each two


def test_a_variant_that_does_not_fit_the_domain_is_one_line(qapp, tmp_path, capsys):
    assert viz(CORNER, plan_file(tmp_path, DIAGONAL), "--variant", "diagonal", "--domain", "a",
               "--export", tmp_path / "x.png") == 2
    assert capsys.readouterr().err == f"error: {BUILTIN / 'diagonal.yml'}: variant 'diagonal' changes domains M, Md, " \
                                      "not A\n"


def test_the_window_of_viz_variant_shows_the_varied_domain_and_opens_files_under_it(qapp, monkeypatch, tmp_path):
    from PyQt5.QtCore import QSettings, QStandardPaths

    default = QStandardPaths.writableLocation(QStandardPaths.GenericConfigLocation)
    QSettings.setPath(QSettings.NativeFormat, QSettings.UserScope, str(tmp_path))  # not the user's
    seen, windows = [], []
    show_window = MainWindow.show
    monkeypatch.setattr(MainWindow, "show", lambda self: windows.append(self) or show_window(self))

    def run(app) -> int:
        window = windows[-1]  # the window viz made
        seen.append((window.track.domain.label, window.status_line.verdict.text()))
        window.open_files([str(CORRIDOR)], [str(plan_file(tmp_path, VISIT, "visit.lp"))])
        seen.append((window.track.domain.label, window.status_line.verdict.text()))
        window.state.document.scenario = None  # (nothing unsaved: the window closes)
        window.close()
        return 0

    monkeypatch.setattr(QApplication, "exec_", run)
    try:
        assert viz(CORNER, plan_file(tmp_path, DIAGONAL), "--variant", "diagonal") == 0
        assert seen[0][0] == "M+diagonal" and "valid plan" in seen[0][1]
        assert seen[1][0] == "M+diagonal" and "1 rule violation" in seen[1][1]  # the goal at the end, in M
    finally:
        QSettings.setPath(QSettings.NativeFormat, QSettings.UserScope, default)


def test_a_file_whose_domain_the_variant_does_not_change_is_refused_in_a_dialog(window, tmp_path):
    show(window, CORNER, plan_file(tmp_path, DIAGONAL), "visit-anytime")
    md = tmp_path / "md.lp"
    md.write_text("init(object(node,1),value(at,(1,1))).\ninit(object(robot,1),value(at,(1,1))).\n"
                  "init(object(destination,1),value(at,(1,1))).\n")
    assert not window.open_files([str(md)])
    assert window.last_error.endswith("variant 'visit-anytime' changes domain M, not Md")
    assert window.scenario.instance.robots and window.track.domain.label == "M+visit-anytime"  # the one shown stays


# --- the Run menu ------------------------------------------------------------------------------------

def test_check_and_solve_with_an_encoding_file_run_under_the_varied_domain(window, qtbot, tmp_path):
    show(window, CORNER, plan_file(tmp_path, DIAGONAL), "diagonal")
    window.jobs.check()
    qtbot.waitUntil(lambda: window.jobs.job is None, timeout=WAIT_MS)
    report = window.jobs.last_outcome
    assert report.domain.label == "M+diagonal" and report.valid
    assert window.statusBar().currentMessage() == (
        "ASP checker: valid plan; it agrees with the verdict shown (M+diagonal)")
    window.jobs.solve_files([str(BUILTIN / "diagonal-plan.lp")])
    qtbot.waitUntil(lambda: window.jobs.job is None, timeout=WAIT_MS)
    outcome = window.jobs.last_outcome
    assert outcome.found and outcome.horizon == 2 and outcome.check.domain.label == "M+diagonal"
    assert window.track.domain.label == "M+diagonal" and "valid plan" in window.status_line.verdict.text()


# --- a domain registered at run time ----------------------------------------------------------------

def test_a_domain_with_a_concern_of_its_own_is_judged_by_the_checker(tmp_path):
    rule = tmp_path / "late.lp"
    rule.write_text("err(late,tooLong,(H)) :- horizon(H), H > 1.\n")
    domain = register(dataclasses.replace(Domain.M, value="mlate", label="Mlate",
                                          checker=(*Domain.M.checker[:-1], str(rule), "goal"),
                                          messages={("late", "tooLong"): lambda _timeline, step: (
                                              "the plan is too long", {})}))
    try:
        track = Track(read_instance(CORNER), plan_of(((1, (1, 0), 1), (1, (1, 0), 2), (1, (0, 1), 3),
                                                      (1, (0, 1), 4))), domain)
        assert track.checked and [v.message for v in track.violations] == ["step 4: the plan is too long"]
    finally:
        unregister(domain)
