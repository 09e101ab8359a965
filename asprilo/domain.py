"""The asprilo problem domains and how to tell which one an instance belongs to.

A, B and C instances share one format, so the instance alone cannot separate them:
quantities make an instance A (the most general reading), quantity-free facts
(``on S`` / ``line P``) make it B.  M-aligned instances (one single-unit line per order,
each ordered product on exactly one shelf, as many orders as robots) are M, and
instances with ``destination`` objects are Md.  An instance without orders has nothing
to deliver and is read as M.  A plan can refine this: an M-aligned instance whose plan
picks up or delivers is read as A (B if its deliveries carry no quantity).  Every tool
takes ``--domain`` to override the guess.
"""

from __future__ import annotations

from enum import Enum

from .errors import InputError
from .model import Instance, Plan


class Domain(str, Enum):
    A = "a"
    B = "b"
    C = "c"
    M = "m"
    MD = "md"

    @classmethod
    def parse(cls, text: str | Domain) -> Domain:
        """``a``/``B``/``md``... -> Domain; an unknown name is bad input."""
        try:
            return cls(str(text.value if isinstance(text, Domain) else text).lower())
        except ValueError:
            names = ", ".join(domain.value for domain in cls)
            raise InputError(f"unknown domain '{text}' (choose one of {names})") from None

    @property
    def label(self) -> str:
        return "Md" if self is Domain.MD else self.name

    @property
    def delivers(self) -> bool:
        """Whether plans of this domain pick up, put down and deliver (A, B, C)."""
        return self in (Domain.A, Domain.B, Domain.C)


def is_m_aligned(instance: Instance) -> bool:
    """One single-unit line per order, each ordered product on one shelf, #orders = #robots."""
    if not instance.orders or len(instance.orders) != len(instance.robots):
        return False
    for order in instance.orders.values():
        if len(order.lines) != 1:
            return False
        (product, units), = order.lines.items()
        if units not in (None, 1) or product not in instance.products:
            return False
        if len(instance.products[product].stock) != 1:
            return False
    return True


def _has_quantities(instance: Instance) -> bool:
    entries = [u for p in instance.products.values() for u in p.stock.values()]
    entries += [u for o in instance.orders.values() for u in o.lines.values()]
    return all(units is not None for units in entries)


def detect_domain(instance: Instance, plan: Plan | None = None) -> Domain:
    """The domain an instance (and optionally its plan) fits; see the module docstring."""
    if instance.destinations:
        return Domain.MD
    if not instance.orders:
        return Domain.M
    if is_m_aligned(instance) and (plan is None or all(action.name == "move" for action in plan.actions)):
        return Domain.M
    if plan is not None and any(action.name == "deliver" and isinstance(action.args, tuple)
                                and len(action.args) == 2 for action in plan.actions):
        return Domain.B
    return Domain.A if _has_quantities(instance) else Domain.B
