"""One problem, three readings: A, B and C read the same orders more and more loosely.

In A a delivery hands over units; in B it closes the line it names, whatever the units; in
C it closes every open line of its station that the shelf holds a product of.  So C relaxes
B and B relaxes A: a plan under a stronger reading is one of the weaker reading too, once
the deliveries that close nothing are left out (:func:`.plans.plan_of`).

:func:`reading_plan` turns a plan given to start from (``asprilo solve --start PLAN``) into
a plan of the reading solved, or says in one sentence why it is none; :func:`plan_readings`
solves the readings in turn, each starting from the plan of the one before, so that the
makespans found never grow from A to B to C.  Solved one by one without that, nothing is
guaranteed: each search is random and stops at its time limit.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from asprilo.checker import check
from asprilo.domain import Delivery, Domain, domains
from asprilo.errors import InputError
from asprilo.model import Instance, Plan

from .plans import plan_of
from .start import tracks_of

if TYPE_CHECKING:
    from .search import AnytimeResult

#: the stronger reading of each delivery (B's closes a line, A's hands over units; C's closes
#: a station's lines, B's one line)
STRONGER = {Delivery.LINE: Delivery.UNITS, Delivery.STATION: Delivery.LINE}


def stronger(domain: Domain) -> Domain | None:
    """The built-in domain whose deliveries are the stronger reading of ``domain``'s (None for
    A, M, Md and rule variants)."""
    kind = None if domain.variants else STRONGER.get(domain.delivery)  # type: ignore[arg-type]
    return next((other for other in domains() if kind is not None and other.delivery is kind
                 and not other.variants and other.goal is domain.goal), None)


def readings(domain: Domain) -> list[Domain]:
    """``domain`` and its stronger readings, the strongest last (C: C, B, A)."""
    chain = [domain]
    while (next_one := stronger(chain[-1])) is not None:
        chain.append(next_one)
    return chain


def reading_plan(instance: Instance, domain: Domain, plan: Plan, name: str | None = None) -> Plan:
    """``plan`` as a plan of ``domain``: as it is when it is one, else turned from the first
    stronger reading it is valid under.  A plan valid under none is bad input
    (:class:`~asprilo.errors.InputError` at ``name``), with the checker's first finding."""
    chain = readings(domain)
    for reading in chain:
        if check(instance, plan, reading).valid:
            break
    else:
        others = " or ".join(reading.label for reading in chain[1:])
        also = f" (nor as {others})" if others else ""
        first = check(instance, plan, domain).errors[0].message
        raise InputError(f"not a valid plan of this instance as {domain.label}{also}: {first}", name)
    if reading is domain:
        return plan
    turned = plan_of(tracks_of(plan, instance), instance, domain)
    verdict = check(instance, turned, domain)
    if not verdict.valid:  # C relaxes B relaxes A: a bug of plan_of
        raise InputError(f"the {reading.label} plan read as {domain.label} fails the check: "
                         f"{verdict.errors[0].message}", name)
    return turned


def plan_readings(instance: Instance, weakest: Domain, time_limit: float, seed: int = 0) -> dict[str, AnytimeResult]:
    """The anytime planner on ``weakest`` and its stronger readings, the strongest first, each
    for ``time_limit`` seconds and starting from the plan found for the reading before (read
    as its own: :func:`reading_plan`): reading label -> its
    :class:`~asprilo.encodings.anytime.search.AnytimeResult`.  Each plan is at most as long as
    the one before, since every search reports only plans shorter than the one it starts from
    (and a plan that cannot be turned into the next reading's is bad input: a bug of
    :func:`.plans.plan_of`)."""
    from .search import plan_anytime  # the search imports this module

    results: dict[str, AnytimeResult] = {}
    start: Plan | None = None
    for domain in reversed(readings(weakest)):
        given = None if start is None else reading_plan(instance, domain, start)
        result = plan_anytime(instance, domain, time_limit, seed=seed, start=given)
        results[domain.label] = result
        start = result.plan if result.plan is not None else given
    return results
