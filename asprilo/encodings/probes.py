"""Negative tests of ``asprilo grade``: illegal plans that a correct encoding must refuse.

A valid plan on every instance of a ladder does not show that an encoding knows the rules:
a student's encoding without the swap constraint may return plans without swaps by luck,
under one configuration and seed, and with swaps under another.  A *probe* asks the
question directly.  It is a tiny instance, an illegal plan (``occurs/3`` facts) that breaks
one rule of SPEC.md section 4 and nothing else, and a horizon at which a legal plan exists.
The encoding is solved on the instance at that horizon with every action of the plan
forced: each of the plan's atoms must be shown by the answer set (other actions may come
on top).  An encoding that knows the rule has no answer set (the probe is *refused*); one
that forgot it has one (*accepted*: the rule is named as forgotten).  Whether a program has
an answer set does not depend on clingo's configuration or seed, so neither does the
verdict; only a time-out or a crash leaves a probe *undecided*.

The actions are forced on what the model shows, as the grader reads plans: the ``#show``
of ``occurs/3`` atoms and of ``#show occurs(...) : Body.`` terms alike (clingo's observer
says under which condition each is shown; a new atom derived from those conditions must be
true).  An encoding with anonymous robots (A/B/C reference encodings) gets its ``names``
program in the same grounding, which derives the ``occurs/3`` atoms.

A ladder names its probes in ``ladder.yml`` (an exercise file alike; docs/GRADING.md)::

    probes:
      - name: swap                              # a short name
        rule: robots may not swap cells          # the rule, as "forgot: ..." says it
        case: robots 1 and 2 between (1,1) and (2,1) at step 1   # the illegal plan in words
        instance: probes/swap.lp                 # paths relative to the manifest
        plan: probes/swap-plan.lp
        horizon: 1                               # default: the plan's makespan
        breaks: ["err(collision,swap,(1,2,1))"]  # optional: the checker's err/3 atoms, exactly

Before an encoding is probed, each plan is checked: a plan the checker accepts (or whose
violations are not ``breaks``) is a mistake in the ladder (:class:`InputError`).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, TextIO

import clingo
from clingo.backend import Observer

from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.model import Instance
from asprilo.reader import read_instance, read_plan
from asprilo.solver import Solver, Status
from asprilo.writer import format_plan
from asprilo.yamlfile import YamlList, YamlMapping

from .registry import Encoding

#: the verdicts of one probe
REFUSED, ACCEPTED, UNDECIDED = "refused", "accepted", "undecided"
#: the keys of a probe in a ladder or exercise file
KEYS = ("name", "rule", "case", "instance", "plan", "horizon", "breaks")
_REQUIRED = ("name", "rule", "case", "instance", "plan")


@dataclass(frozen=True)
class Probe:
    """One illegal plan: ``plan`` (a file of ``occurs/3`` facts) on ``instance``, solved at
    ``horizon``; it breaks ``rule`` (in words), ``case`` says how; ``breaks``: the checker's
    ``err/3`` atoms for it (empty: not stated)."""

    name: str
    rule: str
    case: str
    instance: Path
    plan: Path
    horizon: int
    breaks: tuple[str, ...] = ()

    def atoms(self) -> list[clingo.Symbol]:
        """The plan's actions as ``occurs/3`` symbols."""
        return [clingo.parse_term(line.rstrip(".")) for line in format_plan(read_plan(self.plan)).splitlines()]


