"""An instance built from its facts as read (``init/2``, ``assign/2``): each object kind's
attributes checked against its shape, duplicates that disagree refused, unknown kinds and
attributes kept aside with one warning, the grid expanded, the assignment checked against the
objects; and where a fact stands, for messages."""

from __future__ import annotations

import warnings
from collections.abc import Callable, Iterable, Sequence
from itertools import chain
from typing import Any

import clingo

from .errors import InputError, InputWarning
from .facts import assign_args, assign_terms, format_value, init_fact, init_terms, shape_error
from .limits import Limits, current
from .model import Destination, Instance, Order, Product, Robot, Shelf
from .objects import BUILTIN_ATTRIBUTES, KINDS, ObjectKind, placed_kinds
from .parse import Fn, shown, text_of
from .sources import ScannedFact, Source, line_of, locate

#: the atoms an instance and a plan are read from (others are ignored), with their arities
INSTANCE_NAMES = {"init", "assign"}
_ARITY = {"init": 2, "assign": 2, "occurs": 3}


def _wrong_arity(name: str, arity: int) -> str:
    return f"{name}/{arity} ({name} has {_ARITY[name]} arguments)"


class _InstanceBuilder:
    """Collects ``init/2`` facts, rejecting unknown shapes and conflicting duplicates.

    Each fact comes with its origin, used only to say where a bad fact stands.
    """

    def __init__(self, sources: Sequence[Source], limits: Limits):
        self.sources = sources
        self.limits = limits
        self.unknown: dict[str, Any] = {}  # what is not known -> the origin of its first fact
        self.instance = Instance()
        self.seen: dict[tuple, tuple[Any, Any]] = {}
        self.grid: dict[str, int] = {}
        self.goals: dict[int, tuple[str, int]] = {}
        #: how the kinds that are more than placed are read
        self._readers: dict[str, Callable[[int, str, Any, Any], None]] = {
            "robot": self._robot, "product": self._product, "order": self._order, "grid": self._grid}

    def fail(self, message: str, origin: Any) -> InputError:
        return InputError(message, *where(origin, self.sources))

    def single(self, key: tuple, value: Any, origin: Any, what: str) -> None:
        """Record a value that may be stated once only (a duplicate must be identical)."""
        first = self.seen.get(key)
        if first is not None and first[0] != value:
            raise self.fail(f"{what}: {shown_value(first[0])} and {shown_value(value)}", origin)
        self.seen[key] = (value, origin)

    def add(self, kind: Any, ident: Any, attribute: Any, value: Any, origin: Any) -> None:
        known = KINDS.get(kind)
        if known is None or attribute not in known.attributes:
            what = f"object type '{shown_value(kind)}'" if known is None \
                else f"attribute '{shown_value(attribute)}' of {kind}"
            self.unknown.setdefault(what, origin)
            self.instance.other_facts.append(
                init_fact(format_value(kind), format_value(ident), format_value(attribute), value))
            return
        expected = known.attributes[attribute]
        if not isinstance(ident, int):
            raise self.fail(f"{kind} id must be an integer, got {shown_value(ident)}", origin)
        if not expected.shape(value):
            raise self.fail(f"{kind} {ident}: value of '{attribute}' must be {expected.description}, "
                            f"got {shown_value(value)}", origin)
        if attribute not in BUILTIN_ATTRIBUTES.get(kind, known.attributes):
            self._declared(kind, ident, attribute, value, origin)
        elif known.placed:
            self._placed(known, ident, value, origin)
        else:
            self._readers[kind](ident, attribute, value, origin)

    def check_cells(self) -> None:
        """Every cell within the ``coordinate`` limit (checked once all are read: fast)."""
        limit, instance = self.limits.coordinate, self.instance
        for kind in placed_kinds():
            cells = {robot.id: robot.at for robot in instance.robots.values()} if kind.name == "robot" \
                else kind.cells(instance)
            if max(map(abs, chain.from_iterable(cells.values())), default=0) > limit:
                ident, cell = next((i, c) for i, c in cells.items() if max(map(abs, c)) > limit)
                what = self.limits.exceeded("coordinate", f"{kind.words} {ident} at {format_value(cell)}").message
                raise self.fail(what, self.seen[(kind.words, ident, "at")][1])

    def warn_unknown(self) -> None:
        """One warning naming everything unknown (at the place of the first such fact)."""
        if self.unknown:
            names = ", ".join(self.unknown)
            file, line = where(next(iter(self.unknown.values())), self.sources)
            message = str(InputError(f"ignored (and kept when written): {names}", file, line))
            warnings.warn(InputWarning(message), stacklevel=4)

    def add_atom(self, atom: Fn, origin: Any) -> None:
        """An ``init`` or ``assign`` atom as read that is no plain instance fact: a wrong shape
        is refused, a wrong arity ignored with a warning (the atom kept when written)."""
        if atom.negative:
            return  # -init(..) is another atom, as in clingo
        if len(atom.args) != _ARITY[atom.name]:
            self.unknown.setdefault(_wrong_arity(atom.name, len(atom.args)), origin)
            self.instance.other_facts.append(text_of(atom) + ".")
            return
        if atom.name == "init":
            raise shape_error(atom).at(*where(origin, self.sources))
        try:
            ident, kind, goal = assign_args(atom)
        except InputError as error:
            raise error.at(*where(origin, self.sources)) from None
        self._assign(ident, kind, goal, origin)

    def add_other_symbol(self, atom: clingo.Symbol) -> None:
        """An ``init`` or ``assign`` atom (a clingo symbol) of another arity."""
        self.unknown.setdefault(_wrong_arity(atom.name, len(atom.arguments)), atom)
        self.instance.other_facts.append(f"{atom}.")

    def add_symbol(self, atom: clingo.Symbol) -> None:
        """Add an ``init/2`` atom of any shape (the slow path for unusual terms)."""
        try:
            terms = init_terms(atom)
        except InputError as error:
            raise error.at(*where(atom, self.sources)) from None
        self.add(*terms, atom)

    def assign(self, atom: clingo.Symbol) -> None:
        """Add a labelled goal ``assign(robot(R),shelf(S))`` or ``assign(robot(R),destination(D))``."""
        try:
            ident, kind, goal = assign_terms(atom)
        except InputError as error:
            raise error.at(*where(atom, self.sources)) from None
        self._assign(ident, kind, goal, atom)

    def _assign(self, ident: int, kind: str, goal: int, origin: Any) -> None:
        self.single(("assign", ident), f"{kind}({goal})", origin, f"robot {ident} is assigned two goals")
        self.goals[ident] = (kind, goal)

    # the placed kinds, and one method for each other kind -----------------------------------

    def _placed(self, kind: ObjectKind, ident: int, value: Any, origin: Any) -> None:
        self.single((kind.words, ident, "at"), value, origin, f"{kind.words} {ident} is at two places")
        kind.place(self.instance, ident, value)

    def _declared(self, kind: str, ident: int, attribute: str, value: Any, origin: Any) -> None:
        """An attribute a variant declares (:func:`asprilo.objects.register_attribute`)."""
        self.single((kind, ident, attribute), value, origin, f"{kind} {ident} has two values of {attribute}")
        self.instance.attributes.setdefault((kind, ident), {})[attribute] = value

    def _robot(self, ident: int, attribute: str, value: Any, origin: Any) -> None:
        robot = self.instance.robots.get(ident)
        if robot is None:
            # no cell yet: the robot's at fact may come later (finish() requires one)
            robot = self.instance.robots[ident] = Robot(ident, None)  # type: ignore[arg-type]
        if attribute == "at":
            self.single(("robot", ident, "at"), value, origin, f"robot {ident} is at two places")
            robot.at = value
        else:
            self.single(("robot", ident, "carries"), value, origin, f"robot {ident} carries two shelves")
            robot.carries = value

    def _product(self, ident: int, _attribute: str, value: Any, origin: Any) -> None:
        shelf, units = value if isinstance(value, tuple) else (value, None)
        self.single(("product", ident, shelf), units, origin,
                    f"product {ident} has two quantities on shelf {shelf}")
        product = self.instance.products.get(ident)
        if product is None:
            product = self.instance.products[ident] = Product(ident)
        product.stock[shelf] = units

    def _order(self, ident: int, attribute: str, value: Any, origin: Any) -> None:
        order = self.instance.orders.get(ident)
        if order is None:
            order = self.instance.orders[ident] = Order(ident)
        if attribute == "pickingStation":
            self.single(("order", ident, "station"), value, origin,
                        f"order {ident} names two picking stations")
            order.station = value
            return
        if attribute == "release":
            self.single(("order", ident, "release"), value, origin, f"order {ident} has two release steps")
            order.release = value
            return
        product, units = value if isinstance(value, tuple) else (value, None)
        self.single(("order", ident, product), units, origin,
                    f"order {ident} has two quantities for product {product}")
        order.lines[product] = units

    def _grid(self, _ident: int, attribute: str, value: Any, origin: Any) -> None:
        if value < 1:
            raise self.fail(f"grid {attribute} must be at least 1, got {value}", origin)
        if value > self.limits.coordinate:
            raise self.fail(self.limits.exceeded("coordinate", f"grid {attribute} {value}").message, origin)
        self.single(("grid", attribute), value, origin, f"grid has two values of {attribute}")
        self.grid[attribute] = value

    def finish(self) -> Instance:
        instance = self.instance
        for robot in instance.robots.values():
            if robot.at is None:
                raise self.fail(f"robot {robot.id} has no position (no value(at,(X,Y)))",
                                self.seen[("robot", robot.id, "carries")][1])
        self.check_cells()
        if self.grid:
            self._expand_grid()
        tables: dict[str, dict[int, Shelf] | dict[int, Destination]] = {
            "shelf": instance.shelves, "destination": instance.destinations}
        for ident, (kind, goal) in self.goals.items():
            origin = self.seen[("assign", ident)][1]
            if ident not in instance.robots:
                raise self.fail(f"assign names robot {ident}, which the instance lacks", origin)
            if goal not in tables[kind]:
                raise self.fail(f"assign names {kind} {goal}, which the instance lacks", origin)
            instance.assignment[ident] = (kind, goal)
        return instance

    def _expand_grid(self) -> None:
        if len(self.grid) != 2:
            missing = "ysize" if "xsize" in self.grid else "xsize"
            origin = next(origin for key, (_v, origin) in self.seen.items() if key[0] == "grid")
            raise self.fail(f"grid gives no {missing}", origin)
        width, height = self.grid["xsize"], self.grid["ysize"]
        nodes = self.instance.nodes
        if width * height + len(nodes) > self.limits.facts:
            origin = self.seen[("grid", "xsize")][1]
            raise self.fail(self.limits.exceeded("facts", f"a grid of {width}x{height} nodes").message, origin)
        taken = set(nodes.values())
        next_id = max(nodes) + 1 if nodes else None
        for y in range(1, height + 1):
            for x in range(1, width + 1):
                if (x, y) in taken:
                    continue
                if next_id is None:
                    nodes[(y - 1) * width + x] = (x, y)
                else:
                    nodes[next_id] = (x, y)
                    next_id += 1


