"""The ways to solve, looked up by name in one table (:data:`METHODS`).

``auto`` (:mod:`.auto`: the exact search and the anytime planner together, each in a child
process; where one method serves alone, that one), ``asp`` (:mod:`.exact`: a logic program
over growing horizons, with :mod:`.assigned` for a task assignment and :mod:`.program` for
what is grounded), ``flow`` (:mod:`.flow`: max-flow for M/Md) and ``anytime``
(:mod:`.anytime`).  A new method is a :class:`~asprilo.encodings.solving.method.Method` added
to the table.
"""

from __future__ import annotations

from asprilo.domain import Domain
from asprilo.errors import InputError

from ...registry import Encoding
from ..method import Method, spec_rules, unserved_words
from ..request import SolveRequest
from .anytime import Anytime
from .auto import Auto, resolve
from .exact import ExactSearch
from .flow import MaxFlow

#: every method by its name, in the order the command line lists them
METHODS: dict[str, Method] = {method.name: method for method in (Auto(), ExactSearch(), MaxFlow(), Anytime())}


def method_names() -> list[str]:
    return list(METHODS)


def find_method(name: str) -> Method:
    """The method called ``name``; an unknown name is bad input."""
    method = METHODS.get(name)
    if method is None:
        *others, last = METHODS
        raise InputError(f"unknown method '{name}' (choose {', '.join(others)} or {last})")
    return method


def method_for(request: SolveRequest) -> Method:
    """The method that serves ``request``, once the request is found fit for it (bad input:
    :class:`~asprilo.errors.InputError`)."""
    if request.horizon is not None and request.horizon < 0:
        raise InputError(f"the horizon must be at least 0, got {request.horizon}")
    method = find_method(request.method)
    method.check(request)
    if request.instance.assignment and request.assign:
        raise InputError("the instance assigns goals to robots already; leave out --assign")
    return method


def methods_words(domain: Domain, encoding: Encoding | None = None) -> str:
    """Which methods serve ``domain`` (those that honour its rules) and which do not, in one
    sentence, with the ``encoding`` the exact search runs; ``""`` for a domain with SPEC.md's
    rules (where each method serves the domains it was written for)."""
    if spec_rules(domain):
        return ""
    methods = [method for method in METHODS.values() if method.name != "auto"]
    unserved = [method.words for method in methods if not method.honours(domain)]
    if not unserved:
        return ""
    served = [method.words for method in methods if method.honours(domain)]
    said = f"{domain.label}: {' and '.join(unserved)} know only SPEC.md's rules, not {unserved_words(domain)}"
    if encoding is None:
        return f"{said}; no method serves it without an encoding: give yours (--encoding FILE)"
    if encoding.name in domain.variants:
        runs = f"the model solution of variant '{encoding.name}'"
    else:
        runs = "your encoding" if encoding.own else f"the encoding '{encoding.name}'"
    return f"{said}; {' and '.join(served)} serve{'s' * (len(served) == 1)} it, with {runs}"


__all__ = ["METHODS", "Method", "find_method", "method_for", "method_names", "methods_words", "resolve"]
