"""Solving: one request, one method interface, one vocabulary, one stop-watch.

    from asprilo.encodings.solving import SolveRequest, solve
    outcome = solve("instance.lp", method="asp", encoding="plain", time_limit=60)
    outcome = solve(SolveRequest(instance, Domain.B, horizon=12), cancel=event)

The modules, from the bottom up: :mod:`.status` (``SolveStatus``, ``Attempt``, ``Phase``),
:mod:`.bounds` (the lower bounds, computed once per solve), :mod:`.watch` (time budget,
cancel, listeners, statistics), :mod:`.outcome`, :mod:`.request` (``SolveRequest``),
:mod:`.method` (the ``Method`` interface), :mod:`.methods` (the table of methods: the exact
horizon search, max-flow, anytime), :mod:`.front` (``solve``: the request checked, the
bounds, the watch, the child process, the check of the plan) and :mod:`.minimality` (minimal
for the problem, or only for a user's own encoding, and the words that say it).
"""

from .bounds import LowerBounds, lower_bounds
from .front import request_for, solve, solve_request
from .method import Method
from .methods import METHODS, find_method, method_names
from .methods.program import ground, name_robots
from .outcome import Outcome
from .request import SolveOptions, SolveRequest
from .status import Attempt, Phase, SolveStatus
from .watch import Listeners, Watch

__all__ = ["LowerBounds", "lower_bounds", "request_for", "solve", "solve_request", "Method", "METHODS",
           "find_method", "method_names", "ground", "name_robots", "Outcome", "SolveOptions", "SolveRequest",
           "Attempt", "Phase", "SolveStatus", "Listeners", "Watch"]