def where(origin: Any, sources: Sequence[Source]) -> tuple[str | None, int | None]:
    """The file and line of a fact's origin: ``(source, offset)`` as read, or a clingo symbol."""
    if isinstance(origin, clingo.Symbol):
        return locate(sources, origin)
    return line_of(*origin)


def shown_value(value: Any) -> str:
    """A value as read, fit for a message (shortened, no control character raw)."""
    return shown(format_value(value), 60)


def _no_facts(what: str, sources: Sequence[Source]) -> InputError:
    names = ", ".join(source.name for source in sources) or None
    return InputError(f"no {what} found", names)


def build_instance(sources: Sequence[Source], facts: list[ScannedFact], atoms: list[clingo.Symbol],
                   limits: Limits | None = None) -> Instance:
    """The instance of facts as read from ``sources`` (:func:`asprilo.sources.load_facts`) and of
    ground ``atoms`` (a solver's answer); one warning names what is unknown."""
    builder = _InstanceBuilder(sources, limits or current())
    add = builder.add
    for kind, args, origin in facts:
        if kind == "init":
            kind, ident, attribute, value = args
            add(kind, ident, attribute, value, origin)
        elif kind == "atom" and args.name in INSTANCE_NAMES:
            builder.add_atom(args, origin)
    for atom in atoms:
        if atom.match("init", 2):
            builder.add_symbol(atom)
        elif atom.match("assign", 2):
            builder.assign(atom)
        elif atom.type == clingo.SymbolType.Function and atom.positive and atom.name in INSTANCE_NAMES:
            builder.add_other_symbol(atom)
    if not builder.seen:
        raise _no_facts("instance facts (expected init(object(..),value(..)) facts)", sources)
    instance = builder.finish()
    builder.warn_unknown()
    return instance


def instance_from_atoms(atoms: Iterable[clingo.Symbol], sources: Sequence[Source] = (),
                        limits: Limits | None = None) -> Instance:
    """Build an :class:`Instance` from ground ``init/2`` and ``assign/2`` atoms; others are ignored."""
    return build_instance(sources, [], list(atoms), limits)
