"""The checker's logic programs: for each domain, the concern files its descriptor names
(``Domain.checker``: files beside this module, or paths of a domain's own), fed with an
instance and a plan through the solver driver; the result is the set of ``err/3`` atoms.
``domains/<domain>.lp`` includes the same files, for running the checker with plain clingo.

Facts reach clingo as text.  Moves, the bulk of any large plan, are handed over packed
(``packed.lp``: thirteen moves of one robot in one integer), because clingo parses and
grounds a plain ``occurs/3`` fact several times slower than one packed move; every other
action stays an ``occurs/3`` fact.  So are the nodes of a large floor (thirty cells of a row
in one integer): clingo keeps every parsed fact, about 2 kB for a node's ``init/2`` fact
against 0.2 kB for a ``node/1`` atom it derives (1,000,000 nodes: 1.95 GB against 0.23 GB).
"""

from __future__ import annotations

import threading
from dataclasses import replace
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING

import clingo

from asprilo.domain import Domain
from asprilo.facts import format_action
from asprilo.facts import instance_facts as all_facts
from asprilo.model import Instance, Plan, Term
from asprilo.solver import Solver, Statistics

if TYPE_CHECKING:  # the checker's statements are parsed from a domain's second check on (run_checker)
    import clingo.ast

HERE = Path(__file__).resolve().parent

#: move directions as packed.lp numbers them (0: no move)
_PACKED = {(1, 0): 1, (-1, 0): 2, (0, 1): 3, (0, -1): 4}
_DIGITS = 13  # moves per packed integer: 5**13 - 1 < 2**31
PACK_FROM = 2_000
_ROW_BITS = 30  # cells of a row per packed integer: 2**30 - 1 < 2**31

#: the domains checked in this process so far (their checker is parsed once, at the second check)
_checked: set[Domain] = set()
#: held while a thread loads the checker, parses it or hands its parsed statements to a control:
#: the statements are shared by every check of a domain, and a bench run with --jobs 2 once
#: failed in the checker with 'invalid ast: term expected' (.ci/flows)
_PARSED = threading.Lock()


def concerns(domain: Domain) -> list[Path]:
    """The checker's files for ``domain``, in the order its descriptor names them."""
    return [HERE / f"{name}.lp" if not Path(name).is_absolute() else Path(name) for name in domain.checker]


def instance_facts(instance: Instance, packed: bool | None = None) -> str:
    """The instance as ``init/2`` and ``assign/2`` facts; the nodes as ``packedNodes/3``
    facts (``packed.lp``) with ``packed``, by default from ``PACK_FROM`` nodes on."""
    if packed is None:
        packed = len(instance.nodes) >= PACK_FROM
    if not packed or not instance.nodes:
        return "\n".join(all_facts(instance))
    return "\n".join([*all_facts(replace(instance, nodes={})), *_packed_nodes(instance)])


def _packed_nodes(instance: Instance) -> list[str]:
    """``packedNodes(Y,X0,Bits)``: bit I of Bits says that (X0+I,Y) is a node (I < 30)."""
    import numpy as np
    cells = np.array(list(instance.nodes.values()), dtype=np.int64)
    xs, ys = cells[:, 0], cells[:, 1]
    least = int(xs.min())
    blocks, bits = np.divmod(xs - least, _ROW_BITS)
    keys = np.unique((ys - int(ys.min())) * (int(blocks.max()) + 1) + blocks, return_inverse=True)
    codes = np.zeros(len(keys[0]), dtype=np.int64)
    np.bitwise_or.at(codes, keys[1], np.left_shift(1, bits))
    first = np.unique(keys[1], return_index=True)[1]  # one node of each (row, block)
    return [f"packedNodes({y},{least + block * _ROW_BITS},{code})."
            for y, block, code in zip(ys[first].tolist(), blocks[first].tolist(), codes.tolist(), strict=True)]


