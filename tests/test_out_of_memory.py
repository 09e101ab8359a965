"""A command that runs out of memory says what it was doing then, in one sentence, with the
exit status of README's table: 2 while reading (the data is beyond the machine) or in a
command that found nothing to answer, 1 in a search for a plan (nothing found within the
limits, as when a solve's child process runs out of memory).  The MemoryError is raised at a
chosen point with monkeypatch; the words are the ones each phase is given in asprilo.cli."""

from __future__ import annotations

import argparse

import pytest
from helpers import EXAMPLES, OUTCOME, SMALL_A

from asprilo.cli import main, run_command

M_INSTANCE = EXAMPLES / "paper-m/1x2x4/x11_y6_n66_r2_s16_ps1_pr16_u16_o2_N001.lp"


def _no_memory(*_args, **_kwargs):
    raise MemoryError


def _said(capsys) -> str:
    captured = capsys.readouterr()
    return captured.err


def test_reading_the_input(monkeypatch, capsys):
    from asprilo.sources import Source

    monkeypatch.setattr(Source, "from_path", classmethod(_no_memory))
    assert main(["check", str(SMALL_A), str(OUTCOME)]) == 2
    assert _said(capsys) == ("error: out of memory while reading the input (the limits on data are in README, "
                             "Reading data)\n")


def test_checking_the_plan(monkeypatch, capsys):
    from asprilo.checker import programs

    monkeypatch.setattr(programs, "run_checker", _no_memory)
    assert main(["check", str(SMALL_A), str(OUTCOME)]) == 2
    assert _said(capsys) == "error: out of memory while checking the plan\n"


def test_computing_the_strong_bound_of_a_check(monkeypatch, capsys):
    from asprilo.bounds import delivery

    monkeypatch.setattr(delivery, "station_bound", _no_memory)
    assert main(["check", str(SMALL_A), str(OUTCOME), "--bound", "strong"]) == 2
    assert _said(capsys) == ("error: out of memory while computing the lower bound\n")


@pytest.mark.parametrize(("where", "name", "phase"), [
    ("asprilo.encodings.solving.bounds", "mapf_bounds", "computing the lower bound"),
    ("asprilo.encodings.flow", "flow_plan", "solving"),
])
def test_a_solve_on_valid_input_finds_no_plan_within_the_limits(monkeypatch, capsys, where, name, phase):
    # max-flow on a small M instance runs in this process (a quick run): bound, search, check
    import importlib

    monkeypatch.setattr(importlib.import_module(where), name, _no_memory)
    assert main(["solve", str(M_INSTANCE), "--method", "flow"]) == 1
    assert _said(capsys) == (f"error: out of memory while {phase}\n")


def test_grounding(monkeypatch, capsys):
    import clingo

    from asprilo.solver import Solver

    monkeypatch.setattr(clingo.Control, "ground", _no_memory)

    def run(_args: argparse.Namespace) -> int:
        solver = Solver()
        solver.add("a.")
        solver.ground()
        return 0

    assert run_command(run, argparse.Namespace()) == 2
    assert _said(capsys) == "error: out of memory while grounding\n"


def test_out_of_memory_elsewhere_names_no_phase(capsys):
    assert run_command(_no_memory, argparse.Namespace()) == 2
    assert _said(capsys) == "error: out of memory\n"
