"""What the viewer shows: an instance and a plan, read from files, stdin or dropped files.

Sources are read once and kept, so a reload re-reads the files but never standard input
again, and nothing is ever written next to the user's files.
"""

from __future__ import annotations

import re
import sys
import warnings
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from asprilo.domain import Domain, detect_domain
from asprilo.errors import InputError, InputWarning
from asprilo.model import Instance, Plan
from asprilo.reader import read_instance, read_plan, require_plan_fits_instance
from asprilo.sources import Source, SourceLike, as_sources

from .rules import varied

if TYPE_CHECKING:
    from asprilo.domain.variant_file import VariantFile

_INIT = re.compile(r"\binit\s*\(")
_OCCURS = re.compile(r"\boccurs\s*\(")


@dataclass
class Scenario:
    """An instance, the plan shown on it (possibly empty), and where both came from."""

    instance: Instance
    plan: Plan = field(default_factory=Plan)
    instance_sources: list[Source] = field(default_factory=list)
    plan_sources: list[Source] = field(default_factory=list)
    domain: Domain | None = None  # None: detected from instance and plan
    #: the domain a solve found the plan shown for (None: the plan came otherwise): the plan
    #: is shown under the rules it was solved and checked under, whatever it holds
    solved_in: Domain | None = None
    unfinished: bool = False  # the plan still grows (an online session): no goal check yet
    #: what the reader warned about reading the files (``FILE:LINE: ...``, as ``check`` says
    #: them after ``warning:``): the window shows them until another file is read
    read_warnings: list[str] = field(default_factory=list)

    @property
    def title(self) -> str:
        names = [Path(s.name).name for s in self.instance_sources + self.plan_sources]
        return " + ".join(dict.fromkeys(names)) or "untitled"

    @property
    def files(self) -> tuple[list[str], list[str]]:
        """The file paths behind it (standard input left out): for reload and recent files."""
        def paths(sources: list[Source]) -> list[str]:
            return [s.name for s in sources if not s.name.startswith("<")]
        return paths(self.instance_sources), paths(self.plan_sources)


def load_scenario(instance: SourceLike | Iterable[SourceLike],
                  plans: SourceLike | Iterable[SourceLike] = (), domain: Domain | None = None,
                  variants: Sequence[VariantFile] = ()) -> Scenario:
    """Read an instance and its plan files; without plan files the plan is the instance
    sources' own ``occurs/3`` atoms (one file or stdin may hold both).  The plan is read as
    ``check`` reads it (:func:`asprilo.reader.require_plan_fits_instance`): a plan for another
    instance is refused in the same sentence.  ``variants``: the rule variants it is shown
    under, which must fit its domain (else :class:`InputError`, as ``check`` says it)."""
    instance_sources = as_sources(instance)
    plan_sources = as_sources(plans)

    def read() -> Scenario:
        the_instance = read_instance(instance_sources)
        plan_origin = plan_sources or instance_sources
        the_plan = read_plan(plan_origin)
        require_plan_fits_instance(the_plan, the_instance, plan_origin, domain)
        scenario = Scenario(the_instance, the_plan, instance_sources, plan_sources, domain)
        shown_domain(scenario, variants)
        return scenario
    return _kept_warnings(read)


def shown_domain(scenario: Scenario, variants: Sequence[VariantFile] = ()) -> Domain | None:
    """The domain ``scenario`` is shown in: the one given (``None``: the one its instance and
    plan are detected in), changed by ``variants`` (:class:`InputError` where they do not fit)."""
    if not variants:
        return scenario.domain
    plan = scenario.plan if len(scenario.plan) else None
    return varied(scenario.domain or detect_domain(scenario.instance, plan), variants)


def add_plan(scenario: Scenario, plans: SourceLike | Iterable[SourceLike]) -> Scenario:
    """The same instance with the plan read from ``plans``."""
    plan_sources = as_sources(plans)

    def read() -> Scenario:
        plan = read_plan(plan_sources)
        require_plan_fits_instance(plan, scenario.instance, plan_sources, scenario.domain)
        return Scenario(scenario.instance, plan, scenario.instance_sources, plan_sources, scenario.domain)
    return _kept_warnings(read)


def _kept_warnings(read: Callable[[], Scenario]) -> Scenario:
    """``read()``, with the reader's warnings kept in the scenario (for the window) and given
    on as they came (``viz`` prints them on standard error as ``check`` does)."""
    kept: list[warnings.WarningMessage] = []
    try:
        with warnings.catch_warnings(record=True) as kept:
            warnings.simplefilter("always", InputWarning)  # a file read again warns again
            scenario = read()
    finally:  # before an error too, as before
        for warning in kept:
            warnings.warn_explicit(warning.message, warning.category, warning.filename, warning.lineno)
    scenario.read_warnings = [str(w.message) for w in kept if issubclass(w.category, InputWarning)]
    return scenario


def warnings_said(scenario: Scenario | None) -> str | None:
    """One line for the status bar when reading the scenario's files gave warnings, e.g.
    ``3 warnings reading mistakes.lp: see the Atoms pane`` (``None``: none)."""
    if scenario is None or not scenario.read_warnings:
        return None
    said = scenario.read_warnings
    sources = scenario.instance_sources + scenario.plan_sources
    named = [Path(s.name).name for s in sources if any(text.startswith(f"{s.name}:") for text in said)]
    files = ", ".join(dict.fromkeys(named)) or scenario.title
    return f"{len(said)} warning{'s' if len(said) != 1 else ''} reading {files}: see the Atoms pane"


def reload(scenario: Scenario) -> Scenario:
    """Read the scenario's files again (text from standard input is reused)."""
    def fresh(sources: list[Source]) -> list[Source]:
        return [s if s.name.startswith("<") else Source.from_path(s.name) for s in sources]
    return load_scenario(fresh(scenario.instance_sources), fresh(scenario.plan_sources), scenario.domain)


def sort_files(paths: Iterable[str | Path]) -> tuple[list[Source], list[Source]]:
    """Split files by content: those with ``init`` facts hold an instance, the rest a plan."""
    instances, plans = [], []
    for source in as_sources([str(path) for path in paths]):
        if _INIT.search(source.text):
            instances.append(source)
        elif _OCCURS.search(source.text):
            plans.append(source)
        else:
            raise InputError("holds neither instance facts (init/2) nor plan facts (occurs/3)",
                             source.name)
    return instances, plans


def command_line_inputs(files: list[str]) -> tuple[list[SourceLike], list[SourceLike]]:
    """``viz [INSTANCE] [PLAN ...]``; without files, piped standard input holds the instance
    (and maybe the plan).  Nothing piped in (a terminal, or empty input): nothing to show."""
    if files:
        return list(files[:1]), list(files[1:])
    if sys.stdin is None or sys.stdin.isatty():
        return [], []
    piped = Source.from_stdin()
    return ([piped] if piped.text.strip() else []), []
