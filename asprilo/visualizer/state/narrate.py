"""A step of a plan told in one sentence, and the plan's verdict, for the presentation mode.

    narrate(track, 8)   # 'step 8: robot 3 delivers 1 unit of product 4 at station 1 for order 1, …'
    verdict(track)      # 'invalid plan: 3 rule violations (first at step 23)'

The words come from the simulator's states (what a robot carried before a step, where it
stands after it, which order lines a delivery closed) and its violations
(:mod:`asprilo.simulate.messages`).  A sentence names every action of the step when there
are at most :data:`LISTED`, otherwise the most relevant ones (those of robots that break a
rule, then deliveries, pickups, putdowns, other actions, moves; by robot id) and says how
many more there are.  A broken rule whose words begin with a robot whose action is named
becomes a clause of that action (``…, but the order needs only 5 more``), and the actions
are then set apart by semicolons; the other broken rules follow after a semicolon
(``; rule broken: robots 1 and 2 are both on (3,3)``), at most :data:`SHOWN_VIOLATIONS`
of them.
"""

from __future__ import annotations

from asprilo.domain import Delivery
from asprilo.model import Action, Cell
from asprilo.simulate import Violation, well_formed
from asprilo.writer import format_value

from .track import Track

#: a move's (DX,DY) in words (Y grows downwards; the diagonal ones for a variant's moves)
DIRECTION_WORDS = {(1, 0): "right", (-1, 0): "left", (0, 1): "down", (0, -1): "up",
                   (1, 1): "down-right", (-1, 1): "down-left", (1, -1): "up-right", (-1, -1): "up-left"}
#: a step with at most this many acting objects names them all; one with more names two
LISTED = 3
#: broken rules said in full after the actions (the others counted)
SHOWN_VIOLATIONS = 2
#: how a violation's words go on after naming the robot's action
_CONNECTORS = (", but ", ", which ", "; ")
#: the order in which a step's actions are named (after those of robots that break a rule)
_RANK = {"deliver": 0, "pickup": 1, "putdown": 2, "move": 4}


def narrate(track: Track, step: int) -> str:
    """The state after ``step`` in one sentence: what the plan does at that step and which
    rules it breaks there (``step 0``: the initial state and the instance's problems)."""
    step = min(max(step, 0), track.horizon)
    violations = track.violations_at.get(step, [])
    if step == 0:
        return "step 0: the initial state" + _broken([_words(v) for v in violations])
    groups: dict[tuple, list[Action]] = {}
    for action in track.actions_at(step):
        groups.setdefault((action.kind, action.robot), []).append(action)
    if not groups:
        return f"step {step}: every robot waits" + _broken([_words(v) for v in violations])
    involved = {robot for violation in violations for robot in violation.robots}
    ranked = sorted(groups.items(), key=lambda entry: _relevance(entry[0], entry[1], involved))
    shown = ranked if len(ranked) <= LISTED else ranked[:LISTED - 1]
    told: dict[tuple, list[tuple[str, str]]] = {key: [] for key, _ in shown}
    rest = []
    for violation in violations:
        clause = _clause(violation, told)
        if clause is None:
            rest.append(_words(violation))
    parts = [_attach(_group_words(track, step, actions), told[key]) for key, actions in shown]
    hidden = [actions for _key, actions in ranked[len(shown):]]
    if hidden:
        parts.append(_more(hidden))
    return f"step {step}: {_joined(parts, clauses=any(told.values()))}" + _broken(rest)


def _more(hidden: list[list[Action]]) -> str:
    """``2 more moves``: the actions not named."""
    moves = all(len(actions) == 1 and actions[0].name == "move" for actions in hidden)
    noun = ("move" if moves else "action") + ("" if len(hidden) == 1 else "s")
    return f"{len(hidden)} more {noun}"


def _joined(parts: list[str], clauses: bool) -> str:
    """The actions' words in a row; an action with a clause has commas of its own, so the
    actions are then set apart by semicolons."""
    return "; ".join(parts[:-1]) + "; and " + parts[-1] if clauses and len(parts) > 1 else _and(parts)


def verdict(track: Track, unfinished: bool = False) -> str:
    """``valid plan``, ``invalid plan: 3 rule violations (first at step 23)``, ``no plan``
    (an instance without a plan), or ``no rule broken so far`` (a plan still growing)."""
    violations = track.violations
    if not len(track.plan):
        if violations:
            return f"no plan; the instance breaks {_count(len(violations), 'rule')}"
        return "no plan"
    if not violations:
        return "no rule broken so far" if unfinished else "valid plan"
    first = min(violation.step for violation in violations)
    return f"invalid plan: {_count(len(violations), 'rule violation')} (first at step {first})"


def action_words(track: Track, action: Action) -> str:
    """One action in words, as it plays out in the simulator's states (``robot 2 moves
    right to (4,3)``, ``robot 1 picks up shelf 3 at (2,4)``, ``robot 1 does fly(1,0)``)."""
    robot, step, name, args = action.robot, action.step, action.name, action.args
    who = f"robot {robot}" if action.kind == "robot" else f"{action.kind} {format_value(robot)}"
    if (action.kind != "robot" or robot not in track.robot_index or step < 1
            or name not in track.domain.actions or not well_formed(name, args, track.domain)):
        return f"{who} does {_raw(action)}"
    before, after = track.state(step - 1), track.state(step)
    assert type(robot) is int
    here = _cell(after.robots[robot])
    if name == "move":
        shelf = before.carries.get(robot)
        return f"{who} moves {DIRECTION_WORDS[args]} to {here}" + (f" with shelf {shelf}" if shelf is not None else "")
    if name == "pickup":
        lifted = after.carries.get(robot) if before.carries.get(robot) is None else None
        return f"{who} picks up shelf {lifted} at {here}" if lifted is not None else f"{who} picks up at {here}"
    if name == "putdown":
        shelf = before.carries.get(robot)
        return f"{who} puts down shelf {shelf} at {here}" if shelf is not None else f"{who} puts down at {here}"
    return _delivery_words(track, action, who, after.robots[robot])


