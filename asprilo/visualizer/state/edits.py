"""Checked edits of an instance's initial state, as lists of changes that can be undone.

Every edit function looks at an :class:`Instance` and either returns an :class:`Edit` (what
it says in the undo history, and the table entries it changes with their old and new
values) or raises :class:`EditRefused` with the reason, e.g. *(3,4) is a highway: shelves
may not rest there*.  Nothing here touches Qt: :func:`apply` performs an edit, the document
(``document.py``) calls it forwards and backwards for its undo history.

The rules are the instance rules of the simulator and the checker (SPEC.md §1): objects
stand on nodes; at most one robot, one shelf, one picking station and one destination per
node; shelves rest only on storage nodes (neither highway nor picking station); a carried
shelf is where its robot is.  An edit is refused when it breaks one that held before.
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from asprilo.domain import DEFAULT
from asprilo.model import Cell, Instance, Product, Robot, Shelf
from asprilo.objects import KINDS
from asprilo.simulate.checks import check_instance


class _Missing:
    """The value of an entry that does not exist (before an addition, after a removal)."""

    def __repr__(self) -> str:
        return "MISSING"

    def __deepcopy__(self, _memo) -> _Missing:
        return self


MISSING: Any = _Missing()

#: the object kinds the editor places (asprilo.objects), by the editor's names for them;
#: the instance table that holds each, how one is made, how one and several are called
_KINDS = {"robot": KINDS["robot"], "shelf": KINDS["shelf"], "station": KINDS["pickingStation"],
          "destination": KINDS["destination"]}
TABLES = {name: str(kind.table) for name, kind in _KINDS.items()}
_MAKERS: dict[str, Callable[[int, Cell], Any]] = {name: kind.factory or Robot for name, kind in _KINDS.items()}
NAMES = {name: kind.words for name, kind in _KINDS.items()}
_PLURALS = {name: kind.title for name, kind in _KINDS.items()}
FLOOR_KINDS = ("storage", "highway", "missing")


class EditRefused(Exception):
    """An edit that would make the instance invalid; the message says why."""


@dataclass(frozen=True)
class Change:
    """One entry of an instance table (``"robots"``, ``"nodes"`` ...) before and after."""

    table: str
    key: int
    before: Any
    after: Any


@dataclass
class Edit:
    """What an edit is called in the history and the changes it makes."""

    text: str
    changes: list[Change] = field(default_factory=list)

    @property
    def tables(self) -> set[str]:
        return {change.table for change in self.changes}


def apply(instance: Instance, edit: Edit, undo: bool = False) -> None:
    """Make the changes of ``edit`` (``undo``: take them back, last first)."""
    changes = reversed(edit.changes) if undo else edit.changes
    for change in changes:
        value = change.before if undo else change.after
        table = getattr(instance, change.table)
        if value is MISSING:
            table.pop(change.key, None)
        else:
            table[change.key] = copy.deepcopy(value)


class _Recorder:
    """Collects changes against an instance, one entry at a time, keeping each first 'before'."""

    def __init__(self, instance: Instance):
        self.instance = instance
        self.entries: dict[tuple[str, int], list] = {}

    def set(self, table: str, key: int, value: Any) -> None:
        current = getattr(self.instance, table).get(key, MISSING)
        entry = self.entries.setdefault((table, key), [copy.deepcopy(current), MISSING])
        entry[1] = copy.deepcopy(value)

    def remove(self, table: str, key: int) -> None:
        self.set(table, key, MISSING)

    def edit(self, text: str) -> Edit:
        changes = [Change(table, key, before, after) for (table, key), (before, after) in self.entries.items()
                   if not _same(before, after)]
        return Edit(text, changes)


def _same(before: Any, after: Any) -> bool:
    if before is MISSING or after is MISSING:
        return before is after
    return before == after


# --- what stands where ----------------------------------------------------------------------

def cell_text(cell: Cell) -> str:
    return f"({cell[0]},{cell[1]})"


def floor_kind(instance: Instance, cell: Cell) -> str:
    """``storage``, ``highway`` or ``missing`` (not a node)."""
    if cell in set(instance.highways.values()):
        return "highway"
    return "storage" if cell in instance.cells else "missing"


def objects_at(instance: Instance, cell: Cell) -> list[tuple[str, int]]:
    """``(kind, id)`` of the objects on ``cell``: robots, then shelves, stations, destinations."""
    found = []
    for kind, table in TABLES.items():
        found += [(kind, ident) for ident, thing in sorted(getattr(instance, table).items()) if thing.at == cell]
    return found


def carrier_of(instance: Instance, shelf: int) -> int | None:
    """The robot that carries ``shelf`` from the start, if any."""
    return next((robot.id for robot in sorted(instance.robots.values(), key=lambda r: r.id)
                 if robot.carries == shelf), None)


def next_id(table: dict[int, Any]) -> int:
    return max(table, default=0) + 1


def _node_id(instance: Instance, cell: Cell, width: int, table: dict[int, Cell]) -> int:
    """The conventional id of the node at ``cell``, ``(Y-1)*width+X``, unless it is taken."""
    wanted = (cell[1] - 1) * width + cell[0]
    return wanted if wanted not in table else next_id(table)


def _require_node(instance: Instance, cell: Cell, what: str) -> None:
    if cell not in instance.cells:
        raise EditRefused(f"{cell_text(cell)} is not a floor node: {what} must stand on a node")


def _check_place(instance: Instance, kind: str, cell: Cell, ignore: tuple[str, int] | None = None,
                 carried: int | None = None) -> None:
    """Raise unless an object of ``kind`` (another than ``ignore``) may stand on ``cell``.
    ``carried``: the shelf a robot to be placed there carries.

    The rules are the instance's (:func:`asprilo.simulate.checks.check_instance`, which the
    checker's instance.lp agrees with): an edit may not break one that was kept before.
    Every rule is about one node, so they are checked on the node and what stands on it."""
    here = [(k, i) for k, i in objects_at(instance, cell) if (k, i) != ignore and (k, i) != ("shelf", carried)]
    local = _node_with(instance, cell, here)
    before = instance_errors(local)
    ident = next_id(getattr(local, TABLES[kind]))
    getattr(local, TABLES[kind])[ident] = _MAKERS[kind](ident, cell)
    if carried is not None:
        local.robots[ident].carries = carried
        local.shelves[carried] = Shelf(carried, cell)
    broken = sorted(instance_errors(local) - before)
    if broken:
        raise EditRefused(_refusal(local, kind, cell, ident, carried, broken[0]))


def instance_errors(instance: Instance) -> set[tuple]:
    """The instance rules ``instance`` breaks, as ``(check, *params)``."""
    found: set[tuple] = set()
    check_instance(instance, DEFAULT, lambda _module, check, *params: found.add((check, *params[:-1])))
    return found


def _node_with(instance: Instance, cell: Cell, objects: list[tuple[str, int]]) -> Instance:
    """A copy of ``cell``'s node (if any: storage or highway) with ``objects`` on it."""
    local = Instance()
    if cell in instance.cells:
        local.nodes[1] = cell
    if floor_kind(instance, cell) == "highway":
        local.highways[1] = cell
    for kind, ident in objects:
        table = TABLES[kind]
        getattr(local, table)[ident] = copy.copy(getattr(instance, table)[ident])
    for robot in local.robots.values():
        if robot.carries is not None and robot.carries not in local.shelves:
            robot.carries = None  # its shelf stands elsewhere: another node's business
    return local


