"""Checked edits of the inventory and the orders (the Orders panel's and the shelf dialog's),
as lists of changes that can be undone: see :mod:`.edits` for what an edit is."""

from __future__ import annotations

import copy

from asprilo.model import Instance, Order, Product

from .edits import Edit, EditRefused, _Recorder, next_id

# --- inventory ----------------------------------------------------------------------------------

def set_stock(instance: Instance, shelf: int, stock: dict[int, int | None]) -> Edit:
    """The products on ``shelf`` and their units (``None``: no quantity), replacing what it held."""
    if shelf not in instance.shelves:
        raise EditRefused(f"there is no shelf {shelf}")
    for product, units in stock.items():
        if product < 1:
            raise EditRefused(f"product ids start at 1, not {product}")
        if units is not None and units < 1:
            raise EditRefused(f"product {product}: a shelf holds at least 1 unit (or no quantity)")
    record = _Recorder(instance)
    for product in sorted(set(stock) | {p.id for p in instance.products.values() if shelf in p.stock}):
        old = instance.products.get(product, Product(product))
        new = {s: u for s, u in old.stock.items() if s != shelf}
        if product in stock:
            new[shelf] = stock[product]
            new = dict(sorted(new.items()))
        if new:
            record.set("products", product, Product(product, new))
        else:
            record.remove("products", product)
    return record.edit(f"set the products on shelf {shelf}")


# --- orders ---------------------------------------------------------------------------------------

def add_order(instance: Instance, product: int | None = None, units: int | None = None,
              station: int | None = None) -> Edit:
    """A new order (next free id), with one line when ``product`` is given."""
    ident = next_id(instance.orders)
    record = _Recorder(instance)
    lines = {} if product is None else {product: units}
    record.set("orders", ident, Order(ident, lines, station))
    return record.edit(f"add order {ident}")


def remove_order(instance: Instance, order: int) -> Edit:
    if order not in instance.orders:
        raise EditRefused(f"there is no order {order}")
    record = _Recorder(instance)
    record.remove("orders", order)
    return record.edit(f"remove order {order}")


def _changed_order(instance: Instance, order: int) -> Order:
    if order not in instance.orders:
        raise EditRefused(f"there is no order {order}")
    return copy.deepcopy(instance.orders[order])


def set_order_line(instance: Instance, order: int, product: int, units: int | None,
                   replaces: int | None = None) -> Edit:
    """Order ``order`` asks for ``units`` of ``product`` (``replaces``: the line's old product)."""
    changed = _changed_order(instance, order)
    if product < 1:
        raise EditRefused(f"product ids start at 1, not {product}")
    if units is not None and units < 1:
        raise EditRefused(f"order {order}: a line asks for at least 1 unit (or no quantity)")
    if replaces is not None and replaces != product and product in changed.lines:
        raise EditRefused(f"order {order} already has a line for product {product}")
    lines = {(product if p == replaces else p): u for p, u in changed.lines.items()}
    lines[product] = units
    changed.lines = dict(sorted(lines.items()))
    record = _Recorder(instance)
    record.set("orders", order, changed)
    return record.edit(f"order {order}: product {product}" + ("" if units is None else f" × {units}"))


def remove_order_line(instance: Instance, order: int, product: int) -> Edit:
    changed = _changed_order(instance, order)
    if product not in changed.lines:
        raise EditRefused(f"order {order} has no line for product {product}")
    del changed.lines[product]
    record = _Recorder(instance)
    record.set("orders", order, changed)
    return record.edit(f"order {order}: remove product {product}")


def set_order_station(instance: Instance, order: int, station: int | None) -> Edit:
    changed = _changed_order(instance, order)
    changed.station = station
    record = _Recorder(instance)
    record.set("orders", order, changed)
    return record.edit(f"order {order} goes to picking station {station}")
