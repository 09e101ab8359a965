"""One encoding on one instance, ready to ground for a horizon: the program the horizon
search solves (:class:`Program`), and the plan of a model (:func:`name_robots`).

Besides the encoding and the instance facts, the program gets what the encodings can use
but need not compute: the task assignment it follows, the atoms of a first stage's answer
(``--stage``, as symbols: :mod:`..stage`), ``ruled_out/2`` hints for M/Md with
many robots, floor distances to the stations for A/B/C (``to_station/3``) and the delivery
schedule of the scheduling relaxation as ``hint_serve/3`` (a horizon with hints is searched
in turns with and without them).  Any :class:`~asprilo.encodings.Encoding` works here, a
user's own included: facts it does not use change nothing.
"""

from __future__ import annotations

import time

import clingo

from asprilo.bounds import INFINITE, Floor, delivery_schedule
from asprilo.domain import Bound, Domain, Job
from asprilo.model import Instance, Plan
from asprilo.reader import plan_from_atoms
from asprilo.solver import Result, Solver, Status
from asprilo.writer import format_instance

from ...assignment import Assignment
from ...bounds import unusable_goals
from ...registry import Encoding, find_encoding
from ..stage import add_symbols
from ..watch import Watch

#: M/Md instances with this many robots get ruled_out/2 hints (they ground big programs faster)
HINTED_ROBOTS = 20
#: with hints, a horizon is searched in turns with and without them, each turn twice as long
#: as the turn before last, starting with this many conflicts (counted, not timed, so that a
#: search takes the same path on every machine and under any load); learned clauses are kept
FIRST_TURN = 1_000
#: without hints, a reference encoding is searched in slices of this many conflicts (learned
#: clauses kept; a few seconds each on the exercise-size instances), so that a long search
#: says how far it got between two slices (``Phase.conflicts``); a user's own encoding, which
#: may optimise, is solved in one call
SLICE = 5_000


