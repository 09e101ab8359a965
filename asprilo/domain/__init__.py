"""The asprilo problem domains, as data, and how to tell which one an instance belongs to.

Each domain is a descriptor (:class:`Domain`, one module per built-in domain beside this
one) that tools ask instead of testing a domain's name: its actions, what a delivery does,
its goal, the object kinds it reads, its checker concerns, reference encodings, bound,
anytime work model and generator alignment.  docs/DOMAINS.md shows how to add one.

A, B and C instances share one format, so the instance alone cannot separate them:
quantities make an instance A (the most general reading), quantity-free facts
(``on S`` / ``line P``) make it B.  M-aligned instances (one single-unit line per order,
each ordered product on exactly one shelf, as many orders as robots) are M, and
instances with ``destination`` objects are Md.  An instance without orders has nothing
to deliver and is read as M.  A plan can refine this: an M-aligned instance whose plan
picks up or delivers is read as A (B if its deliveries carry no quantity); an action name
no domain knows (a typo) is warned about by the reader and plays no part.  Every tool
takes ``--domain`` to override the guess.
"""

from __future__ import annotations

from ..model import Instance, Plan
from .a import A
from .b import B
from .c import C
from .descriptor import (
    Bound,
    Delivery,
    Domain,
    Generation,
    Goal,
    Job,
    ReferenceEncoding,
    domains,
    register,
    unregister,
)
from .m import M
from .md import MD
from .templates import Resource, Words

__all__ = ["Bound", "Delivery", "Domain", "Generation", "Goal", "ReferenceEncoding", "Job", "DEFAULT", "Resource",
           "Words", "detect_domain", "domains", "is_m_aligned", "register", "unregister"]

for _builtin in (A, B, C, M, MD):
    register(_builtin)
Domain.A, Domain.B, Domain.C, Domain.M, Domain.MD = A, B, C, M, MD

#: the reading of an instance when nothing says otherwise (the most general one)
DEFAULT = A


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
    """The domain an instance (and optionally its plan) fits; see the module docstring.
    Only actions some domain knows count: a misspelt one (``mvoe``) is the reader's warning,
    never a vote for another domain."""
    if instance.destinations:
        return MD
    if not instance.orders:
        return M
    known = frozenset().union(*(domain.actions for domain in domains()))
    actions = [action for action in (plan.actions if plan is not None else ()) if action.name in known]
    if is_m_aligned(instance) and all(action.name == "move" for action in actions):
        return M
    if any(action.name == "deliver" and isinstance(action.args, tuple) and len(action.args) == 2
           for action in actions):
        return B
    return A if _has_quantities(instance) else B
