"""Read instances and plans (SPEC.md §2-3) from files, strings or stdin: parsed into terms
(:mod:`asprilo.parse`, no clingo), taken apart by the shapes of :mod:`asprilo.facts`."""

from __future__ import annotations

import warnings
from collections.abc import Callable, Iterable, Sequence
from itertools import chain
from typing import Any

import clingo

from .domain import Domain, detect_domain, domains
from .errors import InputError, InputWarning
from .facts import (
    OCCURS_SHAPE,
    action_of,
    assign_args,
    assign_terms,
    format_action,
    format_value,
    init_fact,
    init_terms,
    shape_error,
    value_of,
)
from .limits import Limits, current, require_plan_fits
from .model import Action, Destination, Instance, Order, Plan, Product, Robot, Shelf
from .objects import BUILTIN_ATTRIBUTES, KINDS, ObjectKind, placed_kinds
from .parse import Fn, shown, text_of
from .sources import ScannedFact, Source, SourceLike, as_sources, line_of, load_facts, locate

#: value_of is the tools' way to read single terms
__all__ = ["instance_from_atoms", "plan_from_atoms", "read_instance", "read_instance_and_plan", "read_plan",
           "plan_misfits", "require_known_robots", "require_plan_fits_instance", "value_of"]


def read_instance(inputs: SourceLike | Iterable[SourceLike], limits: Limits | None = None) -> Instance:
    """Read an instance from one or several files (``-`` = stdin) or :class:`Source` objects.

    Facts of object types or attributes asprilo does not know are kept aside
    (``other_facts``) with one :class:`InputWarning` naming them.
    """
    limits = limits or current()
    sources = as_sources(inputs, limits)
    return _build_instance(sources, load_facts(sources, limits, _INSTANCE_NAMES), [], limits)


def read_plan(inputs: SourceLike | Iterable[SourceLike], limits: Limits | None = None) -> Plan:
    """Read a plan from plan files or clingo's printed output.  Instance atoms (``init``,
    ``assign``) are ignored without a word; other atoms are ignored with an
    :class:`InputWarning` that names them, and mistakes a plan's author likely made are
    warned about one by one with a did-you-mean (``occur/3``, ``occurs/2``, an action
    ``mvoe``): see :class:`_PlanMistakes`."""
    limits = limits or current()
    sources = as_sources(inputs, limits)
    return _build_plan(sources, load_facts(sources, limits), [], limits)


def read_instance_and_plan(instance: SourceLike | Iterable[SourceLike], plan: SourceLike | Iterable[SourceLike],
                           limits: Limits | None = None, domain: Domain | None = None) -> tuple[Instance, Plan]:
    """Read both and make sure the plan is one for the instance
    (:func:`require_plan_fits_instance`)."""
    limits = limits or current()
    plan_sources = as_sources(plan, limits)
    the_instance = read_instance(instance, limits)
    the_plan = read_plan(plan_sources, limits)
    require_plan_fits_instance(the_plan, the_instance, plan_sources, domain, limits)
    return the_instance, the_plan


def require_plan_fits_instance(plan: Plan, instance: Instance, sources: Sequence[Source] = (),
                               domain: Domain | None = None, limits: Limits | None = None) -> None:
    """A plan read for an instance is one for it, or one sentence says why not: it moves only
    robots the instance has (else :class:`InputError`: a plan made for another instance), its
    horizon times the robots is within ``robot-steps`` (:func:`asprilo.limits.require_plan_fits`),
    and its actions are the domain's (``domain``, or the one detected): actions of other
    domains are named in one :class:`InputWarning` (the checker then finds each one)."""
    require_known_robots(plan, instance, sources)
    try:
        require_plan_fits(instance, plan, limits)
    except InputError as error:
        raise error.at(sources[0].name if len(sources) == 1 else None) from None
    _warn_foreign_actions(plan, domain or detect_domain(instance, plan), sources)


# --- instances ---------------------------------------------------------------------------

