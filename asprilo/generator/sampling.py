"""Seeded randomness on the Python side: per-instance seeds and samples of candidate pairs.

Everything random in an instance comes from its seed through hashing, never from the order in
which things happen, so the same command and seed give the same instance byte for byte.
"""

from __future__ import annotations

import hashlib
import random
from collections.abc import Hashable, Iterator, Sequence
from typing import TypeVar

T = TypeVar("T")


def digest(*parts: object) -> int:
    """A 64-bit hash of the parts' text: stable across runs and platforms."""
    text = "\x1f".join(str(part) for part in parts)
    return int.from_bytes(hashlib.blake2b(text.encode(), digest_size=8).digest(), "big")


def derive_seed(seed: int, *parts: Hashable) -> int:
    """The seed of a sub-task (instance k of a run, a run of a batch), in 0..2**31-1."""
    return digest(seed, *parts) >> 33


def rng(seed: int, *parts: Hashable) -> random.Random:
    return random.Random(derive_seed(seed, *parts))


def sample_options(rows: Sequence[int], columns: Sequence[T], per_row: int,
                   generator: random.Random) -> Iterator[tuple[int, T]]:
    """About ``per_row`` random columns for every row, every column used about equally often.

    Rows take consecutive runs from a stream of shuffled copies of ``columns``.  When the
    numbers divide evenly, every column appears equally often, so there is always a way to
    match rows and columns one to one (the M alignment needs this).
    """
    stream: list[T] = []
    while len(stream) < len(rows) * per_row:
        copy = list(columns)
        generator.shuffle(copy)
        stream += copy
    for index, row in enumerate(rows):
        for column in dict.fromkeys(stream[index * per_row:(index + 1) * per_row]):
            yield row, column
