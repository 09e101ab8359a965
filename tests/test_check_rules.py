"""One minimal case per check: the ASP checker and the simulator both report exactly the
expected ``err/3`` atoms.  Where a rule cannot break alone (two robots picking up one
shelf stand on one node), the expected set names the companion violation too.
"""

from __future__ import annotations

import pytest
from helpers.worlds import plan, walk, world

from asprilo.checker.programs import err_atoms
from asprilo.domain import Domain
from asprilo.model import Destination, PickingStation, Shelf
from asprilo.simulate import simulate

A, B, C, M, MD = Domain.A, Domain.B, Domain.C, Domain.M, Domain.MD


def _moved(instance, robot=None, shelf=None, station=None):
    """``instance`` with robot 1, shelf 1 or picking station 1 put at a cell (made if missing)."""
    if robot is not None:
        instance.robots[1].at = robot
    if shelf is not None:
        instance.shelves[1] = Shelf(1, shelf)
    if station is not None:
        instance.stations[1] = PickingStation(1, station)
    return instance


def _add_station(instance, cell):
    """``instance`` with one more picking station on ``cell``."""
    number = max(instance.stations, default=0) + 1
    instance.stations[number] = PickingStation(number, cell)
    return instance


def _with_destinations(instance, *cells):
    """``instance`` with destinations 1, 2, ... on ``cells``."""
    for number, cell in enumerate(cells, 1):
        instance.destinations[number] = Destination(number, cell)
    return instance


def _released(instance, step):
    """``instance`` with order 1 released at ``step`` (an online scenario)."""
    instance.orders[1].release = step
    return instance


def _without_shelf(instance, shelf):
    del instance.shelves[shelf]
    return instance


# A robot under shelf 1 (two units of product 1) next to the station of order 1 (one unit).
def deliveries(shelf_units=2, order_units=1, layout="BP", **more):
    return world(layout, products={1: {1: shelf_units}}, orders={1: ({1: order_units}, 1)}, **more)


FETCH = [(1, 1, "pickup"), (2, 1, "E")]  # lifts shelf 1 and brings it to the station

