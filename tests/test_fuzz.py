"""Fuzzing ``check`` and ``info``: valid instances and plans mutated byte-wise (bytes
flipped, inserted, deleted, repeated; BOMs, NULs, non-ASCII, deep nesting, long numbers)
and term-wise (numbers made huge or negative, terms nested deeply, names changed, facts
dropped or repeated, rules and directives added).  Whatever comes out, each command ends
with its verdict (0 or 1) or with bad input (2, one line ``error: ...``), never with an
exception, and in time.  600 cases by default, 6,000 more with ``pytest -m slow``.
"""

from __future__ import annotations

import contextlib
import io
import re
import time
from pathlib import Path

import pytest
from helpers import OUTCOME, SMALL_A
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from asprilo.cli import main

CORPUS = Path(__file__).parent / "hostile"
SEEDS = {  # (instance, plan): a tiny Md corridor and the paper's small domain-A example
    "corridor": ((CORPUS / "base-instance.lp").read_bytes(), (CORPUS / "base-plan.lp").read_bytes()),
    "small-a": (SMALL_A.read_bytes(), OUTCOME.read_bytes()),
}
BUDGET = 30.0  # seconds one command may take

_SPECIAL = [b"\xef\xbb\xbf", b"\x00", b"\xff", b"\xc3", "ü".encode(), "—".encode(), b"\r\n", b"%", b"%*",
            b'"', b"(" * 200, b")", b"9" * 40, b"-2147483648", b"2147483648", b"..", b";", b":-", b"#include",
            b"#script", b"#const n=1.", b"1..1000000000", b"\t", b"\x01", b".", b",", b"X"]

byte_mutation = st.one_of(
    st.tuples(st.just("flip"), st.integers(0, 10**6), st.integers(1, 255)),
    st.tuples(st.just("insert"), st.integers(0, 10**6), st.sampled_from(_SPECIAL) | st.binary(min_size=1, max_size=8)),
    st.tuples(st.just("delete"), st.integers(0, 10**6), st.integers(1, 64)),
    st.tuples(st.just("repeat"), st.integers(0, 10**6), st.integers(1, 64)),
)

_NUMBER = re.compile(rb"-?\d+")
_NAME = re.compile(rb"\b[a-z][A-Za-z_]*\b")
_FACT_END = re.compile(rb"\)\.")

term_mutation = st.one_of(
    st.tuples(st.just("number"), st.integers(0, 10**6),
              st.sampled_from([b"0", b"-1", b"2147483647", b"-2147483647", b"99999999999", b"100001", b"300000",
                               b"10000000", b"(1,1)", b"f(x)", b'"s"', b"(1,2,3)", b"()", b"X", b"1..3"])),
    st.tuples(st.just("nest"), st.integers(0, 10**6), st.integers(50, 3000)),
    st.tuples(st.just("name"), st.integers(0, 10**6),
              st.sampled_from([b"robott", b"energy", b"max_energy", b"grid", b"xsize", b"node", b"occurs", b"init",
                               b"pickup", b"deliver", b"putdown", b"move", b"robot", b"shelf", b"order", b"line"])),
    st.tuples(st.just("drop"), st.integers(0, 10**6), st.just(0)),
    st.tuples(st.just("append"), st.just(0),
              st.sampled_from([b"p(0). p(X+1) :- p(X).", b"#include \"/etc/passwd\".", b"init(object(grid,1),"
                               b"value(xsize,100000)).", b"occurs(object(robot,1),action(move,(1,0)),2147483647).",
                               b"init(object(robot,9),value(at,(300000,1))).", b"#program step(t).",
                               b"init(object(robot,1),value(energy,5)).", b"{ a }.", b"#show p/1."])),
)


def _at(data: bytes, position: int) -> int:
    return position % (len(data) + 1)


def _byte_mutate(data: bytes, mutation: tuple) -> bytes:
    kind, where, what = mutation
    i = _at(data, where)
    if kind == "flip":
        return data[:i] + bytes([(data[i] ^ what) if i < len(data) else what]) + data[i + 1:]
    if kind == "insert":
        return data[:i] + what + data[i:]
    if kind == "delete":
        return data[:i] + data[i + what:]
    return data[:i] + data[i:i + what] * 2 + data[i + what:]


def _term_mutate(data: bytes, mutation: tuple) -> bytes:
    kind, where, what = mutation
    if kind == "append":
        return data + b"\n" + what + b"\n"
    pattern = {"number": _NUMBER, "nest": _NUMBER, "name": _NAME, "drop": _FACT_END}[kind]
    matches = list(pattern.finditer(data))
    if not matches:
        return data
    match = matches[where % len(matches)]
    if kind == "nest":
        replacement = b"f(" * what + match.group(0) + b")" * what
    elif kind == "drop":  # a fact loses its end
        return data[:match.start()] + data[match.end():]
    else:
        replacement = what
    return data[:match.start()] + replacement + data[match.end():]


def _run(arguments: list) -> tuple[int, str]:
    out, err = io.StringIO(), io.StringIO()
    started = time.perf_counter()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main([str(argument) for argument in arguments])
    assert time.perf_counter() - started < BUDGET, arguments
    return code, err.getvalue()


def _exercise(folder: Path, instance: bytes, plan: bytes) -> None:
    instance_path, plan_path = folder / "instance.lp", folder / "plan.lp"
    instance_path.write_bytes(instance)
    plan_path.write_bytes(plan)
    for arguments, verdicts in ((["info", instance_path], {0}), (["info", instance_path, plan_path], {0}),
                                (["check", instance_path, plan_path], {0, 1})):
        code, err = _run(arguments)
        assert code in verdicts | {2}, (arguments, code, err)
        lines = err.splitlines()
        if code == 2:
            assert len([line for line in lines if line.startswith("error: ")]) == 1 and lines[-1].startswith(
                "error: "), err
        assert all(line.startswith(("warning: ", "error: ")) for line in lines), err


@st.composite
def mutated(draw, mutations):
    seed = draw(st.sampled_from(sorted(SEEDS)))
    instance, plan = SEEDS[seed]
    target = draw(st.sampled_from(["instance", "plan", "both"]))
    for mutation in draw(st.lists(mutations, min_size=1, max_size=4)):
        mutate = _byte_mutate if mutation[0] in ("flip", "insert", "delete", "repeat") else _term_mutate
        if target in ("instance", "both"):
            instance = mutate(instance, mutation)
        if target in ("plan", "both"):
            plan = mutate(plan, mutation)
    return instance, plan


def _settings(examples: int, derandomize: bool = True):
    return settings(max_examples=examples, deadline=None, derandomize=derandomize,
                    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])


@_settings(300)
@given(case=mutated(byte_mutation))
def test_byte_mutations(tmp_path, case):
    _exercise(tmp_path, *case)


@_settings(300)
@given(case=mutated(term_mutation))
def test_term_mutations(tmp_path, case):
    _exercise(tmp_path, *case)


@pytest.mark.slow
@_settings(6000, derandomize=False)
@given(case=mutated(st.one_of(byte_mutation, term_mutation)))
def test_many_more_mutations(tmp_path, case):
    _exercise(tmp_path, *case)
