"""What the orders demand of the stock, worked out by the driver before a stage is solved.

A line asks for one unit of a product, and an order asks for a product once, so a product
serves at most one line of each order, however many units it holds.  From this follow the
bounds on the lines of a round (orders.lp), whether the shelves and units of the new
products must be checked against the orders (supply.lp), and how many fill levels the
heuristics of the stock and lines stages tell apart (random.lp).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

from .plan import GenerationPlan


def tiers(items: int, holders: int) -> int:
    """Fill levels to tell apart when ``items`` go to ``holders`` (pairs to shelves, lines to
    products), least filled first: 0 up to the even share, the fullest a holder gets when
    the items are spread evenly (2 to 8).  The levels cost grounding (a heuristic modifier
    per candidate and level), so no more than this."""
    share = -(-items // max(holders, 1))
    return 1 + max(1, min(7, share))


def shelf_tiers(plan: GenerationPlan, pairs: int, shelves: int) -> int:
    """Fill levels of the shelves to tell apart when at most ``pairs`` (product, shelf) pairs
    go to ``shelves`` shelves: 1 (any order of choices will do) when no shelf needs a
    product and the full shelves can never leave a product fewer than spr_max shelves."""
    if plan.prs_min == 0 and shelves - pairs // max(plan.prs_max, 1) >= plan.spr_max:
        return 1
    return tiers(pairs, shelves)


def line_tiers(plan: GenerationPlan, room: Mapping[int, int], orders: int, lines: int) -> int:
    """Levels of units left to tell apart when ``orders`` orders ask for at most ``lines``
    lines: 1 (any order of choices will do) when ol_max products have a unit for every
    order, so that no order can run out of products."""
    if sum(1 for units in room.values() if units >= orders) >= plan.ol_max:
        return 1
    return tiers(lines, sum(1 for units in room.values() if units > 0))


def served(units: Iterable[int], orders: int) -> int:
    """How many lines of ``orders`` orders products with these units left can serve."""
    return sum(min(max(left, 0), orders) for left in units)


def line_bounds(plan: GenerationPlan, room: Mapping[int, int], orders: int, later: int,
                unordered: int) -> tuple[int, int]:
    """The least and most lines that ``orders`` new orders may have in all.

    Every order has ol_min..ol_max lines, each on another product with a unit left
    (``room``: product -> units no line asks for yet); these orders and the ``later`` ones
    together get at most what the products serve, the later ones ol_min lines each; and the
    ``unordered`` products that must be asked for (--oap) the later orders cannot take.
    """
    least = max(orders * plan.ol_min, unordered - later * plan.ol_max)
    most = min(orders * plan.ol_max, served(room.values(), orders),
               served(room.values(), orders + later) - later * plan.ol_min)
    return least, most


def cover_first(plan: GenerationPlan, room: Mapping[int, int], orders: int, later: int, unordered: int) -> bool:
    """With --oap: whether an order takes the products nobody has ordered yet first.  Such a
    choice costs a unit only where it passes over a product with units for every order left
    (which loses the order's chance at it), so: unless such products exist and the units
    left serve fewer than ``unordered`` lines more than the orders need at least; then the
    products with the most units left go first (and use every unit)."""
    if not plan.order_all:
        return False
    if all(units < orders + later for units in room.values()):
        return True
    need = max(orders + later, 1) * plan.ol_min
    return served(room.values(), orders + later) - max(need, unordered) >= unordered


def shelf_supply_need(plan: GenerationPlan, shelves: Mapping[int, int], products: int, later: int,
                      elsewhere: int) -> int:
    """How many lines of the new orders the ``products`` new products of a stock round must be
    able to serve with all their shelves full, or 0 when they can anyway (each has spr_min
    shelves at least).  ``shelves``: the shelf count of each product of earlier rounds (they
    serve what those allow); ``later`` products of later rounds serve what spr_max shelves
    allow; ``elsewhere``: lines the template's products serve."""
    orders = len(plan.orders)
    need = orders * plan.ol_min - elsewhere - served((count * plan.pus_max for count in shelves.values()), orders) \
        - later * min(plan.spr_max * plan.pus_max, orders)
    return need if orders and need > products * min(plan.spr_min * plan.pus_max, orders) else 0


def unit_supply_need(plan: GenerationPlan, shelves: Mapping[int, int], elsewhere: int) -> int:
    """How many lines of the new orders the new products must serve with their units, or 0
    when they do whatever units they get (each holds pus_min on each of its ``shelves``)."""
    orders = len(plan.orders)
    need = orders * plan.ol_min - elsewhere
    least = served((shelves.get(product, plan.spr_min) * plan.pus_min for product in plan.products), orders)
    return need if orders and need > least else 0