CASES = {
    # the instance ---------------------------------------------------------------------
    "instance robotOffFloor": (M, _moved(world("R."), robot=(5, 5)), plan(), ["err(instance,robotOffFloor,(1,0))"]),
    "instance shelfOffFloor": (M, _moved(world("R."), shelf=(3, 1)), plan(), ["err(instance,shelfOffFloor,(1,0))"]),
    "instance stationOffFloor": (M, _moved(world("R."), station=(9, 9)), plan(),
                                 ["err(instance,stationOffFloor,(1,0))"]),
    "instance destinationOffFloor": (MD, _with_destinations(world("R."), (9, 9)), plan(),
                                     ["err(instance,destinationOffFloor,(1,0))",
                                      "err(goal,unoccupiedDestination,(1,0))"]),
    "instance stationCollision": (M, _add_station(world("RP."), (2, 1)), plan(),
                                  ["err(instance,stationCollision,(1,2,0))"]),
    "instance destinationCollision": (MD, _with_destinations(world("R."), (2, 1), (2, 1)), plan(),
                                      ["err(instance,destinationCollision,(1,2,0))",
                                       "err(goal,unoccupiedDestination,(1,0))",
                                       "err(goal,unoccupiedDestination,(2,0))"]),
    "instance robotCollision": (M, _moved(world("RR"), robot=(2, 1)), plan(),
                                ["err(instance,robotCollision,(1,2,0))"]),
    "instance shelfCollision": (M, _moved(world("RSS"), shelf=(3, 1)), plan(),
                                ["err(instance,shelfCollision,(1,2,0))"]),
    "instance shelfOnHighway": (M, _moved(world("R#"), shelf=(2, 1)), plan(),
                                ["err(instance,shelfOnHighway,(1,0))"]),
    "instance shelfOnStation": (M, _moved(world("RP"), shelf=(2, 1)), plan(),
                                ["err(instance,shelfOnStation,(1,0))"]),
    "instance carriedShelfElsewhere": (M, world("RS", carries={1: 1}), plan(),
                                       ["err(instance,carriedShelfElsewhere,(1,1,0))"]),
    "instance sharedShelf": (M, _without_shelf(world("BR", carries={1: 1, 2: 1}), 1), plan(),
                             ["err(instance,sharedShelf,(1,0))"]),
    "instance orderStation": (A, world("BP", products={1: {1: 1}}, orders={1: ({1: 0}, None)}), plan(),
                              ["err(instance,orderStation,(1,0))"]),
    "instance unknownStation": (A, world("BP", products={1: {1: 1}}, orders={1: ({1: 0}, 7)}), plan(),
                                ["err(instance,unknownStation,(1,7,0))"]),
    "instance unknownProduct": (A, world("BP", products={1: {1: 1}}, orders={1: ({5: 0}, 1)}), plan(),
                                ["err(instance,unknownProduct,(1,5,0))"]),
    # the plan's actions ---------------------------------------------------------------
    "action notRobot": (M, world("RS."), plan((1, ("shelf", 1), "move", (1, 0))),
                        ["err(action,notRobot,(shelf,1,1))"]),
    "action unknownRobot": (M, world("R."), plan((1, 7, "E")), ["err(action,unknownRobot,(7,1))"]),
    "action badStep": (M, world("R."), plan((0, 1, "E")), ["err(action,badStep,(1,0))"]),
    "action unknownAction": (A, world("R."), plan((1, 1, "jump")), ["err(action,unknownAction,(1,jump,1))"]),
    "action unknownAction in M": (M, world("B."), plan((1, 1, "pickup")),
                                  ["err(action,unknownAction,(1,pickup,1))"]),
    "action badArguments": (M, world("R.."), plan((1, 1, "move", (2, 0))),
                            ["err(action,badArguments,(1,move,1))"]),
    "action badArguments deliver without units in A": (A, deliveries(), plan(*FETCH, (3, 1, "deliver", (1, 1)),
                                                                           (4, 1, "deliver", (1, 1, 1))),
                                                        ["err(action,badArguments,(1,deliver,3))"]),
    "action concurrent": (A, world("B."), plan((1, 1, "E"), (1, 1, "pickup")),
                          ["err(action,concurrent,(1,1))"]),
    # collisions -----------------------------------------------------------------------
    "collision sameNode": (M, world("R.R"), plan((1, 1, "E"), (1, 2, "W")), ["err(collision,sameNode,(1,2,1))"]),
    "collision swap": (M, world("RR"), plan((1, 1, "E"), (1, 2, "W")), ["err(collision,swap,(1,2,1))"]),
    # move -----------------------------------------------------------------------------
    "move offFloor": (M, world("R"), plan((1, 1, "N")), ["err(move,offFloor,(1,1))"]),
    "move ontoShelf": (A, world("BS"), plan((1, 1, "pickup"), (2, 1, "E")), ["err(move,ontoShelf,(1,2))"]),
    # pickup ---------------------------------------------------------------------------
    "pickup carrying": (A, world("B", carries={1: 1}), plan((1, 1, "pickup")), ["err(pickup,carrying,(1,1))"]),
    "pickup noShelf": (A, world("R"), plan((1, 1, "pickup")), ["err(pickup,noShelf,(1,1))"]),
    "pickup sharedShelf": (A, world("RB"), plan((1, 1, "E"), (2, 1, "pickup"), (2, 2, "pickup")),
                           ["err(collision,sameNode,(1,2,1))", "err(collision,sameNode,(1,2,2))",
                            "err(pickup,sharedShelf,(1,2))"]),
    # putdown --------------------------------------------------------------------------
    "putdown notCarrying": (A, world("R"), plan((1, 1, "putdown")), ["err(putdown,notCarrying,(1,1))"]),
    "putdown onHighway": (A, world("B#"), plan((1, 1, "pickup"), (2, 1, "E"), (3, 1, "putdown")),
                          ["err(putdown,onHighway,(1,3))"]),
    "putdown onStation": (A, world("BP"), plan((1, 1, "pickup"), (2, 1, "E"), (3, 1, "putdown")),
                          ["err(putdown,onStation,(1,3))"]),
    "putdown offFloor": (A, world("B", carries={1: 1}), plan((1, 1, "N"), (2, 1, "putdown")),
                         ["err(move,offFloor,(1,1))", "err(putdown,offFloor,(1,2))"]),
    "putdown ontoShelf": (A, world("BS"), plan((1, 1, "pickup"), (2, 1, "E"), (3, 1, "putdown")),
                          ["err(move,ontoShelf,(1,2))", "err(putdown,ontoShelf,(1,3))"]),
    # deliver: where the faulty delivery does not spoil the order, a valid one fulfils it
    "deliver notCarrying": (A, _moved(world("R.", products={1: {1: 2}}, orders={1: ({1: 1}, 1)}),
                                      station=(1, 1), shelf=(2, 1)),
                            plan((1, 1, "deliver", (1, 1, 1)), (2, 1, "E"), (3, 1, "pickup"), (4, 1, "W"),
                                 (5, 1, "deliver", (1, 1, 1))),
                            ["err(deliver,notCarrying,(1,1))"]),
    "deliver unknownOrder": (A, deliveries(), plan(*FETCH, (3, 1, "deliver", (9, 1, 1)), (4, 1, "deliver", (1, 1, 1))),
                             ["err(deliver,unknownOrder,(1,3))"]),
    "deliver wrongStation": (A, deliveries(), plan((1, 1, "pickup"), (2, 1, "deliver", (1, 1, 1)), (3, 1, "E"),
                                                   (4, 1, "deliver", (1, 1, 1))),
                             ["err(deliver,wrongStation,(1,2))"]),
    "deliver wrongStation in B": (B, world("PBP", products={1: {1: None}}, orders={1: ({1: None}, 2)}),
                                  plan((1, 1, "pickup"), (2, 1, "W"), (3, 1, "deliver", (1, 1)), *walk(1, "EE", 4),
                                       (6, 1, "deliver", (1, 1))),
                                  ["err(deliver,wrongStation,(1,3))"]),
    "deliver notOnShelf": (A, world("BPB", products={1: {1: 1}, 2: {2: 1}}, orders={1: ({1: 1, 2: 1}, 1)}),
                           plan(*FETCH, (1, 2, "pickup"), (3, 1, "deliver", (1, 2, 1)), (4, 1, "deliver", (1, 1, 1)),
                                (5, 1, "W"), (6, 2, "W"), (7, 2, "deliver", (1, 2, 1))),
                           ["err(deliver,notOnShelf,(1,3))"]),
    "deliver orderAmount": (A, deliveries(shelf_units=2, order_units=1),
                            plan(*FETCH, (3, 1, "deliver", (1, 1, 2))), ["err(deliver,orderAmount,(1,3))"]),
    "deliver orderAmount of a product not ordered": (A, world("BP", products={1: {1: 1}, 2: {1: 1}},
                                                               orders={1: ({1: 1}, 1)}),
                                                     plan(*FETCH, (3, 1, "deliver", (1, 2, 1)),
                                                          (4, 1, "deliver", (1, 1, 1))),
                                                     ["err(deliver,orderAmount,(1,3))"]),
    "deliver shelfAmount": (A, deliveries(shelf_units=1, order_units=2),
                            plan(*FETCH, (3, 1, "deliver", (1, 1, 2))), ["err(deliver,shelfAmount,(1,3))"]),
    "deliver shelfAmount after the stock ran out": (A, deliveries(shelf_units=1, order_units=2),
                                                    plan(*FETCH, (3, 1, "deliver", (1, 1, 1)),
                                                         (4, 1, "deliver", (1, 1, 1))),
                                                    ["err(deliver,shelfAmount,(1,4))"]),
    "deliver lineClosed in B": (B, deliveries(None, None), plan(*FETCH, (3, 1, "deliver", (1, 1)),
                                                                (4, 1, "deliver", (1, 1))),
                                ["err(deliver,lineClosed,(1,4))"]),
    "deliver lineClosed in C": (C, world("BP", products={1: {1: None}}, orders={1: ({1: None}, 1), 2: ({1: None}, 1)}),
                                plan(*FETCH, (3, 1, "deliver", (1, 1)), (4, 1, "deliver", (2, 1))),
                                ["err(deliver,lineClosed,(1,4))"]),
    # released at step 3: known after step 3, so the delivery at step 3 comes too early
    "deliver beforeRelease in A": (A, _released(deliveries(), 3), plan(*FETCH, (3, 1, "deliver", (1, 1, 1))),
                                   ["err(deliver,beforeRelease,(1,3))"]),
    "deliver beforeRelease in B": (B, _released(deliveries(None, None), 5), plan(*FETCH, (3, 1, "deliver", (1, 1))),
                                   ["err(deliver,beforeRelease,(1,3))"]),
    "deliver beforeRelease in C": (C, _released(deliveries(None, None), 3), plan(*FETCH, (3, 1, "deliver", (1, 1))),
                                   ["err(deliver,beforeRelease,(1,3))"]),
    # the goal ---------------------------------------------------------------------------
    "goal unfilledOrder in A": (A, deliveries(order_units=2), plan(*FETCH, (3, 1, "deliver", (1, 1, 1))),
                                ["err(goal,unfilledOrder,(1,1,1,3))"]),
    "goal unfilledOrder in B": (B, deliveries(None, 3), plan(*FETCH), ["err(goal,unfilledOrder,(1,1,3,2))"]),
    "goal unfilledOrder in C": (C, deliveries(None, None), plan(*FETCH), ["err(goal,unfilledOrder,(1,1,1,2))"]),
    "goal unfilledOrder in M": (M, world("R.S", products={1: {1: 1}}, orders={1: ({1: 1}, None)}),
                                plan((1, 1, "E")), ["err(goal,unfilledOrder,(1,1,1,1))"]),
    # M online (released at step 2): the robot under the shelf at step 2, not after the release
    "goal unfilledOrder in M, reached only at the release": (
        M, _released(world("R.S", products={1: {1: 1}}, orders={1: ({1: 1}, None)}), 2),
        plan(*walk(1, "EE"), (3, 1, "W")), ["err(goal,unfilledOrder,(1,1,1,3))"]),
    "goal unoccupiedDestination": (MD, world("R.D"), plan((1, 1, "E")),
                                   ["err(goal,unoccupiedDestination,(1,1))"]),
}