class Program:
    """``encoding`` on ``instance``: grounded for one horizon at a time in a fresh solver
    attached to ``watch``, or step by step for an incremental encoding.

    ``assignment``, when set, is the task assignment the program follows (its facts are
    loaded with the instance); ``staged``, when set, the atoms of the first stage's answer
    (loaded as facts, whatever the encoding).
    """

    def __init__(self, instance: Instance, domain: Domain, encoding: Encoding, watch: Watch):
        self.instance, self.domain, self.encoding, self.watch = instance, domain, encoding, watch
        self.floor = Floor(instance.cells)
        self.facts = format_instance(instance, [])
        self.assignment: Assignment | None = None
        self.staged: list[clingo.Symbol] | None = None
        self._distances: str | None = None
        #: clingo's warnings on a user's encoding (each once, e.g. an atom no rule derives)
        self.warnings: list[str] = []

    def grounded(self, horizon: int) -> tuple[Solver, bool]:
        """The encoding grounded for exactly this horizon in a fresh solver, and whether it has hints."""
        if self.encoding.incremental:
            solver = self.fresh(None)
            self.watch.phase("grounding", horizon)
            solver.ground(incmode_parts(horizon))
            self.heard(solver)
            solver.assign_external(f"query({horizon})", True)
            return solver, False
        solver = Solver(self.encoding.theory, self.encoding.options,
                        constants={**dict(self.encoding.constants), "horizon": horizon})
        hinted = self._load(solver, horizon)
        self.watch.attach(solver)
        self.watch.phase("grounding", horizon)
        solver.ground()
        self.heard(solver)
        return solver, hinted

    def fresh(self, horizon: int | None) -> Solver:
        """A solver with the program loaded (not grounded), attached to the watch: for an
        incremental encoding (``horizon`` ``None``) the one solver of all horizons."""
        solver = Solver(self.encoding.theory, self.encoding.options, constants=dict(self.encoding.constants))
        self._load(solver, horizon)
        self.watch.attach(solver)
        return solver

    def heard(self, solver: Solver) -> None:
        """Keep clingo's warnings on a user's encoding (those of grounding and loading)."""
        if self.encoding.own:
            self.warnings += [message.strip() for message in solver.messages
                              if message.strip() and message.strip() not in self.warnings]

    def solve(self, solver: Solver, horizon: int, limit: float | None = None, hinted: bool = False) -> Result:
        """Solve the grounded program within ``limit`` seconds and the watch's time."""
        remaining = self.watch.remaining()
        if limit is not None:
            remaining = limit if remaining is None else min(limit, remaining)
        self.watch.phase("solving", horizon)
        if not hinted:
            if self.encoding.own:
                return solver.solve(time_limit=remaining)
            return self._solve_in_slices(solver, horizon, remaining)
        return self._solve_in_turns(solver, horizon, remaining)

    def solve_at(self, horizon: int, limit: float | None = None) -> Result:
        """Ground and solve the encoding for exactly this horizon, in a fresh solver."""
        solver, hinted = self.grounded(horizon)
        return self.solve(solver, horizon, limit, hinted)

    def probe(self, horizon: int, conflicts: int) -> tuple[Result, int]:
        """Ground and solve for this horizon within ``conflicts`` conflicts (hints on where
        the program has them): the result and the conflicts used."""
        solver, hinted = self.grounded(horizon)
        solver.assign_external("use_hints", hinted)
        self.watch.phase("solving", horizon)
        result = solver.solve(time_limit=self.watch.remaining(), conflicts=conflicts)
        return result, max(1, solver.stats.conflicts)

    def plan(self, result: Result) -> Plan:
        """The plan of a model."""
        symbols = [_with_values(symbol, result.assignment) for symbol in result.symbols]
        return name_robots(self.encoding, self.facts, symbols)

    def _solve_in_slices(self, solver: Solver, horizon: int, limit: float | None) -> Result:
        """Search in slices of :data:`SLICE` conflicts on one grounding, saying the conflicts
        so far after each."""
        end = None if limit is None else time.perf_counter() + limit
        before = solver.stats.conflicts
        while True:
            left = None if end is None else max(end - time.perf_counter(), 0.0)
            result = solver.solve(time_limit=left, conflicts=SLICE)
            if result.status is not Status.UNKNOWN or result.timed_out or self.watch.cancelled:
                return result
            self.watch.phase("solving", horizon, solver.stats.conflicts - before)

    def _solve_in_turns(self, solver: Solver, horizon: int, limit: float | None) -> Result:
        """Search with and without hints in turns on one grounding (turns of 1,000, 1,000,
        2,000, 2,000, ... conflicts), saying the conflicts so far after each."""
        end = None if limit is None else time.perf_counter() + limit
        before = solver.stats.conflicts
        turn, hints = FIRST_TURN, True
        while True:
            left = None if end is None else max(end - time.perf_counter(), 0.0)
            solver.assign_external("use_hints", hints)
            result = solver.solve(time_limit=left, conflicts=turn)
            if result.status is not Status.UNKNOWN or result.timed_out or self.watch.cancelled:
                return result
            self.watch.phase("solving", horizon, solver.stats.conflicts - before)
            if not hints:
                turn *= 2
            hints = not hints

    def _load(self, solver: Solver, horizon: int | None) -> bool:
        """Load the instance, what the encoding may use, and the encoding; whether the
        program has search hints."""
        solver.add(self.facts)
        if self.staged is not None:
            add_symbols(solver, self.staged)
        if self.encoding.own:
            self._load_own(solver)
            return False
        if self.assignment is not None:
            solver.add(self.assignment.text())
        elif horizon is not None and self.domain.work is Job.GOALS and len(self.instance.robots) >= HINTED_ROBOTS:
            hints = unusable_goals(self.instance, horizon, self.floor)
            solver.add("".join(f"ruled_out({r},({x},{y})).\n" for r, (x, y) in hints))
        if self.domain.work is Job.TRIPS:
            solver.add(self._station_distances())
        hinted = False
        if horizon is not None and self.domain.bound is Bound.DELIVERY:
            carried = carriers(self.assignment) if self.assignment is not None else None
            schedule = delivery_schedule(self.instance, self.domain, self.floor, horizon, carried)
            solver.add("".join(f"hint_serve({o},{p},{t}).\n" for o, p, t in schedule))
            hinted = bool(schedule)
        solver.load(self.encoding.program)
        return hinted

    def _load_own(self, solver: Solver) -> None:
        """A user's encoding: its files (older parts renamed) and what runs it as meant."""
        if self.assignment is not None:
            solver.add(self.assignment.text())
        renamed = dict(self.encoding.renamed)
        for file in self.encoding.files:
            solver.load(file, renamed, self.encoding.dropped)
        if self.encoding.additions:
            solver.add(self.encoding.additions)

    def _station_distances(self) -> str:
        """``to_station/3`` facts (abc/distance.lp would compute them layer by layer)."""
        if self._distances is None:
            stations = sorted({station.at for station in self.instance.stations.values()})
            table = self.floor.distances(stations, self.floor.cells)
            facts = ["distances_given."]
            for row, (px, py) in enumerate(stations):
                for column, (x, y) in enumerate(self.floor.cells):
                    if table[row, column] != INFINITE:
                        facts.append(f"to_station(({px},{py}),({x},{y}),{int(table[row, column])}).")
            self._distances = "\n".join(facts)
        return self._distances