def _refusal(node: Instance, kind: str, cell: Cell, ident: int, carried: int | None, broken: tuple) -> str:
    """Why placing a ``kind`` (``ident`` in ``node``, the copy of ``cell``'s node) on ``cell``
    breaks the rule ``broken``."""
    check, *params = broken
    name, where = NAMES[kind], cell_text(cell)
    other = next((p for p in params if p != ident), None)
    if check.endswith("OffFloor"):
        return f"{where} is not a floor node: a {name} must stand on a node"
    if check == "shelfCollision" and kind == "robot":
        return f"shelf {other} rests on {where}: a robot carrying shelf {carried} cannot go under it"
    if check.endswith("Collision"):
        return f"{name} {other} already stands on {where}: two {_PLURALS[kind]} may not share a node"
    if check == "shelfOnHighway":
        return f"{where} is a highway: shelves may not rest there"
    if check == "shelfOnStation" and kind == "shelf":
        return f"picking station {min(node.stations)} is on {where}: shelves may not rest there"
    if check == "shelfOnStation":
        return f"shelf {params[0]} rests on {where}: a picking station needs a node without shelves"
    return f"{name} on {where} breaks the instance rule {check}"


# --- objects ------------------------------------------------------------------------------------

def add_object(instance: Instance, kind: str, cell: Cell) -> Edit:
    """A new robot, shelf, picking station or destination (next free id) on ``cell``."""
    _check_place(instance, kind, cell)
    table = TABLES[kind]
    ident = next_id(getattr(instance, table))
    record = _Recorder(instance)
    record.set(table, ident, _MAKERS[kind](ident, cell))
    return record.edit(f"add {NAMES[kind]} {ident} at {cell_text(cell)}")


