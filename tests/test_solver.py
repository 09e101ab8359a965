"""The clingo driver: programs, multi-shot parts, theories, limits, statistics."""

from __future__ import annotations

import threading

import clingo
import pytest

from asprilo.errors import InputError
from asprilo.solver import Solver, Status


def names(result):
    return sorted(str(symbol) for symbol in result.symbols)


def test_multi_shot_parts():
    solver = Solver()
    solver.add("#program step(t). at(t) :- not stop(t). #external stop(t). #program base. start.")
    solver.ground([("base", []), ("step", [1])])
    assert names(solver.solve()) == ["at(1)", "start"]
    solver.ground([("step", [2])])
    solver.assign_external("stop(1)", True)
    assert names(solver.solve()) == ["at(2)", "start", "stop(1)"]
    assert solver.stats.models == 2
    assert solver.stats.rules > 0 and solver.stats.ground_time > 0


def test_facts_and_constants():
    solver = Solver(constants={"n": 3})
    solver.add("p(1..n).")
    solver.add_facts([clingo.Function("q", [clingo.Number(5)]), "r(a)"])
    solver.ground()
    assert names(solver.solve()) == ["p(1)", "p(2)", "p(3)", "q(5)", "r(a)"]


def test_unsatisfiable_and_optimisation():
    solver = Solver()
    solver.add("a. :- a.")
    solver.ground()
    assert solver.solve().status is Status.UNSAT
    best = Solver()
    best.add("{p(1..4)}. :- #count{X: p(X)} < 2. #minimize{X: p(X)}.")
    best.ground()
    result = best.solve()
    assert (result.status, result.cost, result.optimal, names(result)) == (
        Status.SAT, [3], True, ["p(1)", "p(2)"])


def test_clingcon_integer_variables():
    solver = Solver(theory="clingcon")
    solver.add("&dom{1..5} = x. &sum{x} >= 4. &sum{y} = x + 1. &dom{0..9} = y.")
    solver.ground()
    result = solver.solve()
    assert result.status is Status.SAT
    assert result.assignment["x"] >= 4 and result.assignment["y"] == result.assignment["x"] + 1


def test_clingo_dl_difference_constraints():
    solver = Solver(theory="dl")
    solver.add("&diff{a - b} <= -3. &diff{0 - a} <= 0.")
    solver.ground()
    result = solver.solve()
    assert result.status is Status.SAT
    assert result.assignment["b"] - result.assignment["a"] >= 3


def test_time_limit_stops_a_hard_search():
    solver = Solver()
    # pigeon hole: 11 pigeons, 10 holes -- hard for CDCL without symmetry breaking
    solver.add("""pigeon(1..11). hole(1..10).
                  1 { in(P,H) : hole(H) } 1 :- pigeon(P).
                  :- in(P,H), in(Q,H), P < Q.""")
    solver.ground()
    results = []
    search = threading.Thread(target=lambda: results.append(solver.solve(time_limit=0.3)), daemon=True)
    search.start()
    search.join(120)  # only against a hang (a search without its limit would take far longer)
    assert not search.is_alive()
    # stopped by the limit, before it could prove anything
    assert (results[0].status, results[0].timed_out) == (Status.UNKNOWN, True)


def test_syntax_error_names_the_file(tmp_path):
    program = tmp_path / "broken.lp"
    program.write_text("a.\nb(.\n")
    with pytest.raises(InputError) as error:
        Solver().load(program)
    assert str(error.value) == f"{program}:2: syntax error, unexpected ., expecting ) or ;"
    with pytest.raises(InputError) as error:
        Solver(theory="clingcon").load(program)
    assert str(error.value).startswith(f"{program}:2: syntax error")
    with pytest.raises(InputError) as error:
        Solver().load(tmp_path / "missing.lp")
    assert str(error.value) == f"{tmp_path}/missing.lp: no such file"
