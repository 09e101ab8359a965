"""Domain C: as B, but one delivery closes every open line at the station that the
carried shelf can serve."""

from .descriptor import Bound, Delivery, Domain, Generation, Goal, Job
from .shared import ABC_PLAIN, CARRYING, CARRYING_RULES, DELIVERING, abc_encoding

C = Domain(
    value="c", label="C",
    summary="one delivery closes every line at its station that the carried shelf holds",
    actions=CARRYING,
    delivery=Delivery.STATION,
    goal=Goal.LINES,
    reads=DELIVERING,
    checker=(*CARRYING_RULES, "deliver_bc", "fulfil_c", "goal"),
    encodings=(abc_encoding("plain", "abc/c.lp", ABC_PLAIN),),
    bound=Bound.DELIVERY,
    work=Job.TRIPS,
    generation=Generation(quantities=False, exercise=dict(
        width=11, height=6, structured=True, zone_x=4, zone_y=2, stations=2, robots=3,
        shelves=8, products=4, units=16, orders=3, ol_min=1, ol_max=2)),
)