def remove_object(instance: Instance, kind: str, ident: int) -> Edit:
    """Remove an object; a shelf takes its stock with it and robots carrying it carry nothing;
    labelled goals of the object or at it go too."""
    if ident not in getattr(instance, TABLES[kind]):
        raise EditRefused(f"there is no {NAMES[kind]} {ident}")
    record = _Recorder(instance)
    _forget(instance, kind, ident, record)
    return record.edit(f"remove {NAMES[kind]} {ident}")


def _forget(instance: Instance, kind: str, ident: int, record: _Recorder) -> None:
    """Record the removal of an object with what depends on it: a shelf's stock and carrier,
    the labelled goals of a robot or at a shelf or destination."""
    record.remove(TABLES[kind], ident)
    if kind == "shelf":
        _forget_shelf(instance, ident, record)
    for robot, goal in instance.assignment.items():
        if (kind == "robot" and robot == ident) or goal == (kind, ident):
            record.remove("assignment", robot)


def _forget_shelf(instance: Instance, shelf: int, record: _Recorder) -> None:
    for product in instance.products.values():
        if shelf in product.stock:
            stock = {s: u for s, u in product.stock.items() if s != shelf}
            if stock:
                record.set("products", product.id, Product(product.id, stock))
            else:
                record.remove("products", product.id)
    for robot in instance.robots.values():
        if robot.carries == shelf:
            record.set("robots", robot.id, Robot(robot.id, robot.at, None))


def move_object(instance: Instance, kind: str, ident: int, cell: Cell) -> Edit:
    """Put an object on another node; a robot takes the shelf it carries along.  A carried
    shelf moves with its robot."""
    table = TABLES[kind]
    thing = getattr(instance, table).get(ident)
    if thing is None:
        raise EditRefused(f"there is no {NAMES[kind]} {ident}")
    if kind == "shelf" and (robot := carrier_of(instance, ident)) is not None:
        return move_object(instance, "robot", robot, cell)
    if thing.at == cell:
        return Edit(f"move {NAMES[kind]} {ident}")
    carried = thing.carries if kind == "robot" else None
    _check_place(instance, kind, cell, ignore=(kind, ident), carried=carried)
    record = _Recorder(instance)
    moved = copy.deepcopy(thing)
    moved.at = cell
    record.set(table, ident, moved)
    if carried is not None and carried in instance.shelves:
        record.set("shelves", carried, Shelf(carried, cell))
    return record.edit(f"move {NAMES[kind]} {ident} to {cell_text(cell)}")


def set_carries(instance: Instance, robot: int, shelf: int | None) -> Edit:
    """Let ``robot`` start carrying ``shelf`` (which must stand on its node), or nothing."""
    thing = instance.robots.get(robot)
    if thing is None:
        raise EditRefused(f"there is no robot {robot}")
    record = _Recorder(instance)
    if shelf is None:
        record.set("robots", robot, Robot(robot, thing.at, None))
        return record.edit(f"robot {robot} puts shelf {thing.carries} down")
    if shelf not in instance.shelves:
        raise EditRefused(f"there is no shelf {shelf}")
    if instance.shelves[shelf].at != thing.at:
        raise EditRefused(f"shelf {shelf} does not stand on robot {robot}'s node {cell_text(thing.at)}")
    holder = carrier_of(instance, shelf)
    if holder is not None and holder != robot:
        raise EditRefused(f"robot {holder} already carries shelf {shelf}")
    record.set("robots", robot, Robot(robot, thing.at, shelf))
    return record.edit(f"robot {robot} carries shelf {shelf}")


# --- the floor --------------------------------------------------------------------------------

def set_floor(instance: Instance, cell: Cell, kind: str, width: int | None = None) -> Edit:
    """Make ``cell`` a storage node, a highway node, or no node at all (a wall).  New nodes
    get the id ``(Y-1)*width+X`` (``width``: the grid's, default the floor's) when it is free."""
    if kind not in FLOOR_KINDS:
        raise ValueError(f"unknown floor kind {kind!r}")
    if cell[0] < 1 or cell[1] < 1:
        raise EditRefused(f"{cell_text(cell)} lies outside the grid (X and Y start at 1)")
    if floor_kind(instance, cell) == kind:
        return Edit(f"{cell_text(cell)} is already {_floor_words(kind)}")
    _check_floor(instance, cell, kind)
    width = width or max(instance.size[0], cell[0])
    record = _Recorder(instance)
    node = next((i for i, at in instance.nodes.items() if at == cell), None)
    highway = next((i for i, at in instance.highways.items() if at == cell), None)
    if kind == "missing":
        record.remove("nodes", node)
    elif node is None:
        node = _node_id(instance, cell, width, instance.nodes)
        record.set("nodes", node, cell)
    if kind == "highway":
        wanted = node if node not in instance.highways else next_id(instance.highways)
        record.set("highways", wanted, cell)
    elif highway is not None:
        record.remove("highways", highway)
    return record.edit(f"make {cell_text(cell)} {_floor_words(kind)}")


