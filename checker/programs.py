"""The checker's logic programs: one per domain (``domains/<domain>.lp``, made of the
concern files beside this module), fed with an instance and a plan through the solver
driver; the result is the set of ``err/3`` atoms.

Facts reach clingo as text.  Moves, the bulk of any large plan, are handed over packed
(``packed.lp``: thirteen moves of one robot in one integer), because clingo parses and
grounds a plain ``occurs/3`` fact several times slower than one packed move; every other
action stays an ``occurs/3`` fact.
"""

from __future__ import annotations

from pathlib import Path

import clingo
import numpy as np

from asprilo.domain import Domain
from asprilo.model import Instance, Plan
from asprilo.solver import Solver, Statistics
from asprilo.writer import format_action, format_instance

HERE = Path(__file__).resolve().parent

#: move directions as packed.lp numbers them (0: no move)
_PACKED = {(1, 0): 1, (-1, 0): 2, (0, 1): 3, (0, -1): 4}
_DIGITS = 13  # moves per packed integer: 5**13 - 1 < 2**31


def program(domain: Domain) -> Path:
    """The checker for ``domain``: a file including the concerns it is made of."""
    return HERE / "domains" / f"{domain.value}.lp"


def instance_facts(instance: Instance) -> str:
    """The instance as ``init/2`` facts."""
    return format_instance(instance, header=[])


def plan_facts(instance: Instance, plan: Plan, packed: bool = True) -> str:
    """The plan as facts: ``packedMoves/3`` for the moves of robots of the instance at steps
    >= 1 that are the robot's only action at their step, ``occurs/3`` for all others
    (for all actions with ``packed=False``)."""
    if not packed:
        return "\n".join(format_action(action) + "." for action in plan.actions)
    robots = sorted(r for r in instance.robots if isinstance(r, int))
    row = {robot: i for i, robot in enumerate(robots)}
    blocks = -(-max(plan.horizon, 1) // _DIGITS)
    digits = np.zeros((len(robots), blocks * _DIGITS), dtype=np.int64)
    others: list[str] = []
    actions = plan.actions  # sorted: one robot's actions at one step are adjacent
    last = len(actions) - 1
    for i, action in enumerate(actions):
        code = _PACKED.get(action.args) if action.name == "move" and action.kind == "robot" else None
        if (code is None or action.step < 1 or action.robot not in row
                or type(action.args[0]) is not int
                or (i > 0 and _same_slot(actions[i - 1], action))
                or (i < last and _same_slot(actions[i + 1], action))):
            others.append(format_action(action) + ".")
        else:
            digits[row[action.robot], action.step - 1] = code
    weights = 5 ** np.arange(_DIGITS, dtype=np.int64)
    codes = digits.reshape(len(robots), blocks, _DIGITS) @ weights
    packed = [f"packedMoves({robots[r]},{1 + b * _DIGITS},{codes[r, b]})."
              for r, b in zip(*np.nonzero(codes))]
    return "\n".join(packed + others)


def _same_slot(a, b) -> bool:
    return a.step == b.step and a.robot == b.robot and a.kind == b.kind


def run_checker(facts: str, domain: Domain) -> tuple[list[clingo.Symbol], Statistics]:
    """Ground and solve the checker of ``domain`` on ``facts``; its ``err/3`` atoms."""
    solver = Solver(options=["--warn=none"])
    solver.load(program(domain))
    solver.load(HERE / "packed.lp")
    solver.add(facts)
    solver.ground()
    result = solver.solve()
    return [symbol for symbol in result.symbols if symbol.match("err", 3)], solver.stats


def err_atoms(instance: Instance, plan: Plan, domain: Domain,
              packed: bool = True) -> tuple[list[clingo.Symbol], Statistics]:
    """The ``err/3`` atoms of ``plan`` on ``instance`` in ``domain``."""
    return run_checker(instance_facts(instance) + "\n" + plan_facts(instance, plan, packed), domain)
