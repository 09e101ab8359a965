"""Goals and id labels on the map: which objects are framed as goals at each step (M, Md with
labelled goals, A), how the frames look, and labels that show only where they can be read."""

from __future__ import annotations

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pytest  # noqa: E402
from helpers import OUTCOME  # noqa: E402
from helpers.viewer import shown_window  # noqa: E402
from PyQt5.QtCore import Qt  # noqa: E402

from asprilo.domain import Domain  # noqa: E402
from asprilo.reader import read_instance, read_plan  # noqa: E402
from asprilo.sources import Source  # noqa: E402
from asprilo.visualizer.scene import style  # noqa: E402
from asprilo.visualizer.state.goals import Goal, goals_at  # noqa: E402
from asprilo.visualizer.state.track import Track  # noqa: E402

pytestmark = pytest.mark.gui


def grid(width: int, height: int) -> str:
    return " ".join(f"init(object(node,{(y - 1) * width + x}),value(at,({x},{y})))."
                    for y in range(1, height + 1) for x in range(1, width + 1))


#: 3x3, robots 1 (1,1) and 2 (3,3); shelf 1 (2,1), 2 (3,1), 3 (1,3) hold products 1, 2, 3;
#: order 1 asks for product 2, order 2 for product 3: the goals are shelves 2 and 3.
#: Robot 1 drives right twice: under shelf 1 at step 1, under shelf 2 at step 2.
M_TEXT = grid(3, 3) + """
init(object(pickingStation,1),value(at,(2,2))).
init(object(robot,1),value(at,(1,1))). init(object(robot,2),value(at,(3,3))).
init(object(shelf,1),value(at,(2,1))). init(object(shelf,2),value(at,(3,1))). init(object(shelf,3),value(at,(1,3))).
init(object(product,1),value(on,1)). init(object(product,2),value(on,2)). init(object(product,3),value(on,3)).
init(object(order,1),value(line,2)). init(object(order,1),value(pickingStation,1)).
init(object(order,2),value(line,3)). init(object(order,2),value(pickingStation,1)).
occurs(object(robot,1),action(move,(1,0)),1). occurs(object(robot,1),action(move,(1,0)),2).
"""
#: 3x2, robots 1 (1,1) and 2 (3,1); destination 1 (1,2), destination 2 (3,2) is robot 1's labelled
#: goal.  At step 1 both robots move down: robot 1 onto destination 1, robot 2 onto destination 2.
MD_TEXT = grid(3, 2) + """
init(object(robot,1),value(at,(1,1))). init(object(robot,2),value(at,(3,1))).
init(object(destination,1),value(at,(1,2))). init(object(destination,2),value(at,(3,2))).
assign(robot(1),destination(2)).
occurs(object(robot,1),action(move,(0,1)),1). occurs(object(robot,2),action(move,(0,1)),1).
"""


def track_of(text: str) -> Track:
    source = Source("goals.lp", text)
    return Track(read_instance(source), read_plan(source))


def test_m_goals_are_the_ordered_shelves_reached_when_a_robot_stands_under_one():
    track = track_of(M_TEXT)
    assert track.domain is Domain.M
    assert goals_at(track, 0) == goals_at(track, 1) == [Goal("shelf", 2, False), Goal("shelf", 3, False)]
    assert goals_at(track, 2) == [Goal("shelf", 2, True, by=1), Goal("shelf", 3, False)]


def test_md_labelled_goals_count_only_for_their_robot():
    track = track_of(MD_TEXT)
    assert track.domain is Domain.MD
    assert goals_at(track, 0) == [Goal("destination", 1, False), Goal("destination", 2, False, robot=1)]
    assert goals_at(track, 1) == [Goal("destination", 1, True, by=1), Goal("destination", 2, False, robot=1)]


def test_a_goals_are_the_shelves_open_lines_need_with_their_stations():
    # outcome.txt (see test_viz_panels.py): order 1 at PS1 asks for products 2 and 4, orders 2
    # and 3 at PS2 for 4, 5 and 1, 3.  Shelf 1 holds 3, 4, 5; shelf 2 holds 2, 4, 5; shelf 3
    # holds 2, 4; shelves 9 and 12 hold product 1.  After step 7 robot 3 stands on PS1 (4,1)
    # with shelf 1 and delivers its one unit of product 4 to order 1 at step 8; then shelf 1
    # holds nothing PS1 still needs.  After step 29 every order is done.
    track = Track(read_instance(OUTCOME), read_plan(OUTCOME))
    both = (1, 2)
    assert goals_at(track, 0) == [Goal("shelf", 1, False, stations=both), Goal("shelf", 2, False, stations=both),
                                  Goal("shelf", 3, False, stations=both), Goal("shelf", 9, False, stations=(2,)),
                                  Goal("shelf", 12, False, stations=(2,))]
    assert Goal("shelf", 1, True, stations=both, at=1) in goals_at(track, 7)
    assert Goal("shelf", 1, False, stations=(2,)) in goals_at(track, 8)
    assert goals_at(track, 29) == []


