"""The editor refuses exactly the edits that the ASP checker's instance rules reject.

Differential: on random small floors, every placement, move and floor change the editor
accepts leaves the checker's ``err(instance,...)`` atoms as they were (none new), and every
one it refuses adds one.  The editor applies the simulator's rules
(:func:`asprilo.simulate.checks.check_instance`); the checker is instance.lp.
"""

from __future__ import annotations

import contextlib
import copy
import random
from functools import partial

import pytest

from asprilo.checker.programs import err_atoms
from asprilo.domain import Domain
from asprilo.model import Instance, Plan, Shelf
from asprilo.visualizer.state import edits
from asprilo.visualizer.state.edits import EditRefused

KINDS = ["robot", "shelf", "station", "destination"]
WIDTH, HEIGHT = 3, 3


def _checker_errors(instance: Instance) -> set[str]:
    atoms, _ = err_atoms(instance, Plan([]), Domain.M)
    return {str(atom) for atom in atoms if atom.arguments[0].name == "instance"}


def _random_floor(rng: random.Random) -> Instance:
    """A 3x3 floor with a few walls and highways and a few objects, every edit checked."""
    floor = edits.grid(WIDTH, HEIGHT)
    for _ in range(rng.randint(0, 3)):
        _try(floor, lambda: edits.set_floor(floor, _cell(rng), rng.choice(["highway", "missing"])))
    for _ in range(rng.randint(0, 6)):
        _try(floor, lambda: edits.add_object(floor, rng.choice(KINDS), _cell(rng)))
    for robot in floor.robots.values():
        shelf = next((s for s in floor.shelves.values() if s.at == robot.at), None)
        if shelf is not None and rng.random() < 0.5:
            _try(floor, lambda robot=robot, shelf=shelf: edits.set_carries(floor, robot.id, shelf.id))
    return floor


def _cell(rng: random.Random) -> tuple[int, int]:
    return rng.randint(1, WIDTH), rng.randint(1, HEIGHT)


def _try(instance: Instance, edit) -> None:
    with contextlib.suppress(EditRefused):
        edits.apply(instance, edit())


def _placed(instance: Instance, kind: str, cell) -> Instance:
    """``instance`` with a new object of ``kind`` on ``cell``, unchecked."""
    after = copy.deepcopy(instance)
    table = getattr(after, edits.TABLES[kind])
    ident = edits.next_id(table)
    table[ident] = edits._MAKERS[kind](ident, cell)
    return after


def _moved(instance: Instance, kind: str, ident: int, cell) -> Instance:
    """``instance`` with an object (and a robot's shelf, a shelf's robot) moved, unchecked."""
    after = copy.deepcopy(instance)
    if kind == "shelf" and (robot := edits.carrier_of(after, ident)) is not None:
        kind, ident = "robot", robot
    getattr(after, edits.TABLES[kind])[ident].at = cell
    if kind == "robot" and after.robots[ident].carries in after.shelves:
        after.shelves[after.robots[ident].carries] = Shelf(after.robots[ident].carries, cell)
    return after


def _floored(instance: Instance, cell, kind: str) -> Instance:
    after = copy.deepcopy(instance)
    after.nodes = {i: c for i, c in after.nodes.items() if c != cell}
    after.highways = {i: c for i, c in after.highways.items() if c != cell}
    if kind != "missing":
        after.nodes[max(after.nodes, default=0) + 1] = cell
    if kind == "highway":
        after.highways[max(after.highways, default=0) + 1] = cell
    return after


def _agrees(instance: Instance, edit, unchecked: Instance) -> str:
    """Whether the editor's verdict on ``edit`` is the checker's on the edited instance."""
    new = _checker_errors(unchecked) - _checker_errors(instance)
    try:
        edit()
    except EditRefused as refused:
        assert new, f"refused although the checker finds nothing new: {refused}"
        return "refused"
    assert not new, f"accepted although the checker finds {sorted(new)}"
    return "accepted"


@pytest.mark.parametrize("seed", range(12))
def test_the_editor_refuses_what_the_checker_rejects(seed):
    rng = random.Random(seed)
    verdicts = []
    for _ in range(25):
        instance = _random_floor(rng)
        cell = _cell(rng)
        kind = rng.choice(KINDS)
        verdicts.append(_agrees(instance, partial(edits.add_object, instance, kind, cell),
                                _placed(instance, kind, cell)))
        objects = [(k, i) for k in KINDS for i in getattr(instance, edits.TABLES[k])]
        if objects:
            kind, ident = rng.choice(objects)
            verdicts.append(_agrees(instance, partial(edits.move_object, instance, kind, ident, cell),
                                    _moved(instance, kind, ident, cell)))
        floor = rng.choice(edits.FLOOR_KINDS)
        if edits.floor_kind(instance, cell) != floor:
            verdicts.append(_agrees(instance, partial(edits.set_floor, instance, cell, floor),
                                    _floored(instance, cell, floor)))
    assert "refused" in verdicts and "accepted" in verdicts
