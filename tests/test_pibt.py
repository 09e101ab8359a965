"""Single PIBT steps (asprilo/encodings/anytime/pibt.py) worked out by hand on corridors:
priority inheritance, no swaps, LaCAM's fixed moves."""

from __future__ import annotations

import pytest

from asprilo.bounds import Floor
from asprilo.encodings.anytime.pibt import Pibt
from asprilo.encodings.anytime.roadmap import Roadmap

LINE = Roadmap(Floor([(x, 1) for x in range(1, 5)]))


def _cells(roadmap: Roadmap, vertices: list[int] | None) -> list[tuple[int, int]] | None:
    return None if vertices is None else [roadmap.cells[vertex] for vertex in vertices]


@pytest.mark.parametrize("seed", range(5))
def test_a_robot_pushes_the_one_in_its_way_on_ahead(seed):
    # robot 0 on (1,1) wants (4,1); robot 1 stands on its goal (2,1), in the way.  Robot 0
    # takes (2,1); robot 1, pushed, may not go to (1,1) (the two would swap) and cannot stay:
    # by hand it goes on to (3,1), whatever the ties
    v = LINE.vertex
    pibt = Pibt(LINE, [v((4, 1)), v((2, 1))], seed)
    assert _cells(LINE, pibt.step([v((1, 1)), v((2, 1))], [0, 1])) == [(2, 1), (3, 1)]


def test_a_robot_at_its_goal_stays_when_nobody_pushes():
    v = LINE.vertex
    pibt = Pibt(LINE, [v((4, 1)), v((1, 1))])
    # robot 1 on its goal (1,1) first, robot 0 on (3,1) heading for (4,1): both by hand
    assert _cells(LINE, pibt.step([v((3, 1)), v((1, 1))], [1, 0])) == [(4, 1), (1, 1)]


def test_fixed_moves_onto_one_vertex_or_swapping_give_no_step():
    v = LINE.vertex
    pibt = Pibt(LINE, [v((4, 1)), v((1, 1))])
    at = [v((2, 1)), v((3, 1))]
    assert pibt.step(at, [0, 1], [(0, v((3, 1))), (1, v((2, 1)))]) is None  # a swap
    assert pibt.step(at, [0, 1], [(0, v((3, 1))), (1, v((3, 1)))]) is None  # one vertex
    # a fixed move the other robot cannot give way to: robot 1 on (3,1) must leave it, to
    # (4,1) (not (2,1), robot 0's, a swap): by hand the step is [(3,1), (4,1)]
    assert _cells(LINE, pibt.step(at, [1, 0], [(0, v((3, 1)))])) == [(3, 1), (4, 1)]