# --- on the map ---------------------------------------------------------------------------------------

@pytest.fixture
def window(qtbot, tmp_path_factory):
    return shown_window(qtbot, tmp_path_factory)


def marks(window) -> dict[tuple[int, int], tuple[str, bool, str, str]]:
    """Cell -> (kind, reached, tag, colour) of every goal frame shown."""
    found = {}
    for kind in ("shelf", "destination"):
        for item in window.stage.scene.table(kind).values():
            if item.goal is not None and item.goal.isVisible():
                look = item.goal.look
                found[style.cell_at(item.pos())] = (kind, look.reached, look.tag, look.colour.name())
    return found


def test_goal_frames_on_the_map_for_m(window, write):
    assert window.open_files([str(write("m.lp", M_TEXT))])
    goal = style.GOAL.name()
    assert marks(window) == {(3, 1): ("shelf", False, "", goal), (1, 3): ("shelf", False, "", goal)}
    window.go_to(2)
    assert marks(window) == {(3, 1): ("shelf", True, "\u2713 R1", style.DELIVERY.name()),
                             (1, 3): ("shelf", False, "", goal)}
    window.commands["goals"].trigger()  # off
    assert marks(window) == {}
    window.commands["goals"].trigger()
    assert len(marks(window)) == 2


def test_goal_frames_on_the_map_for_md_in_the_colour_of_the_labelled_robot(window, write):
    assert window.open_files([str(write("md.lp", MD_TEXT))])
    robot_1 = window.stage.scene.robots[1].colour.name()
    assert marks(window) == {(1, 2): ("destination", False, "", style.GOAL.name()),
                             (3, 2): ("destination", False, "R1", robot_1)}
    window.go_to(1)
    assert marks(window) == {(1, 2): ("destination", True, "\u2713 R1", style.DELIVERY.name()),
                             (3, 2): ("destination", False, "R1", robot_1)}


def test_goal_frames_on_the_map_for_a_follow_the_shelves(window):
    assert window.open_files([str(OUTCOME)])
    initial = {shelf: cell for shelf, cell in window.track.state(0).shelves.items()}
    goal = style.GOAL.name()
    assert marks(window) == {initial[1]: ("shelf", False, "\u2192PS1,PS2", goal),
                             initial[2]: ("shelf", False, "\u2192PS1,PS2", goal),
                             initial[3]: ("shelf", False, "\u2192PS1,PS2", goal),
                             initial[9]: ("shelf", False, "\u2192PS2", goal),
                             initial[12]: ("shelf", False, "\u2192PS2", goal)}
    window.go_to(7)
    assert marks(window)[(4, 1)] == ("shelf", True, "\u2713 PS1", style.DELIVERY.name())  # shelf 1 at PS1
    window.go_to(8)
    assert marks(window)[(4, 1)] == ("shelf", False, "\u2192PS2", goal)
    window.go_to(29)
    assert marks(window) == {}


def labels(window) -> dict[str, bool]:
    """Kind -> whether the labels of that kind are shown (all alike)."""
    scene, shown = window.stage.scene, {}
    for kind in ("robot", "shelf", "station"):
        states = {(item.label is not None and item.label.isVisible()) if kind != "station" else item.tag.isVisible()
                  for item in scene.table(kind).values()}
        assert len(states) == 1, kind
        shown[kind] = states.pop()
    return shown


def test_id_labels_toggle_and_hide_when_too_small_to_read(window, qtbot):
    window.open_files([str(OUTCOME)])
    view = window.view
    view.zoom_by(40 / view.pixels_per_cell)
    assert labels(window) == {"robot": True, "shelf": True, "station": True}
    qtbot.keyClick(window, Qt.Key_I)
    assert labels(window) == {"robot": False, "shelf": False, "station": False}
    qtbot.keyClick(window, Qt.Key_I)
    assert labels(window) == {"robot": True, "shelf": True, "station": True}
    # labels are 0.3 (robots) and 0.2 (shelves, stations) cells high and need 7 pixels
    view.zoom_by(30 / view.pixels_per_cell)
    assert labels(window) == {"robot": True, "shelf": False, "station": False}
    view.zoom_by(20 / view.pixels_per_cell)
    assert labels(window) == {"robot": False, "shelf": False, "station": False}
    view.zoom_by(35 / view.pixels_per_cell)
    assert labels(window) == {"robot": True, "shelf": True, "station": True}
