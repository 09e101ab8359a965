"""What the anytime planner's errand tests share: an A instance's work as first assigned, and
one robot's actions written by hand."""

from __future__ import annotations

from asprilo.bounds import Floor
from asprilo.domain import Domain
from asprilo.encodings.anytime.grid import Grid
from asprilo.encodings.anytime.work import Work
from asprilo.model import Instance


def assigned_work(instance: Instance) -> Work:
    """The work of the domain-A ``instance`` after its first assignment (1 s at most)."""
    work = Work(instance, Domain.A, Grid(Floor(instance.cells)), 0)
    assert work.assign(1.0, lambda: False)
    return work


def hand(*steps) -> list[tuple]:
    """The actions of one robot, one per step from 1: a direction, or ``name`` or
    ``name:arguments``."""
    actions = []
    for step, action in enumerate(steps, 1):
        if isinstance(action, tuple):
            actions.append((step, "move", action))
        else:
            name, _, args = action.partition(":")
            actions.append((step, name, tuple(int(a) for a in args.split(",")) if args else ()))
    return actions
