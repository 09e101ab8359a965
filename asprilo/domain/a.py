"""Domain A: robots bring shelves to picking stations and hand over units of products;
order lines and shelves count quantities."""

from .descriptor import Bound, Delivery, Domain, Generation, Goal, Job
from .shared import ABC_PLAIN, CARRYING, CARRYING_RULES, DELIVERING, abc_encoding

A = Domain(
    value="a", label="A",
    summary="deliveries count units: lines and stock drop by the units handed over",
    actions=CARRYING,
    delivery=Delivery.UNITS,
    goal=Goal.LINES,
    reads=DELIVERING,
    checker=(*CARRYING_RULES, "deliver_a", "fulfil_a", "goal"),
    encodings=(
        abc_encoding("plain", "abc/a.lp", ABC_PLAIN),
        abc_encoding("clingcon", "abc/clingcon/a.lp", "plain, with quantities as clingcon integer variables",
                     theory="clingcon"),
    ),
    bound=Bound.DELIVERY,
    work=Job.TRIPS,
    generation=Generation(quantities=True, exercise=dict(
        width=11, height=6, structured=True, zone_x=4, zone_y=2, stations=2, robots=3,
        shelves=8, products=4, units=16, orders=2, ol_min=1, ol_max=1)),
)
