"""The ways a carried shelf can take past resting shelves, as sets of shelves to move first.

A robot carrying a shelf cannot enter a cell where another shelf rests, so a way shorter
than the way around the resting shelves (:mod:`asprilo.bounds.trip`'s ``clear/3``) needs
*every* shelf on it moved off first.  :func:`passages` lists, for one shelf and station, each
length such a way can have with the fewest shelves in it: the pairs (moves, shelves) that no
other way beats in both (fewer or as many moves, and a subset of its shelves).  Any way
shorter than the way around contains the shelves of one of these pairs, with at least its
moves, so requiring one pair's shelves to be lifted in time is a rule every plan obeys.
"""

from __future__ import annotations

from collections.abc import Mapping

from ..model import DIRECTIONS, Cell

#: the (cell, shelves) states one listing may visit, and all listings of one instance
#: together; beyond them the caller falls back to one shelf per way (each shelf in the way
#: alone, which every plan obeys too)
PASSAGE_STATES = 2_000
INSTANCE_STATES = 40_000


def passages(cells: set[Cell], resting: Mapping[Cell, int], start: Cell, station: Cell,
             near: Mapping[Cell, float], fewer_than: float,
             limit: int = PASSAGE_STATES) -> tuple[list[tuple[int, frozenset[int]]] | None, int]:
    """The pairs (moves, shelves) of the ways from ``start`` to ``station`` with fewer than
    ``fewer_than`` moves, each with the shelves resting on its cells (``resting``: cell ->
    shelf, the carried shelf's own cell left out), none beaten by another; ``near``: each
    cell's floor distance to ``station``.  ``None`` when the listing would visit more than
    ``limit`` states; and the states visited."""
    seen: dict[Cell, list[frozenset[int]]] = {start: [frozenset()]}
    layer = [(start, frozenset[int]())]
    found: list[tuple[int, frozenset[int]]] = []
    states = 1
    moves = 0
    while layer:
        moves += 1
        following = []
        for (x, y), shelves in layer:
            for dx, dy in DIRECTIONS:
                cell = (x + dx, y + dy)
                if cell not in cells or moves + near[cell] >= fewer_than:
                    continue
                held = shelves | {resting[cell]} if cell in resting else shelves
                if cell == station:
                    found.append((moves, held))
                    continue
                known = seen.setdefault(cell, [])
                if any(earlier <= held for earlier in known):
                    continue
                known.append(held)
                following.append((cell, held))
                states += 1
                if states > limit:
                    return None, states
        layer = following
    return _unbeaten(found), states


def _unbeaten(found: list[tuple[int, frozenset[int]]]) -> list[tuple[int, frozenset[int]]]:
    """The pairs of ``found`` that no other pair beats (as few moves or fewer, a subset of
    its shelves), each once."""
    kept: list[tuple[int, frozenset[int]]] = []
    for moves, shelves in sorted(set(found), key=lambda pair: (pair[0], len(pair[1]), sorted(pair[1]))):
        if not any(earlier <= shelves for _, earlier in kept):
            kept.append((moves, shelves))
    return kept
