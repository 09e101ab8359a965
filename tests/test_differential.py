"""The ASP checker and the plain-Python simulator are two independent implementations of
SPEC.md §4: on random and mutated plans, on small random instances of every domain, they
must report exactly the same violations (compared as ``err/3`` atoms).

Hypothesis picks the domain, how plans reach clingo (packed or plain ``occurs/3``) and a
seeded random generator that builds the case (cheap to draw, and a failing case prints
its seed).  The default run checks 2,100 cases (850 random plans, 850 guided plans, 400
mutations of a valid plan); ``pytest -m slow`` checks 40,000 more.
"""

from __future__ import annotations

import random

import pytest
from helpers import OUTCOME, SMALL_A
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from asprilo.checker.programs import err_atoms
from asprilo.domain import Domain, domains
from asprilo.model import DIRECTIONS, Action, Destination, Instance, Order, PickingStation, Plan, Product, Robot, Shelf
from asprilo.reader import read_instance, read_plan
from asprilo.simulate import simulate

NAMES = ["move"] * 6 + ["pickup", "putdown"] * 2 + ["deliver"] * 3 + ["wait"]
OFF_FLOOR = (0, 1)


# --- instances ---------------------------------------------------------------------------

def random_instance(rng: random.Random, domain: Domain, clean: bool) -> Instance:
    """A tiny warehouse: a partial grid of up to 4x3 nodes, up to 3 robots, 4 shelves,
    2 stations, 3 products and 2 orders.  Unless ``clean``, objects may stand off the floor
    or on one node, robots carry shelves that are elsewhere, orders name unknown products
    and stations, and so on."""
    instance = _random_floor(rng, clean)
    spare = _random_robots_and_shelves(rng, instance, clean)
    _random_stock_and_orders(rng, instance, domain, clean, spare)
    _random_goals(rng, instance, domain)
    return instance


def _random_floor(rng: random.Random, clean: bool) -> Instance:
    """Nodes, highways and picking stations."""
    width, height = rng.randint(1, 4), rng.randint(1, 3)
    grid = [(x, y) for y in range(1, height + 1) for x in range(1, width + 1)]
    nodes = [cell for cell in grid if rng.randint(0, 5)] or grid[:1]
    instance = Instance(nodes=dict(enumerate(nodes, start=1)))
    instance.highways = {i: cell for i, cell in instance.nodes.items() if rng.randint(0, 3) == 0}
    for station in range(1, rng.randint(int(clean), 2) + 1):
        instance.stations[station] = PickingStation(station, rng.choice(nodes + [OFF_FLOOR] * (not clean)))
    return instance


def _random_robots_and_shelves(rng: random.Random, instance: Instance, clean: bool) -> list[int]:
    """Robots, shelves and what robots carry; the ids of shelves the instance lacks."""
    nodes = list(instance.nodes.values())
    blocked = set(instance.highways.values()) | {s.at for s in instance.stations.values()}

    def places(count: int, storage: bool) -> list:
        if not clean:
            return [rng.choice(nodes + [OFF_FLOOR]) for _ in range(count)]
        free = [cell for cell in nodes if not storage or cell not in blocked]
        return rng.sample(free, min(count, len(free)))

    for robot, cell in enumerate(places(rng.randint(1, 3), storage=False) or nodes[:1], start=1):
        instance.robots[robot] = Robot(robot, cell)
    for shelf, cell in enumerate(places(rng.randint(int(clean), 4), storage=True), start=1):
        instance.shelves[shelf] = Shelf(shelf, cell)
    shelves = list(instance.shelves) or [1]
    spare = [] if clean else [9]  # a shelf the instance does not have
    if not clean:
        for robot in instance.robots.values():
            if rng.randint(0, 4) == 0:
                robot.carries = rng.choice(shelves + spare)
    return spare


def _random_stock_and_orders(rng: random.Random, instance: Instance, domain: Domain, clean: bool,
                             spare: list[int]) -> None:
    shelves = list(instance.shelves) or [1]
    quantities = domain is Domain.A or rng.randint(0, 3) == 0

    def units():
        return rng.randint(int(clean), 4) if quantities else None

    for product in range(1, rng.randint(int(clean), 3) + 1):
        on = rng.sample(shelves + spare, rng.randint(int(clean), min(2, len(shelves + spare))))
        instance.products[product] = Product(product, {shelf: units() for shelf in on})
    stations = list(instance.stations) + ([] if clean else [None, 7])
    products = list(instance.products) if clean and instance.products else [1, 2, 3, 4]
    for order in range(1, rng.randint(int(clean), 2) + 1):
        if stations:
            lines = {rng.choice(products): units() for _ in range(rng.randint(1, 2))}
            instance.orders[order] = Order(order, lines, rng.choice(stations))


