"""The A/B/C encodings lose no plan: their minimal makespans equal independent ones.

- On the tiniest instances, a brute-force search over all joint moves (tests/oracles/brute_force.py).
- On random small ones, the previous identity-based encoding (tests/oracles/identity-abc/).
- Each pruning technique switched off (-c bands=0, -c deadlines=0) gives the same minimum.
- The makespan bound never exceeds the minimum.
- A shelf that serves lines at two stations keeps its name until its last delivery.
"""

from __future__ import annotations

import pytest
from helpers import EXAMPLES, ROOT
from helpers.warehouses import minimal_makespan, random_two_station_warehouse, random_warehouse
from oracles.brute_force import minimal_makespan as brute_force

from asprilo.bounds import makespan_bound
from asprilo.domain import Domain
from asprilo.encodings import solve
from asprilo.model import Instance, Order, PickingStation, Product, Robot, Shelf
from asprilo.reader import read_instance

DOMAINS = [Domain.A, Domain.B, Domain.C]
ORACLE = ROOT / "tests" / "oracles" / "identity-abc"
TINY = ["x2_y2_n4_r2_s2_ps1_pr2_u4_o2_N1", "x3_y3_n9_r1_s1_ps1_pr1_u1_o1_N1", "x4_y4_n16_r2_s3_ps1_pr2_u4_o2_N1"]


@pytest.mark.parametrize("name", TINY)
@pytest.mark.parametrize("domain", DOMAINS, ids=lambda d: d.value)
def test_the_example_minima_equal_brute_force(name, domain):
    instance = read_instance(EXAMPLES / "encodings-repo" / f"{name}.lp")
    expected = brute_force(instance, domain.value)
    outcome = solve(instance, domain)
    assert (outcome.horizon, outcome.minimal, outcome.check.valid) == (expected, True, True)
    assert makespan_bound(instance, domain) <= expected


def one_shelf_for_two_stations(same_station: bool) -> Instance:
    """A 3x2 floor: stations on (1,1) and (3,1), one robot on (2,1), one shelf on (2,2)
    holding one unit each of products 1 and 2; order 1 wants product 1 at station 1, order 2
    product 2 at station 2 (or at station 1 too, with ``same_station``)."""
    instance = Instance()
    for ident, cell in enumerate([(x, y) for y in (1, 2) for x in (1, 2, 3)], 1):
        instance.nodes[ident] = cell
    instance.stations = {1: PickingStation(1, (1, 1)), 2: PickingStation(2, (3, 1))}
    instance.robots[1] = Robot(1, (2, 1))
    instance.shelves[1] = Shelf(1, (2, 2))
    instance.products = {1: Product(1, {1: 1}), 2: Product(2, {1: 1})}
    instance.orders = {1: Order(1, {1: 1}, 1), 2: Order(2, {2: 1}, 1 if same_station else 2)}
    return instance


# by hand: step 1 walk under the shelf, 2 lift it, 3-4 carry it to (1,1), 5 deliver; then
# 6-7 carry it to (3,1) and 8 deliver -- or, both lines at (1,1), deliver again at 6 (A, B)
# or close both lines with the one delivery at 5 (C).  The makespan bound reaches these
# minima: the trip relaxation (asprilo/bounds/trip.lp) knows that one shelf serves both
# stations, two cells apart, where each station alone is served at 5.
@pytest.mark.parametrize(("same_station", "domain", "expected"), [
    (False, Domain.A, 8), (False, Domain.B, 8), (False, Domain.C, 8),
    (True, Domain.A, 6), (True, Domain.B, 6), (True, Domain.C, 5)])
def test_a_shelf_stays_named_until_its_last_delivery(same_station, domain, expected):
    instance = one_shelf_for_two_stations(same_station)
    assert brute_force(instance, domain.value) == expected
    assert makespan_bound(instance, domain) == expected
    outcome = solve(instance, domain)
    assert (outcome.horizon, outcome.minimal, outcome.check.valid) == (expected, True, True)


@pytest.mark.parametrize("units", [10**8, 10**9])
def test_huge_quantities_bound_as_single_units_do(units):
    # the shelf holds every unit both orders want, so only the trips count: 8, as above.  The
    # relaxation sums units instead of choosing amounts (which would ground 10**8 atoms); with
    # 10**9 its sums would overflow clingo's 32-bit integers, so it only counts deliveries
    instance = one_shelf_for_two_stations(same_station=False)
    instance.products = {1: Product(1, {1: units}), 2: Product(2, {1: units})}
    instance.orders = {1: Order(1, {1: units}, 1), 2: Order(2, {2: units}, 2)}
    assert makespan_bound(instance, Domain.A) == 8


