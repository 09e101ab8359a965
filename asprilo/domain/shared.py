"""Parts the built-in domains share."""

from .descriptor import ReferenceEncoding

#: the checker's concerns of every domain: the world, the instance, the actions' form,
#: the state and its collisions, the moves' directions and moves (each domain adds its own,
#: then "goal")
WORLD_RULES = ("world", "instance", "action", "state", "collision", "directions", "move")
#: ... and those of the domains whose robots carry shelves
CARRYING_RULES = (*WORLD_RULES, "pickup", "putdown", "deliver", "release")

#: the object kinds and actions of the delivering domains A, B and C
DELIVERING = frozenset({"node", "highway", "robot", "shelf", "pickingStation", "product", "order"})
CARRYING = frozenset({"move", "pickup", "putdown", "deliver"})


def abc_encoding(name: str, program: str, summary: str, theory: str | None = None) -> ReferenceEncoding:
    """An A/B/C reference encoding: anonymous robots, named by abc/names.lp, searched with
    the domain heuristics of abc/hints.lp (while the external use_hints is true)."""
    return ReferenceEncoding(name, program, theory=theory, summary=summary, names="abc/names.lp",
                             options=("--heuristic=Domain",))


ABC_PLAIN = "anonymous robots, named shelves in distance bands + the domain's deliveries"

#: the reference encodings of M and Md (an Md instance's destinations are read as goal cells)
MAPF_ENCODINGS = (
    ReferenceEncoding("plain", "m/plain.lp", summary="positions as cells (paper Listings 1-2)"),
    ReferenceEncoding("split", "m/split.lp", summary="X and Y positions as separate atoms"),
    ReferenceEncoding("clingcon", "m/clingcon.lp", theory="clingcon",
                      summary="X and Y as clingcon integer variables"),
    ReferenceEncoding("dl", "m/dl.lp", theory="dl", summary="X and Y as clingo-dl difference-logic variables"),
    ReferenceEncoding("plain-inc", "m/incremental/plain.lp", incremental=True,
                      summary="plain, multi-shot over the horizon"),
    ReferenceEncoding("split-inc", "m/incremental/split.lp", incremental=True,
                      summary="split, multi-shot over the horizon"),
    ReferenceEncoding("clingcon-inc", "m/incremental/clingcon.lp", theory="clingcon", incremental=True,
                      summary="clingcon, multi-shot over the horizon"),
)
