"""The interface every way to solve implements (:class:`Method`), and how the front end
finds the method of a request.

A method has a name (``asprilo solve --method NAME``), checks the requests it is given
(:class:`~asprilo.errors.InputError` for one it cannot serve) and runs a checked request
under a :class:`.Watch`.  The request it runs carries the lower bounds; the front end
checks the plan it returns (unless the method did) and runs it in a child process when
asked.  A new method is a subclass registered in the table of :mod:`.methods`.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import ClassVar

from .outcome import Outcome
from .request import SolveRequest
from .watch import Watch


class Method(ABC):
    """One way to find a plan."""

    #: the name requests use (``SolveRequest.method``)
    name: ClassVar[str]
    #: whether it runs a logic program (``SolveRequest.encoding``, resolved by name when the
    #: caller gives a name)
    encoded: ClassVar[bool] = False
    #: whether it runs its parts in child processes itself (the front end then never runs it
    #: in a child, ``isolate`` or not)
    isolates_itself: ClassVar[bool] = False

    def check(self, request: SolveRequest) -> None:
        """Raise :class:`~asprilo.errors.InputError` if this method cannot serve ``request``
        (by default it serves every request)."""
        return None

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
