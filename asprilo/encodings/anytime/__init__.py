"""An anytime planner for every domain: a checked plan fast, then better ones.

    from asprilo.encodings.anytime import plan_anytime
    result = plan_anytime(instance, domain, time_limit=30)
    result.plan, result.makespan, result.bound, result.minimal, result.history

Python orchestrates; the search is done by the logic programs beside this file
(``route.lp``, ``assign_goals.lp``, ``assign_shelves.lp``); see asprilo/encodings/README.md.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

#: the time limit when none is given (seconds)
DEFAULT_SECONDS = 60.0

if TYPE_CHECKING:
    from .search import AnytimeResult, Improvement, plan_anytime

__all__ = ["DEFAULT_SECONDS", "AnytimeResult", "Improvement", "plan_anytime"]


def __getattr__(name: str) -> Any:
    """The planner's names, imported when first asked for (its modules are many: a command
    that only needs the default time limit does not load them)."""
    if name in ("AnytimeResult", "Improvement", "plan_anytime"):
        from . import search
        return getattr(search, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
