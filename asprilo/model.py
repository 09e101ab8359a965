"""The warehouse instance and the plan as plain Python objects (SPEC.md sections 1-3).

Objects keep the identifiers of the facts they come from.  Quantities are ``None`` where
an instance uses the quantity-free forms ``value(on,S)`` / ``value(line,P)``.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass, field
from typing import Any, NamedTuple

Cell = tuple[int, int]
#: a term of a fact as a Python value (:func:`asprilo.facts.value_of`): a number, a tuple of
#: terms, or the text of any other term
Term = int | str | tuple["Term", ...]

#: The four moves, as (DX,DY) with (1,1) top-left and Y growing downwards.
DIRECTIONS: tuple[Cell, ...] = ((1, 0), (-1, 0), (0, 1), (0, -1))


@dataclass
class Robot:
    id: int
    at: Cell
    carries: int | None = None


@dataclass
class Shelf:
    id: int
    at: Cell


@dataclass
class PickingStation:
    id: int
    at: Cell


@dataclass
class Destination:
    """A cell that some robot must occupy at the horizon (domain Md)."""

    id: int
    at: Cell


@dataclass
class Product:
    """A product and its stock: shelf id -> units (``None`` when no quantity is given)."""

    id: int
    stock: dict[int, int | None] = field(default_factory=dict)


@dataclass
class Order:
    """An order: product id -> requested units (``None``: no quantity), its station, and the
    step it is released at (online scenarios: known after that step; ``None``: an offline
    order, known from the start and fulfilled at the horizon)."""

    id: int
    lines: dict[int, int | None] = field(default_factory=dict)
    station: int | None = None
    release: int | None = None


@dataclass
class Instance:
    """A warehouse: floor, objects, inventory and orders, in their initial state."""

    nodes: dict[int, Cell] = field(default_factory=dict)
    highways: dict[int, Cell] = field(default_factory=dict)
    robots: dict[int, Robot] = field(default_factory=dict)
    shelves: dict[int, Shelf] = field(default_factory=dict)
    stations: dict[int, PickingStation] = field(default_factory=dict)
    products: dict[int, Product] = field(default_factory=dict)
    orders: dict[int, Order] = field(default_factory=dict)
    destinations: dict[int, Destination] = field(default_factory=dict)
    #: labelled goals (M/Md): robot id -> ("shelf", S) or ("destination", D), from
    #: ``assign(robot(R),shelf(S))`` / ``assign(robot(R),destination(D))`` facts
    assignment: dict[int, tuple[str, int]] = field(default_factory=dict)
    #: ``init/2`` facts of object types or attributes asprilo does not know (e.g. a robot's
    #: ``energy``), as text: ignored by every tool, written back with the instance
    other_facts: list[str] = field(default_factory=list)
    #: values of the attributes variants declare (a robot's ``energy``: registered with
    #: :func:`asprilo.objects.register_attribute`): (kind, id) -> attribute -> value
    attributes: dict[tuple[str, int], dict[str, Term]] = field(default_factory=dict)
    #: objects of the placed kinds registered beyond SPEC.md's (:func:`asprilo.objects.register_kind`):
    #: kind -> id -> cell
    placed: dict[str, dict[int, Cell]] = field(default_factory=dict)

    # --- the floor -----------------------------------------------------------------------

    @property
    def cells(self) -> set[Cell]:
        """All usable floor cells."""
        return set(self.nodes.values())

    @property
    def size(self) -> Cell:
        """``(X,Y)``: the extent of the floor (largest coordinates of any node)."""
        if not self.nodes:
            return (0, 0)
        return (max(x for x, _ in self.nodes.values()), max(y for _, y in self.nodes.values()))

    @property
    def storage_cells(self) -> set[Cell]:
        """Nodes where a shelf may rest: neither highway nor picking station."""
        blocked = set(self.highways.values()) | {station.at for station in self.stations.values()}
        return self.cells - blocked

    def assigned_cells(self) -> dict[int, Cell]:
        """Robot id -> the cell its labelled goal (shelf or destination) starts on."""
        tables: dict[str, dict[int, Shelf] | dict[int, Destination]] = {
            "shelf": self.shelves, "destination": self.destinations}
        return {robot: tables[kind][goal].at for robot, (kind, goal) in self.assignment.items()}

    # --- inventory -----------------------------------------------------------------------

    def shelf_stock(self) -> dict[int, dict[int, int | None]]:
        """Shelf id -> product id -> units: the inventory seen from the shelves."""
        stock: dict[int, dict[int, int | None]] = defaultdict(dict)
        for product in self.products.values():
            for shelf, units in product.stock.items():
                stock[shelf][product.id] = units
        return dict(stock)

    @property
    def units(self) -> int:
        """Total product units in stock (a quantity-free entry counts as one unit)."""
        return sum(1 if units is None else units
                   for product in self.products.values() for units in product.stock.values())

    def counts(self) -> dict[str, int]:
        """The figures a file name and header report."""
        x, y = self.size
        return {
            "x": x, "y": y, "nodes": len(self.nodes), "highways": len(self.highways),
            "robots": len(self.robots), "shelves": len(self.shelves),
            "stations": len(self.stations), "products": len(self.products),
            "units": self.units, "orders": len(self.orders),
            "destinations": len(self.destinations),
        }

    def file_name(self, number: int | str = 1, digits: int = 3) -> str:
        """The standard name ``x.._y.._n.._r.._s.._ps.._pr.._u.._o.._N<k>.lp`` (SPEC.md §2)."""
        c = self.counts()
        k = str(number).zfill(digits) if isinstance(number, int) else number
        return (f"x{c['x']}_y{c['y']}_n{c['nodes']}_r{c['robots']}_s{c['shelves']}"
                f"_ps{c['stations']}_pr{c['products']}_u{c['units']}_o{c['orders']}_N{k}.lp")


class Action(NamedTuple):
    """``occurs(object(Kind,Robot),action(Name,Args),Step)``.

    ``args`` is the action's argument term as a Python value: a tuple such as ``(1,0)`` or
    ``()`` for well-formed actions; ints and strings (the term's text) stand for other
    terms.  ``robot`` is a robot id where the plan is well-formed, but any term as read
    (``object(robot,r1)``, ``object(robot,(1,2))``).  ``kind`` is the object type named in
    the fact; anything but ``robot`` is a plan error.
    """

    step: int
    robot: Term
    name: str
    args: Any = ()
    kind: str = "robot"


@dataclass
class Plan:
    """A parallel plan: a set of robot actions at time steps >= 1."""

    actions: list[Action] = field(default_factory=list)

    def __post_init__(self) -> None:
        self.actions = sorted(dict.fromkeys(self.actions), key=_action_key)

    @property
    def horizon(self) -> int:
        """The makespan: the largest time step of any action (0 for the empty plan)."""
        return max((action.step for action in self.actions), default=0)

    def at_step(self, step: int) -> list[Action]:
        return [action for action in self.actions if action.step == step]

    def by_step(self) -> dict[int, list[Action]]:
        steps: dict[int, list[Action]] = defaultdict(list)
        for action in self.actions:
            steps[action.step].append(action)
        return dict(steps)

    def __len__(self) -> int:
        return len(self.actions)


def _action_key(action: Action) -> tuple:
    """Order by step, then robot; actions that tie keep the order they were given in."""
    step, robot, name, _args, kind = action
    if kind == "robot" and type(robot) is int:
        return (step, 0, "", 0, robot, name)
    return (step, kind != "robot", kind, 1 if type(robot) is not int else 0,
            robot if type(robot) is int else str(robot), name)
