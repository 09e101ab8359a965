"""Own incremental encodings run with clingo incmode's meaning (issue 47, item 1): incmode
grounds ``base`` and ``check(0)``, then ``step(t)`` and ``check(t)`` for every t, and only
moves the ``query(t)`` external.  The encodings of tests/encodings/m-parts/ (the public
collection's style: one concern per file) show their plan from ``#program check(t)``,
``step(t)`` or ``base``; each must give a valid plan of the ladder's stored minimum, which
was established independently of the grader (asprilo/encodings/ladders/m/ladder.yml).

The same files through ``grade`` and ``bench`` (the viewer: test_viz_own_encoding.py), a
clingcon 5 incremental program among them (``encoding-clingcon.iclp``), and side by side
with native incmode: Debian's clingo 5.4 binary (package ``gringo``, which CI installs),
whose first satisfiable horizon must be ours."""

from __future__ import annotations

import json
import shutil
import subprocess

import clingo
import pytest
from helpers import ROOT

from asprilo.bench.results import load_results
from asprilo.checker import check
from asprilo.cli import main
from asprilo.domain import Domain
from asprilo.encodings import SolveStatus, solve
from asprilo.encodings.ladder import bundled_ladder
from asprilo.encodings.own import own_encoding
from asprilo.reader import plan_from_atoms, read_instance

PARTS = ROOT / "tests" / "encodings" / "m-parts"
#: the plan shown from each part, and the check(t) one with clingcon's variables
STYLES = ["encoding-check.ilp", "encoding-step.ilp", "encoding-base.ilp", "encoding-clingcon.iclp"]
LADDER = bundled_ladder(Domain.M)


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


@pytest.mark.parametrize("name", STYLES)
def test_grade_finds_every_rung_valid_at_its_minimum_and_every_probe_refused(name, capsys):
    assert main(["grade", str(PARTS / name), "--domain", "m", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert [(rung["result"], rung["makespan"], rung["minimal"]) for rung in report["instances"]] == [
        ("valid", rung.minimum, True) for rung in LADDER.rungs]
    assert [(probe["name"], probe["result"]) for probe in report["probes"]] == [
        ("swap", "refused"), ("vertex", "refused"), ("off-floor", "refused")]


def test_a_bench_suite_solves_every_style_at_the_minimum(tmp_path, capsys):
    encodings = "".join(f"  {name.split('.')[0]}: {{files: [\"{PARTS / name}\"]}}\n" for name in STYLES)
    files = ", ".join(f'"{rung.file}"' for rung in LADDER.rungs[:3])
    suite = tmp_path / "suite.yml"
    suite.write_text(f"name: parts\ntime_limit: 60\nencodings:\n{encodings}instances:\n  m: {{files: [{files}]}}\n"
                     f"runs:\n  - {{domain: m, encoding: [{', '.join(n.split('.')[0] for n in STYLES)}]}}\n")
    assert main(["bench", str(suite), "-o", str(tmp_path / "out"), "--plots", "none"]) == 0
    capsys.readouterr()
    solved = sorted((record["encoding"], record["instance"], record["status"], record["horizon"])
                    for record in load_results(tmp_path / "out"))
    assert solved == sorted((name.split(".")[0], str(rung.file), "solved", rung.minimum)
                            for name in STYLES for rung in LADDER.rungs[:3])


def _native_clingo() -> str | None:
    """A clingo binary that runs incmode itself (clingo 5's ``#include <incmode>``)."""
    path = shutil.which("clingo")
    if path is None:
        return None
    version = subprocess.run([path, "--version"], capture_output=True, text=True, timeout=60).stdout
    return path if version.startswith("clingo version 5.") else None


NATIVE = _native_clingo()


@pytest.mark.skipif(NATIVE is None, reason="no native clingo 5 binary (apt-get install gringo)")
@pytest.mark.parametrize("name", STYLES[:3])  # clingo 5.4's binary knows no clingcon
@pytest.mark.parametrize("rung", LADDER.rungs, ids=lambda rung: rung.name)
def test_native_incmode_gives_a_plan_of_the_same_makespan(name, rung):
    shown = subprocess.run([NATIVE, str(rung.file), str(PARTS / name), "-c", "imax=20", "-V0", "--out-atomf=%s."],
                           capture_output=True, text=True, timeout=120).stdout
    native = plan_from_atoms(clingo.parse_term(atom[:-1]) for atom in shown.split() if atom.startswith("occurs("))
    instance = read_instance(rung.file)
    ours = solve(instance, encoding=own_encoding([PARTS / name]), max_horizon=20)
    assert native.horizon == ours.horizon == rung.minimum
    assert check(instance, native).valid and check(instance, ours.plan).valid


def test_includes_side_by_side_on_one_line_are_found_next_to_the_including_file(tmp_path, monkeypatch):
    """``#include "moves.ilp". #include "goal.ilp".`` on one line and one more alone on the next,
    solved from another folder: each file is found next to the including one (before, the file
    was copied for the include alone on its line, and the two side by side were then looked for
    next to the copy)."""
    folder = tmp_path / "enc"
    shutil.copytree(PARTS, folder)
    (folder / "oneline.ilp").write_text('#include "moves.ilp". #include "goal.ilp".\n#include "show-check.ilp".\n')
    (tmp_path / "elsewhere").mkdir()
    monkeypatch.chdir(tmp_path / "elsewhere")
    rung = LADDER.rungs[0]
    outcome = solve(read_instance(rung.file), encoding=own_encoding([folder / "oneline.ilp"]), max_horizon=12)
    assert (outcome.status, outcome.horizon) == (SolveStatus.FOUND, rung.minimum)
