"""Domain B: as A, but a delivery closes a whole order line and quantities are ignored."""

from .descriptor import Bound, Delivery, Domain, Generation, Goal, Job
from .shared import ABC_PLAIN, CARRYING, CARRYING_RULES, DELIVERING, abc_encoding

B = Domain(
    value="b", label="B",
    summary="a delivery closes one order line; quantities are ignored",
    actions=CARRYING,
    delivery=Delivery.LINE,
    goal=Goal.LINES,
    reads=DELIVERING,
    checker=(*CARRYING_RULES, "deliver_bc", "fulfil_b", "goal"),
    encodings=(abc_encoding("plain", "abc/b.lp", ABC_PLAIN),),
    bound=Bound.DELIVERY,
    work=Job.TRIPS,
    generation=Generation(quantities=False, exercise=dict(
        width=11, height=6, structured=True, zone_x=4, zone_y=2, stations=2, robots=3,
        shelves=8, products=4, units=16, orders=2, ol_min=1, ol_max=2)),
)
