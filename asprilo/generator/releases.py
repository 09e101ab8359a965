"""Order streams for online scenarios (``gen --release``): the step each order is released
at, drawn by a seeded process over ``--release-over`` steps, orders in id order.

- ``steady``: evenly spaced: order k of n (k = 0, 1, ...) at step floor(k * over / n);
- ``poisson``: the arrival times of a Poisson process with n arrivals in [0, over): n
  times drawn uniformly and sorted, each rounded down to its step;
- ``bursts``: bursts of ``burst`` orders, the bursts evenly spaced as ``steady`` spaces orders.

The same seed gives the same steps; each instance of a run draws from its own seed.
"""

from __future__ import annotations

import math

from asprilo.model import Instance

from .sampling import rng

#: the processes ``--release`` takes
PROCESSES = ("steady", "poisson", "bursts")


def release_steps(count: int, over: int, process: str, seed: int, burst: int = 5) -> list[int]:
    """The release steps of ``count`` orders (ascending)."""
    if process == "steady":
        return [k * over // count for k in range(count)]
    if process == "poisson":
        draw = rng(seed, "releases")
        return sorted(min(over - 1, math.floor(draw.random() * over)) for _ in range(count))
    bursts = math.ceil(count / burst) if count else 0
    return [(k // burst) * over // bursts for k in range(count)]


def release_orders(instance: Instance, process: str, over: int, burst: int, seed: int) -> None:
    """Give the orders of ``instance`` their release steps, in id order."""
    steps = release_steps(len(instance.orders), over, process, seed, burst)
    for order, step in zip(sorted(instance.orders), steps, strict=True):
        instance.orders[order].release = step
