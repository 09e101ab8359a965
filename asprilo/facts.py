"""The shapes of asprilo's facts (SPEC.md §2-3), known here and nowhere else::

    init(object(Type,Id),value(Attribute,Value)).               an instance
    assign(robot(R),shelf(S)).  assign(robot(R),destination(D)).  labelled goals (M, Md)
    occurs(object(robot,R),action(Name,Args),T).                 a plan

How they are written, read from text (:func:`scan_facts`: plain facts by a regular
expression, the fast path, everything else by :mod:`asprilo.parse`), and taken apart as
terms or as clingo symbols; terms as Python values.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from sys import intern
from typing import Any

import clingo
from clingo import SymbolType

from .errors import InputError
from .limits import Limits, StepCounter
from .model import Action, Instance
from .objects import KINDS
from .parse import Constant, Fn, Reader, Term, line_at, parse_terms, python_value, shown, text_of

INIT_SHAPE = "init(object(Type,Id),value(Attribute,Value))"
ASSIGN_SHAPE = "assign(robot(R),shelf(S)) or assign(robot(R),destination(D))"
OCCURS_SHAPE = "occurs(object(robot,R),action(Name,Args),T)"


# --- terms -------------------------------------------------------------------------------

def value_of(symbol: clingo.Symbol) -> Any:
    """A term as a Python value: numbers -> int, tuples -> tuple, anything else -> its text."""
    kind = symbol.type
    if kind == SymbolType.Number:
        return symbol.number
    if kind == SymbolType.Function and symbol.name == "" and symbol.positive:
        return _tuple_value(symbol)
    if kind == SymbolType.Function and not symbol.arguments and not symbol.negative:
        return symbol.name
    return str(symbol)


def _tuple_value(symbol: clingo.Symbol) -> tuple:
    """A tuple symbol as a Python tuple, nested tuples without recursion (terms may nest
    as deeply as the ``depth`` limit allows)."""
    stack: list[tuple[list[clingo.Symbol], list[Any]]] = [(symbol.arguments, [])]
    while True:
        arguments, done = stack[-1]
        if len(done) < len(arguments):
            child = arguments[len(done)]
            if child.type == SymbolType.Function and child.name == "" and child.positive and child.arguments:
                stack.append((child.arguments, []))
            else:
                done.append(value_of(child))
            continue
        stack.pop()
        value = tuple(done)
        if not stack:
            return value
        stack[-1][1].append(value)


def format_value(value: Any) -> str:
    """A Python value (as :func:`value_of` makes them) as an ASP term."""
    if not isinstance(value, tuple):
        return str(value)
    out: list[str] = []
    stack: list[Any] = [value]
    while stack:
        item = stack.pop()
        if type(item) is _Text:
            out.append(item)
        elif isinstance(item, tuple):
            stack.append(_Text(",)" if len(item) == 1 else ")"))
            for index in range(len(item) - 1, -1, -1):
                stack.append(item[index])
                if index:
                    stack.append(_Text(","))
            out.append("(")
        else:
            out.append(str(item))
    return "".join(out)


class _Text(str):
    """A piece of punctuation on :func:`format_value`'s stack (not a value)."""


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
        if order.release is not None:
            facts.append(init_fact("order", i, "release", order.release))
    return facts


#: how the kinds that are more than placed are written (a grid is written as its nodes)
_WRITERS: dict[str, Callable[[Instance], list[str]]] = {
    "robot": _robot_facts, "product": _product_facts, "order": _order_facts, "grid": lambda _instance: []}


def fact_groups(instance: Instance) -> list[tuple[str, list[str]]]:
    """The facts of an instance in canonical order, grouped by object kind: (title, facts)."""
    groups = []
    for kind in KINDS.values():
        if kind.name in _WRITERS:
            facts = _WRITERS[kind.name](instance)
        else:
            facts = [init_fact(kind.name, i, "at", cell) for i, cell in sorted(kind.cells(instance).items())]
        facts += [init_fact(kind.name, ident, attribute, value)
                  for (name, ident), values in sorted(instance.attributes.items()) if name == kind.name
                  for attribute, value in sorted(values.items())]
        groups.append((kind.title, facts))
    groups += [
        ("labelled goals: robot -> goal", [assign_fact(robot, kind, goal)
                                           for robot, (kind, goal) in sorted(instance.assignment.items())]),
        ("facts asprilo does not use (kept as they were read)", list(instance.other_facts)),
    ]
    return [(title, facts) for title, facts in groups if facts]


