"""The rules a plan is shown under, without Qt: the domain the viewer's rule variants make
(``viz --variant``), whether the Python simulator knows all of its rules, and the ASP
checker's verdict where it does not.

The simulator (:mod:`asprilo.simulate`) replays SPEC.md's rules with the domain's moves; a
variant's other rules (two robots crossing, energy, sides, a relaxed goal) and the checker
concerns of a domain registered at run time are known to the checker only.  For such a
domain the viewer shows the checker's violations, and where the domain's goal is not the
simulator's (a concern of its base replaced), the order lines the checker calls unfilled
had the plan ended at the step shown (:func:`unfilled_lines` of a check of the plan's
first steps).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.model import Instance, Plan
from asprilo.simulate import Violation

if TYPE_CHECKING:
    from asprilo.domain.variant_file import VariantFile

Line = tuple[int, int]
#: the goal's check of an order line not filled at the horizon
UNFILLED = ("goal", "unfilledOrder")
#: the varied domains made so far: (base, variant files) -> domain (one descriptor per pair,
#: so that the checker parses its programs once and the registry keeps one of each)
_VARIED: dict[tuple[Domain, tuple], Domain] = {}


def varied(domain: Domain, variants: Sequence[VariantFile]) -> Domain:
    """``domain`` changed by ``variants`` in turn (the same descriptor for the same pair);
    :class:`InputError` when a variant does not fit the domain."""
    if not variants:
        return domain
    key = (domain, tuple(variants))
    if key not in _VARIED:
        from asprilo.domain.variants import with_variants  # YAML and variant files: only with variants
        _VARIED[key] = with_variants(domain, list(variants))
    return _VARIED[key]


def simulator_knows(domain: Domain) -> bool:
    """Whether the simulator knows every rule of ``domain``: SPEC.md's moves, no variant, and
    only the checker's own concerns (a domain registered at run time may add files of its own)."""
    from asprilo.domain.variants import is_standard
    return is_standard(domain) and not any(Path(concern).is_absolute() for concern in domain.checker)


def goal_known(domain: Domain) -> bool:
    """Whether the simulator's open order lines are the checker's: the domain keeps every
    concern of the built-in domain it starts from (the moves' aside, which decide no goal)."""
    if not domain.variants:
        return True
    from asprilo.domain.variants import DIRECTIONS_CONCERN, base_of
    try:
        base = Domain.parse(base_of(domain))
    except InputError:
        return False
    return not set(base.checker) - set(domain.checker) - {DIRECTIONS_CONCERN}


def checker_violations(instance: Instance, plan: Plan, domain: Domain) -> list[Violation]:
    """The ASP checker's violations of ``plan`` (in the simulator's words where it has them,
    the variant's templates otherwise); a checker that cannot run (a variant's program with a
    mistake) is one violation that says why."""
    from asprilo.checker import check
    try:
        return list(check(instance, plan, domain, bound=None).errors)
    except InputError as error:
        return [Violation("checker", "failed", (0,), 0, f"the ASP checker of {domain.label} cannot run: {error}")]


def about_orders(domain: Domain, violation: Violation) -> bool:
    """Whether ``violation`` says an order is not served: the goal's ``unfilledOrder``, or a
    variant's check whose words name an order first (a relaxed goal's)."""
    return (violation.module, violation.check) == UNFILLED or _kinds(domain, violation)[:1] == ["order"]


def unfilled_lines(instance: Instance, domain: Domain, violations: Sequence[Violation]) -> set[Line]:
    """The order lines ``violations`` call unfilled: ``(order, product)`` where they name both,
    every line of the order where they name the order alone."""
    lines: set[Line] = set()
    for violation in violations:
        params: tuple[Any, ...] = violation.params
        if not about_orders(domain, violation) or not params:
            continue
        order = params[0]
        named = (violation.module, violation.check) == UNFILLED or _kinds(domain, violation)[1:2] == ["product"]
        products = [params[1]] if named and len(params) > 1 else \
            list(instance.orders[order].lines) if order in instance.orders else []
        lines.update((order, product) for product in products)
    return lines


def _kinds(domain: Domain, violation: Violation) -> list[str]:
    """The kinds of a check's parameters as a variant's words name them (none for others)."""
    params: tuple[tuple[str, str], ...] = getattr(domain.messages.get((violation.module, violation.check)),
                                                   "params", ())
    return [kind for _name, kind in params]


def plan_until(plan: Plan, step: int) -> Plan:
    """The plan's actions up to ``step``: the plan as if it ended there."""
    return Plan([action for action in plan.actions if action.step <= step])
