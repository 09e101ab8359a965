"""The instance and the plan as ASP atoms, one fact per line, without Qt: the text the atoms
pane shows, what each line is about (to find an object's facts, an action's step), and
the plan read back from edited text."""

from __future__ import annotations

import re
import warnings
from dataclasses import dataclass, field

from asprilo.domain import Domain
from asprilo.errors import InputWarning
from asprilo.model import Instance, Plan
from asprilo.reader import read_plan, require_plan_fits_instance
from asprilo.sources import Source
from asprilo.writer import format_instance, format_plan

PLAN_SOURCE = "<plan atoms>"
_INIT = re.compile(r"^init\(object\((\w+),(-?\d+)\),value\((\w+),\(?(-?\d+)")
_ASSIGN = re.compile(r"^assign\(robot\((-?\d+)\),(\w+)\((-?\d+)\)\)")
_OCCURS = re.compile(r"^occurs\(object\(robot,(-?\d+)\),action\(.*\),(-?\d+)\)\.\s*(%.*)?$")
_KINDS = {"pickingStation": "station"}
#: attribute -> the kind of object its value names (``robot carries S``, ``order pickingStation P``, ...)
_NAMED = {"carries": "shelf", "on": "shelf", "pickingStation": "station", "line": "product"}


@dataclass(frozen=True)
class AtomLine:
    """One line of text and what it is about."""

    text: str
    subjects: frozenset[tuple[str, int]] = field(default_factory=frozenset)
    step: int | None = None  # the step of an ``occurs/3`` fact


def about(text: str) -> AtomLine:
    """What a line of facts is about: the objects it names, the step of an action."""
    line = text.strip()
    match = _INIT.match(line)
    if match:
        kind, ident, attribute, value = match.groups()
        subjects = {(_KINDS.get(kind, kind), int(ident))}
        if attribute in _NAMED:
            subjects.add((_NAMED[attribute], int(value)))
        return AtomLine(text, frozenset(subjects))
    match = _ASSIGN.match(line)
    if match:
        robot, kind, goal = match.groups()
        return AtomLine(text, frozenset({("robot", int(robot)), (kind, int(goal))}))
    match = _OCCURS.match(line)
    if match:
        return AtomLine(text, frozenset({("robot", int(match.group(1)))}), int(match.group(2)))
    return AtomLine(text)


def instance_lines(instance: Instance) -> list[AtomLine]:
    """The instance's facts in the canonical order, grouped under comments."""
    text = format_instance(instance, [])
    body = text[text.index("#program base."):]
    return [about(line) for line in body.splitlines()]


def plan_lines(plan: Plan) -> list[AtomLine]:
    """The plan's ``occurs/3`` facts, by step and robot."""
    return [about(line) for line in format_plan(plan).splitlines()]


@dataclass(frozen=True)
class Note:
    """Something the reader said of a plan it read (a warning): the words, as ``check``
    prints them after ``warning:``, and the line it names (from 1), if any."""

    text: str
    line: int | None = None


_PLACE = re.compile(re.escape(PLAN_SOURCE) + r":(\d+):")


def read_plan_text(text: str, instance: Instance, domain: Domain | None = None) -> tuple[Plan, list[Note]]:
    """The plan that edited text holds and what the reader said of it (``check``'s warnings:
    an atom that is no plan atom, an action no domain knows, with a did-you-mean); bad text
    raises ``InputError`` naming the line, as does a plan for robots the instance lacks."""
    source = Source(PLAN_SOURCE, text)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", InputWarning)
        plan = read_plan(source)
        require_plan_fits_instance(plan, instance, [source], domain)
    notes = []
    for warning in caught:
        if not issubclass(warning.category, InputWarning):
            warnings.warn_explicit(warning.message, warning.category, warning.filename, warning.lineno)
            continue
        words = str(warning.message)
        place = _PLACE.match(words)
        notes.append(Note(words, int(place.group(1)) if place else None))
    return plan, notes


def lines_about(lines: list[AtomLine], subject: tuple[str, int]) -> list[int]:
    """The numbers of the lines that name ``subject``."""
    return [number for number, line in enumerate(lines) if subject in line.subjects]