#: the atoms an instance and a plan are read from (others are ignored), with their arities
_INSTANCE_NAMES = {"init", "assign"}
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
        return InputError(message, *_where(origin, self.sources))

    def single(self, key: tuple, value: Any, origin: Any, what: str) -> None:
        """Record a value that may be stated once only (a duplicate must be identical)."""
        first = self.seen.get(key)
        if first is not None and first[0] != value:
            raise self.fail(f"{what}: {_shown(first[0])} and {_shown(value)}", origin)
        self.seen[key] = (value, origin)

    def add(self, kind: Any, ident: Any, attribute: Any, value: Any, origin: Any) -> None:
        known = KINDS.get(kind)
        if known is None or attribute not in known.attributes:
            what = f"object type '{_shown(kind)}'" if known is None else f"attribute '{_shown(attribute)}' of {kind}"
            self.unknown.setdefault(what, origin)
            self.instance.other_facts.append(
                init_fact(format_value(kind), format_value(ident), format_value(attribute), value))
            return
        expected = known.attributes[attribute]
        if not isinstance(ident, int):
            raise self.fail(f"{kind} id must be an integer, got {_shown(ident)}", origin)
        if not expected.shape(value):
            raise self.fail(f"{kind} {ident}: value of '{attribute}' must be {expected.description}, "
                            f"got {_shown(value)}", origin)
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
            file, line = _where(next(iter(self.unknown.values())), self.sources)
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
            raise shape_error(atom).at(*_where(origin, self.sources))
        try:
            ident, kind, goal = assign_args(atom)
        except InputError as error:
            raise error.at(*_where(origin, self.sources)) from None
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
            raise error.at(*_where(atom, self.sources)) from None
        self.add(*terms, atom)

    def assign(self, atom: clingo.Symbol) -> None:
        """Add a labelled goal ``assign(robot(R),shelf(S))`` or ``assign(robot(R),destination(D))``."""
        try:
            ident, kind, goal = assign_terms(atom)
        except InputError as error:
            raise error.at(*_where(atom, self.sources)) from None
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


def _where(origin: Any, sources: Sequence[Source]) -> tuple[str | None, int | None]:
    if isinstance(origin, clingo.Symbol):
        return locate(sources, origin)
    return line_of(*origin)


def _shown(value: Any) -> str:
    """A value as read, fit for a message (shortened, no control character raw)."""
    return shown(format_value(value), 60)


def _no_facts(what: str, sources: Sequence[Source]) -> InputError:
    names = ", ".join(source.name for source in sources) or None
    return InputError(f"no {what} found", names)


def _build_instance(sources: Sequence[Source], facts: list[ScannedFact], atoms: list[clingo.Symbol],
                    limits: Limits | None = None) -> Instance:
    builder = _InstanceBuilder(sources, limits or current())
    add = builder.add
    for kind, args, origin in facts:
        if kind == "init":
            kind, ident, attribute, value = args
            add(kind, ident, attribute, value, origin)
        elif kind == "atom" and args.name in _INSTANCE_NAMES:
            builder.add_atom(args, origin)
    for atom in atoms:
        if atom.match("init", 2):
            builder.add_symbol(atom)
        elif atom.match("assign", 2):
            builder.assign(atom)
        elif atom.type == clingo.SymbolType.Function and atom.positive and atom.name in _INSTANCE_NAMES:
            builder.add_other_symbol(atom)
    if not builder.seen:
        raise _no_facts("instance facts (expected init(object(..),value(..)) facts)", sources)
    instance = builder.finish()
    builder.warn_unknown()
    return instance


def instance_from_atoms(atoms: Iterable[clingo.Symbol], sources: Sequence[Source] = (),
                        limits: Limits | None = None) -> Instance:
    """Build an :class:`Instance` from ground ``init/2`` and ``assign/2`` atoms; others are ignored."""
    return _build_instance(sources, [], list(atoms), limits)


# --- plans -------------------------------------------------------------------------------

def _action_of(atom: clingo.Symbol, sources: Sequence[Source]) -> Action:
    try:
        return action_of(atom)
    except InputError as error:
        raise error.at(*locate(sources, atom)) from None


def _known_actions() -> list[str]:
    """The action names some domain knows (for a did-you-mean)."""
    return sorted(set().union(*(domain.actions for domain in domains())))


#: the kinds of object that act in plans
_ACTING = ["robot"]
#: other atoms named in one warning at most
_NAMED_AT_MOST = 5