@pytest.mark.parametrize("seed", range(8))
@pytest.mark.parametrize("domain", DOMAINS, ids=lambda d: d.value)
def test_random_tiny_minima_equal_brute_force(seed, domain):
    instance = random_warehouse(seed, width=3, height=3, robots=2, shelves=2, lines=2,
                                units=domain is Domain.A)
    expected = brute_force(instance, domain.value, limit=16)
    bound = makespan_bound(instance, domain)
    found = minimal_makespan(instance, domain, limit=16)
    assert found == expected
    assert expected is None or bound <= expected


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("domain", DOMAINS, ids=lambda d: d.value)
def test_random_small_minima_equal_the_identity_encoding_and_need_no_pruning(seed, domain):
    instance = random_warehouse(100 + seed, width=4, height=3, robots=2, shelves=3, lines=2,
                                units=domain is Domain.A)
    expected = minimal_makespan(instance, domain, program=ORACLE / f"{domain.value}.lp", limit=20)
    assert minimal_makespan(instance, domain, limit=20) == expected
    assert minimal_makespan(instance, domain, {"bands": 0}, limit=20) == expected
    assert minimal_makespan(instance, domain, {"deadlines": 0}, limit=20) == expected
    assert expected is None or makespan_bound(instance, domain) <= expected


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(200, 260))
@pytest.mark.parametrize("domain", DOMAINS, ids=lambda d: d.value)
def test_many_more_random_minima_agree(seed, domain):
    instance = random_warehouse(seed, width=4, height=3, robots=2, shelves=3, lines=2, units=domain is Domain.A)
    expected = minimal_makespan(instance, domain, program=ORACLE / f"{domain.value}.lp", limit=20)
    assert minimal_makespan(instance, domain, limit=20) == expected
    assert expected is None or makespan_bound(instance, domain) <= expected


def no_plan_shorter_than(bound: float, instance: Instance, domain: Domain) -> bool:
    """Whether the exact encoding has no plan one step below ``bound`` (robots may wait, so
    a plan of any shorter makespan would be one too)."""
    return bound == float("inf") or bound < 1 or minimal_makespan(instance, domain, start=int(bound) - 1,
                                                                  limit=int(bound) - 1) is None


@pytest.mark.parametrize("seed", range(10))
@pytest.mark.parametrize("domain", DOMAINS, ids=lambda d: d.value)
def test_the_bound_with_two_stations_and_shared_shelves_is_admissible(seed, domain):
    instance = random_two_station_warehouse(seed)
    assert no_plan_shorter_than(makespan_bound(instance, domain), instance, domain)


def assert_the_bound_is_the_minimum(seed: int, size: tuple[int, int, int], domain: Domain) -> None:
    """The exact encoding has no plan one step below the bound and has one at the bound."""
    robots, shelves, height = size
    instance = random_two_station_warehouse(seed, robots=robots, shelves=shelves, height=height)
    bound = makespan_bound(instance, domain)
    assert minimal_makespan(instance, domain, start=int(bound) - 1, limit=int(bound)) == bound


# Instances where a robot has to fetch a second shelf or move one out of the way: the
# relaxation counts that robot's time (touch/3 in asprilo/bounds/trip.lp), and its bound is
# the minimum the exact encoding finds (one or two steps more than before touch/3).
@pytest.mark.parametrize(("seed", "size", "domain"), [
    (90, (2, 5, 4), Domain.C), (106, (2, 5, 4), Domain.B), (214, (2, 5, 4), Domain.B),
    (212, (2, 3, 3), Domain.A), (255, (3, 5, 5), Domain.A), (459, (3, 5, 5), Domain.A)])
def test_the_bound_counts_the_robot_that_moves_a_shelf_aside(seed, size, domain):
    assert_the_bound_is_the_minimum(seed, size, domain)


# Instances where the steps between two actions are longer than floor distances say: a shelf
# is never set down where another one stands (asprilo/bounds/trip.py, _gaps; seed 242: the
# robot's cycle in asprilo/bounds/delivery.py).  The bound is the minimum the exact encoding
# finds (one or two steps more than before).
@pytest.mark.parametrize(("seed", "size", "domain"), [
    (178, (2, 5, 4), Domain.A), (352, (2, 3, 3), Domain.A),
    pytest.param(214, (2, 5, 4), Domain.A, marks=pytest.mark.slow),
    pytest.param(242, (2, 5, 4), Domain.C, marks=pytest.mark.slow),
    pytest.param(268, (2, 3, 3), Domain.A, marks=pytest.mark.slow)])
def test_the_bound_sets_shelves_down_only_on_free_cells(seed, size, domain):
    assert_the_bound_is_the_minimum(seed, size, domain)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(10, 80))
@pytest.mark.parametrize("domain", DOMAINS, ids=lambda d: d.value)
def test_the_bound_with_two_stations_and_shared_shelves_is_admissible_on_many_more(seed, domain):
    instance = random_two_station_warehouse(seed, robots=3, shelves=4, height=4)
    assert no_plan_shorter_than(makespan_bound(instance, domain), instance, domain)
