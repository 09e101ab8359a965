"""Orders written during an online session, before they are sent to the solver (no Qt).

The drafts live beside the session's world: the order editor shows and edits them like
the orders of an instance; Send hands their ``init/2`` facts to the session (which tells
the solver and adds them to the world), Discard drops them.  Their ids follow the world's
orders; should the world get an order of the same id meanwhile, the draft takes the next
free one.
"""

from __future__ import annotations

from collections.abc import Callable
from contextlib import AbstractContextManager, nullcontext

from asprilo.model import Instance, Order
from asprilo.online.protocol import instance_facts

from . import edits
from .edits import Edit, EditRefused
from .observe import Signal


class DraftOrders:
    """Orders not sent yet, edited through checked edits like the instance's own."""

    def __init__(self, world: Instance, refuse: Callable[[str], None]):
        self.world, self.refuse = world, refuse
        self.instance = Instance()
        self.changed = Signal()  # the drafts changed
        self.sync()

    @property
    def drafts(self) -> dict[int, Order]:
        return {ident: order for ident, order in self.instance.orders.items() if self.shows(ident)}

    def shows(self, order: int) -> bool:
        """Whether the order editor lists ``order``: only drafts, not the world's orders."""
        return order not in self.world.orders

    def sync(self) -> None:
        """Follow the world (it grew): its stations, products and orders, the drafts beside them."""
        drafts = list(self.drafts.values())
        self.instance = Instance(stations=self.world.stations, products=self.world.products,
                                 shelves=self.world.shelves, orders=dict(self.world.orders))
        for order in drafts:
            ident = order.id if order.id not in self.instance.orders else edits.next_id(self.instance.orders)
            self.instance.orders[ident] = Order(ident, dict(order.lines), order.station)

    def perform(self, make: Callable[[], Edit]) -> bool:
        """Make an edit of the drafts (refused edits are said through ``refuse``)."""
        try:
            edit = make()
        except EditRefused as refusal:
            self.refuse(str(refusal))
            return False
        edits.apply(self.instance, edit)
        self.changed.emit()
        return bool(edit.changes)

    def group(self, _text: str) -> AbstractContextManager:
        return nullcontext()

    def problems(self) -> list[str]:
        """Why the drafts cannot be sent as they are."""
        held = set(self.world.products)
        found = []
        for order in sorted(self.drafts.values(), key=lambda o: o.id):
            if not order.lines:
                found.append(f"order {order.id} has no lines yet")
            if order.station not in self.world.stations:
                found.append(f"order {order.id} names no picking station of the warehouse")
            found += [f"order {order.id} asks for product {product}, which no shelf holds"
                      for product in sorted(order.lines) if product not in held]
        return found

    def take(self) -> str:
        """The drafts' ``init/2`` facts, to send; the drafts are gone from here."""
        facts = instance_facts(Instance(orders=self.drafts))
        self.discard()
        return facts

    def discard(self) -> None:
        self.instance.orders = dict(self.world.orders)
        self.changed.emit()
