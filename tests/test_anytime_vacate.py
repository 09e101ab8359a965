"""A shelf put down on the cell another shelf has left for good (issue 45: the ``vacate``
neighbourhood of the anytime planner's search, ``Work.vacated`` and ``Work.offered``).

The floor, derived by hand: station (1,1), highway (2..4,1) and (1,2), a storage cell (5,1);
shelves 1, 2 and 3 on (2,2), (3,2) and (5,2), a storage cell (4,2) between them; the robots
on (1,3) and (2,3) (highway cells).  Robot 1 brings shelf 3 and then shelf 1; robot 2 brings
shelf 2, its last, which it never brings back (it parks with it elsewhere).

Where robot 1 puts shelf 3 down after its delivery on (1,1), counted as the steps carrying it
there from the station plus the steps walking on to shelf 1 (2,2):
- (4,2), spare: E E E S, 4, then W W, 2: 6;
- (5,1), spare: 4, then 4: 8;
- its own cell (5,2), entered from (5,1) or (4,2): 5, then 3: 8;
- (3,2), the cell of shelf 2, entered from (3,1): 3, then W, 1: 4.
So it goes on (4,2), and on (3,2) once that cell is offered.
"""

from __future__ import annotations

from helpers.worlds import world

from asprilo.bounds import Floor
from asprilo.domain import Domain
from asprilo.encodings.anytime.errands import Trip
from asprilo.encodings.anytime.grid import Grid
from asprilo.encodings.anytime.work import Work


def _work() -> Work:
    instance = world("P###./#SS.S/RR", products={1: {1: 1}, 2: {2: 1}, 3: {3: 1}},
                     orders={1: ({1: 1, 2: 1, 3: 1}, 1)})
    for node, cell in instance.nodes.items():
        if cell in ((1, 3), (2, 3)):
            instance.highways[node] = cell
    work = Work(instance, Domain.A, Grid(Floor(instance.cells)), 0)
    work.trips = {1: [Trip(3, [((1, 1), ((1, 3),), (1, 3, 1))]), Trip(1, [((1, 1), ((1, 1),), (1, 1, 1))])],
                  2: [Trip(2, [((1, 1), ((1, 2),), (1, 2, 1))])]}
    return work


def _putdown(work: Work):
    return [task.cells for task in work.errand(1, set()) if task.name == "putdown"]


def test_the_cells_left_for_good_are_those_of_other_robots_last_shelves():
    work = _work()
    assert work.vacated({3, 1}) == [(3, 2)]
    assert work.vacated() == [(2, 2), (3, 2)]  # shelf 1 is robot 1's last


def test_a_shelf_goes_on_a_cell_left_for_good_only_once_it_is_offered():
    work = _work()
    assert _putdown(work) == [((4, 2),)]
    work.offered = frozenset({(3, 2)})
    assert _putdown(work) == [((3, 2),)]
    assert work.claims == {3: (3, 2)}