def _check_floor(instance: Instance, cell: Cell, kind: str) -> None:
    """Raise unless what stands on ``cell`` may stand on floor of ``kind`` (the instance rules
    of :func:`_check_place`)."""
    here = objects_at(instance, cell)
    local = _node_with(instance, cell, here)
    before = instance_errors(local)
    local.nodes, local.highways = ({1: cell} if kind != "missing" else {}), ({1: cell} if kind == "highway" else {})
    broken = sorted(instance_errors(local) - before)
    if not broken:
        return
    if kind == "missing":
        names = ", ".join(f"{NAMES[k]} {i}" for k, i in here)
        raise EditRefused(f"{names} stand{'s' if len(here) == 1 else ''} on {cell_text(cell)}: remove it first")
    shelf = next(params[0] for check, *params in broken if check == "shelfOnHighway")
    raise EditRefused(f"shelf {shelf} rests on {cell_text(cell)}: a highway must stay free of shelves")


def _floor_words(kind: str) -> str:
    return {"storage": "a storage node", "highway": "a highway", "missing": "a wall (no node)"}[kind]


def grid(width: int, height: int) -> Instance:
    """A new instance: a full ``width`` x ``height`` grid of storage nodes, nothing on it."""
    if width < 1 or height < 1:
        raise EditRefused(f"a grid needs at least one column and one row, not {width}x{height}")
    return Instance(nodes={(y - 1) * width + x: (x, y) for y in range(1, height + 1) for x in range(1, width + 1)})


def resize(instance: Instance, width: int, height: int) -> Edit:
    """Change the grid to ``width`` x ``height``: new cells become storage nodes; nodes and
    objects beyond the new size go (shelves with their stock)."""
    if width < 1 or height < 1:
        raise EditRefused(f"a grid needs at least one column and one row, not {width}x{height}")

    def inside(cell: Cell) -> bool:
        return cell[0] <= width and cell[1] <= height

    record = _Recorder(instance)
    for kind, table in TABLES.items():
        for ident, thing in getattr(instance, table).items():
            if not inside(thing.at):
                _forget(instance, kind, ident, record)
    for table in ("nodes", "highways"):
        for ident, cell in getattr(instance, table).items():
            if not inside(cell):
                record.remove(table, ident)
    _add_new_cells(instance, width, height, {i for i, cell in instance.nodes.items() if inside(cell)}, record)
    return record.edit(f"resize the grid to {width}x{height}")


def _add_new_cells(instance: Instance, width: int, height: int, taken: set[int], record: _Recorder) -> None:
    """Storage nodes on the cells a grid grown to ``width`` x ``height`` gains."""
    old_width, old_height = instance.size
    for y in range(1, height + 1):
        for x in range(1, width + 1):
            if x > old_width or y > old_height:
                wanted = (y - 1) * width + x
                ident = wanted if wanted not in taken else max(taken, default=0) + 1
                taken.add(ident)
                record.set("nodes", ident, (x, y))


# --- whole instances ------------------------------------------------------------------------------

def replace_all(instance: Instance, new: Instance, text: str) -> Edit:
    """Replace every table of ``instance`` by those of ``new`` (e.g. the generator's result)."""
    record = _Recorder(instance)
    for table in ("nodes", "highways", "robots", "shelves", "stations", "products", "orders", "destinations",
                  "assignment"):
        old_entries, new_entries = getattr(instance, table), getattr(new, table)
        for key in set(old_entries) | set(new_entries):
            record.set(table, key, new_entries.get(key, MISSING))
    return record.edit(text)


def template_of(instance: Instance) -> Instance:
    """The layout for ``gen -T``: floor, highways, picking stations, robots and shelves,
    without products and orders (the generator adds those)."""
    kept = copy.deepcopy(instance)
    kept.products, kept.orders, kept.destinations, kept.assignment = {}, {}, {}, {}
    return kept
