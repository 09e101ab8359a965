"""The shapes of asprilo's facts (SPEC.md §2-3), known here and nowhere else::

    init(object(Type,Id),value(Attribute,Value)).               an instance
    assign(robot(R),shelf(S)).  assign(robot(R),destination(D)).  labelled goals (M, Md)
    occurs(object(robot,R),action(Name,Args),T).                 a plan

How they are written, recognised in plain text without clingo (the fast path of the
reader), and taken apart once clingo has grounded them; terms as Python values.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

import clingo
from clingo import SymbolType

from .errors import InputError
from .model import Action, Instance
from .objects import KINDS

INIT_SHAPE = "init(object(Type,Id),value(Attribute,Value))"
ASSIGN_SHAPE = "assign(robot(R),shelf(S)) or assign(robot(R),destination(D))"
OCCURS_SHAPE = "occurs(object(robot,R),action(Name,Args),T)"


# --- terms -------------------------------------------------------------------------------

def value_of(symbol: clingo.Symbol) -> Any:
    """A term as a Python value: numbers -> int, tuples -> tuple, anything else -> its text."""
    kind = symbol.type
    if kind == SymbolType.Number:
        return symbol.number
    if kind == SymbolType.Function and symbol.name == "":
        return tuple(value_of(argument) for argument in symbol.arguments)
    if kind == SymbolType.Function and not symbol.arguments and not symbol.negative:
        return symbol.name
    return str(symbol)


def format_value(value: Any) -> str:
    """A Python value (as :func:`value_of` makes them) as an ASP term."""
    if isinstance(value, tuple):
        inner = ",".join(format_value(item) for item in value)
        return f"({inner},)" if len(value) == 1 else f"({inner})"
    return str(value)


# --- writing -----------------------------------------------------------------------------

def init_fact(kind: str, ident: Any, attribute: str, value: Any) -> str:
    """``init(object(kind,ident),value(attribute,value)).``"""
    return f"init(object({kind},{ident}),value({attribute},{format_value(value)}))."


def assign_fact(robot: int, kind: str, goal: int) -> str:
    """``assign(robot(R),shelf(S)).`` or ``assign(robot(R),destination(D)).``"""
    return f"assign(robot({robot}),{kind}({goal}))."


def format_action(action: Action) -> str:
    """The ``occurs/3`` atom of an action (without the final period)."""
    return (f"occurs(object({action.kind},{action.robot}),"
            f"action({action.name},{format_value(action.args)}),{action.step})")


def _robot_facts(instance: Instance) -> list[str]:
    facts = []
    for i, robot in sorted(instance.robots.items()):
        facts.append(init_fact("robot", i, "at", robot.at))
        if robot.carries is not None:
            facts.append(init_fact("robot", i, "carries", robot.carries))
    return facts


def _product_facts(instance: Instance) -> list[str]:
    return [init_fact("product", i, "on", shelf if units is None else (shelf, units))
            for i, product in sorted(instance.products.items()) for shelf, units in sorted(product.stock.items())]


def _order_facts(instance: Instance) -> list[str]:
    facts = []
    for i, order in sorted(instance.orders.items()):
        facts += [init_fact("order", i, "line", product if units is None else (product, units))
                  for product, units in sorted(order.lines.items())]
        if order.station is not None:
            facts.append(init_fact("order", i, "pickingStation", order.station))
    return facts


#: how the kinds that are more than placed are written (a grid is written as its nodes)
_WRITERS: dict[str, Callable[[Instance], list[str]]] = {
    "robot": _robot_facts, "product": _product_facts, "order": _order_facts, "grid": lambda _instance: []}


def fact_groups(instance: Instance) -> list[tuple[str, list[str]]]:
    """The facts of an instance in canonical order, grouped by object kind: (title, facts)."""
    groups = []
    for kind in KINDS.values():
        if kind.name in _WRITERS:
            groups.append((kind.title, _WRITERS[kind.name](instance)))
        else:
            cells = kind.cells(instance)
            groups.append((kind.title, [init_fact(kind.name, i, "at", cell) for i, cell in sorted(cells.items())]))
    groups += [
        ("labelled goals: robot -> goal", [assign_fact(robot, kind, goal)
                                           for robot, (kind, goal) in sorted(instance.assignment.items())]),
        ("facts asprilo does not use (kept as they were read)", list(instance.other_facts)),
    ]
    return [(title, facts) for title, facts in groups if facts]


def instance_facts(instance: Instance) -> list[str]:
    """Every fact of an instance, in canonical order."""
    return [fact for _title, facts in fact_groups(instance) for fact in facts]


# --- recognising plain facts in text -----------------------------------------------------

# numbers of up to nine digits (longer ones go through clingo, which has 32 bits), ASCII names
_INT = r"(-?\d{1,9})"
_INIT = re.compile(
    r"init\(\s*object\(\s*(\w+)\s*,\s*" + _INT + r"\s*\)\s*,\s*value\(\s*(\w+)\s*,\s*"
    r"(?:\(\s*" + _INT + r"\s*,\s*" + _INT + r"\s*\)|" + _INT + r")\s*\)\s*\)\s*\.", re.ASCII)
_OCCURS = re.compile(
    r"occurs\(\s*object\(\s*(\w+)\s*,\s*" + _INT + r"\s*\)\s*,\s*action\(\s*(\w+)\s*,\s*"
    r"\(\s*((?:-?\d{1,9}\s*(?:,\s*-?\d{1,9}\s*)*)?)\)\s*\)\s*,\s*" + _INT + r"\s*\)\s*\.", re.ASCII)
_SKIP = re.compile(r"(?:\s+|%(?!\*)[^\n]*|#program\s+base\s*\.)+")


def _init_args(match: re.Match) -> tuple[str, int, str, tuple[int, int] | int]:
    kind, ident, attribute, x, y, single = match.groups()
    return (kind, int(ident), attribute, (int(x), int(y)) if single is None else int(single))


def _occurs_args(match: re.Match) -> tuple:
    kind, ident, name, args, step = match.groups()
    values = tuple(map(int, args.split(","))) if args.strip() else ()
    return (kind, int(ident), name, values, int(step))


def scan_facts(text: str, most: int | None = None) -> list[tuple[str, tuple, int]] | None:
    """Read text made only of plain ``init/2`` / ``occurs/3`` facts, comments and
    ``#program base.`` without clingo: ``(name, arguments, offset)`` for each fact, where
    ``init`` has ``(Type, Id, Attribute, Value)`` and ``occurs`` has ``(Type, Id, Name, Args,
    T)``; ``None`` when the text holds anything else.  Scanning stops after ``most + 1``
    facts (the caller refuses that many)."""
    facts: list[tuple[str, tuple, int]] = []
    position, end = 0, len(text)
    skip, init, occurs = _SKIP.match, _INIT.match, _OCCURS.match
    while True:
        gap = skip(text, position)
        if gap:
            position = gap.end()
        if position >= end:
            return facts
        match = init(text, position)
        if match:
            facts.append(("init", _init_args(match), position))
        else:
            match = occurs(text, position)
            if not match:
                return None
            facts.append(("occurs", _occurs_args(match), position))
        position = match.end()
        if most is not None and len(facts) > most:
            return facts


# --- taking grounded atoms apart ---------------------------------------------------------

def init_terms(atom: clingo.Symbol) -> tuple[Any, Any, Any, Any]:
    """``(Type, Id, Attribute, Value)`` of an ``init/2`` atom (:class:`InputError` if it has
    another shape)."""
    match = _INIT.fullmatch(str(atom) + ".")
    if match:
        return _init_args(match)
    obj, val = atom.arguments
    if not (obj.match("object", 2) and val.match("value", 2)):
        raise InputError(f"expected {INIT_SHAPE}, got {atom}")
    (kind, ident), (attribute, value) = obj.arguments, val.arguments
    return value_of(kind), value_of(ident), value_of(attribute), value_of(value)


def assign_terms(atom: clingo.Symbol) -> tuple[int, str, int]:
    """``(R, shelf|destination, Id)`` of an ``assign/2`` atom (:class:`InputError` if it has
    another shape)."""
    robot, goal = atom.arguments
    if not (robot.match("robot", 1) and (goal.match("shelf", 1) or goal.match("destination", 1))
            and all(term.arguments[0].type == SymbolType.Number for term in (robot, goal))):
        raise InputError(f"expected {ASSIGN_SHAPE}, got {atom}")
    return robot.arguments[0].number, goal.name, goal.arguments[0].number


def action_of(atom: clingo.Symbol) -> Action:
    """The action of an ``occurs/3`` atom (:class:`InputError` if it has another shape)."""
    match = _OCCURS.fullmatch(str(atom) + ".")
    if match:
        kind, robot, name, args, step = _occurs_args(match)
        return Action(step, robot, name, args, kind)
    obj, action, step = atom.arguments
    if not (obj.match("object", 2) and action.match("action", 2)):
        raise InputError(f"expected {OCCURS_SHAPE}, got {atom}")
    if step.type != SymbolType.Number:
        raise InputError(f"the time step of {atom} must be an integer")
    return Action(step=step.number, robot=value_of(obj.arguments[1]), name=str(value_of(action.arguments[0])),
                  args=value_of(action.arguments[1]), kind=str(value_of(obj.arguments[0])))
