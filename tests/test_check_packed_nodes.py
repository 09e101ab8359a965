"""The nodes of a large floor reach the checker packed (issue 46, item 7): thirty cells of a
row in one integer (``packedNodes/3``, ``packed.lp``), because clingo keeps every parsed
``init/2`` fact (2 kB a node).  Packed or not, the checker finds the same broken rules."""

from __future__ import annotations

import pytest

from asprilo.checker.programs import PACK_FROM, err_atoms, instance_facts
from asprilo.domain import Domain
from asprilo.model import Action, Instance, Plan, Robot

HOLES = {(0, 0), (31, 1), (-6, -2)}
#: 71 x 5 cells less three holes; rows cross the packing's blocks of thirty (x = -35, -5, 25)
CELLS = [(x, y) for y in range(-2, 3) for x in range(-35, 36) if (x, y) not in HOLES]
#: robot -> (start, move at step 1): into a hole, out of the floor on three sides, onto a node
ROBOTS = {1: ((-1, 0), (1, 0)), 2: ((30, 1), (1, 0)), 3: ((35, 2), (0, 1)), 4: ((-35, -2), (-1, 0)),
          5: ((24, -1), (1, 0)), 6: ((-5, -2), (-1, 0))}


def _instance(copies: int = 1) -> Instance:
    nodes = {i + 1: cell for i, cell in enumerate(CELLS * copies)}
    return Instance(nodes=nodes, robots={r: Robot(r, start) for r, (start, _move) in ROBOTS.items()})


def _plan(robot: int) -> Plan:
    return Plan([Action(1, robot, "move", ROBOTS[robot][1])])


#: robot 1 goes into the hole (0,0), 2 into (31,1), 3 above the top row, 4 left of the first
#: column, 6 into (-6,-2); robot 5 from (24,-1) onto the node (25,-1)
OFF = {1: True, 2: True, 3: True, 4: True, 5: False, 6: True}


@pytest.mark.parametrize("packed", [True, False])
@pytest.mark.parametrize("robot", sorted(ROBOTS))
def test_moves_off_the_floor_are_found_packed_or_not(robot, packed):
    atoms = [str(atom) for atom in err_atoms(_instance(), _plan(robot), Domain.M, packed=packed)[0]]
    assert atoms == ([f"err(move,offFloor,({robot},1))"] if OFF[robot] else [])


def test_large_floors_are_packed_by_default_and_a_cell_given_twice_is_one_node():
    assert len(CELLS) == 352 and len(CELLS) * 6 >= PACK_FROM
    facts = instance_facts(_instance(6)).splitlines()  # every cell given six times
    assert [f for f in facts if f.startswith("init(object(node,")] == []
    assert len([f for f in facts if f.startswith("packedNodes(")]) == 5 * 3  # 5 rows, 3 blocks of 30 each
    assert [str(atom) for atom in err_atoms(_instance(6), _plan(2), Domain.M)[0]] == ["err(move,offFloor,(2,1))"]
    assert [str(atom) for atom in err_atoms(_instance(6), _plan(5), Domain.M)[0]] == []
