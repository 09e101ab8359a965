"""The attributes rule variants declare, drawn for the generated objects (``gen --variant``,
``--energy``): each object of the kind gets a value drawn uniformly from the variant's range,
from the instance's seed, so the same command and seed give the same values."""

from __future__ import annotations

from collections.abc import Sequence

from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.model import Instance

from .sampling import rng

#: (kind, attribute, least, most)
Drawn = tuple[str, str, int, int]
#: the kinds whose objects can be given attributes, and where an instance keeps them
_TABLES = {"robot": "robots", "shelf": "shelves", "pickingStation": "stations", "product": "products",
           "order": "orders", "destination": "destinations"}


def drawn_attributes(domain: Domain, variants: Sequence[str], energy: str | None) -> tuple[Drawn, ...]:
    """What to draw: the ranges of the variants ``variants`` (applied to ``domain``, which they
    must fit), with ``energy`` (``MIN-MAX``) as the robots' energy range."""
    drawn: dict[tuple[str, str], Drawn] = {}
    if variants:
        from asprilo.domain.variants import with_variants  # YAML: only for a call that names a variant
        drawn = {(kind, attribute): (kind, attribute, least, most)
                 for kind, attribute, least, most in with_variants(domain, variants).attributes}
    if energy is not None:
        least, most = _span(energy)
        drawn[("robot", "energy")] = ("robot", "energy", least, most)
    for kind, attribute, _least, _most in drawn.values():
        if kind not in _TABLES:
            raise InputError(f"gen draws attributes of robots, shelves, picking stations, products, orders and "
                             f"destinations, not of {kind} ({attribute})")
    return tuple(drawn.values())


def _span(text: str) -> tuple[int, int]:
    least, dash, most = text.partition("-")
    try:
        span = (int(least), int(most)) if dash else (int(text), int(text))
    except ValueError:
        raise InputError(f"--energy takes MIN-MAX (two whole numbers), got {text!r}") from None
    if not 0 <= span[0] <= span[1] <= 2**31 - 1:
        raise InputError(f"--energy takes MIN-MAX with 0 <= MIN <= MAX, got {text!r}")
    return span


def draw(instance: Instance, drawn: Sequence[Drawn], seed: int) -> None:
    """Give every object of each kind in ``drawn`` its value (in place)."""
    for kind, attribute, least, most in drawn:
        choose = rng(seed, "attribute", kind, attribute)
        for ident in sorted(getattr(instance, _TABLES[kind])):
            instance.attributes.setdefault((kind, ident), {})[attribute] = choose.randint(least, most)
