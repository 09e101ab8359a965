"""The viewer's Qt-free state: the undo history, the document (instance and plan edits,
unsaved edits), and what the state tells its observers."""

from __future__ import annotations

from helpers import OUTCOME, SMALL_A

from asprilo.model import Action, Plan
from asprilo.reader import read_instance, read_plan
from asprilo.sources import Source
from asprilo.visualizer.state import edits
from asprilo.visualizer.state.document import INSTANCE, PLAN, Document
from asprilo.visualizer.state.history import History
from asprilo.visualizer.state.loading import Scenario, load_scenario
from asprilo.visualizer.state.viewer import ViewerState


class Counter:
    """A step that counts how often it was done; ``log`` records redo/undo in order."""

    def __init__(self, text: str, log: list[str]):
        self.text, self.log = text, log

    def redo(self) -> None:
        self.log.append(f"+{self.text}")

    def undo(self) -> None:
        self.log.append(f"-{self.text}")


def test_history_undoes_in_reverse_and_forgets_what_was_undone_when_a_step_is_pushed():
    log: list[str] = []
    history = History()
    for name in "abc":
        history.push(Counter(name, log))
    history.undo()
    history.undo()
    assert log == ["+a", "+b", "+c", "-c", "-b"]
    assert (history.undo_text, history.redo_text, history.count) == ("a", "b", 3)
    history.push(Counter("d", log))
    assert history.count == 2 and not history.can_redo and history.undo_text == "d"


def test_history_groups_are_one_entry_and_empty_groups_none():
    log: list[str] = []
    history = History()
    with history.group("stroke"):
        history.push(Counter("a", log))
        with history.group("inner"):
            history.push(Counter("b", log))
        assert not history.can_undo  # a group is not finished
    with history.group("nothing"):
        pass
    assert history.count == 1 and history.undo_text == "stroke"
    history.undo()
    assert log == ["+a", "+b", "-b", "-a"]


def test_history_marks_say_what_changed_since_and_when_it_cannot_come_back():
    log: list[str] = []
    history = History()
    history.push(Counter("a", log))
    history.mark("saved")
    assert history.since("saved") == []
    history.push(Counter("b", log))
    assert [step.text for step in history.since("saved")] == ["b"]
    history.undo()
    history.undo()
    assert [step.text for step in history.since("saved")] == ["a"]
    history.push(Counter("c", log))  # the saved position (after "a") can no longer come back
    assert history.since("saved") is None


def small() -> Scenario:
    return load_scenario([str(SMALL_A)])


def test_document_edits_the_instance_and_knows_what_is_unsaved():
    document = Document()
    seen = []
    document.changed.connect(seen.append)
    document.open(small())
    assert not document.modified and document.path is not None and document.path.name == SMALL_A.name
    assert document.perform(edits.add_object(document.instance, "robot", (2, 2)))
    assert document.instance.robots[4].at == (2, 2)
    assert document.modified and document.unsaved(INSTANCE) and not document.unsaved(PLAN)
    assert seen[-1].edit.text == "add robot 4 at (2,2)" and seen[-1].time == 0.0
    document.history.undo()
    assert 4 not in document.instance.robots and not document.modified
    assert not document.perform(edits.Edit("nothing"))  # no changes: no step


def test_plan_edits_are_undoable_and_saving_the_plan_leaves_the_instance_unsaved(tmp_path):
    document = Document()
    document.open(load_scenario([str(OUTCOME)]))
    original = document.plan
    shorter = Plan([a for a in original.actions if a.step <= 10])
    assert document.replace_plan(shorter, "keep the first ten steps")
    assert document.plan.horizon == 10 and document.unsaved(PLAN) and not document.unsaved(INSTANCE)
    document.perform(edits.add_object(document.instance, "robot", (11, 6)))
    document.save_plan(tmp_path / "plan.lp")
    assert read_plan(tmp_path / "plan.lp") == shorter
    assert document.scenario.plan_sources[0].name == str(tmp_path / "plan.lp")
    assert not document.unsaved(PLAN) and document.unsaved(INSTANCE) and document.modified
    document.history.undo()
    document.history.undo()
    assert document.plan == original and document.unsaved(PLAN)  # differs from the file saved


def test_draft_plans_stay_out_of_the_history_until_the_result_goes_in_as_one_step():
    document = Document()
    document.open(load_scenario([str(OUTCOME)]))
    original, sources = document.plan, document.scenario.plan_sources
    first, better = (Plan([a for a in original.actions if a.step <= steps]) for steps in (10, 5))
    shown = []
    document.changed.connect(lambda change: shown.append((change.plan, document.plan.horizon)))
    document.draft_plan(first)
    document.draft_plan(better)
    assert shown == [(True, 10), (True, 5)] and document.history.count == 0 and not document.modified
    assert document.replace_plan(better, "solve (anytime, makespan 5)", sources=[])
    assert document.history.count == 1 and document.plan == better and document.modified
    document.history.undo()
    assert document.plan == original and document.scenario.plan_sources == sources  # the plan before the drafts
    document.draft_plan(first)
    document.drop_draft()
    assert document.plan == original and document.scenario.plan_sources == sources
    assert shown[-2:] == [(True, 10), (True, original.horizon)] and document.history.count == 1
    document.draft_plan(first)
    assert not document.replace_plan(original, "solve (anytime)")  # the same plan as before: no step
    assert document.plan == original and shown[-1] == (True, original.horizon) and document.history.count == 1


def test_saving_the_instance_keeps_the_plan_it_came_with(tmp_path):
    document = Document()
    document.open(load_scenario([str(OUTCOME)]))
    assert document.path is None  # outcome.txt holds the plan too: saving there would lose it
    saved = []
    document.saved.connect(lambda: saved.append(document.scenario.title))
    document.save(tmp_path / "instance.lp")
    assert read_instance(tmp_path / "instance.lp") == read_instance(OUTCOME)
    assert saved == ["instance.lp + outcome.txt"]


def test_state_rebuilds_the_track_and_filters_the_selection():
    state = ViewerState()
    events = []
    state.shown.connect(lambda keep: events.append(("shown", keep)))
    state.track_changed.connect(lambda change: events.append(("changed", change.time)))
    state.document.open(load_scenario([str(OUTCOME)]))
    assert state.track.horizon == 29
    state.selection.set([3, 1])
    assert state.selection.focus == ("robot", 3)
    state.document.perform(edits.remove_object(state.document.instance, "robot", 3))
    assert state.track.robot_ids == [1, 2] and state.selection.robots == [1]
    assert state.selection.focus == ("robot", 1)  # robot 3 is gone: the next selected one
    state.document.replace_plan(Plan([Action(1, 1, "move", (1, 0))]), "one move", time=None)
    assert state.track.horizon == 1
    assert events == [("shown", False), ("changed", 0.0), ("changed", None)]
    state.document.open(Scenario(read_instance(Source("tiny", "init(object(node,1),value(at,(1,1)))."))))
    assert state.selection.robots == [] and state.track.horizon == 0


def test_locks_say_why():
    state = ViewerState()
    assert state.layout_lock() is None and state.order_lock() is None
    state.begin_job("Solve")
    assert state.layout_lock() == state.order_lock() == "solve is running: wait or cancel it (Ctrl+.) to edit"
    state.end_job()
    state.session.start("online: solver 127.0.0.1:5000")
    assert state.layout_lock().startswith("an online session owns the world") and state.order_lock() is None
    state.session.end("disconnected", "; 1 order line still open")
    assert state.session.ended_because == "disconnected; 1 order line still open"
    state.session.dismiss()
    assert state.session.ended_because is None and state.session.last_reason == "disconnected"
