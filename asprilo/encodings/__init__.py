"""Reference encodings per domain and style, their registry, and the solve front end.

    from asprilo.encodings import solve, reference_encodings
    outcome = solve("instance.lp", encoding="plain", time_limit=60)
    outcome.plan, outcome.horizon, outcome.minimal, outcome.stats

``solve`` also takes a :class:`SolveRequest`; the methods behind it live in :mod:`.solving`.
"""

from .registry import Encoding, encoding_names, find_encoding, reference_encodings
from .solving import Attempt, LowerBounds, Outcome, Phase, SolveRequest, SolveStatus, solve

__all__ = ["Encoding", "encoding_names", "find_encoding", "reference_encodings",
           "Attempt", "LowerBounds", "Outcome", "Phase", "SolveRequest", "SolveStatus", "solve"]