def _random_goals(rng: random.Random, instance: Instance, domain: Domain) -> None:
    """Md destinations; labelled goals now and then (M, Md)."""
    if domain is Domain.MD:
        for destination in range(1, rng.randint(1, 2) + 1):
            instance.destinations[destination] = Destination(destination, rng.choice(list(instance.nodes.values())))
    goals = {Domain.MD: ("destination", instance.destinations), Domain.M: ("shelf", instance.shelves)}
    if domain in goals and goals[domain][1] and rng.randint(0, 2) == 0:  # labelled goals
        kind, table = goals[domain]
        for robot in instance.robots:
            if rng.randint(0, 2):
                instance.assignment[robot] = (kind, rng.choice(list(table)))


# --- plans -------------------------------------------------------------------------------

def _arguments(rng: random.Random, name: str, instance: Instance):
    if name == "move":
        return rng.choice(list(DIRECTIONS) * 4 + [(2, 0), (), "north", (1, 0, 0)])
    if name in ("pickup", "putdown"):
        return rng.choice([(), (), (), (1,)])
    order, product, shape = rng.choice(list(instance.orders) + [5]), rng.randint(1, 4), rng.randint(0, 4)
    if shape == 0:
        return (order, product)
    if shape == 1:
        return "x"
    return (order, product, rng.randint(-1, 4))


def random_plan(rng: random.Random, instance: Instance) -> Plan:
    """Any actions at all: mostly by robots of the instance at steps 1..5, now and then by
    other objects, at steps <= 0, with unknown names or ill-shaped arguments."""
    robots = list(instance.robots) * 3 + [8]
    actions = []
    for _ in range(rng.randint(0, 12)):
        step = rng.randint(1, 5) if rng.randint(0, 3) else rng.randint(-1, 0)
        name = rng.choice(NAMES)
        actions.append(Action(step, rng.choice(robots), name, _arguments(rng, name, instance),
                              "shelf" if rng.randint(0, 15) == 0 else "robot"))
    return Plan(actions)


def guided_plan(rng: random.Random, instance: Instance) -> Plan:
    """Plans that mostly make sense (robots head for shelves, lift them, carry them to a
    station and deliver ordered products they hold), so that later steps get to check deep
    state; with a slip or two (an action dropped or moved, renamed, to another step)."""
    position = {r.id: r.at for r in instance.robots.values()}
    resting = {s.id: s.at for s in instance.shelves.values()}
    carried = {r.id: r.carries for r in instance.robots.values() if r.carries is not None}
    for shelf in carried.values():
        resting.pop(shelf, None)
    actions = []
    for step in range(1, rng.randint(1, 10) + 1):
        for robot in instance.robots:
            action = _guided_action(rng, instance, step, robot, (position, resting, carried))
            if action is not None:
                actions.append(action)
    for _ in range(rng.randint(0, 2)):
        if actions:
            slip = actions.pop(rng.randrange(len(actions)))
            if rng.randint(0, 1):
                actions.append(Action(rng.randint(0, slip.step + 1), slip.robot, rng.choice(NAMES), slip.args))
    return Plan(actions)


def _guided_action(rng: random.Random, instance: Instance, step: int, robot: int, world: tuple) -> Action | None:
    """What ``robot`` does at ``step``: deliver, pick up, put down, move or wait; ``world``
    (positions, resting shelves, carried shelves) follows the action."""
    position, resting, carried = world
    here, shelf, choice = position[robot], carried.get(robot), rng.randint(0, 9)
    orders = [o for o in instance.orders.values()
              if o.station in instance.stations and instance.stations[o.station].at == here]
    if shelf is not None and orders and choice < 6:
        order = rng.choice(orders)
        products = sorted(set(order.lines) & set(instance.shelf_stock().get(shelf, {}))) or list(order.lines)
        return Action(step, robot, "deliver", (order.id, rng.choice(products), rng.randint(1, 3)))
    if shelf is None and here in resting.values() and choice < 6:
        carried[robot] = next(s for s, cell in resting.items() if cell == here)
        del resting[carried[robot]]
        return Action(step, robot, "pickup", ())
    if shelf is not None and choice == 6:
        resting[carried.pop(robot)] = here
        return Action(step, robot, "putdown", ())
    if choice < 9:
        goals = [s.at for s in instance.stations.values()] if shelf is not None else list(resting.values())
        direction = _step_towards(rng, here, instance.cells, choice < 7, goals)
        position[robot] = (here[0] + direction[0], here[1] + direction[1])
        return Action(step, robot, "move", direction)
    return None


