"""The A/B/C encodings lose no plan: their minimal makespans equal independent ones.

- On the tiniest instances, a brute-force search over all joint moves (tests/oracles/brute_force.py).
- On random small ones, the previous identity-based encoding (tests/oracles/identity-abc/).
- Each pruning technique switched off (-c bands=0, -c deadlines=0) gives the same minimum.
- The makespan bound never exceeds the minimum.
"""

from __future__ import annotations

import pytest
from helpers import EXAMPLES, ROOT
from helpers.warehouses import minimal_makespan, random_warehouse
from oracles.brute_force import minimal_makespan as brute_force

from asprilo.bounds import makespan_bound
from asprilo.domain import Domain
from asprilo.encodings import solve
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