def instance_facts(instance: Instance) -> list[str]:
    """Every fact of an instance, in canonical order."""
    return [fact for _title, facts in fact_groups(instance) for fact in facts]


# --- reading facts from text ----------------------------------------------------------------

# Plain facts, recognised by a regular expression (the fast path): blanks as clingo's
# (space, tab, line ends), identifiers as clingo's (not the keyword 'not'), numbers of up
# to nine digits without leading zeros (others go through the parser, which checks their
# range), an action's arguments as a tuple of no or at least two numbers ('(5)' is 5, not
# a tuple: the parser reads it), the final period not the start of '..'.
_B = r"[ \t\r\n]*+"
_ID = r"((?!not(?![A-Za-z0-9_']))[_']*+[a-z][A-Za-z0-9_']*+)"
_NUM = r"-?(?:0|[1-9][0-9]{0,8})"
_INT = "(" + _NUM + ")"
# The two alone are compiled where a grounded atom is taken apart (re's own cache keeps them):
# reading files needs only the two together (_PLAIN), and ``check`` starts without the rest.
_INIT = (
    rf"init\({_B}object\({_B}{_ID}{_B},{_B}{_INT}{_B}\){_B},{_B}value\({_B}{_ID}{_B},{_B}"
    rf"(?:\({_B}{_INT}{_B},{_B}{_INT}{_B}\)|{_INT}){_B}\){_B}\){_B}\.(?!\.)")
_OCCURS = (
    rf"occurs\({_B}object\({_B}{_ID}{_B},{_B}{_INT}{_B}\){_B},{_B}action\({_B}{_ID}{_B},{_B}"
    rf"\({_B}((?:{_NUM}{_B},{_B}{_NUM}{_B}(?:,{_B}{_NUM}{_B})*)?)\){_B}\){_B},{_B}{_INT}{_B}\){_B}\.(?!\.)")
_SKIP = re.compile(r"(?:[ \t\r\n]++|%(?!\*)[^\r\n]*+|#program[ \t\r\n]++base[ \t\r\n]*+\.(?!\.))++")
#: the deepest nesting of a plain fact: init(value(at,(X,Y)))
_PLAIN_DEPTH = 3


#: either plain fact: init's groups 1-6, occurs' 7-11
_PLAIN = re.compile(f"{_INIT}|{_OCCURS}")


def _init_args(match: re.Match) -> tuple[str, int, str, tuple[int, int] | int]:
    kind, ident, attribute, x, y, single = match.groups()[:6]
    return (intern(kind), int(ident), intern(attribute), (int(x), int(y)) if single is None else int(single))


def _occurs_args(match: re.Match) -> tuple:
    kind, ident, name, args, step = match.groups()[-5:]
    values = _ACTION_ARGS.get(args)
    if values is None:
        values = tuple(map(int, args.split(","))) if args.strip() else ()
        if len(_ACTION_ARGS) < 1_000:  # the few an action takes ((0,1), (), ...): each made once
            _ACTION_ARGS[args] = values
    return (intern(kind), int(ident), intern(name), values, int(step))


#: action arguments as written -> their value (a plan repeats the same few a million times)
_ACTION_ARGS: dict[str, tuple] = {}


