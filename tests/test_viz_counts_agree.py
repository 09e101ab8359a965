"""The viewer's counts agree with ``check`` (offscreen; issue 47, item 5): after a solve the
status bar, the verdict in the corner, the Violations panel and the Orders panel judge the
plan found under the same rules as the checker did -- the domain it was solved for.

The corridor: robot 1 at (1,1), a picking station at (2,1), shelf 1 holding one unit of
product 1 at (3,1); order 1 asks for that unit at the station.  It is M-aligned, so a plan of
moves alone is read as M and one that picks up as A.  Derived by hand:

- the loaded plan (two moves east, a pickup at step 3) is read as A, where order 1 is not
  served: one violation, at step 3;
- solved in that domain A, an M-style encoding that walks two steps east to the shelf
  (two moves, horizon 2) leaves order 1 lacking its 1 unit: one violation, at step 2, and
  the order's line open with 1 unit missing.  Read as M (moves only) the same plan would be
  valid: the viewer showed "breaks 1 rule" beside "valid plan" before it kept the domain.
"""

from __future__ import annotations

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import re  # noqa: E402

import pytest  # noqa: E402
from helpers.viewer import shown_window  # noqa: E402
from PyQt5.QtWidgets import QMessageBox  # noqa: E402

from asprilo.checker import check  # noqa: E402
from asprilo.domain import Domain  # noqa: E402
from asprilo.reader import read_instance  # noqa: E402
from asprilo.visualizer.panels.violation_list import sentence  # noqa: E402

pytestmark = pytest.mark.gui
WAIT_MS = 60_000  # a hang guard: no job may take longer here

CORRIDOR = """\
init(object(node,1),value(at,(1,1))).
init(object(node,2),value(at,(2,1))).
init(object(node,3),value(at,(3,1))).
init(object(pickingStation,1),value(at,(2,1))).
init(object(robot,1),value(at,(1,1))).
init(object(shelf,1),value(at,(3,1))).
init(object(product,1),value(on,(1,1))).
init(object(order,1),value(line,(1,1))).
init(object(order,1),value(pickingStation,1)).
"""

PICKUP_PLAN = """\
occurs(object(robot,1),action(move,(1,0)),1).
occurs(object(robot,1),action(move,(1,0)),2).
occurs(object(robot,1),action(pickup,()),3).
"""

TYPO_PLAN = """\
occurs(object(robot,1),action(mvoe,(1,0)),1).
occurs(object(robot,1),action(move,(1,0)),2).
"""

WALK = """\
% two steps east to the shelf that holds the ordered product: a domain-M walk (for the tests)
cell(C)     :- init(object(node,_),value(at,C)).
at(C,0)     :- init(object(robot,_),value(at,C)).
goal(C)     :- init(object(order,_),value(line,(P,_))), init(object(product,P),value(on,(S,_))),
               init(object(shelf,S),value(at,C)).
direction((1,0);(-1,0);(0,1);(0,-1)).
{ move(D,T) : direction(D) } 1 :- T = 1..2.
at((X+DX,Y+DY),T) :- at((X,Y),T-1), move((DX,DY),T).
at(C,T) :- at(C,T-1), T = 1..2, not move(_,T).
:- move((DX,DY),T), at((X,Y),T-1), not cell((X+DX,Y+DY)).
:- goal(C), not at(C,2).
occurs(object(robot,R),action(move,D),T) :- move(D,T), init(object(robot,R),value(at,_)).
#show occurs/3.
"""


@pytest.fixture
def files(tmp_path):
    for name, text in (("corridor.lp", CORRIDOR), ("pickup.lp", PICKUP_PLAN), ("typo.lp", TYPO_PLAN),
                       ("walk.lp", WALK)):
        (tmp_path / name).write_text(text)
    return tmp_path


@pytest.fixture
def window(qtbot, tmp_path_factory, monkeypatch):
    window = shown_window(qtbot, tmp_path_factory)
    monkeypatch.setattr(QMessageBox, "question", lambda *args: QMessageBox.Discard)
    yield window
    window.jobs.cancel()
    qtbot.waitUntil(lambda: window.jobs.job is None, timeout=WAIT_MS)


def orders_panel(window, step: int) -> list[tuple[int, int, bool, int | None]]:
    """(order, product, done, units missing) per line of the Orders panel at ``step``."""
    model = window.panels.tables["orders"].model
    model.show_step(step)
    return [(row.order, row.product, model.line_done(row), model.missing(row)) for row in model.rows]


def corner(window) -> str:
    """The verdict in the status bar's corner, without its markup."""
    return re.sub(r"<[^>]+>", "", window.status_line.verdict.text())


def test_a_solve_is_shown_under_the_rules_it_was_solved_for(window, qtbot, files):
    assert window.open_files([str(files / "corridor.lp")], [str(files / "pickup.lp")])
    assert window.track.domain is Domain.A and len(window.track.violations) == 1
    assert window.jobs.solve_files([str(files / "walk.lp")]) is not None
    qtbot.waitUntil(lambda: window.jobs.job is None, timeout=WAIT_MS)

    plan = window.scenario.plan
    assert sorted((a.step, a.name, a.args) for a in plan.actions) == [(1, "move", (1, 0)), (2, "move", (1, 0))]
    report = check(read_instance(files / "corridor.lp"), plan, Domain.A)
    assert [error.message for error in report.errors] == [
        "step 2 (the horizon): order 1 still lacks 1 unit of product 1"]
    # every place says the same: one violation of domain A, order 1 lacking its unit
    assert window.track.domain is Domain.A
    assert [v.message for v in window.track.violations] == [error.message for error in report.errors]
    assert re.fullmatch(r"the plan found in \d+\.\d s breaks 1 rule: makespan 2, 2 actions \(A, walk: .*\); "
                        r"the checker's violations are in the Violations panel", window.statusBar().currentMessage())
    assert corner(window).startswith("\u26a0 1 rule violation")
    violations = window.panels.tables["violations"]
    assert [sentence(row) for row in violations.model.rows] == [
        "at the horizon: order 1 still lacks 1 unit of product 1"]
    assert window.panels.docks["violations"].windowTitle() == "Violations — ASP checker (1)"
    assert orders_panel(window, 2) == [(1, 1, False, 1)]

    # undo: the loaded plan, read as A again (its pickup), with its one violation at step 3
    window.editor.commands["undo"].trigger()
    assert window.scenario.plan.horizon == 3 and window.track.domain is Domain.A
    assert [v.message for v in window.track.violations] == [
        "step 3 (the horizon): order 1 still lacks 1 unit of product 1"]
    # redo: the solved plan under A again
    window.editor.commands["redo"].trigger()
    assert window.track.domain is Domain.A and len(window.track.violations) == 1


def test_a_misspelt_move_is_shown_in_domain_m_with_checks_count(window, files):
    assert window.open_files([str(files / "corridor.lp")], [str(files / "typo.lp")])
    report = check(read_instance(files / "corridor.lp"), window.scenario.plan)
    assert report.domain is Domain.M
    assert [error.message for error in report.errors] == [
        "step 1: robot 1 does 'mvoe', which is not an action of domain M",
        "step 2 (the horizon): order 1 is not fulfilled: no robot stands under a shelf holding product 1"]
    assert window.track.domain is Domain.M
    assert [v.message for v in window.track.violations] == [error.message for error in report.errors]
    assert corner(window).startswith("\u26a0 2 rule violations")
    assert window.panels.docks["violations"].windowTitle() == "Violations (2)"
    assert orders_panel(window, 2) == [(1, 1, False, 1)]
