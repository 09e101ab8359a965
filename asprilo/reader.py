"""Read instances and plans (SPEC.md §2-3) from files, strings or stdin: parsed into terms
(:mod:`asprilo.parse`, no clingo), taken apart by the shapes of :mod:`asprilo.facts`; an
instance built by :mod:`asprilo.instance_builder`, a plan here."""

from __future__ import annotations

import warnings
from collections.abc import Iterable, Sequence
from typing import Any

import clingo

from .domain import Domain, detect_domain, domains
from .errors import InputError, InputWarning
from .facts import OCCURS_SHAPE, action_of, format_action, shape_error, value_of
from .instance_builder import INSTANCE_NAMES, build_instance, instance_from_atoms, shown_value, where
from .limits import Limits, StepCounter, current, require_plan_fits
from .model import Action, Instance, Plan
from .parse import shown
from .sources import ScannedFact, Source, SourceLike, as_sources, load_facts, locate

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
    return build_instance(sources, load_facts(sources, limits, INSTANCE_NAMES), [], limits)


def read_plan(inputs: SourceLike | Iterable[SourceLike], limits: Limits | None = None,
              robots: int | None = None) -> Plan:
    """Read a plan from plan files or clingo's printed output.  Instance atoms (``init``,
    ``assign``) are ignored without a word; other atoms are ignored with an
    :class:`InputWarning` that names them, and mistakes a plan's author likely made are
    warned about one by one with a did-you-mean (``occur/3``, ``occurs/2``, an action
    ``mvoe``): see :class:`_PlanMistakes`.  ``robot-steps`` is counted while the plan is
    read (:class:`asprilo.limits.StepCounter`), with the ``robots`` of its instance where
    known."""
    limits = limits or current()
    sources = as_sources(inputs, limits)
    return _build_plan(sources, load_facts(sources, limits, steps=StepCounter(limits, robots)), [], limits)


def read_instance_and_plan(instance: SourceLike | Iterable[SourceLike], plan: SourceLike | Iterable[SourceLike],
                           limits: Limits | None = None, domain: Domain | None = None) -> tuple[Instance, Plan]:
    """Read both and make sure the plan is one for the instance
    (:func:`require_plan_fits_instance`)."""
    limits = limits or current()
    plan_sources = as_sources(plan, limits)
    the_instance = read_instance(instance, limits)
    the_plan = read_plan(plan_sources, limits, len(the_instance.robots))
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
            warnings.warn(InputWarning(str(InputError(message, *where(origin, self.sources)))), stacklevel=5)

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
        elif kind == "init" or (kind == "atom" and args.name in INSTANCE_NAMES):
            mistakes.with_instance = True
        elif kind == "atom" and not args.negative:
            if args.name == "occurs" and len(args.args) == 3:
                raise shape_error(args).at(*where(origin, sources))
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
        raise InputError(what, *where(origins[far], sources))
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
        names = ", ".join(shown_value(robot) for robot in robots[:_NAMED_AT_MOST]) + \
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
            raise InputError(f"the plan moves robot {shown_value(action.robot)}, but the instance has "
                             f"{_robots_of(instance)} (plan and instance do not fit)",
                             *locate(sources, format_action(action)))


def _close_matches(word: str, candidates: Sequence[str], n: int = 3, cutoff: float = 0.6) -> list[str]:
    """:func:`difflib.get_close_matches`, imported when a mistake is to be named (reading
    a well-formed file never needs it)."""
    from difflib import get_close_matches
    return get_close_matches(word, candidates, n=n, cutoff=cutoff)
