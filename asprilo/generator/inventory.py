"""Products on shelves and orders of a generation plan: the M alignment, the ranges with their
defaults, and whether the totals fit together (checked before any solving).
"""

from __future__ import annotations

import math
from collections import Counter
from typing import Any

from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.model import Instance

from .config import GeneratorConfig
from .options import BY_NAME

RANGE_NAMES = ("products", "units", "orders", "pus_min", "pus_max", "prs_min", "prs_max", "spr_min", "spr_max",
               "ol_min", "ol_max")
RANGE_PAIRS = (("pus_min", "pus_max"), ("prs_min", "prs_max"), ("spr_min", "spr_max"), ("ol_min", "ol_max"))


def _flag(name: str) -> str:
    return BY_NAME[name].flag


def new_count(total: int, existing: int, flag: str, what: str) -> int:
    """How many objects to add so that there are ``total`` (a template may hold some already)."""
    if total < existing:
        raise InputError(f"{flag} {total}: the template has {existing} {what} already")
    return total - existing


def ranges(c: GeneratorConfig, domain: Domain, shelves: int, robots: int) -> dict[str, Any]:
    """The ranges and totals after the domain's alignment, defaults filled in (totals may stay None)."""
    values = {name: getattr(c, name) for name in RANGE_NAMES}
    if domain.generation is not None and domain.generation.aligned:
        _align_m(values, shelves, robots, domain)
    for name in RANGE_NAMES:
        if values[name] is None and BY_NAME[name].default is not None:
            values[name] = BY_NAME[name].default
    for low, high in RANGE_PAIRS:
        if values[high] >= 1 and values[low] > values[high]:
            raise InputError(f"{_flag(low)} {values[low]} exceeds {_flag(high)} {values[high]}")
    return values


def _align_m(values: dict[str, Any], shelves: int, robots: int, domain: Domain) -> None:
    """M's alignment: one unit of one product per shelf, one line of one unit per order, an order per robot."""
    aligned = {"products": shelves, "units": shelves, "orders": robots, "pus_min": 1, "pus_max": 1,
               "prs_min": 1, "prs_max": 1, "spr_min": 1, "spr_max": 1, "ol_min": 1, "ol_max": 1}
    why = {"products": f"as many products as shelves ({shelves})",
           "units": f"one unit per shelf ({shelves})", "orders": f"as many orders as robots ({robots})"}
    for name, wanted in aligned.items():
        if values[name] is not None and values[name] != wanted:
            reason = why.get(name, "one product per shelf, on one shelf, one unit, one line per order")
            raise InputError(f"--domain {domain.value}: {reason}; got {_flag(name)} {values[name]}")
        values[name] = wanted


def inventory(r: dict[str, Any], existing: Instance, shelves: int) -> dict[str, Any]:
    """Which products are new and how many (product, shelf) pairs and units they get."""
    product_total = r["products"] if r["products"] is not None else len(existing.products)
    new = new_count(product_total, len(existing.products), "-P", "products")
    units = r["units"] - existing.units if r["units"] is not None else None
    _check_products(r, existing, shelves, product_total, new, units)
    fixed_pairs = sum(len(p.stock) for p in existing.products.values())
    spr_max = min(r["spr_max"] if r["spr_max"] >= 1 else shelves, shelves)
    prs_max = min(r["prs_max"] if r["prs_max"] >= 1 else product_total, product_total)
    # a shelf takes each new product once, up to prs_max with the template's products on it
    stocked = Counter(shelf for product in existing.products.values() for shelf in product.stock)
    loads = [stocked[shelf] for shelf in existing.shelves] + [0] * (shelves - len(existing.shelves))
    deficit = [max(0, r["prs_min"] - load) for load in loads]
    least = max(new * r["spr_min"], sum(deficit))
    most = min(new * spr_max, sum(min(max(0, prs_max - load), new) for load in loads))
    ranges_text = (f"-P {product_total}, -s {shelves}, --sprmin/--sprmax {r['spr_min']}/{r['spr_max']}, "
                   f"--prsmin/--prsmax {r['prs_min']}/{r['prs_max']}")
    if new and (least > most or max(deficit, default=0) > new):
        raise InputError(f"the products do not fit on the shelves: {ranges_text}")
    if not new:
        least = most = 0
    pus_max = r["pus_max"] if r["pus_max"] >= 1 else \
        (max(units, r["pus_min"]) if units is not None else r["pus_min"] + 9)
    if units is not None and new:
        least, most, pus_max = _fit_units(r, units, (least, most), pus_max, existing.units, ranges_text)
    spr_min, prs_min = r["spr_min"], r["prs_min"]
    if new:  # tighten the ranges by the totals, so the solver need not count across products
        spr_max = min(spr_max, most - (new - 1) * spr_min)
        spr_min = max(spr_min, least - (new - 1) * spr_max)
        prs_max = min(prs_max, most + fixed_pairs - (shelves - 1) * prs_min)
        prs_min = max(prs_min, least + fixed_pairs - (shelves - 1) * prs_max)
    target = min(most, max(least, round(math.sqrt(max(least, 1) * most))))
    first = max(existing.products, default=0) + 1
    return {"products": range(first, first + new), "product_total": product_total, "units": units,
            "pus_min": r["pus_min"], "pus_max": pus_max, "prs_min": prs_min, "prs_max": prs_max,
            "spr_min": spr_min, "spr_max": spr_max, "pairs": (least, target, most)}