def plan_facts(instance: Instance, plan: Plan, packed: bool | None = None) -> str:
    """The plan as facts: ``packedMoves/3`` for the well-formed moves of robots of the
    instance at steps >= 1 that are the robot's only action at their step, ``occurs/3``
    for all other actions (for all actions with ``packed=False``; by default moves are
    packed from ``PACK_FROM`` actions on, where parsing time begins to count)."""
    actions = plan.actions
    if packed is None:
        packed = len(actions) >= PACK_FROM
    if not packed or not actions:
        return "\n".join(format_action(action) + "." for action in actions)
    import numpy as np
    robots = sorted(instance.robots)
    row: dict[Term, int] = {robot: i for i, robot in enumerate(robots)}
    rows = np.array([row.get(a.robot, -1) if a.kind == "robot" else -1 for a in actions], dtype=np.int64)
    steps = np.array([a.step for a in actions], dtype=np.int64)
    codes = np.array([_PACKED[a.args] if a.name == "move" and a.args in _PACKED and type(a.args[0]) is int
                      else 0 for a in actions], dtype=np.int64)
    horizon = max(int(steps.max()), 1)
    slots = rows * (horizon + 1) + steps
    _, slot, counts = np.unique(slots, return_inverse=True, return_counts=True)
    alone = counts[slot] == 1
    packable = (codes > 0) & (rows >= 0) & (steps >= 1) & alone
    blocks = -(-horizon // _DIGITS)
    digits = np.zeros((len(robots), blocks * _DIGITS), dtype=np.int64)
    digits[rows[packable], steps[packable] - 1] = codes[packable]
    weights = 5 ** np.arange(_DIGITS, dtype=np.int64)
    packed_codes = digits.reshape(len(robots), blocks, _DIGITS) @ weights
    lines = [f"packedMoves({robots[r]},{1 + b * _DIGITS},{packed_codes[r, b]})."
             for r, b in zip(*np.nonzero(packed_codes), strict=True)]
    lines += [format_action(actions[i]) + "." for i in np.nonzero(~packable)[0]]
    return "\n".join(lines)


def _files(domain: Domain) -> list[Path]:
    """The checker of ``domain`` and packed.lp."""
    return [*concerns(domain), HERE / "packed.lp"]


@cache
def _statements(domain: Domain) -> tuple[clingo.ast.AST, ...]:
    """The checker of ``domain`` and packed.lp, parsed once; dropped at exit, before the
    modules are torn down (``clingo.ast``, imported after this module, goes first, and a
    statement's finalizer calls into it)."""
    import atexit

    import clingo.ast
    statements: list[clingo.ast.AST] = []
    clingo.ast.parse_files([str(path) for path in _files(domain)], statements.append)
    atexit.unregister(_statements.cache_clear)  # registered once
    atexit.register(_statements.cache_clear)
    return tuple(statements)


def run_checker(facts: str, domain: Domain) -> tuple[list[clingo.Symbol], Statistics]:
    """Ground and solve the checker of ``domain`` on ``facts``; its ``err/3`` atoms.

    The first check of a domain in a process loads the checker's files as they are (the
    ``check`` command checks once: no ``clingo.ast``, no parse kept); from the second on, the
    statements parsed once are handed over (a process that checks many plans: a solve, a
    benchmark), which is quicker than reading the files again.  A domain's facts and constants
    (a variant's moves and costs) come with them."""
    solver = Solver(options=["--warn=none"], constants=dict(domain.constants))
    with _PARSED:  # one thread at a time parses, or builds from the shared statements
        if domain in _checked:
            from clingo.ast import ProgramBuilder
            with ProgramBuilder(solver.control) as builder:
                for statement in _statements(domain):
                    builder.add(statement)
        else:
            for path in _files(domain):
                if path.parent == HERE:
                    solver.control.load(str(path))
                else:  # a module of a variant's or a domain's own: its mistakes are said in words
                    solver.load(path)
            _checked.add(domain)
    solver.add(facts + "\n" + domain.checker_facts)
    solver.ground()
    # one answer set, found without search: the program negates only what earlier steps decided
    with solver.control.solve(yield_=True) as answers:
        atoms = next(iter(answers)).symbols(shown=True)  # goal.lp shows err/3 only
    return atoms, solver.stats


def err_atoms(instance: Instance, plan: Plan, domain: Domain,
              packed: bool | None = None) -> tuple[list[clingo.Symbol], Statistics]:
    """The ``err/3`` atoms of ``plan`` on ``instance`` in ``domain``."""
    return run_checker(instance_facts(instance, packed) + "\n" + plan_facts(instance, plan, packed), domain)
