"""The ASP checker and the plain-Python simulator are two independent implementations of
SPEC.md §4: on random and mutated plans, on small random instances of every domain, they
must report exactly the same violations (compared as ``err/3`` atoms).

The default run checks 2,100 cases (850 random, 850 guided, 400 mutated); ``pytest -m slow`` runs many more.
"""

from __future__ import annotations

import pytest
from conftest import OUTCOME, SMALL_A
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from asprilo.checker.programs import err_atoms
from asprilo.domain import Domain
from asprilo.model import DIRECTIONS, Action, Destination, Instance, Order, PickingStation, Plan, Product, Robot, Shelf
from asprilo.reader import read_instance, read_plan
from asprilo.simulate import simulate

DOMAINS = list(Domain)
NAMES = ["move"] * 6 + ["pickup", "putdown"] * 2 + ["deliver"] * 3 + ["wait"]


# --- instances ---------------------------------------------------------------------------

@st.composite
def instances(draw, domain: Domain, clean_odds: int = 1) -> Instance:
    """A tiny warehouse: a partial grid of up to 4x3 nodes, up to 3 robots, 4 shelves,
    2 stations, 3 products and 2 orders; one in ``clean_odds + 1`` has instance errors
    (objects off the floor or on one node, shelves on highways, unknown products ...)."""
    width, height = draw(st.integers(1, 4)), draw(st.integers(1, 3))
    grid = [(x, y) for y in range(1, height + 1) for x in range(1, width + 1)]
    nodes = [cell for cell in grid if draw(st.integers(0, 5))] or grid[:1]
    clean = draw(st.integers(0, clean_odds)) > 0
    instance = Instance()
    instance.nodes = dict(enumerate(nodes, start=1))
    instance.highways = {i: cell for i, cell in instance.nodes.items() if draw(st.integers(0, 3)) == 0}
    free = list(nodes)

    def place(storage: bool = False):
        if not clean:
            return draw(st.sampled_from(nodes + [(0, 1)]))
        blocked = set(instance.highways.values()) | {s.at for s in instance.stations.values()}
        options = [cell for cell in free if not storage or cell not in blocked]
        if not options:
            return None
        cell = draw(st.sampled_from(options))
        free.remove(cell)
        return cell

    for station in range(1, draw(st.integers(0 if not clean else 1, 2)) + 1):
        instance.stations[station] = PickingStation(station, draw(st.sampled_from(nodes + [(0, 1)] * (not clean))))
    for robot in range(1, draw(st.integers(1, 3)) + 1):
        cell = place()
        if cell is not None:
            instance.robots[robot] = Robot(robot, cell)
    if not instance.robots:
        instance.robots[1] = Robot(1, nodes[0])
    free = list(nodes)
    for shelf in range(1, draw(st.integers(int(clean), 4)) + 1):
        cell = place(storage=True)
        if cell is not None:
            instance.shelves[shelf] = Shelf(shelf, cell)
    shelf_ids = list(instance.shelves) or [1]
    spare = [] if clean else [9]
    for robot in instance.robots.values():
        if not clean and draw(st.integers(0, 4)) == 0:
            robot.carries = draw(st.sampled_from(shelf_ids + spare))
    quantities = domain is Domain.A or draw(st.integers(0, 3)) == 0
    units = st.integers(0 if not clean else 1, 4) if quantities else st.none()
    for product in range(1, draw(st.integers(int(clean), 3)) + 1):
        shelves = draw(st.lists(st.sampled_from(shelf_ids + spare), min_size=int(clean), max_size=2, unique=True))
        instance.products[product] = Product(product, {s: draw(units) for s in shelves})
    station_ids = list(instance.stations) + ([None, 7] if not clean else [])
    products = list(instance.products) if clean and instance.products else [1, 2, 3, 4]
    for order in range(1, draw(st.integers(int(clean), 2)) + 1):
        if not station_ids:
            break
        lines = draw(st.dictionaries(st.sampled_from(products), units, min_size=1, max_size=2))
        instance.orders[order] = Order(order, lines, draw(st.sampled_from(station_ids)))
    if domain is Domain.MD:
        for destination in range(1, draw(st.integers(1, 2)) + 1):
            instance.destinations[destination] = Destination(destination, draw(st.sampled_from(nodes)))
    return instance


# --- plans -------------------------------------------------------------------------------

def _arguments(draw, name: str, instance: Instance):
    if name == "move":
        return draw(st.sampled_from(list(DIRECTIONS) * 4 + [(2, 0), (), "north", (1, 0, 0)]))
    if name in ("pickup", "putdown"):
        return draw(st.sampled_from([(), (), (), (1,)]))
    order = draw(st.sampled_from(list(instance.orders) + [5]))
    product = draw(st.integers(1, 4))
    shape = draw(st.integers(0, 4))
    if shape == 0:
        return (order, product)
    if shape == 1:
        return "x"
    return (order, product, draw(st.integers(-1, 4)))


@st.composite
def random_plans(draw, instance: Instance) -> Plan:
    """Any actions at all: mostly by robots of the instance at steps 1..5, now and then by
    other objects, at step 0, with unknown names or ill-shaped arguments."""
    robots = list(instance.robots)
    actions = []
    for _ in range(draw(st.integers(0, 12))):
        step = draw(st.one_of(st.integers(1, 5), st.integers(1, 5), st.integers(1, 5), st.integers(-1, 0)))
        robot = draw(st.one_of(st.sampled_from(robots), st.sampled_from(robots), st.sampled_from(robots),
                               st.just(8)))
        kind = draw(st.sampled_from(["robot"] * 15 + ["shelf"]))
        name = draw(st.sampled_from(NAMES))
        actions.append(Action(step, robot, name, _arguments(draw, name, instance), kind))
    return Plan(actions)


