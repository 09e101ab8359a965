"""Domain M: multi-agent path finding.  Robots only move; an order is served when some
robot stands under the one shelf holding its product at the horizon."""

from .descriptor import Bound, Domain, Generation, Goal, Job
from .shared import MAPF_ENCODINGS, WORLD_RULES

M = Domain(
    value="m", label="M",
    summary="robots only move; each order's shelf must have a robot under it at the end",
    actions=frozenset({"move"}),
    delivery=None,
    goal=Goal.SHELVES,
    reads=frozenset({"node", "highway", "robot", "shelf", "product", "order"}),
    checker=(*WORLD_RULES, "fulfil_m", "assigned", "goal"),
    encodings=MAPF_ENCODINGS,
    bound=Bound.MAPF,
    work=Job.GOALS,
    generation=Generation(aligned=True, quantities=True, exercise=dict(
        width=19, height=9, structured=True, zone_x=5, zone_y=2, stations=3, robots=10,
        shelves=60, products=60, units=60, orders=10, prs_min=1, prs_max=1)),
)