class _PlanMistakes:
    """What a plan file holds besides its actions, and actions no domain knows: each likely
    mistake in one :class:`InputWarning` with a did-you-mean, at the place of its first
    atom; instance atoms (``init``, ``assign``: clingo's output shows both) pass without a
    word, any other atom is named in one warning (ignored) -- unless the text holds an
    instance too (a file of both, clingo's output of an encoding without ``#show``: other
    atoms are expected there)."""

    def __init__(self, sources: Sequence[Source]):
        self.sources = sources
        self.with_instance = False  # instance atoms seen
        self.mistakes: dict[str, tuple[str, Any]] = {}  # what -> (message, origin of the first)
        self.other: dict[str, Any] = {}  # name/arity of other atoms -> origin of the first
        self.actions: set[str] = set()  # the action names seen
        self.kinds: set[str] = set()  # the kinds of object seen acting

    def atom(self, name: str, arity: int, origin: Any) -> None:
        """An atom other than ``occurs/3`` (and not an instance atom)."""
        what = f"{name}/{arity}"
        if what in self.mistakes or what in self.other:
            return
        if name == "occurs":
            self.mistakes[what] = (f"{what} is ignored: occurs has 3 arguments, {OCCURS_SHAPE} "
                                   "(a parenthesis in the wrong place?)", origin)
        elif _close_matches(name, ["occurs"], n=1, cutoff=0.6):
            self.mistakes[what] = (f"{_shown_name(name)}/{arity} is ignored: did you mean occurs/3?", origin)
        else:
            self.other[what] = origin

    def action(self, kind: Any, name: Any, origin: Any) -> None:
        """An action of an ``occurs/3`` atom: its name and the kind of object doing it."""
        if name not in self.actions:
            self.actions.add(name)
            known = _known_actions()
            if name not in known:
                close = _close_matches(str(name), known, n=1)
                hint = f": did you mean {close[0]}?" if close else ""
                self.mistakes[f"action {name}"] = (
                    f"there is no action '{_shown_name(name)}'{hint} (the actions: {', '.join(known)})", origin)
        if kind not in self.kinds:
            self.kinds.add(kind)
            if kind not in _ACTING:
                close = _close_matches(str(kind), _ACTING, n=1)
                hint = f": did you mean {close[0]}?" if close else ""
                self.mistakes[f"kind {kind}"] = (f"only robots act, not object({_shown_name(kind)},..){hint}", origin)

    def warn(self) -> None:
        found = list(self.mistakes.values())
        if self.other and not self.with_instance:
            names = list(self.other)
            more = len(names) - _NAMED_AT_MOST
            listed = ", ".join(_shown_name(name, 40) for name in names[:_NAMED_AT_MOST]) + \
                (f" and {more} more" if more > 0 else "")
            found.append((f"ignored: {listed} (a plan is made of occurs/3 atoms)", next(iter(self.other.values()))))
        for message, origin in sorted(found, key=lambda item: self._order(item[1])):
            warnings.warn(InputWarning(str(InputError(message, *_where(origin, self.sources)))), stacklevel=5)

    def _order(self, origin: Any) -> tuple[int, int]:
        """Where an origin stands: (source, offset) for facts as read, else in the order found."""
        if isinstance(origin, tuple):
            source, offset = origin
            return next((i for i, s in enumerate(self.sources) if s is source), len(self.sources)), offset
        return len(self.sources), 0


def _shown_name(name: Any, most: int = 30) -> str:
    return shown(str(name), most)


def _build_plan(sources: Sequence[Source], facts: list[ScannedFact], atoms: list[clingo.Symbol],
                limits: Limits | None = None) -> Plan:
    actions: list[Action] = []
    origins: list[Any] = []
    mistakes = _PlanMistakes(sources)
    for kind, args, origin in facts:
        if kind == "occurs":
            actions.append(Action(args[4], args[1], args[2], args[3], args[0]))
            origins.append(origin)
            mistakes.action(args[0], args[2], origin)
        elif kind == "init" or (kind == "atom" and args.name in _INSTANCE_NAMES):
            mistakes.with_instance = True
        elif kind == "atom" and not args.negative:
            if args.name == "occurs" and len(args.args) == 3:
                raise shape_error(args).at(*_where(origin, sources))
            mistakes.atom(args.name, len(args.args), origin)
    for atom in atoms:  # a solver's answer: only occurs/N of another arity is said
        if atom.match("occurs", 3):
            actions.append(_action_of(atom, sources))
            origins.append(atom)
        elif atom.type == clingo.SymbolType.Function and atom.positive and atom.name == "occurs":
            mistakes.atom(atom.name, len(atom.arguments), atom)
    limits = limits or current()
    far = next((i for i, action in enumerate(actions) if abs(action.step) > limits.robot_steps), None)
    if far is not None:
        what = limits.exceeded("robot_steps", f"an action at step {actions[far].step:,}").message
        raise InputError(what, *_where(origins[far], sources))
    mistakes.warn()
    return Plan(actions)