def _step_towards(rng: random.Random, here, cells, purposeful: bool, goals: list):
    """A direction onto the floor, towards the nearest goal when ``purposeful``."""
    x, y = here
    options = [d for d in DIRECTIONS if (x + d[0], y + d[1]) in cells] or list(DIRECTIONS)
    if goals and purposeful:
        gx, gy = min(goals, key=lambda g: abs(g[0] - x) + abs(g[1] - y))
        options = [d for d in options if abs(gx - x - d[0]) + abs(gy - y - d[1]) < abs(gx - x) + abs(gy - y)] \
            or options
    return rng.choice(options)


_OUTCOME = (read_instance(SMALL_A), read_plan(OUTCOME))


def mutated_outcome(rng: random.Random) -> Plan:
    """The valid 29-step plan of the paper's example with a few actions dropped, moved to
    another step, given to another robot or changed in their name, units or arguments."""
    actions = list(_OUTCOME[1].actions)
    for _ in range(rng.randint(1, 3)):
        index = rng.randrange(len(actions))
        action, how = actions[index], rng.randint(0, 3)
        if how == 0:
            del actions[index]
        elif how == 1:
            actions[index] = Action(rng.randint(0, 30), action.robot, action.name, action.args)
        elif how == 2:
            actions[index] = Action(action.step, rng.randint(1, 4), action.name, action.args)
        elif action.name == "deliver" and len(action.args) == 3:
            order, product, units = action.args
            actions[index] = Action(action.step, action.robot, "deliver", (order, product, units + rng.randint(-2, 2)))
        else:
            actions[index] = Action(action.step, action.robot, rng.choice(NAMES),
                                    rng.choice(list(DIRECTIONS) + [()]))
    return Plan(actions)


# --- the tests ---------------------------------------------------------------------------

def _agree(domain: Domain, instance: Instance, plan: Plan, packed: bool) -> None:
    checker = {str(atom) for atom in err_atoms(instance, plan, domain, packed=packed)[0]}
    simulator = {violation.atom for violation in simulate(instance, plan, domain).violations}
    assert checker == simulator


def _settings(examples: int):
    return settings(max_examples=examples, deadline=None, suppress_health_check=[HealthCheck.too_slow])


domains, seeds, feeds = st.sampled_from(domains()), st.randoms(use_true_random=True), st.booleans()


def check_random_plan(domain, rng, packed):
    instance = random_instance(rng, domain, clean=rng.randint(0, 1) == 1)
    _agree(domain, instance, random_plan(rng, instance), packed)


def check_guided_plan(domain, rng, packed):
    instance = random_instance(rng, domain, clean=rng.randint(0, 3) > 0)
    _agree(domain, instance, guided_plan(rng, instance), packed)


@_settings(850)
@given(domains, seeds, feeds)
def test_random_plans(domain, rng, packed):
    check_random_plan(domain, rng, packed)


@_settings(850)
@given(domains, seeds, feeds)
def test_guided_plans(domain, rng, packed):
    check_guided_plan(domain, rng, packed)


@_settings(400)
@given(st.sampled_from([Domain.A, Domain.B, Domain.C]), seeds, feeds)
def test_mutated_outcome(domain, rng, packed):
    _agree(domain, _OUTCOME[0], mutated_outcome(rng), packed)


@pytest.mark.slow
@_settings(20000)
@given(domains, seeds, feeds)
def test_random_plans_long(domain, rng, packed):
    check_random_plan(domain, rng, packed)


@pytest.mark.slow
@_settings(20000)
@given(domains, seeds, feeds)
def test_guided_plans_long(domain, rng, packed):
    check_guided_plan(domain, rng, packed)