@dataclass
class Probed:
    """What an encoding did with one probe: ``result`` is ``refused``, ``accepted`` (the
    rule is forgotten) or ``undecided`` (``reason`` says why); ``seconds``: the whole run."""

    probe: Probe
    result: str
    seconds: float
    reason: str = ""

    @property
    def forgot(self) -> bool:
        return self.result == ACCEPTED

    def line(self) -> str:
        """The probe in a line of the grader's report."""
        probe = self.probe
        if self.result == ACCEPTED:
            return f"forgot: {probe.rule} ({probe.name} probe: {probe.case})"
        if self.result == UNDECIDED:
            return f"undecided: {probe.rule} ({probe.name} probe: {self.reason})"
        return f"kept: {probe.rule} ({probe.name} probe refused)"

    def as_json(self) -> dict[str, Any]:
        """One entry of ``probes`` in ``asprilo grade --json`` (docs/GRADING.md)."""
        probe = self.probe
        return {"name": probe.name, "rule": probe.rule, "case": probe.case, "instance": str(probe.instance),
                "plan": str(probe.plan), "horizon": probe.horizon, "result": self.result,
                "forgot": self.forgot, "seconds": round(self.seconds, 3), "reason": self.reason or None}


def summary(probed: Sequence[Probed]) -> dict[str, int]:
    """The counts of a run's probes: ``probes``, ``refused``, ``forgotten``, ``undecided``."""
    results = [item.result for item in probed]
    return {"probes": len(results), "refused": results.count(REFUSED), "forgotten": results.count(ACCEPTED),
            "undecided": results.count(UNDECIDED)}


def add_probes(report: dict[str, Any], probed: Sequence[Probed] | None) -> None:
    """Add the probes to a report of ``asprilo grade --json`` (where they ran: ``probed``
    not ``None``): ``probes``, one entry each, and their counts as ``summary.probes``."""
    if probed is not None:
        report["probes"] = [item.as_json() for item in probed]
        report["summary"]["probes"] = summary(probed)


def summary_words(probed: Sequence[Probed]) -> str:
    """E.g. ``probes: 2/3 refused, forgot 1 rule (swap)``."""
    counts = summary(probed)
    words = [f"probes: {counts['refused']}/{counts['probes']} refused"]
    if counts["forgotten"]:
        names = ", ".join(item.probe.name for item in probed if item.forgot)
        words.append(f"forgot {counts['forgotten']} rule{'s' * (counts['forgotten'] != 1)} ({names})")
    if counts["undecided"]:
        words.append(f"{counts['undecided']} undecided")
    return ", ".join(words)


# --- reading -------------------------------------------------------------------------------

def read_probes(manifest: Path, items: object, line: int) -> tuple[Probe, ...]:
    """The probes listed under ``probes:`` in ``manifest`` (a ladder or exercise file);
    ``line``: where the key is.  Bad input: :class:`InputError` ``FILE:LINE``."""
    if not isinstance(items, YamlList):
        raise InputError("'probes' is a list of probes (name, rule, case, instance, plan)", str(manifest), line)
    probes = tuple(_probe(manifest, item, at) for item, at in zip(items, items.item_lines, strict=True))
    names = [probe.name for probe in probes]
    twice = next((name for name in names if names.count(name) > 1), None)
    if twice is not None:
        raise InputError(f"two probes are called {twice!r}", str(manifest), line)
    return probes


def _probe(manifest: Path, item: object, line: int) -> Probe:
    where = str(manifest)
    if not isinstance(item, YamlMapping):
        raise InputError("a probe is a mapping with name, rule, case, instance and plan", where, line)
    unknown = sorted(set(map(str, item)) - set(KEYS))
    if unknown:
        raise InputError(f"unknown key {unknown[0]!r} (a probe has {', '.join(KEYS)})", where,
                         item.line_of(unknown[0]))
    missing = [key for key in _REQUIRED if key not in item]
    if missing:
        raise InputError(f"the probe has no {missing[0]!r}", where, item.line)
    files = {}
    for key in ("instance", "plan"):
        path = manifest.parent / str(item[key])
        if not path.is_file():
            raise InputError(f"no such {key} file: {path}", where, item.line_of(key))
        files[key] = path
    plan = read_plan(files["plan"])
    if not plan.actions:
        raise InputError(f"the probe's plan {files['plan']} has no occurs/3 actions", where, item.line_of("plan"))
    horizon = item.get("horizon", plan.horizon)
    if not isinstance(horizon, int) or isinstance(horizon, bool) or horizon < plan.horizon:
        raise InputError(f"the horizon is a whole number, at least the plan's makespan {plan.horizon}; got "
                         f"{horizon!r}", where, item.line_of("horizon"))
    breaks = item.get("breaks", [])
    breaks = [breaks] if isinstance(breaks, str) else breaks
    if not isinstance(breaks, list) or not all(isinstance(atom, str) for atom in breaks):
        raise InputError("'breaks' lists the checker's err/3 atoms, e.g. [\"err(collision,swap,(1,2,1))\"]", where,
                         item.line_of("breaks"))
    return Probe(str(item["name"]), str(item["rule"]), str(item["case"]), files["instance"], files["plan"], horizon,
                 tuple(breaks))


