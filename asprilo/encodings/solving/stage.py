"""The first stage of a two-stage encoding (``asprilo solve --encoding plan.lp --stage
assign.lp``): solved once, before the horizon search, with the instance and the encoding's
constants; the shown atoms of its first answer become facts of the encoding at every horizon.

This is the pipe ``clingo assign.lp inst.lp | clingo - plan.lp inst.lp`` done inside one
solve: the answer's atoms go to the second program as clingo symbols, in facts built as
syntax trees (:func:`add_symbols`), never as text read back by a parser.  A stage without an
answer ends the solve with that said in words.
"""

from __future__ import annotations

import time
from collections.abc import Iterable
from dataclasses import dataclass, field

import clingo
from clingo import ast

from asprilo.solver import Solver, Status

from ..registry import Encoding
from .watch import Watch

#: what clingo says of an optimising program asked for one model (the first answer is meant)
_FIRST_ONLY = "#models not 0"


@dataclass
class StageAnswer:
    """What the first stage gave: ``SAT`` with the shown ``symbols`` of its first answer,
    ``UNSAT`` (no answer set), or ``UNKNOWN`` (the time ran out, or the caller cancelled);
    clingo's ``warnings`` on it and the seconds it took."""

    status: Status
    symbols: list[clingo.Symbol] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    seconds: float = 0.0

    @property
    def facts(self) -> list[str]:
        """The atoms as text, for reports."""
        return [str(symbol) for symbol in self.symbols]


def solve_stage(stage: Encoding, facts: str, watch: Watch, horizon: int | None = None) -> StageAnswer:
    """Solve ``stage`` once with the instance ``facts`` (the text the search grounds too) and
    the stage's constants (and ``horizon``, when the search has one), up to its first answer,
    within ``watch``'s time."""
    started = time.perf_counter()
    constants: dict[str, int | str] = dict(stage.constants)
    if horizon is not None:
        constants["horizon"] = horizon
    solver = Solver(stage.theory, ("--models=1",), constants=constants)
    solver.add(facts)
    renamed = dict(stage.renamed)
    for file in stage.files:
        solver.load(file, renamed, stage.dropped)
    if stage.additions:
        solver.add(stage.additions)
    watch.attach(solver)
    watch.phase("assigning", 0)
    solver.ground()
    warnings = _said(solver)
    result = solver.solve(time_limit=watch.remaining())
    warnings += [message for message in _said(solver) if message not in warnings]
    atoms = [symbol for symbol in result.symbols if symbol.type is clingo.SymbolType.Function and symbol.name]
    warnings += [f"the first stage shows {symbol}, which is no atom: left out" for symbol in result.symbols
                 if symbol not in atoms]
    return StageAnswer(result.status, atoms if result.status is Status.SAT else [], warnings,
                       time.perf_counter() - started)


def _said(solver: Solver) -> list[str]:
    """clingo's messages so far, each on one line, but the one on asking an optimising
    program for one model (the first answer is what a stage gives)."""
    said = [" ".join(message.split()) for message in solver.messages if message.strip()]
    solver.messages.clear()
    return [message for message in said if not message.startswith(_FIRST_ONLY)]


def add_symbols(solver: Solver, symbols: Iterable[clingo.Symbol]) -> None:
    """Add each symbol as a fact to ``solver``'s ``base`` part: built as a syntax tree that
    holds the symbol itself, so no text of it is ever parsed."""
    place = ast.Position("<first stage>", 1, 1)
    location = ast.Location(place, place)
    with ast.ProgramBuilder(solver.control) as builder:
        builder.add(ast.Program(location, "base", []))
        for symbol in symbols:
            atom = ast.SymbolicAtom(ast.SymbolicTerm(location, symbol))
            builder.add(ast.Rule(location, ast.Literal(location, ast.Sign.NoSign, atom), []))


def stage_words(stage: Encoding, answer: StageAnswer) -> str:
    """Why the search cannot start after a stage without an answer, in words."""
    files = ", ".join(str(file) for file in stage.files)
    if answer.status is Status.UNSAT:
        return f"the first stage ({files}) has no answer set on this instance: there are no facts to plan with"
    return f"the first stage ({files}) found no answer within the time limit"
