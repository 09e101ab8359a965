"""Mistakes explained where they are made (issue 33, item 1): plan atoms that are no plan
atoms and actions no domain knows are warned about with FILE:LINE and a did-you-mean; a
missing '.' is said on its own line; a plan made for another instance is one sentence;
``check`` and ``viz`` give the same verdict and exit status on the same files; ``viz
--export`` of an invalid plan says so; ``gen`` says when what it made has nothing to do;
``solve`` says when the plan of a user's encoding does not fit the instance."""

from __future__ import annotations

import os
import warnings

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pytest  # noqa: E402
from helpers import OUTCOME, SMALL_A, WRONG_OUTCOME  # noqa: E402

from asprilo.cli import main  # noqa: E402
from asprilo.domain import Domain  # noqa: E402
from asprilo.errors import InputError  # noqa: E402
from asprilo.limits import Limits  # noqa: E402
from asprilo.model import Action, Plan  # noqa: E402
from asprilo.parse import parse_terms  # noqa: E402
from asprilo.reader import plan_misfits, read_instance, read_plan  # noqa: E402
from asprilo.sources import Source  # noqa: E402

MOVE = "occurs(object(robot,1),action(move,(1,0)),1)."


def warned(text: str, name: str = "plan.lp") -> tuple[int, list[str]]:
    """The actions read from ``text`` and the reader's warnings."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        plan = read_plan(Source(name, text))
    return len(plan), [str(warning.message) for warning in caught]


# --- the reader: atoms that are no plan atoms, actions no domain knows ------------------------------

@pytest.mark.parametrize("text, actions, message", [
    ("occur(object(robot,1),action(move,(1,0)),1).\n", 0, "plan.lp:1: occur/3 is ignored: did you mean occurs/3?"),
    (f"{MOVE}\nocurs(object(robot,2),action(move,(1,0)),2).\n", 1,
     "plan.lp:2: ocurs/3 is ignored: did you mean occurs/3?"),
    ("occurs(object(robot,1),action(move,(1,0),1)).\n", 0,
     "plan.lp:1: occurs/2 is ignored: occurs has 3 arguments, occurs(object(robot,R),action(Name,Args),T) "
     "(a parenthesis in the wrong place?)"),
    ("occurs(object(robot,1),action(mvoe,(1,0)),1).\n", 1,
     "plan.lp:1: there is no action 'mvoe': did you mean move? (the actions: deliver, move, pickup, putdown)"),
    ("occurs(object(robot,1),action(fly,()),1).\n", 1,
     "plan.lp:1: there is no action 'fly' (the actions: deliver, move, pickup, putdown)"),
    ("occurs(object(robto,1),action(move,(1,0)),1).\n", 1,
     "plan.lp:1: only robots act, not object(robto,..): did you mean robot?"),
    (f"{MOVE}\n\nposition(robot(1),(2,1),1). holds(1). position(robot(2),(1,1),0).\n", 1,
     "plan.lp:3: ignored: position/3, holds/1 (a plan is made of occurs/3 atoms)"),
])
def test_each_mistake_in_a_plan_file_is_warned_about_with_its_line(text, actions, message):
    assert warned(text) == (actions, [message])


def test_several_mistakes_are_warned_about_once_each_in_the_order_of_the_file():
    text = ("occurs(object(robot,1),action(mvoe,(1,0)),1).\n"
            "occur(object(robot,2),action(move,(1,0)),1).\n"
            "occurs(object(robot,3),action(mvoe,(1,0)),2).\n"
            "occur(object(robot,3),action(move,(1,0)),1).\n"
            "occurs(object(robot,1),action(move,(1,0))).\n")
    assert warned(text)[1] == [
        "plan.lp:1: there is no action 'mvoe': did you mean move? (the actions: deliver, move, pickup, putdown)",
        "plan.lp:2: occur/3 is ignored: did you mean occurs/3?",
        "plan.lp:5: occurs/2 is ignored: occurs has 3 arguments, occurs(object(robot,R),action(Name,Args),T) "
        "(a parenthesis in the wrong place?)"]


def test_instance_atoms_in_a_plan_file_pass_without_a_word():
    assert warned(OUTCOME.read_text())[1] == []  # init/2 and occurs/3: clingo's output shows both
    text = "init(object(robot,1),value(at,(1,1))). assign(robot(1),shelf(2)). -occurs(a,b,c).\n" + MOVE
    assert warned(text) == (1, [])
    # with an instance, other atoms are expected (an encoding without #show): only near misses are said
    text = "init(object(robot,1),value(at,(1,1))). position(1,2,3). occur(a,b,c).\n" + MOVE
    assert warned(text) == (1, ["plan.lp:1: occur/3 is ignored: did you mean occurs/3?"])


def test_a_solvers_answer_says_only_occurs_of_another_arity():
    import clingo

    from asprilo.reader import plan_from_atoms
    atoms = [clingo.parse_term(MOVE[:-1]), clingo.parse_term("position(1,2,3)"), clingo.parse_term("occur(a,b,c)")]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert len(plan_from_atoms(atoms)) == 1
    assert caught == []


# --- a missing '.' ----------------------------------------------------------------------------------

@pytest.mark.parametrize("text, message", [
    (f"{MOVE[:-1]}\n{MOVE}\n",
     "t.lp:1: a '.' is missing at the end of this line? (syntax error, unexpected <IDENTIFIER> on line 2)"),
    (f"{MOVE}\n{MOVE[:-1]}\n", "t.lp:2: a '.' is missing at the end of this line? (syntax error, unexpected EOF)"),
    (f"{MOVE[:-1]}", "t.lp:1: a '.' is missing at the end of this line? (syntax error, unexpected EOF)"),
    (f"{MOVE}\n{MOVE[:-1]}  % a comment\n\n% another\n{MOVE}",
     "t.lp:2: a '.' is missing at the end of this line? (syntax error, unexpected <IDENTIFIER> on line 5)"),
    ("p(1)\n-q(2).", "t.lp:1: a '.' is missing at the end of this line? (syntax error, unexpected - on line 2)"),
    ("p\n#const n = 1.",
     "t.lp:1: a '.' is missing at the end of this line? (syntax error, unexpected #const on line 2)"),
    ("p(1).\r\np(2)\r\np(3).", "t.lp:2: a '.' is missing at the end of this line? "
                               "(syntax error, unexpected <IDENTIFIER> on line 3)"),
    # not a missing '.': on one line, or what follows cannot start a statement
    (f"{MOVE[:-1]} {MOVE}", "t.lp:1: syntax error, unexpected <IDENTIFIER>"),
    ("p(1)\n, q(2).", "t.lp:2: syntax error, unexpected \",\""),
])
def test_a_missing_period_is_said_on_the_line_that_lacks_it(text, message):
    with pytest.raises(InputError) as error:
        parse_terms(text, "t.lp", Limits())
    assert str(error.value) == message


def test_a_missing_period_in_an_instance_is_said_the_same_way(tmp_path):
    path = tmp_path / "i.lp"
    path.write_text("init(object(node,1),value(at,(1,1)))\ninit(object(robot,1),value(at,(1,1))).\n")
    with pytest.raises(InputError) as error:
        read_instance(path)
    assert str(error.value) == (f"{path}:1: a '.' is missing at the end of this line? "
                                "(syntax error, unexpected <IDENTIFIER> on line 2)")


# --- plans that do not fit the instance ---------------------------------------------------------------

def test_what_makes_a_plan_one_for_another_instance_or_domain_in_words():
    instance = read_instance(SMALL_A)
    fits = read_plan(OUTCOME)
    assert plan_misfits(fits, instance) == []
    alien = Plan([Action(1, 9, "move", (1, 0)), Action(1, 12, "move", (0, 1)), Action(2, 1, "mvoe", (1, 0)),
                  Action(3, 1, "pickup", ())])
    assert plan_misfits(alien, instance, Domain.M) == [
        "it moves robots 9, 12, but the instance has robots 1..3",
        "there is no action 'mvoe' (did you mean move?)",
        "it uses pickup, which domain M lacks (its actions: move)"]


# --- check and viz: the same verdict and exit status on the same files ----------------------------------

def run(capsys, command: str, *args) -> tuple[int, str, str]:
    code = main([command, *map(str, args)])
    out, err = capsys.readouterr()
    return code, out, err


BROKEN = {
    "other.lp": "occurs(object(robot,9),action(move,(1,0)),1).\n",
    "dot.lp": f"{MOVE[:-1]}\noccurs(object(robot,2),action(move,(0,-1)),1).\n",
    "occur.lp": "occur(object(robot,1),action(move,(1,0)),1).\n",
    "mvoe.lp": "occurs(object(robot,1),action(mvoe,(1,0)),1).\n",
}


@pytest.mark.gui
@pytest.mark.parametrize("name, code, said", [
    ("other.lp", 2, ["error: {plan}:1: the plan moves robot 9, but the instance has robots 1..3 "
                     "(plan and instance do not fit)"]),
    ("dot.lp", 2, ["error: {plan}:1: a '.' is missing at the end of this line? "
                   "(syntax error, unexpected <IDENTIFIER> on line 2)"]),
    ("occur.lp", 1, ["warning: {plan}:1: occur/3 is ignored: did you mean occurs/3?",
                     "invalid plan: 6 violations (domain A (detected), horizon 0)"]),
    ("mvoe.lp", 1, ["warning: {plan}:1: there is no action 'mvoe': did you mean move? "
                    "(the actions: deliver, move, pickup, putdown)",
                    "invalid plan: 7 violations (domain A (detected), horizon 1)"]),
    (WRONG_OUTCOME, 1, ["invalid plan: 3 violations (domain A (detected), horizon 29)"]),
    (OUTCOME, 0, []),
])
def test_check_and_viz_agree_on_the_same_files(qapp, tmp_path, capsys, name, code, said):
    plan = tmp_path / name if name in BROKEN else name
    if name in BROKEN:
        plan.write_text(BROKEN[name])
    expected = [line.format(plan=plan) for line in said]
    checked, out, err = run(capsys, "check", SMALL_A, plan)
    assert checked == code
    lines = err.splitlines() + [line for line in out.splitlines() if line.startswith(("invalid plan", "valid plan"))]
    assert lines == expected or (code == 0 and lines[-1].startswith("valid plan"))
    picture = tmp_path / "state.png"
    shown, out, err = run(capsys, "viz", SMALL_A, plan, "--export", picture)
    assert shown == code and out == ""
    lines = [line for line in err.splitlines() if not line.startswith("wrote ")]
    assert [line.removesuffix("; check INSTANCE PLAN lists them") for line in lines] == \
        [line for line in expected if not line.startswith("valid")]
    assert picture.exists() == (code != 2)  # a picture of an invalid plan is written all the same


@pytest.mark.gui
def test_viz_export_of_an_invalid_plan_says_so_after_writing_it(qapp, tmp_path, capsys):
    out = tmp_path / "strip.png"
    code, printed, err = run(capsys, "viz", WRONG_OUTCOME, "--export", out, "--strip", "1-2", "--cell", 20)
    assert (code, printed) == (1, "") and out.exists()
    assert err.startswith(f"wrote {out}: ") and err.endswith(
        ", the states after steps 1 to 2\n"
        "invalid plan: 3 violations (domain A (detected), horizon 29); check INSTANCE PLAN lists them\n")
    assert run(capsys, "viz", SMALL_A, "--export", out) == (0, "", f"wrote {out}: 1472x832\n")  # no plan, no verdict


def test_a_plan_for_another_domain_is_said_in_one_warning(capsys):
    code, out, err = run(capsys, "check", SMALL_A, WRONG_OUTCOME, "--domain", "m")
    assert code == 1
    assert err == (f"warning: {WRONG_OUTCOME}:158: the plan uses deliver, pickup, putdown, which domain M lacks "
                   "(its actions: move): a plan made for another domain or instance?\n")
    assert "invalid plan: 23 violations (domain M, horizon 29)" in out


# --- gen: nothing to do -------------------------------------------------------------------------------------

GEN = ["-x", "5", "-y", "5", "-s", "2", "-p", "1", "-P", "2", "-u", "4", "-C"]


@pytest.mark.parametrize("extra, message", [
    (["-r", "2"], "warning: no orders: the instance has nothing to do (give -o N; "
                  "or add orders later with -T FILE -o N)\n"),
    (["-o", "1"], "warning: no robots: nobody can fulfil the orders (give -r N)\n"),
    (["-r", "2", "-o", "1"], ""),
    (["-r", "2", "--domain", "m", "-u", "2"], ""),  # M: an order per robot
])
def test_gen_says_when_its_instance_has_nothing_to_do(capsys, extra, message):
    code, out, err = run(capsys, "gen", *GEN, *extra)
    assert code == 0 and "init(object(" in out
    assert err == message


# --- solve: the plan of a user's own encoding that does not fit ------------------------------------------

#: a 4x4 floor, one robot, one order of one unit
TINY = "\n".join(f"init(object(node,{(y - 1) * 4 + x}),value(at,({x},{y})))."
                 for y in range(1, 5) for x in range(1, 5)) + """
