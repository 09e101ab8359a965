"""Replay a plan step by step (SPEC.md §4) in plain Python: the state after every step and
every rule the plan breaks.

This is the second, independent implementation of the rules that the ASP checker
(``asprilo.checker``) implements; the two report exactly the same violations, named as the
checker's ``err(Module,Check,Params)`` atoms.  The visualizer animates from it.

How a plan that breaks a rule changes the state (the checker does the same):

- An action takes effect only when it is well formed: a robot of the instance acts at a
  step >= 1, it is the robot's only action at that step, the name is an action of the
  domain and the arguments have the right shape.  Otherwise it is reported and ignored.
- ``move`` always takes effect: the robot (and the shelf it carries) goes where the plan
  says, even off the floor, onto another robot or a resting shelf.
- ``pickup`` lifts the shelf resting on the robot's node unless the robot already carries
  one or none rests there.  Where an earlier error left several shelves resting on one
  node the smallest id is lifted; where several robots pick up one shelf at once the
  robot with the smallest id gets it.  (The same tie-break settles an instance in which
  several robots carry one shelf.)
- ``putdown`` puts the carried shelf down wherever the robot stands (also on a highway,
  a picking station, off the floor or onto another shelf); without a shelf it does nothing.
- ``deliver`` takes effect when the robot carries a shelf, stands on the order's picking
  station and, in A and B, the shelf lists the product.  In A the units the order line
  misses and the units on the shelf both drop by N, never below zero: an over-delivery
  is reported and then completes the line instead of spoiling every later step.  In B it
  closes the line (O,P); in C it closes every open line, of every order of that
  station, whose product the shelf lists.
- In A a quantity-free fact (``on S`` / ``line P``) counts as one unit.

State checks are event based: collisions and swaps of robots at every step; a shelf
coming onto a node where another shelf rests is reported by the action that does it.

The package: :mod:`.actions` (which actions take effect), :mod:`.replay` (the replay),
:mod:`.checks` (the instance at step 0, the goal at the horizon), :mod:`.timeline` (the
states it records), :mod:`.violations` and :mod:`.messages` (broken rules in plain words).
"""

from __future__ import annotations

from ..domain import Domain, detect_domain
from ..limits import require_plan_fits
from ..model import Instance, Plan
from .actions import well_formed
from .replay import replay
from .timeline import Line, State, Stock, Timeline
from .violations import Violation, sort_violations

__all__ = ["Line", "State", "Stock", "Timeline", "Violation", "simulate", "sort_violations",
           "well_formed"]


def simulate(instance: Instance, plan: Plan, domain: Domain | None = None) -> Timeline:
    """Replay ``plan`` on ``instance`` (domain detected when not given); a plan beyond the
    ``robot-steps`` limit is refused (:class:`~asprilo.errors.InputError`)."""
    require_plan_fits(instance, plan)
    domain = domain or detect_domain(instance, plan)
    history, findings = replay(instance, plan, domain)
    return Timeline(instance, plan, domain, history, findings)