def scan_facts(text: str, name: str, limits: Limits, constants: dict[str, Constant] | None = None,
               names: set[str] | None = None, room: int | None = None, fast: bool = True,
               steps: StepCounter | None = None) -> list[tuple[str, Any, int]]:
    """The facts of a text (after :func:`asprilo.parse.resolve_constants` found the
    constants of everything read with it): ``(kind, arguments, offset)`` each, where an
    ``init/2`` fact of the instance shape is ``("init", (Type, Id, Attribute, Value))``, an
    ``occurs/3`` fact of the plan shape ``("occurs", (Type, Id, Name, Args, T))`` (both
    with Python values) and any other fact ``("atom", Fn)`` -- kept only
    when ``names`` is ``None`` or holds its name.  Refuses more than ``room`` facts (and
    #const) and everything :class:`asprilo.parse.Reader` refuses; with ``steps``, a plan
    beyond ``robot-steps`` at the action that passes it.  ``fast=False`` reads every fact
    token by token (a test compares both ways)."""
    reader = Reader(text, name, limits, constants, quick=fast)
    facts: list[tuple[str, Any, int]] = []
    count, end, position = 0, len(text), 0
    skip, plain = _SKIP.match, _PLAIN.match if fast and limits.depth >= _PLAIN_DEPTH else None
    clash, most = set(constants or ()), limits.fact_chars
    room = limits.facts if room is None else room
    while True:
        gap = skip(text, position)
        if gap:
            position = gap.end()
        if position >= end:
            return facts
        count += 1
        if count > room:
            raise limits.exceeded("facts", f"more than {limits.facts:,} facts").at(name)
        start = position
        match = plain(text, position) if plain else None
        if match and match.end() - position <= most and (not clash or clash.isdisjoint(match.group(1, 3, 7, 9))):
            facts.append(("init", _init_args(match), position) if match.lastindex < 7 else  # type: ignore[operator]
                         ("occurs", _occurs_args(match), position))
            position = match.end()
        else:
            position, count = _statement(reader, position, facts, names, count)
            if position < 0:
                return facts
        if steps is not None and facts[-1:] and facts[-1][0] == "occurs" and facts[-1][2] >= start:
            _count(steps, facts[-1][1], name, text, facts[-1][2])


def _count(steps: StepCounter, args: tuple, name: str, text: str, position: int) -> None:
    """An action (read at ``position``) counted against ``robot-steps``: refused at its line
    beyond it."""
    try:
        steps.add(args[0], args[1], args[4])
    except InputError as error:
        raise error.at(name, line_at(text, position)) from None


def _statement(reader: Reader, position: int, facts: list, names: set[str] | None, count: int) -> tuple[int, int]:
    """Read the statement at ``position`` with the parser (not the fast path); ``(end,
    count)``, the end ``-1`` when no statement is left."""
    statement = reader.statement(position)
    if statement is None:
        return -1, count
    kind, atom, start, position = statement
    if atom is None:
        return position, count - (kind == "program")
    form = _form(atom)
    if form is not None:
        facts.append((form[0], form[1], start))
    elif names is None or atom.name in names:
        facts.append(("atom", atom, start))
    return position, count


def _form(atom: Fn) -> tuple[str, tuple] | None:
    """An ``init/2`` or ``occurs/3`` atom of the right shape in the fast path's form."""
    if atom.negative or atom.name not in ("init", "occurs"):
        return None
    args = atom.args
    if atom.name == "init" and len(args) == 2 and _is(args[0], "object", 2) and _is(args[1], "value", 2):
        (kind, ident), (attribute, value) = args[0].args, args[1].args
        return "init", (python_value(kind), python_value(ident), python_value(attribute), python_value(value))
    if atom.name == "occurs" and len(args) == 3 and _is(args[0], "object", 2) and _is(args[1], "action", 2) \
            and type(args[2]) is int:
        (kind, ident), (name, action_args) = args[0].args, args[1].args
        return "occurs", (str(python_value(kind)), python_value(ident), str(python_value(name)),
                          python_value(action_args), args[2])
    return None


def _is(term: Any, name: str, arity: int) -> bool:
    return type(term) is Fn and term.name == name and len(term.args) == arity and not term.negative


def fact_text(kind: str, args: Any) -> str:
    """A fact as :func:`scan_facts` gives it, written as clingo writes its atom."""
    if kind == "init":
        return init_fact(*args)[:-1]
    if kind == "occurs":
        return format_action(Action(args[4], args[1], args[2], args[3], args[0]))
    return text_of(args)


def fact_atom(kind: str, args: Any) -> Fn:
    """A fact as :func:`scan_facts` gives it, as an atom: every value back to its term
    (:func:`term_of`)."""
    if kind == "init":
        kind_name, ident, attribute, value = args
        return Fn("init", (Fn("object", (term_of(kind_name), term_of(ident))),
                           Fn("value", (term_of(attribute), term_of(value)))))
    if kind == "occurs":
        kind_name, ident, name, action_args, step = args
        return Fn("occurs", (Fn("object", (term_of(kind_name), term_of(ident))),
                             Fn("action", (term_of(name), term_of(action_args))), step))
    return args


_NAME = re.compile(r"[_']*+[a-z][A-Za-z0-9_']*+")


