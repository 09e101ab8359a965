"""The viewer's scene and animation: items sit where the simulator says, at every step."""

from __future__ import annotations

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pytest  # noqa: E402
from helpers import EXAMPLES, OUTCOME, SMALL_A, WRONG_OUTCOME  # noqa: E402
from PyQt5.QtCore import QPointF  # noqa: E402

from asprilo.model import Action, Instance, Plan, Robot, Shelf  # noqa: E402
from asprilo.reader import read_instance, read_plan  # noqa: E402
from asprilo.simulate import simulate  # noqa: E402
from asprilo.visualizer.scene import style  # noqa: E402
from asprilo.visualizer.scene.animator import Animator  # noqa: E402
from asprilo.visualizer.scene.marks import Badge, CellMark  # noqa: E402
from asprilo.visualizer.scene.paths import PathMode, Trails  # noqa: E402
from asprilo.visualizer.scene.warehouse import HIGHWAY, MISSING, STORAGE, WarehouseScene  # noqa: E402
from asprilo.visualizer.state.track import Track  # noqa: E402

pytestmark = pytest.mark.gui

PLANNED = [(OUTCOME, OUTCOME), (WRONG_OUTCOME, WRONG_OUTCOME),
           (EXAMPLES / "encodings-repo/x46_y15_n690_r10_s160_ps10_pr5_u10_o2_N1.lp",
            EXAMPLES / "encodings-repo/x46_y15_n690_r10_s160_ps10_pr5_u10_o2_N1.plan")]


def cell_of(item) -> tuple[float, float]:
    """The (possibly fractional) cell an item is centred on."""
    return (item.pos().x() / style.CELL + 0.5, item.pos().y() / style.CELL + 0.5)


def build(instance_path, plan_path=None):
    instance = read_instance(instance_path)
    plan = read_plan(plan_path) if plan_path else Plan()
    scene = WarehouseScene(instance)
    track = Track(instance, plan)
    return instance, plan, scene, track, Animator(scene, track)


def test_scene_holds_every_object_of_the_instance(qapp):
    instance = read_instance(SMALL_A)
    scene = WarehouseScene(instance)
    assert sorted(scene.robots) == [1, 2, 3]
    assert sorted(scene.shelves) == list(range(1, 13))
    assert sorted(scene.stations) == [1, 2]
    assert cell_of(scene.robots[1]) == (1, 6)
    assert cell_of(scene.shelves[12]) == (10, 4)
    assert cell_of(scene.stations[2]) == (8, 1)
    assert scene.floor.size == (11, 6)
    assert scene.floor.kinds[0, 0] == HIGHWAY          # (1,1)
    assert scene.floor.kinds[2, 1] == STORAGE          # (2,3)
    assert (scene.floor.kinds == MISSING).sum() == 0


def test_missing_nodes_and_off_floor_cells_widen_the_picture(qapp):
    instance = Instance(nodes={1: (1, 1), 2: (3, 1)}, robots={1: Robot(1, (1, 1))})
    scene = WarehouseScene(instance)
    assert scene.floor.kinds.tolist() == [[STORAGE, MISSING, STORAGE]]
    before = scene.picture_rect()
    scene.include_cells([(5, 4)])
    after = scene.picture_rect()
    assert after.right() == pytest.approx((5 + 0.25) * style.CELL)
    assert after.bottom() == pytest.approx((4 + 0.25) * style.CELL)
    assert before.right() == pytest.approx((3 + 0.25) * style.CELL)


def test_objects_can_be_added_and_removed(qapp):
    scene = WarehouseScene(read_instance(SMALL_A))
    scene.add_robot(Robot(7, (2, 2)))
    scene.add_shelf(Shelf(20, (2, 3)))
    assert cell_of(scene.robots[7]) == (2, 2) and scene.robots[7].scene() is scene
    scene.remove("robot", 7)
    scene.remove("shelf", 20)
    assert 7 not in scene.robots and 20 not in scene.shelves
    tag = scene.stations[1].tag                  # the station's tag is drawn above robots
    assert tag.scene() is scene and tag.zValue() > scene.robots[1].zValue()
    scene.stations[1].setPos(style.centre((2, 2)))
    assert style.cell_at(tag.pos()) == (2, 2)    # and follows it
    scene.remove("station", 1)
    assert tag.scene() is None
    assert sum(1 for item in scene.items() if getattr(item, "kind", "") == "robot") == 3


@pytest.mark.parametrize("instance_path, plan_path", PLANNED)
def test_items_sit_where_the_simulator_says_at_every_step(qapp, instance_path, plan_path):
    instance, plan, scene, track, animator = build(instance_path, plan_path)
    timeline = simulate(instance, plan)
    assert track.horizon == timeline.horizon == plan.horizon
    for step in list(range(timeline.horizon + 1)) + [3, 0]:  # forwards, then jumps back
        animator.show(step)
        state = timeline.state(step)
        for robot, cell in state.robots.items():
            assert cell_of(scene.robots[robot]) == cell, (step, robot)
        for shelf, cell in state.shelves.items():
            assert cell_of(scene.shelves[shelf]) == cell, (step, shelf)
        carried = set(state.carries.values())
        for shelf, item in scene.shelves.items():
            assert item.carried == (shelf in carried), (step, shelf)
            if item.carried:
                carrier = next(r for r, s in state.carries.items() if s == shelf)
                assert item.carrier == scene.robots[carrier].colour