def incmode_parts(horizon: int) -> list[tuple[str, list[int]]]:
    """The parts clingo's incmode has grounded when it solves at ``horizon``: ``base`` and
    ``check(0)``, then ``step(t)`` and ``check(t)`` for every t from 1 to ``horizon``.  A
    ``check(t)`` of an earlier step stays in the program (a ``#show`` there shows that step's
    atoms); only its ``query(t)`` is false, as incmode releases it."""
    parts: list[tuple[str, list[int]]] = [("base", []), ("check", [0])]
    for step in range(1, horizon + 1):
        parts += [("step", [step]), ("check", [step])]
    return parts


def carriers(assignment: Assignment) -> dict[int, int]:
    """Shelf -> robot of a task assignment (``assign(robot(R),shelf(S),pickingStation(P))``)."""
    carried = {}
    for fact in assignment.facts:
        robot, shelf = clingo.parse_term(fact).arguments[:2]
        carried[shelf.arguments[0].number] = robot.arguments[0].number
    return carried


def _with_values(symbol: clingo.Symbol, values: dict[str, int]) -> clingo.Symbol:
    """``symbol`` with every subterm that names a theory variable replaced by its value
    (clingcon encodings show deliveries as ``serve(O,P,given(S,O,P),T)``)."""
    if not values or symbol.type is not clingo.SymbolType.Function:
        return symbol
    name = str(symbol)
    if name in values:
        return clingo.Number(values[name])
    if not symbol.arguments:
        return symbol
    return clingo.Function(symbol.name, [_with_values(a, values) for a in symbol.arguments], symbol.positive)


def name_robots(encoding: Encoding, facts: str, symbols: list[clingo.Symbol]) -> Plan:
    """The plan of a model: its ``occurs/3`` atoms, or -- for an encoding with anonymous
    robots -- the plan its ``names`` program makes of the model's atoms."""
    if encoding.names is None:
        return plan_from_atoms(symbols)
    solver = Solver(options=["--warn=none"])
    solver.load(encoding.names)
    solver.add(facts)
    solver.add_facts(symbols)
    solver.ground()
    return plan_from_atoms(solver.solve().symbols)


def ground(instance: Instance, domain: Domain | str, horizon: int, encoding: str | Encoding = "plain") -> Solver:
    """The program the horizon search grounds for ``horizon`` (encoding, instance, distances,
    hints), grounded and ready to solve: for measurements and experiments."""
    domain = Domain.parse(domain)
    program = encoding if isinstance(encoding, Encoding) else find_encoding(domain, encoding)
    with Watch() as watch:
        return Program(instance, domain, program, watch).grounded(horizon)[0]