def _check_products(r: dict[str, Any], existing: Instance, shelves: int, product_total: int, new: int,
                    units: int | None) -> None:
    if units is not None and units < 0:
        raise InputError(f"-u {r['units']}: the template's products hold {existing.units} units already")
    if new and not shelves:
        raise InputError(f"-P {product_total} products need shelves (-s or --sc)")
    if new and r["spr_min"] > shelves:
        raise InputError(f"--sprmin {r['spr_min']} exceeds the number of shelves (-s {shelves})")
    if shelves and r["prs_min"] > product_total:
        raise InputError(f"--prsmin {r['prs_min']} exceeds the number of products (-P {product_total})")
    if not new and units:
        raise InputError(f"-u {r['units']}: there are no new products (-P) to hold the units")
    loads = Counter(shelf for product in existing.products.values() for shelf in product.stock)
    shelf, load = max(loads.items(), key=lambda item: (item[1], -item[0]), default=(0, 0))
    if 1 <= r["prs_max"] < load:  # (the fullest shelf)
        raise InputError(f"--prsmax {r['prs_max']}: shelf {shelf} of the template holds {load} products already")


def _fit_units(r: dict[str, Any], units: int, pairs: tuple[int, int], pus_max: int, fixed_units: int,
               ranges_text: str) -> tuple[int, int, int]:
    """Narrow the (product, shelf) pairs to those that can hold ``units`` units; the new pus_max."""
    least, most = pairs
    low, high = max(least, -(-units // pus_max)), min(most, units // r["pus_min"])
    if low > high:
        raise InputError(f"-u {r['units']}: with {ranges_text}, --pusmin/--pusmax "
                         f"{r['pus_min']}/{r['pus_max']} the shelves hold "
                         f"{least * r['pus_min'] + fixed_units}..{most * pus_max + fixed_units} units")
    return low, high, min(pus_max, units - (low - 1) * r["pus_min"])  # room left by the other pairs


def orders(c: GeneratorConfig, r: dict[str, Any], stock: dict[str, Any], existing: Instance,
           stations: int) -> dict[str, Any]:
    """Which orders are new, and their lines."""
    order_total = r["orders"] if r["orders"] is not None else len(existing.orders)
    new = new_count(order_total, len(existing.orders), "-o", "orders")
    products = stock["product_total"]
    ol_max = min(r["ol_max"] if r["ol_max"] >= 1 else products, products)
    if new:
        _check_orders(r, stock, existing, stations, order_total, new)
    if c.order_all:
        ordered = {p for o in existing.orders.values() for p in o.lines}
        if new * ol_max + len(ordered) < products:
            raise InputError(f"--oap: -o {order_total} orders with --olmax {r['ol_max']} lines "
                             f"cannot ask for all -P {products} products")
    first = max(existing.orders, default=0) + 1
    return {"orders": range(first, first + new), "order_total": order_total, "ol_min": r["ol_min"],
            "ol_max": ol_max, "order_all": c.order_all}


def _check_orders(r: dict[str, Any], stock: dict[str, Any], existing: Instance, stations: int, order_total: int,
                  new: int) -> None:
    products = stock["product_total"]
    if not products:
        raise InputError(f"-o {order_total} orders need products (-P)")
    if not stations:
        raise InputError(f"-o {order_total} orders need picking stations (-p)")
    if r["ol_min"] > products:
        raise InputError(f"--olmin {r['ol_min']} exceeds the number of products (-P {products})")
    fixed = sum(q or 1 for o in existing.orders.values() for q in o.lines.values())
    units = r["units"] if r["units"] is not None else existing.units + stock["pairs"][2] * stock["pus_max"]
    if new * r["ol_min"] + fixed > units:
        raise InputError(f"-o {order_total} orders with --olmin {r['ol_min']} lines each ask for "
                         f"more units than the shelves hold ({units}, -u)")
    _check_serving(r, stock, existing, order_total, new)


def _check_serving(r: dict[str, Any], stock: dict[str, Any], existing: Instance, order_total: int,
                   new: int) -> None:
    """An order asks for a product once, so a product serves at most one line of each new
    order: a new one as many as its units (spr_max x pus_max at most), a template's one as
    many as the units its orders leave."""
    most = stock["spr_max"] * stock["pus_max"]
    serve = len(stock["products"]) * min(most, new)
    if stock["units"] is not None:
        serve = min(serve, stock["units"])
    asked = Counter(p for o in existing.orders.values() for p in o.lines)
    for product in existing.products.values():
        left = sum(1 if units is None else units for units in product.stock.values()) - asked[product.id]
        serve += min(max(left, 0), new)
    need = new * r["ol_min"]
    if need > serve:
        raise InputError(f"-o {order_total} orders with --olmin {r['ol_min']} lines each need {need} lines on "
                         f"different products, but the products serve at most {serve} (an order asks for a "
                         f"product once; a new product holds at most {most} units, --sprmax x --pusmax)")
