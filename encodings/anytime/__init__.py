"""An anytime planner for every domain: a checked plan fast, then better ones.

    from asprilo.encodings.anytime import plan_anytime
    result = plan_anytime(instance, domain, time_limit=30)
    result.plan, result.makespan, result.bound, result.minimal, result.history

Python orchestrates; the search is done by the logic programs beside this file
(``route.lp``, ``assign_goals.lp``, ``assign_shelves.lp``); see encodings/README.md.
"""

from .search import DEFAULT_SECONDS, AnytimeResult, Improvement, plan_anytime

__all__ = ["DEFAULT_SECONDS", "AnytimeResult", "Improvement", "plan_anytime"]