def test_hand_checked_positions_of_outcome(qapp):
    _instance, _plan, scene, _track, animator = build(OUTCOME, OUTCOME)
    animator.show(4)  # robot 3 went up three cells and lifted shelf 1 at (3,3)
    assert cell_of(scene.robots[3]) == (3, 3)
    assert scene.shelves[1].carried and not scene.shelves[2].carried
    animator.show(8)  # robot 1: right x4, up x3, picks up shelf 2 at (5,3)
    assert cell_of(scene.robots[1]) == (5, 3) and scene.shelves[2].carried
    animator.show(0)
    assert not any(item.carried for item in scene.shelves.values())


def test_in_between_frames_interpolate_and_show_badges(qapp):
    _instance, _plan, scene, _track, animator = build(OUTCOME, OUTCOME)
    animator.show(0.25)  # step 1: robot 1 moves right, robots 2 and 3 move up
    assert cell_of(scene.robots[1]) == (1.25, 6)
    assert cell_of(scene.robots[2]) == (2, 5.75)
    animator.show(7.5)  # step 8: robot 1 picks up, robot 3 delivers
    badges = [item for item in scene.items() if isinstance(item, Badge)]
    assert sorted(badge.label.text() for badge in badges) == ["+1 × product 4", "↑ pick up"]
    animator.show(8)
    assert not any(isinstance(item, Badge) for item in scene.items())


def test_violations_mark_their_objects_at_their_step(qapp):
    _instance, _plan, scene, track, animator = build(WRONG_OUTCOME, WRONG_OUTCOME)
    animator.show(22)
    assert not any(item.flagged for item in scene.objects())
    animator.show(23)
    assert [r for r, item in scene.robots.items() if item.flagged] == [1]
    assert [s for s, item in scene.shelves.items() if item.flagged] == [2]
    animator.show(24)
    assert not any(item.flagged for item in scene.objects())
    animator.highlight(track.violations[0])  # stays marked at any time
    assert scene.robots[1].flagged
    animator.highlight(None)
    assert not scene.robots[1].flagged


def test_robot_off_the_floor_is_drawn_and_flagged(qapp):
    instance = Instance(nodes={1: (1, 1), 2: (2, 1)}, robots={1: Robot(1, (2, 1))})
    plan = Plan([Action(1, 1, "move", (1, 0)), Action(2, 1, "move", (0, 1))])
    scene = WarehouseScene(instance)
    track = Track(instance, plan)
    animator = Animator(scene, track)
    animator.show(2)
    assert cell_of(scene.robots[1]) == (3, 2)
    assert scene.robots[1].flagged
    assert scene.picture_rect().contains(scene.robots[1].pos())
    marked = {style.cell_at(mark.rect().center()) for mark in scene.items() if isinstance(mark, CellMark)}
    assert track.violations and all(v.step <= 2 for v in track.violations)
    assert marked <= {(3, 1), (3, 2)}
    animator.show(0)
    assert not scene.robots[1].flagged


def test_trails_follow_the_path_of_selected_robots(qapp):
    _instance, _plan, scene, track, _animator = build(OUTCOME, OUTCOME)
    trails = Trails(scene, track)
    trails.show([3], step=0)
    cells = [style.cell_at(point) for point in trails._points(3, 0, None)]
    assert cells[:4] == [(3, 6), (3, 5), (3, 4), (3, 3)]   # waits and pickups add no points
    path = trails._items[3].path()
    assert path.elementCount() > len(cells)                 # a polyline and the goal ring
    trails.show([3], step=29)
    assert trails._items[3].path().isEmpty()                # nothing remains at the end
    trails.show([3], step=29, mode=PathMode.WHOLE)
    assert not trails._items[3].past.path().isEmpty()
    trails.show([])
    assert not trails._items


def test_coarse_detail_draws_resting_shelves_as_one_layer(qapp):
    instance, plan, scene, track, animator = build(OUTCOME, OUTCOME)
    timeline = simulate(instance, plan)
    scene.set_detail(False)
    animator.show_goals(False)  # (a shelf an open order needs is framed as an item of its own)
    for step in (0, 29, 5, 18, 0):  # jumps: shelves were carried away and put down meanwhile
        animator.show(step)
        state = timeline.state(step)
        path = scene.shelf_layer.path()
        corners = [path.elementAt(i) for i in range(0, path.elementCount(), 5)]  # a rect: 5 elements
        drawn = {style.cell_at(QPointF(corner.x + 1, corner.y + 1)) for corner in corners}
        resting = {cell for shelf, cell in state.shelves.items() if shelf not in state.carries.values()}
        assert drawn == resting, step
        assert all(item.isVisible() == item.carried for item in scene.shelves.values())
    scene.set_detail(True)
    assert not scene.shelf_layer.isVisible() and all(item.isVisible() for item in scene.shelves.values())
