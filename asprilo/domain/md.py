"""Domain Md: multi-agent path finding with explicit destinations instead of M's
shelf/product/order triples; every destination must be occupied at the horizon."""

from .descriptor import Bound, Domain, Goal, Job
from .shared import MAPF_ENCODINGS, WORLD_RULES

MD = Domain(
    value="md", label="Md",
    summary="robots only move; every destination must be occupied at the end",
    actions=frozenset({"move"}),
    delivery=None,
    goal=Goal.DESTINATIONS,
    reads=frozenset({"node", "highway", "robot", "destination"}),
    checker=(*WORLD_RULES, "fulfil_md", "assigned", "goal"),
    encodings=MAPF_ENCODINGS,
    bound=Bound.MAPF,
    work=Job.GOALS,
    generation=None,
    made_by="generate m and convert it",
)