VALID = {
    "A": (A, deliveries(), plan(*FETCH, (3, 1, "deliver", (1, 1, 1)))),
    "A, released at step 2, delivered at 3": (A, _released(deliveries(), 2),
                                              plan(*FETCH, (3, 1, "deliver", (1, 1, 1)))),
    "A from two shelves": (A, world("BPB", products={1: {1: 1, 2: 1}}, orders={1: ({1: 2}, 1)}),
                           plan(*FETCH, (1, 2, "pickup"), (3, 1, "deliver", (1, 1, 1)), (4, 1, "W"), (5, 2, "W"),
                                (6, 2, "deliver", (1, 1, 1)))),
    "B, units ignored": (B, deliveries(1, 5), plan(*FETCH, (3, 1, "deliver", (1, 1, 7)))),
    "C, one delivery closes the lines of two orders": (
        C, world("BP", products={1: {1: None}, 2: {1: None}}, orders={1: ({1: None}, 1), 2: ({1: None, 2: None}, 1)}),
        plan(*FETCH, (3, 1, "deliver", (2, 2)))),
    "M, a robot under the shelf": (M, world("R.S", products={1: {1: 1}}, orders={1: ({1: 1}, None)}),
                                   plan(*walk(1, "EE"))),
    "M online, a goal once reached stays reached": (M, _released(world("R.S", products={1: {1: 1}},
                                                                       orders={1: ({1: 1}, None)}), 1),
                                                    plan(*walk(1, "EE"), (3, 1, "W"))),
    "Md": (MD, world("R.D"), plan(*walk(1, "EE"))),
    "a robot drives under a resting shelf": (A, world("RS"), plan((1, 1, "E"), (2, 1, "W"))),
}


def _both(domain, instance, steps):
    checker = sorted(str(atom) for atom in err_atoms(instance, steps, domain)[0])
    simulator = sorted(v.atom for v in simulate(instance, steps, domain).violations)
    return checker, simulator


@pytest.mark.parametrize("name", CASES)
def test_each_check_alone(name):
    domain, instance, steps, expected = CASES[name]
    checker, simulator = _both(domain, instance, steps)
    assert checker == sorted(expected)
    assert simulator == sorted(expected)


@pytest.mark.parametrize("name", VALID)
def test_valid_plans(name):
    domain, instance, steps = VALID[name]
    assert _both(domain, instance, steps) == ([], [])
