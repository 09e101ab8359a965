"""Minimal for the problem, or only for the encoding: one notion and the sentences that say it
(``solve``, its ``--json``, ``grade``, ``bench``, the viewer, ``check --watch``).

A plan is *minimal* only when it is valid and its makespan meets what is proven for the
problem: the domain's lower bound, or the minimum a trusted source proved -- the reference
encodings' horizon search, max-flow for M/Md, a ladder's stored minimum, a teacher's model
solution in ``grade``.  A user's own encoding proves less: when it refutes every horizon
below its plan's, its plan is *the shortest plan this encoding allows*, which a weaker action
model (a move forbidden, one robot at a time) makes longer than the problem's minimum.  So
an outcome says both (:func:`settle`): ``minimal`` for the problem and ``encoding_minimal``
for the encoding, with the problem's ``minimum`` where it is known; and the horizons an own
encoding refutes do not raise the bound proven for the problem (``trusted``).  An invalid
plan is neither.

    settle(request, outcome)                      # in solve, after every method
    learn_minimum(outcome, instance)              # the CLI: the ladder's or max-flow's minimum
    proof(outcome)  # "proven minimal", "the shortest plan this encoding allows (10); the problem's minimum is 8, ..."
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.model import Instance

from .outcome import Outcome
from .status import SolveStatus

if TYPE_CHECKING:
    from .request import SolveRequest

#: how long max-flow may take to find the minimum an own encoding is compared with (a hang guard)
FLOW_SECONDS = 10.0


@dataclass(frozen=True)
class Minimum:
    """The problem's minimal makespan (``makespan``) and who proved it, in words (``by``:
    ``by max-flow``, ``as the A ladder stores it for 05-x4_y4_r2.lp``)."""

    makespan: int
    by: str


def settle(request: SolveRequest, outcome: Outcome) -> None:
    """Say what ``outcome``'s plan is minimal for.  A reference encoding or method proves its
    search's claim for the problem; a user's own encoding (``Encoding.own``) only for itself:
    its plan is minimal for the problem where it meets the lower bound.  An invalid plan is
    minimal for nothing (not even along an assignment)."""
    encoding = request.encoding
    outcome.trusted = encoding is None or not encoding.own or request.method != "asp"
    if outcome.plan is not None and not outcome.found:
        outcome.minimal = outcome.encoding_minimal = outcome.minimal_along_assignment = False
        return
    if not outcome.found or outcome.horizon is None:
        return
    outcome.encoding_minimal = outcome.encoding_minimal or outcome.minimal  # settled twice: the same
    if not outcome.trusted:
        outcome.minimal = outcome.horizon <= outcome.lower_bound
    if outcome.minimal:
        outcome.minimum, outcome.minimum_by = outcome.horizon, ""


def learn_minimum(outcome: Outcome, instance: Instance, seconds: float = FLOW_SECONDS) -> None:
    """For a valid plan of an own encoding not proven minimal for the problem: the problem's
    minimum where it is cheap to know (:func:`known_minimum`); a plan of that makespan is then
    minimal."""
    if not outcome.found or outcome.trusted or outcome.minimal or outcome.horizon is None:
        return
    known = known_minimum(instance, outcome.domain, seconds)
    if known is None:
        return
    outcome.minimum, outcome.minimum_by = known.makespan, known.by
    outcome.minimal = outcome.horizon <= known.makespan


def known_minimum(instance: Instance, domain: Domain, seconds: float = FLOW_SECONDS) -> Minimum | None:
    """The minimal makespan of ``instance`` under ``domain``'s rules, cheaply: stored in the
    domain's bundled ladder (the very instance), else by max-flow where it serves the domain
    (M, Md) within ``seconds``; ``None``: unknown."""
    stored = ladder_minimum(instance, domain)
    if stored is not None:
        return stored
    from .methods import find_method

    if not find_method("flow").honours(domain):
        return None
    from .front import solve

    try:
        found = solve(instance, domain, method="flow", time_limit=seconds)
    except InputError:  # an instance max-flow does not take (said by solve where it matters): unknown
        return None
    if found.found and found.minimal and found.horizon is not None:
        return Minimum(found.horizon, "by max-flow")
    return None


def ladder_minimum(instance: Instance, domain: Domain) -> Minimum | None:
    """The minimum the bundled ladder of ``domain`` stores for ``instance`` (the same facts as
    one of its instances), or ``None``."""
    from asprilo.reader import read_instance

    from ..ladder import bundled_domains, bundled_ladder

    if domain.value not in bundled_domains():
        return None
    ladder = bundled_ladder(domain)
    for rung in ladder.rungs:
        if rung.minimum is not None and read_instance(rung.file) == instance:
            return Minimum(rung.minimum, f"as {ladder.label} stores it for {rung.file.name}")
    return None


def proof(outcome: Outcome) -> str:
    """What is proven of a valid plan's makespan, in words: ``proven minimal`` (by a minimum
    known besides the search: which); for an own encoding that refuted every shorter horizon,
    :func:`sentence`; else the problem's minimum or the bound proven for it, and the gap (with
    a first stage, whether no shorter plan follows its answer)."""
    if outcome.minimal:  # (by a minimum known besides the search: said whose)
        return "proven minimal" + (f": {problem_minimum(outcome.minimum, by=outcome.minimum_by)}"
                                   if outcome.minimum_by else "")
    horizon = outcome.horizon if outcome.horizon is not None else 0
    if outcome.encoding_minimal:
        return sentence(horizon, outcome.minimum, outcome.proven_bound, outcome.minimum_by)
    along = "minimal along the first stage's answer; " if outcome.stage and outcome.minimal_along_assignment else ""
    if outcome.minimum is not None:
        steps = horizon - outcome.minimum
        return (f"{along}not minimal: {problem_minimum(outcome.minimum, outcome.proven_bound, outcome.minimum_by)}, "
                f"gap {steps} step{'s' * (steps != 1)}")
    bound, gap = outcome.proven_bound, outcome.gap
    if not bound or bound == math.inf or gap is None:
        return f"{along}not proven minimal"
    return (f"{along}not proven minimal: no plan is shorter than {bound:g}, gap {gap:g} step{'s' * (gap != 1)}, "
            f"{100 * gap / bound:.0f}%")


def sentence(makespan: int, minimum: int | None, at_least: float | None = None, by: str = "") -> str:
    """The plan of an encoding that allows none shorter, its makespan above what is proven for
    the problem: ``the shortest plan this encoding allows (10); the problem's minimum is 8, by
    max-flow`` (``minimum``: ``None`` where unknown; ``at_least``: no plan is shorter)."""
    return f"the shortest plan this encoding allows ({makespan}); {problem_minimum(minimum, at_least, by)}"


def problem_minimum(minimum: int | None, at_least: float | None = None, by: str = "") -> str:
    """``the problem's minimum is 8[, BY]``, or ``the problem's minimum is unknown[: no plan is
    shorter than L]``."""
    if minimum is not None:
        return f"the problem's minimum is {minimum}" + (f", {by}" if by else "")
    if at_least and math.isfinite(at_least):
        return f"the problem's minimum is unknown: no plan is shorter than {at_least:g}"
    return "the problem's minimum is unknown"


def refuted_words(outcome: Outcome, horizons: str, several: bool = True) -> str:
    """The horizons refuted (``horizons``: as the caller shows them, ``several`` or one), in
    words: for the problem (``no plan is shorter than L``), or for a user's own encoding only."""
    plural = "s" * several
    if outcome.trusted:
        return f"refuted horizon{plural} {horizons}: no plan is shorter than {outcome.proven_bound:g}"
    return (f"your encoding has no plan at horizon{plural} {horizons} (refuted for the encoding only, not for the "
            "problem)")


def no_plan_headline(outcome: Outcome) -> str:
    """``no plan exists``, or for a user's own encoding that has no answer set, what that
    proves: nothing for the problem."""
    if outcome.status is not SolveStatus.NONE or outcome.trusted or outcome.lower_bound == math.inf:
        return "no plan exists"
    refuted = outcome.refuted
    if refuted:
        return refuted_words(outcome, ", ".join(map(str, refuted)), len(refuted) > 1)
    return "no plan with your encoding (not refuted for the problem)"