def violations(probe: Probe, domain: Domain) -> list[str]:
    """The ``err/3`` atoms the checker reports for the probe's plan under ``domain``'s rules."""
    from asprilo.checker import check  # the checker only where a probe is checked

    return [error.atom for error in check(read_instance(probe.instance), read_plan(probe.plan), domain,
                                          bound=None).errors]


def require_illegal(probe: Probe, domain: Domain) -> None:
    """A probe whose plan the checker accepts, or whose violations are not its ``breaks``,
    is a mistake in the ladder: :class:`InputError` naming the plan."""
    found = violations(probe, domain)
    if not found:
        raise InputError(f"the {probe.name} probe's plan breaks no rule of {domain.label}: a probe's plan must be "
                         "illegal", str(probe.plan))
    if probe.breaks and sorted(found) != sorted(probe.breaks):
        raise InputError(f"the {probe.name} probe's plan breaks {', '.join(found)}, not {', '.join(probe.breaks)} "
                         "as its 'breaks' says", str(probe.plan))


# --- probing ---------------------------------------------------------------------------------

def probe_encoding(encoding: Encoding, probes: Sequence[Probe], domain: Domain, *, time_limit: float,
                   memory_limit: int | None = None,
                   on_start: Callable[[int, int, Probe], None] | None = None,
                   checked: bool = False) -> Iterator[Probed]:
    """Run every probe on ``encoding``, each in a child process under ``time_limit``
    seconds (and ``memory_limit`` MB); every plan is checked first (:func:`require_illegal`)
    unless the caller has (``checked``).  ``on_start(number, count, probe)`` is called before each."""
    for probe in () if checked else probes:
        require_illegal(probe, domain)
    for number, probe in enumerate(probes, 1):
        if on_start is not None:
            on_start(number, len(probes), probe)
        yield run_probe(encoding, probe, domain, time_limit=time_limit, memory_limit=memory_limit)


def probe_report(encoding: Encoding, probes: Sequence[Probe], domain: Domain, *, time_limit: float,
                 memory_limit: int | None = None, out: TextIO | None = None,
                 on_start: Callable[[int, int, Probe], None] | None = None,
                 on_done: Callable[[], None] | None = None, checked: bool = False) -> list[Probed]:
    """:func:`probe_encoding`, a line per probe on ``out`` (when given) as each ends;
    ``on_done()`` is called after each (and after a failure)."""
    probed = []
    try:
        for item in probe_encoding(encoding, probes, domain, time_limit=time_limit, memory_limit=memory_limit,
                                   on_start=on_start, checked=checked):
            if on_done is not None:
                on_done()
            probed.append(item)
            if out is not None:
                out.write(item.line() + "\n")
                out.flush()
    finally:
        if on_done is not None:
            on_done()
    return probed


