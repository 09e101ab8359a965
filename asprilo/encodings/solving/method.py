"""The interface every way to solve implements (:class:`Method`), and how the front end
finds the method of a request.

A method has a name (``asprilo solve --method NAME``), checks the requests it is given
(:class:`~asprilo.errors.InputError` for one it cannot serve) and runs a checked request
under a :class:`.Watch`.  The request it runs carries the lower bounds; the front end
checks the plan it returns (unless the method did) and runs it in a child process when
asked.  A new method is a subclass registered in the table of :mod:`.methods`.

A method says which rules its plans follow (:meth:`Method.honours`): those that run a logic
program follow the domain's own encodings (or the caller's); max-flow and the anytime planner
are written in Python for SPEC.md's rules and honour only domains with exactly those rules
(:func:`spec_rules`), not a rule variant nor a domain registered with a checker concern more.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import ClassVar

from asprilo.domain import Domain
from asprilo.errors import InputError

from .outcome import Outcome
from .request import SolveRequest
from .watch import Watch


class Method(ABC):
    """One way to find a plan."""

    #: the name requests use (``SolveRequest.method``)
    name: ClassVar[str]
    #: the method in words (``the exact search``)
    words: ClassVar[str] = ""
    #: whether it runs a logic program (``SolveRequest.encoding``, resolved by name when the
    #: caller gives a name)
    encoded: ClassVar[bool] = False
    #: whether it runs its parts in child processes itself (the front end then never runs it
    #: in a child, ``isolate`` or not)
    isolates_itself: ClassVar[bool] = False
    #: whether it computes the lower bounds itself, beside its search (the front end then
    #: leaves them to it: the strong bound of a large A/B/C floor takes minutes)
    bounds_beside: ClassVar[bool] = False

    def honours(self, domain: Domain) -> bool:
        """Whether the plans of this method follow ``domain``'s rules (by default they do: a
        method that runs a logic program runs the domain's own encoding or the caller's)."""
        return True

    def check(self, request: SolveRequest) -> None:
        """Raise :class:`~asprilo.errors.InputError` if this method cannot serve ``request``
        (by default it serves every request)."""
        return None

    def refuse_other_rules(self, request: SolveRequest, words: str, rules: str = "SPEC.md's rules") -> None:
        """For a method that runs no logic program (``words`` names it: "the flow method"; it
        knows ``rules``): refuse an encoding of one's own (it would go unused), a domain whose
        rules it does not honour, and a first stage."""
        if request.encoding is not None and request.encoding.own:
            raise InputError(runs_no_encoding(self.name))
        if not self.honours(request.domain):
            raise InputError(f"{words} knows only {rules}, not {unserved_words(request.domain)}; leave "
                             f"out --method (the exact search runs the domain's own encoding) or give your own "
                             f"with --encoding FILE")
        if request.stage is not None:
            raise InputError(f"--stage goes with an encoding: {words} runs none")

    def quick(self, request: SolveRequest) -> bool:
        """Whether ``request`` is so small that this method answers it before a child process
        would have started: then it runs here even with ``isolate`` (no memory limit asked)."""
        return False

    def time_limit(self, request: SolveRequest) -> float | None:
        """The seconds it may take (``None``: no limit)."""
        return request.time_limit

    def label(self, request: SolveRequest) -> str:
        """What the outcome names as its ``encoding``."""
        return self.name

    @abstractmethod
    def run(self, request: SolveRequest, watch: Watch) -> Outcome:
        """Solve ``request`` (checked, with its lower bounds) within ``watch``'s limits."""


def runs_no_encoding(method: str) -> str:
    """Why ``--method METHOD`` (one that runs no logic program) refuses ``--encoding``."""
    return (f"--method {method} runs no encoding, so --encoding would be ignored: leave out --method to run "
            f"the encoding with the exact search, or --encoding to run the {method} method")


def spec_rules(domain: Domain) -> bool:
    """Whether ``domain``'s rules are those of a built-in domain (SPEC.md): its moves, its
    checker concerns and their facts and constants, its actions, deliveries and goal are those
    of A, B, C, M or Md.  A domain registered at run time under another name with the same
    rules has them; a rule variant (``M+diagonal``) or a domain with a checker concern more
    (docs/EXTENDING.md's Mc) has not, whatever its name."""
    from asprilo.domain import a, b, c, m, md
    from asprilo.domain.variants import is_standard

    return is_standard(domain) and any(
        (domain.checker, domain.constants, domain.actions, domain.delivery, domain.goal, domain.work)
        == (builtin.checker, builtin.constants, builtin.actions, builtin.delivery, builtin.goal, builtin.work)
        for builtin in (a.A, b.B, c.C, m.M, md.MD))


def unserved_words(domain: Domain) -> str:
    """Why the methods written for SPEC.md's rules do not serve ``domain``, in words."""
    if domain.variants:
        names = ", ".join(f"'{name}'" for name in domain.variants)
        return f"the rules of variant{'s' * (len(domain.variants) > 1)} {names}"
    return f"the rules of domain {domain.label} (its checker concerns are not those of a built-in domain)"