def plan_from_atoms(atoms: Iterable[clingo.Symbol], sources: Sequence[Source] = (),
                    limits: Limits | None = None) -> Plan:
    """Build a :class:`Plan` from the ``occurs/3`` atoms among ``atoms``."""
    return _build_plan(sources, [], list(atoms), limits)


def _warn_foreign_actions(plan: Plan, domain: Domain, sources: Sequence[Source]) -> None:
    """One warning naming the actions of other domains that the plan uses (a plan for another
    domain, or instance); names no domain knows were warned about when the plan was read."""
    known = set(_known_actions())
    foreign = sorted({action.name for action in plan.actions if action.name in known} - set(domain.actions))
    if not foreign:
        return
    first = next(action for action in plan.actions if action.name in foreign)
    mine = ", ".join(sorted(domain.actions))
    message = (f"the plan uses {', '.join(foreign)}, which domain {domain.label} lacks (its actions: {mine}): "
               "a plan made for another domain or instance?")
    warnings.warn(InputWarning(str(InputError(message, *locate(sources, format_action(first))))), stacklevel=3)


def plan_misfits(plan: Plan, instance: Instance, domain: Domain | None = None) -> list[str]:
    """What makes a plan one for another instance or domain, in words (nothing: it fits): robots
    the instance lacks, action names no domain knows (with a did-you-mean), actions of other
    domains than ``domain`` (or the one detected).  For plans that are not read from a file
    (a solver's answer), where :func:`require_plan_fits_instance` has no line to name."""
    said = []
    robots = list(dict.fromkeys(action.robot for action in plan.actions
                                if action.kind == "robot" and action.robot not in instance.robots))
    if robots:
        names = ", ".join(_shown(robot) for robot in robots[:_NAMED_AT_MOST]) + \
            (f" and {len(robots) - _NAMED_AT_MOST} more" if len(robots) > _NAMED_AT_MOST else "")
        said.append(f"it moves robot{'s' * (len(robots) > 1)} {names}, but the instance has {_robots_of(instance)}")
    known = _known_actions()
    for name in sorted({action.name for action in plan.actions} - set(known), key=str):
        close = _close_matches(str(name), known, n=1)
        said.append(f"there is no action '{_shown_name(name)}'" + (f" (did you mean {close[0]}?)" if close else ""))
    domain = domain or detect_domain(instance, plan)
    foreign = sorted({action.name for action in plan.actions if action.name in known} - set(domain.actions))
    if foreign:
        said.append(f"it uses {', '.join(foreign)}, which domain {domain.label} lacks "
                    f"(its actions: {', '.join(sorted(domain.actions))})")
    return said


def _robots_of(instance: Instance) -> str:
    """``robots 1..3``, ``robot 1`` or ``no robots``."""
    if not instance.robots:
        return "no robots"
    low, high = min(instance.robots), max(instance.robots)
    return f"robot {low}" if low == high else f"robots {low}..{high}"


def require_known_robots(plan: Plan, instance: Instance, sources: Sequence[Source] = ()) -> None:
    """Reject a plan whose actions name a robot the instance does not have."""
    for action in plan.actions:
        if action.kind == "robot" and action.robot not in instance.robots:
            raise InputError(f"the plan moves robot {_shown(action.robot)}, but the instance has "
                             f"{_robots_of(instance)} (plan and instance do not fit)",
                             *locate(sources, format_action(action)))


def _close_matches(word: str, candidates: Sequence[str], n: int = 3, cutoff: float = 0.6) -> list[str]:
    """:func:`difflib.get_close_matches`, imported when a mistake is to be named (reading
    a well-formed file never needs it)."""
    from difflib import get_close_matches
    return get_close_matches(word, candidates, n=n, cutoff=cutoff)