def _delivery_words(track: Track, action: Action, who: str, cell: Cell) -> str:
    order, product = action.args[0], action.args[1]
    station = next((s.id for s in sorted(track.instance.stations.values(), key=lambda s: s.id) if s.at == cell), None)
    where = f"station {station}" if station is not None else _cell(cell)
    if track.domain.delivery is Delivery.UNITS:
        return f"{who} delivers {_count(action.args[2], 'unit')} of product {product} at {where} for order {order}"
    text = f"{who} delivers product {product} at {where} for order {order}"
    closed = _closed_lines(track, action, station)
    if closed == [(order, product)]:
        units = track.instance.orders[order].lines.get(product)
        return text + (f" (the whole line: {_count(units, 'unit')})" if units is not None else " (the whole line)")
    if closed:
        by_order: dict[int, list[int]] = {}
        for line_order, line_product in closed:
            by_order.setdefault(line_order, []).append(line_product)
        lines = ", ".join(f"order {o} product{'s' if len(ps) > 1 else ''} {_and([str(p) for p in ps])}"
                          for o, ps in by_order.items())
        return text + f", closing {len(closed)} lines: {lines}"
    return text


def _closed_lines(track: Track, action: Action, station: int | None) -> list[tuple[int, int]]:
    """The order lines ``action`` (a delivery in B or C) closed: in B its own line, in C
    every line of an order of that station whose product the robot's shelf holds."""
    step, robot = action.step, action.robot
    before, after = track.state(step - 1), track.state(step)
    shelf = before.carries.get(robot)  # type: ignore[arg-type]
    if shelf is None or station is None:
        return []
    gone = sorted(line for line in before.open_lines if line not in after.open_lines)
    if track.domain.delivery is Delivery.LINE:
        return [line for line in gone if line == (action.args[0], action.args[1])]
    stock = track.instance.shelf_stock().get(shelf, {})
    orders = track.instance.orders
    return [(o, p) for o, p in gone if o in orders and orders[o].station == station and p in stock]


def _group_words(track: Track, step: int, actions: list[Action]) -> str:
    """The actions of one object at one step: one action, or several at once (none of which
    takes effect)."""
    if len(actions) == 1:
        return action_words(track, actions[0])
    first = actions[0]
    who = f"robot {first.robot}" if first.kind == "robot" else f"{first.kind} {format_value(first.robot)}"
    return f"{who} does {len(actions)} actions at once ({', '.join(_raw(a) for a in actions)})"


def _relevance(key: tuple, actions: list[Action], involved: set[int]) -> tuple:
    kind, robot = key
    rank = _RANK.get(actions[0].name, 3) if len(actions) == 1 and kind == "robot" else 3
    return (robot not in involved, rank, kind != "robot", type(robot) is not int, robot if type(robot) is int else 0,
            str(robot))


def _clause(violation: Violation, told: dict[tuple, list[tuple[str, str]]]) -> str | None:
    """Add the violation as a clause to the named action of its robot, if its words begin
    with that robot and go on with ``, but``, ``, which`` or ``;`` (else ``None``)."""
    text = _words(violation)
    for (kind, robot), clauses in told.items():
        if kind != "robot" or not text.startswith(f"robot {robot} "):
            continue
        found = [(text.find(c), c) for c in _CONNECTORS if c in text]
        if found:
            position, connector = min(found)
            clauses.append((connector, text[position + len(connector):]))
            return text
    return None


def _attach(words: str, clauses: list[tuple[str, str]]) -> str:
    """``words, but A and B`` / ``words, which C`` / ``words; D``."""
    for connector in dict.fromkeys(connector for connector, _ in clauses):
        words += connector + " and ".join(text for c, text in clauses if c == connector)
    return words


def _broken(texts: list[str]) -> str:
    if not texts:
        return ""
    said = "; ".join(texts[:SHOWN_VIOLATIONS])
    more = f"; and {len(texts) - SHOWN_VIOLATIONS} more" if len(texts) > SHOWN_VIOLATIONS else ""
    label = "rule broken" if len(texts) == 1 else f"{len(texts)} rules broken"
    return f"; {label}: {said}{more}"


def _words(violation: Violation) -> str:
    """A violation's words without the ``step N:`` (``instance:``) the simulator puts first."""
    message = violation.message
    for prefix in (f"step {violation.step} (the horizon): ", f"step {violation.step}: ", "instance: "):
        if message.startswith(prefix):
            return message[len(prefix):]
    return message


def _raw(action: Action) -> str:
    return action.name + (format_value(action.args) if action.args != () else "")


def _cell(cell) -> str:
    return f"({int(cell[0])},{int(cell[1])})"


def _count(number: int, noun: str) -> str:
    return f"{number} {noun}" + ("" if number == 1 else "s")


def _and(parts: list[str]) -> str:
    return parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + " and " + parts[-1]