init(object(pickingStation,1),value(at,(1,2))). init(object(robot,1),value(at,(4,1))).
init(object(shelf,1),value(at,(2,3))). init(object(product,1),value(on,(1,1))).
init(object(order,1),value(line,(1,1))). init(object(order,1),value(pickingStation,1)).
"""
ALIEN_ENCODING = """#const horizon=1.
time(1..horizon).
occurs(object(robot,7),action(mvoe,(0,1)),T) :- time(T).
#show occurs/3.
"""


def test_solve_says_in_one_sentence_that_an_encodings_plan_does_not_fit(tmp_path, capsys):
    instance, encoding = tmp_path / "tiny.lp", tmp_path / "mine.lp"
    instance.write_text(TINY)
    encoding.write_text(ALIEN_ENCODING)
    code, _out, err = run(capsys, "solve", instance, "--encoding", encoding, "--time-limit", "30")
    assert code == 1
    assert ("your encoding's plan does not fit the instance: it moves robot 7, but the instance has robot 1; "
            "there is no action 'mvoe' (did you mean move?)") in err.splitlines()


# --- the viewer's atoms pane ------------------------------------------------------------------------------

@pytest.fixture
def atoms(qtbot, tmp_path_factory, monkeypatch):
    from helpers.viewer import shown_window
    from PyQt5.QtWidgets import QMessageBox
    monkeypatch.setattr(QMessageBox, "question", lambda *args: QMessageBox.Discard)  # closing at the end
    window = shown_window(qtbot, tmp_path_factory)
    assert window.open_files([str(OUTCOME)])
    window.docks["atoms"].show()
    window.docks["atoms"].raise_()
    pane = window.docks["atoms"].widget()
    qtbot.waitUntil(lambda: pane.shown, timeout=10_000)  # a hang guard
    return pane


def plain(html: str) -> str:
    from PyQt5.QtGui import QTextDocument
    document = QTextDocument()
    document.setHtml(html)
    return document.toPlainText()


@pytest.mark.gui
def test_the_atoms_pane_says_what_check_would_warn_about_and_marks_the_lines(atoms):
    atoms.plan_box.setPlainText(f"{MOVE}\noccur(object(robot,2),action(move,(1,0)),1).\n"
                                "occurs(object(robot,3),action(mvoe,(0,1)),1).")
    atoms.read_now()
    assert plain(atoms.plan_note.text()).splitlines() == [
        "2 actions, horizon 1: 8 violations",
        "warning: <plan atoms>:2: occur/3 is ignored: did you mean occurs/3?",
        "warning: <plan atoms>:3: there is no action 'mvoe': did you mean move? "
        "(the actions: deliver, move, pickup, putdown)"]
    assert len(atoms.state.document.plan) == 2  # read all the same
    assert [mark.cursor.block().blockNumber() for mark in atoms.plan_box.extraSelections()
            if mark.format.background().color().name() == "#ffe8cc"] == [1, 2]


@pytest.mark.gui
def test_the_atoms_pane_says_where_a_period_is_missing(atoms):
    original = atoms.state.document.plan
    atoms.plan_box.setPlainText(f"{MOVE[:-1]}\noccurs(object(robot,2),action(move,(1,0)),1).")
    atoms.read_now()
    assert plain(atoms.plan_note.text()) == ("<plan atoms>:1: a '.' is missing at the end of this line? "
                                             "(syntax error, unexpected <IDENTIFIER> on line 2) (the plan shown stays)")
    assert atoms.state.document.plan is original


# --- check --watch: the warnings of a run below its heading ------------------------------------------------

def test_a_watched_recheck_says_the_readers_warnings_below_its_heading(tmp_path, monkeypatch):
    import io
    from pathlib import Path

    from asprilo.cli.reruns import PlanCheck
    monkeypatch.chdir(tmp_path)
    instance, plan = Path("i.lp"), Path("p.lp")
    instance.write_text("init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))).\n"
                        "init(object(robot,1),value(at,(1,1))).\n")
    plan.write_text("occurs(object(robot,1),action(move,(1,0)),1).\noccur(object(robot,1),action(move,(-1,0)),2).\n")
    out = io.StringIO()
    PlanCheck(instance, plan, None, 5, out)([])
    lines = out.getvalue().splitlines()
    assert lines[0].endswith("watching i.lp, p.lp (Ctrl-C ends): checking ---")
    assert lines[1:] == ["warning: p.lp:2: occur/3 is ignored: did you mean occurs/3?",
                         "valid plan (domain M (detected), horizon 1)"]
