"""Order streams for online scenarios (``gen --release``, asprilo/generator/releases.py): each
process's steps derived by hand, seeded draws reproducible, the options refused in words."""

from __future__ import annotations

import pytest

from asprilo.errors import InputError
from asprilo.generator import GeneratorConfig, generate
from asprilo.generator.releases import release_steps

SMALL = {"-x": 8, "-y": 6, "-p": 1, "-r": 2, "-s": 6, "-P": 4, "-u": 20, "-o": 6}


def test_steady_spaces_the_orders_evenly():
    assert release_steps(6, 12, "steady", seed=1) == [0, 2, 4, 6, 8, 10]  # k * 12 // 6
    assert release_steps(4, 10, "steady", seed=1) == [0, 2, 5, 7]         # 0, 10/4, 20/4, 30/4 rounded down


def test_bursts_come_together_and_the_bursts_are_spaced_evenly():
    # 6 orders in bursts of 2: 3 bursts at 0, 12 // 3, 24 // 3
    assert release_steps(6, 12, "bursts", seed=1, burst=2) == [0, 0, 4, 4, 8, 8]
    assert release_steps(5, 10, "bursts", seed=1, burst=2) == [0, 0, 3, 3, 6]  # 3 bursts: 0, 10 // 3, 20 // 3


def test_poisson_draws_sorted_steps_within_the_span_again_for_the_same_seed():
    steps = release_steps(200, 50, "poisson", seed=7)
    assert steps == sorted(steps) and all(0 <= step < 50 for step in steps) and len(steps) == 200
    assert steps == release_steps(200, 50, "poisson", seed=7) != release_steps(200, 50, "poisson", seed=8)


def test_gen_writes_a_release_step_for_every_order_in_id_order():
    config = GeneratorConfig.from_options({**SMALL, "--release": "steady", "--release-over": 12})
    (item,) = generate(config, seed=3)
    assert [(o, order.release) for o, order in sorted(item.instance.orders.items())] == [
        (1, 0), (2, 2), (3, 4), (4, 6), (5, 8), (6, 10)]
    # the default span: twice the orders
    (item,) = generate(GeneratorConfig.from_options({**SMALL, "--release": "steady"}), seed=3)
    assert [order.release for order in item.instance.orders.values()] == [0, 2, 4, 6, 8, 10]


@pytest.mark.parametrize(("options", "words"), [
    ({"--release": "often"}, "--release must be one of steady, poisson, bursts, got 'often'"),
    ({"--release-over": 10}, "--release-over: give --release too (steady, poisson or bursts)"),
    ({"--release": "steady", "-o": 0}, "--release: there are no orders to release (give -o)"),
])
def test_release_options_are_refused_in_words(options, words):
    with pytest.raises(InputError) as refused:
        generate(GeneratorConfig.from_options({**SMALL, **options}))
    assert refused.value.message == words
