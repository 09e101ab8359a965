"""Own incremental encodings run with clingo incmode's meaning (issue 47, item 1): incmode
grounds ``base`` and ``check(0)``, then ``step(t)`` and ``check(t)`` for every t, and only
moves the ``query(t)`` external.  The encodings of tests/encodings/m-parts/ (the public
collection's style: one concern per file) show their plan from ``#program check(t)``,
``step(t)`` or ``base``; each must give a valid plan of the ladder's stored minimum, which
was established independently of the grader (asprilo/encodings/ladders/m/ladder.yml)."""

from __future__ import annotations

import pytest
from helpers import ROOT

from asprilo.checker import check
from asprilo.domain import Domain
from asprilo.encodings import SolveStatus, solve
from asprilo.encodings.ladder import bundled_ladder
from asprilo.encodings.own import own_encoding
from asprilo.reader import read_instance

PARTS = ROOT / "tests" / "encodings" / "m-parts"


@pytest.mark.parametrize("part", ["check", "step", "base"])
@pytest.mark.parametrize("rung", [0, 1, 2])
def test_a_show_in_any_part_keeps_every_step_of_the_plan(part, rung):
    ladder = bundled_ladder(Domain.M)
    step = ladder.rungs[rung]
    instance = read_instance(step.file)
    outcome = solve(instance, encoding=own_encoding([PARTS / f"encoding-{part}.ilp"]), max_horizon=12)
    assert outcome.status is SolveStatus.FOUND
    assert outcome.horizon == step.minimum
    assert check(instance, outcome.plan).valid