@st.composite
def guided_plans(draw, instance: Instance) -> Plan:
    """Plans that mostly make sense (moves onto nodes, pickups under shelves, deliveries of
    ordered products on the carried shelf at the order's station), so that later steps get
    to check deep state; with a slip now and then."""
    position = {r.id: r.at for r in instance.robots.values()}
    cells = set(instance.nodes.values())
    resting = {s.id: s.at for s in instance.shelves.values()}
    carried = {r.id: r.carries for r in instance.robots.values() if r.carries is not None}
    for shelf in carried.values():
        resting.pop(shelf, None)
    stock = instance.shelf_stock()
    actions = []
    for step in range(1, draw(st.integers(1, 10)) + 1):
        for robot in instance.robots:
            here = position[robot]
            shelf = carried.get(robot)
            orders = [o for o in instance.orders.values() if o.station in instance.stations
                      and instance.stations[o.station].at == here]
            choice = draw(st.integers(0, 9))
            if shelf is not None and orders and choice < 6:
                order = draw(st.sampled_from(orders))
                products = sorted(set(order.lines) & set(stock.get(shelf, {}))) or list(order.lines)
                units = draw(st.integers(1, 3))
                actions.append(Action(step, robot, "deliver", (order.id, draw(st.sampled_from(products)), units)))
            elif shelf is None and here in resting.values() and choice < 6:
                carried[robot] = next(s for s, cell in resting.items() if cell == here)
                del resting[carried[robot]]
                actions.append(Action(step, robot, "pickup", ()))
            elif shelf is not None and choice == 6:
                resting[carried.pop(robot)] = here
                actions.append(Action(step, robot, "putdown", ()))
            elif choice < 9:
                x, y = here
                options = [d for d in DIRECTIONS if (x + d[0], y + d[1]) in cells] or list(DIRECTIONS)
                goals = [s.at for s in instance.stations.values()] if shelf is not None else list(resting.values())
                if goals and choice < 7:  # head for a station with a shelf, for a shelf without
                    goal = min(goals, key=lambda g: abs(g[0] - x) + abs(g[1] - y))
                    closer = [d for d in options if abs(goal[0] - x - d[0]) + abs(goal[1] - y - d[1])
                              < abs(goal[0] - x) + abs(goal[1] - y)]
                    options = closer or options
                direction = draw(st.sampled_from(options))
                position[robot] = (x + direction[0], y + direction[1])
                actions.append(Action(step, robot, "move", direction))
    for _ in range(draw(st.integers(0, 2))):  # slips
        if actions:
            victim = draw(st.sampled_from(actions))
            actions.remove(victim)
            if draw(st.booleans()):
                actions.append(Action(draw(st.integers(0, victim.step + 1)), victim.robot,
                                      draw(st.sampled_from(NAMES)), victim.args))
    return Plan(actions)


@st.composite
def cases(draw, plans=random_plans):
    domain = draw(st.sampled_from(DOMAINS))
    instance = draw(instances(domain, 3 if plans is guided_plans else 1))
    return domain, instance, draw(plans(instance)), draw(st.booleans())


def _agree(domain: Domain, instance: Instance, plan: Plan, packed: bool = True) -> None:
    checker = {str(atom) for atom in err_atoms(instance, plan, domain, packed=packed)[0]}
    simulator = {violation.atom for violation in simulate(instance, plan, domain).violations}
    assert checker == simulator


# --- the tests ---------------------------------------------------------------------------

FAST = settings(max_examples=850, deadline=None, suppress_health_check=[HealthCheck.too_slow])
SLOW = settings(max_examples=20000, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@FAST
@given(cases(random_plans))
def test_random_plans(case):
    _agree(*case)


@FAST
@given(cases(guided_plans))
def test_guided_plans(case):
    _agree(*case)


_OUTCOME = (read_instance(SMALL_A), read_plan(OUTCOME))


@st.composite
def mutated_outcomes(draw):
    """The valid 29-step plan of the paper's example with a few actions dropped, moved to
    another step, given to another robot or changed in their arguments."""
    instance, plan = _OUTCOME
    actions = list(plan.actions)
    for _ in range(draw(st.integers(1, 3))):
        index = draw(st.integers(0, len(actions) - 1))
        action = actions[index]
        how = draw(st.integers(0, 3))
        if how == 0:
            del actions[index]
        elif how == 1:
            actions[index] = Action(draw(st.integers(0, 30)), action.robot, action.name, action.args)
        elif how == 2:
            actions[index] = Action(action.step, draw(st.integers(1, 4)), action.name, action.args)
        elif action.name == "deliver" and len(action.args) == 3:
            order, product, units = action.args
            actions[index] = Action(action.step, action.robot, "deliver",
                                    (order, product, units + draw(st.integers(-2, 2))))
        else:
            actions[index] = Action(action.step, action.robot, draw(st.sampled_from(NAMES)),
                                    draw(st.sampled_from(list(DIRECTIONS) + [()])))
    return draw(st.sampled_from([Domain.A, Domain.B, Domain.C])), instance, Plan(actions)


@settings(max_examples=400, deadline=None)
@given(mutated_outcomes())
def test_mutated_outcome(case):
    _agree(*case)


@pytest.mark.slow
@SLOW
@given(cases(random_plans))
def test_random_plans_long(case):
    _agree(*case)


@pytest.mark.slow
@SLOW
@given(cases(guided_plans))
def test_guided_plans_long(case):
    _agree(*case)
