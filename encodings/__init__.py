"""Reference encodings per domain and style, their registry, and the solve front end.

    from asprilo.encodings import solve, ENCODINGS
    outcome = solve("instance.lp", encoding="plain", time_limit=60)
    outcome.plan, outcome.horizon, outcome.minimal, outcome.stats
"""

from .registry import ENCODINGS, Encoding, encoding_names, find_encoding
from .search import Attempt, Outcome, Phase, SolveStatus, solve

__all__ = ["ENCODINGS", "Encoding", "encoding_names", "find_encoding",
           "Attempt", "Outcome", "Phase", "SolveStatus", "solve"]