def run_probe(encoding: Encoding, probe: Probe, domain: Domain, *, time_limit: float,
              memory_limit: int | None = None) -> Probed:
    """One probe on ``encoding`` in a child process: refused, accepted or undecided."""
    from asprilo.isolation import run_isolated  # starting children costs imports: only here
    from asprilo.memory import default_memory_mb

    if memory_limit is None:  # a user's program: limited by default (README)
        memory_limit = default_memory_mb()
    started = time.perf_counter()
    instance = read_instance(probe.instance)
    atoms = [str(atom) for atom in probe.atoms()]
    try:
        child = run_isolated(forced_answer, (instance, domain, encoding, atoms, probe.horizon),
                             time_limit=time_limit, memory_mb=memory_limit)
    except InputError as error:  # clingo refused the encoding on the probe's instance
        return Probed(probe, UNDECIDED, time.perf_counter() - started, f"clingo refused it: {error}")
    seconds = time.perf_counter() - started
    if child.status == "done":
        status = child.value
        if status == Status.SAT.value:
            return Probed(probe, ACCEPTED, seconds)
        if status == Status.UNSAT.value:
            return Probed(probe, REFUSED, seconds)
        return Probed(probe, UNDECIDED, seconds, f"time limit ({time_limit:g} s)")
    reasons = {"timeout": f"time limit ({time_limit:g} s)", "memout": f"memory limit ({memory_limit} MB)"}
    reason = reasons.get(child.status) or f"the solver's process crashed{': ' + child.detail if child.detail else ''}"
    return Probed(probe, UNDECIDED, seconds, reason)


def forced_answer(instance: Instance, domain: Domain, encoding: Encoding, atoms: Sequence[str], horizon: int,
                  report: Callable[[Any], None] | None = None) -> str:
    """Whether ``encoding`` on ``instance`` at ``horizon`` has an answer set that shows every
    one of ``atoms``: ``sat``, ``unsat`` or ``unknown`` (a value of :class:`Status`).  Runs
    in the child process of :func:`run_probe` (``report`` is its channel, unused)."""
    from .solving.methods.program import Program, incmode_parts
    from .solving.watch import Watch

    shown = ShownConditions()
    with Watch() as watch:
        if encoding.incremental:
            solver = Program(instance, domain, encoding, watch).fresh(None)
            solver.control.register_observer(shown)
            solver.ground(incmode_parts(horizon))
            solver.assign_external(f"query({horizon})", True)
        else:
            constants = tuple((name, value) for name, value in encoding.constants if name != "horizon")
            at_horizon = replace(encoding, constants=(*constants, ("horizon", str(horizon))))
            solver = Program(instance, domain, at_horizon, watch).fresh(horizon)
            if encoding.names is not None:  # anonymous robots: their names derive occurs/3 here
                solver.load(encoding.names)
            solver.control.register_observer(shown)
            solver.ground()
        force(solver, shown, [clingo.parse_term(atom) for atom in atoms])
        return solver.solve().status.value


class ShownConditions(Observer):
    """A clingo observer that keeps, for each shown ``occurs/3`` atom or term, the
    conditions under which it is shown (program literals; an empty condition: always)."""

    def __init__(self) -> None:
        self.conditions: dict[clingo.Symbol, list[list[int]]] = {}

    def output_atom(self, symbol: clingo.Symbol, atom: int) -> None:
        if symbol.match("occurs", 3):
            self.conditions.setdefault(symbol, []).append([atom] if atom else [])

    def output_term(self, symbol: clingo.Symbol, condition: Sequence[int]) -> None:
        if symbol.match("occurs", 3):
            self.conditions.setdefault(symbol, []).append(list(condition))


def force(solver: Solver, shown: ShownConditions, atoms: Sequence[clingo.Symbol]) -> None:
    """Add to the grounded program that every one of ``atoms`` is shown: a fresh atom per
    action, derived from each condition that shows it, must be true (an action the
    program can never show makes the program unsatisfiable).  Optimisation is switched off:
    any answer set answers the question."""
    with solver.control.backend() as backend:
        for atom in atoms:
            forced = backend.add_atom()
            for condition in shown.conditions.get(atom, []):
                backend.add_rule([forced], condition)
            backend.add_rule([], [-forced])
    solve = solver.control.configuration.solve
    solve.opt_mode = "ignore"  # type: ignore[union-attr]  # a group of the configuration, not a value
    solve.models = "1"  # type: ignore[union-attr]
