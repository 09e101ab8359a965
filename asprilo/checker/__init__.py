"""The modular plan checker (SPEC.md §4-5): logic programs per domain and the diagnostics
and metrics built on them.

    from asprilo.checker import check
    report = check(instance, plan)          # domain detected when not given
    report.valid, report.errors[0].atom, report.errors[0].message, report.metrics

Each broken rule is an atom ``err(Module,Check,Params)`` derived by the logic program of
one concern (``asprilo/checker/<Module>.lp``); see ``asprilo/checker/README.md`` for every check.
"""

from __future__ import annotations

from asprilo.domain import Domain, detect_domain
from asprilo.limits import require_plan_fits
from asprilo.model import Instance, Plan

from .programs import err_atoms
from .report import STRENGTHS, Report, Strength, build_report

__all__ = ["check", "Report", "STRENGTHS", "Strength"]


def check(instance: Instance, plan: Plan, domain: Domain | None = None, *, makespan_bound: float | None = None,
          sum_of_costs_bound: float | None = None, bound: Strength | None = "cheap") -> Report:
    """Check ``plan`` on ``instance`` with the ASP checker of ``domain`` (a plan beyond the
    ``robot-steps`` limit is refused: :class:`~asprilo.errors.InputError`).

    ``makespan_bound`` and ``sum_of_costs_bound``: the lower bounds of the metrics, when the
    caller has computed them already (a solver checking its plans); those not given are
    computed here, after the verdict, at strength ``bound``: ``cheap`` (the default:
    milliseconds) or ``strong`` (the strongest: up to seconds on A/B/C), or ``None`` (none:
    :func:`~asprilo.checker.report.add_bounds` puts them in later).  The verdict and the
    violations do not depend on it; ``report.metrics["bounds"]`` says which bounds the
    metrics show (``given``, ``cheap`` or ``strong``).
    """
    require_plan_fits(instance, plan)
    domain = domain or detect_domain(instance, plan)
    atoms, statistics = err_atoms(instance, plan, domain)
    return build_report(instance, plan, domain, atoms, statistics.as_dict(), (makespan_bound, sum_of_costs_bound),
                        bound)
