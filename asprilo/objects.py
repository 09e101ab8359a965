"""The kinds of objects an instance is made of (SPEC.md §1-2), as one table: each kind's
fact name, its attributes and the shapes of their values, where an :class:`Instance`
keeps its objects, and how messages and written instances name them.

The reader, the writer and the cell-limit check go through this table.  A kind that is
only *placed* (an id at a cell, like ``shelf`` or ``pickingStation``) needs nothing but
its entry: :func:`register_kind` adds one (docs/EXTENDING.md, "Adding an object kind").
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from typing import Any

from .model import Cell, Destination, Instance, PickingStation, Shelf


def is_cell(value: Any) -> bool:
    return type(value) is tuple and len(value) == 2 and type(value[0]) is int and type(value[1]) is int


def _is_int(value: Any) -> bool:
    return isinstance(value, int)


def _is_step(value: Any) -> bool:
    return _is_int(value) and value >= 0


def _is_count(value: Any) -> bool:
    return _is_int(value) or is_cell(value)


def _is_term(_value: Any) -> bool:
    return True


@dataclass(frozen=True)
class Attribute:
    """An attribute's value: the test of its shape and the words messages describe it with."""

    shape: Callable[[Any], bool]
    description: str

    @staticmethod
    def named(shape: str) -> Attribute:
        """The attribute a variant declares: ``integer`` or ``term`` (any term)."""
        return INTEGER if shape == "integer" else TERM


CELL = Attribute(is_cell, "a cell (X,Y)")
INTEGER = Attribute(_is_int, "an integer")
TERM = Attribute(_is_term, "a term")


@dataclass(frozen=True)
class ObjectKind:
    """One kind of object: ``init(object(name,Id),value(Attribute,Value))``.

    ``words`` name one object in messages (``picking station 2``), ``title`` the group of
    its facts in a written instance.  A placed kind (``placed``: only ``at``) keeps its
    objects in the :class:`Instance` field ``table`` -- as cells (nodes, highways), as
    objects made by ``factory`` -- or, for a kind SPEC.md does not define, as cells in
    ``Instance.placed[name]``.
    """

    name: str
    words: str
    title: str
    attributes: dict[str, Attribute]
    table: str | None = None
    factory: Callable[[int, Cell], Any] | None = None

    @cached_property
    def placed(self) -> bool:
        """Whether an object of the kind is only an id at a cell (attributes a variant
        declares aside: they are kept in ``Instance.attributes``)."""
        return set(BUILTIN_ATTRIBUTES.get(self.name, self.attributes)) == {"at"}

    def objects(self, instance: Instance) -> dict[int, Any]:
        """A placed kind's objects in ``instance``: id -> cell (or object with ``.at``)."""
        if self.table is None:
            return instance.placed.get(self.name, {})
        return getattr(instance, self.table)

    def cells(self, instance: Instance) -> dict[int, Cell]:
        """A placed kind's objects in ``instance``: id -> cell."""
        objects = self.objects(instance)
        return objects if self.factory is None else {ident: item.at for ident, item in objects.items()}

    def place(self, instance: Instance, ident: int, cell: Cell) -> None:
        objects = instance.placed.setdefault(self.name, {}) if self.table is None else getattr(instance, self.table)
        objects[ident] = cell if self.factory is None else self.factory(ident, cell)


def _placed(name: str, words: str, title: str, table: str | None = None,
            factory: Callable[[int, Cell], Any] | None = None) -> ObjectKind:
    return ObjectKind(name, words, title, {"at": CELL}, table, factory)


#: every known kind, in the order a written instance lists them
KINDS: dict[str, ObjectKind] = {kind.name: kind for kind in (
    _placed("node", "node", "nodes", "nodes"),
    _placed("highway", "highway", "highways", "highways"),
    _placed("pickingStation", "picking station", "picking stations", "stations", PickingStation),
    ObjectKind("robot", "robot", "robots", {"at": CELL, "carries": Attribute(_is_int, "a shelf id")}, "robots"),
    _placed("shelf", "shelf", "shelves", "shelves", Shelf),
    ObjectKind("product", "product", "products on shelves",
               {"on": Attribute(_is_count, "(Shelf,Units) or Shelf")}, "products"),
    ObjectKind("order", "order", "orders", {"line": Attribute(_is_count, "(Product,Units) or Product"),
                                            "pickingStation": Attribute(_is_int, "a picking station id"),
                                            "release": Attribute(_is_step, "a step (0 or more)")}, "orders"),
    _placed("destination", "destination", "destinations", "destinations", Destination),
    ObjectKind("grid", "grid", "grid", {"xsize": Attribute(_is_int, "an integer"),
                                        "ysize": Attribute(_is_int, "an integer")}),
)}


#: the attributes of every kind as SPEC.md defines them (those beyond come from variants)
BUILTIN_ATTRIBUTES: dict[str, frozenset[str]] = {name: frozenset(kind.attributes) for name, kind in KINDS.items()}


def register_attribute(kind: str, attribute: str, value: Attribute) -> None:
    """Make an attribute of a kind known (a variant's robot ``energy``): its values are read
    with their shape checked, kept in ``Instance.attributes`` and written back."""
    known = KINDS[kind]
    if attribute in BUILTIN_ATTRIBUTES.get(kind, ()):
        raise ValueError(f"{kind} has an attribute {attribute} of its own")
    KINDS[kind] = ObjectKind(known.name, known.words, known.title, {**known.attributes, attribute: value},
                             known.table, known.factory)


def register_kind(kind: ObjectKind) -> ObjectKind:
    """Make a new placed kind known to the reader and the writer (its objects are kept in
    ``Instance.placed``)."""
    if not kind.placed or kind.table is not None:
        raise ValueError(f"only placed kinds kept in Instance.placed can be registered, not {kind.name}")
    KINDS[kind.name] = kind
    return kind


def unregister_attribute(kind: str, attribute: str) -> None:
    """Forget an attribute registered for a while (a test's variant)."""
    known = KINDS[kind]
    if attribute in known.attributes and attribute not in BUILTIN_ATTRIBUTES.get(kind, ()):
        KINDS[kind] = ObjectKind(known.name, known.words, known.title,
                                 {name: value for name, value in known.attributes.items() if name != attribute},
                                 known.table, known.factory)


def unregister_kind(name: str) -> None:
    """Forget a kind registered for a while (a test's)."""
    if name in KINDS and KINDS[name].table is None:
        del KINDS[name]


def registered_kinds() -> list[ObjectKind]:
    """The kinds registered or given attributes at run time (:func:`register_kind`,
    :func:`register_attribute`), which a fresh interpreter (a child process started by
    ``spawn``) must be told of."""
    return [kind for kind in KINDS.values()
            if kind.table is None or set(kind.attributes) != BUILTIN_ATTRIBUTES.get(kind.name)]


def restore_kind(kind: ObjectKind) -> None:
    """Take in a kind a parent process registered or gave attributes (see :func:`registered_kinds`)."""
    if kind.table is None:
        KINDS[kind.name] = kind
    else:
        for attribute, value in kind.attributes.items():
            if attribute not in KINDS[kind.name].attributes:
                register_attribute(kind.name, attribute, value)


def placed_kinds() -> list[ObjectKind]:
    """The kinds whose objects stand on a cell (their ``at`` is checked against the limits)."""
    return [kind for kind in KINDS.values() if "at" in kind.attributes]