def term_of(value: Any) -> Term:
    """The term of a Python value as :func:`asprilo.parse.python_value` makes them (its
    inverse): numbers, names, tuples, and the text of any other term (a string, ``f(1)``,
    ``-a``, ``#sup``) read back as the term clingo writes so."""
    if type(value) is int:
        return value
    if isinstance(value, tuple):
        stack: list[tuple[tuple, list]] = [(value, [])]  # without recursion: tuples nest up to 'depth'
        while True:
            items, done = stack[-1]
            if len(done) < len(items):
                item = items[len(done)]
                if isinstance(item, tuple):
                    stack.append((item, []))
                else:
                    done.append(term_of(item))
                continue
            stack.pop()
            term = Fn("", tuple(done))
            if not stack:
                return term
            stack[-1][1].append(term)
    text = str(value)
    if _NAME.fullmatch(text) and text != "not":
        return Fn(text)
    room = Limits(depth=500, fact_chars=len(text) + 16, string_chars=len(text))
    return parse_terms(f"v({text}).", "<value>", room)[0][0].args[0]


def assign_args(atom: Fn) -> tuple[int, str, int]:
    """``(R, shelf|destination, Id)`` of an ``assign/2`` atom as read (:class:`InputError`
    if it has another shape)."""
    robot, goal = atom.args
    if not (_is(robot, "robot", 1) and (_is(goal, "shelf", 1) or _is(goal, "destination", 1))
            and type(robot.args[0]) is int and type(goal.args[0]) is int):
        raise InputError(f"expected {ASSIGN_SHAPE}, got {shown(text_of(atom))}")
    return robot.args[0], goal.name, goal.args[0]


def shape_error(atom: Fn) -> InputError:
    """Why an ``init/2`` or ``occurs/3`` atom as read has not the shape of its kind."""
    if atom.name == "init":
        return InputError(f"expected {INIT_SHAPE}, got {shown(text_of(atom))}")
    if _is(atom.args[0], "object", 2) and _is(atom.args[1], "action", 2):
        return InputError(f"the time step of {shown(text_of(atom))} must be an integer")
    return InputError(f"expected {OCCURS_SHAPE}, got {shown(text_of(atom))}")


# --- taking grounded atoms apart ---------------------------------------------------------

def init_terms(atom: clingo.Symbol) -> tuple[Any, Any, Any, Any]:
    """``(Type, Id, Attribute, Value)`` of an ``init/2`` atom (:class:`InputError` if it has
    another shape)."""
    match = re.fullmatch(_INIT, str(atom) + ".")
    if match:
        return _init_args(match)
    obj, val = atom.arguments
    if not (obj.match("object", 2) and val.match("value", 2)):
        raise InputError(f"expected {INIT_SHAPE}, got {shown(str(atom))}")
    (kind, ident), (attribute, value) = obj.arguments, val.arguments
    return value_of(kind), value_of(ident), value_of(attribute), value_of(value)


def assign_terms(atom: clingo.Symbol) -> tuple[int, str, int]:
    """``(R, shelf|destination, Id)`` of an ``assign/2`` atom (:class:`InputError` if it has
    another shape)."""
    robot, goal = atom.arguments
    if not (robot.match("robot", 1) and (goal.match("shelf", 1) or goal.match("destination", 1))
            and all(term.arguments[0].type == SymbolType.Number for term in (robot, goal))):
        raise InputError(f"expected {ASSIGN_SHAPE}, got {shown(str(atom))}")
    return robot.arguments[0].number, goal.name, goal.arguments[0].number


def action_of(atom: clingo.Symbol) -> Action:
    """The action of an ``occurs/3`` atom (:class:`InputError` if it has another shape)."""
    match = re.fullmatch(_OCCURS, str(atom) + ".")
    if match:
        kind, robot, name, args, step = _occurs_args(match)
        return Action(step, robot, name, args, kind)
    obj, action, step = atom.arguments
    if not (obj.match("object", 2) and action.match("action", 2)):
        raise InputError(f"expected {OCCURS_SHAPE}, got {shown(str(atom))}")
    if step.type != SymbolType.Number:
        raise InputError(f"the time step of {shown(str(atom))} must be an integer")
    return Action(step=step.number, robot=value_of(obj.arguments[1]), name=str(value_of(action.arguments[0])),
                  args=value_of(action.arguments[1]), kind=str(value_of(obj.arguments[0])))
