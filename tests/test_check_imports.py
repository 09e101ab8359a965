"""``check`` starts in a blink: a fresh interpreter that checks a plan imports what the verdict
needs and nothing else (no numpy, no solver, no writer, no watch, no JSON without --json, no
bounds of another domain), and the checker gives the same atoms whether its files are loaded
(a process's first check of a domain) or its parsed statements handed over (the checks after)."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from helpers import OUTCOME, SMALL_A, WRONG_OUTCOME

from asprilo.checker import programs
from asprilo.domain import Domain
from asprilo.reader import read_instance, read_plan

#: what a check of a plan never needs (some of them only on other paths: --json, --watch, --bound strong)
NEVER = ["numpy", "scipy", "yaml", "PyQt5", "multiprocessing", "difflib", "tempfile", "clingo.ast",
         "asprilo.encodings", "asprilo.generator", "asprilo.visualizer", "asprilo.simulate", "asprilo.writer",
         "asprilo.isolation", "asprilo.cli.reruns", "asprilo.cli.watching", "asprilo.bounds.trip"]


def _check_imports(argv: list[str]) -> tuple[int, set[str], str]:
    """The exit status of ``check ARGV`` run as the ``check`` command in a fresh interpreter, the
    modules loaded at its end and its standard error."""
    program = ("import sys\nfrom asprilo.cli import check_main\nsys.argv[0] = 'check'\ncode = check_main()\n"
               "print(sorted(sys.modules))\nsys.exit(code)\n")
    done = subprocess.run([sys.executable, "-c", program, *argv], capture_output=True, text=True, timeout=120)
    return done.returncode, set(json.loads(done.stdout.splitlines()[-1].replace("'", '"'))), done.stderr


def _loaded(modules: set[str], names: list[str]) -> list[str]:
    return [name for name in names if any(module == name or module.startswith(name + ".") for module in modules)]


def test_a_check_of_a_valid_a_plan_imports_only_what_its_verdict_needs():
    code, modules, errors = _check_imports([str(SMALL_A), str(OUTCOME)])
    assert (code, errors) == (0, "")
    assert _loaded(modules, NEVER) == []
    assert _loaded(modules, ["json", "asprilo.bounds.mapf"]) == []  # an A bound; JSON only with --json
    assert {"clingo", "asprilo.checker", "asprilo.bounds.delivery"} <= modules


def test_a_check_of_an_invalid_plan_imports_the_simulator_for_its_words_and_nothing_else():
    code, modules, _errors = _check_imports([str(SMALL_A), str(WRONG_OUTCOME), "--json"])
    assert code == 1 and {"asprilo.simulate", "json"} <= modules
    replay = ["asprilo.simulate", "numpy"]  # the replay that words the violations takes numpy
    assert _loaded(modules, [name for name in NEVER if name not in replay]) == []


def test_a_check_of_an_m_plan_loads_the_m_bound_only(tmp_path):
    instance, steps = tmp_path / "m.lp", tmp_path / "p.lp"
    instance.write_text("".join(f"init(object(node,{k}),value(at,({k},1))). " for k in range(1, 4))
                        + "init(object(robot,1),value(at,(1,1))). init(object(shelf,1),value(at,(3,1))). "
                        "init(object(product,1),value(on,(1,1))). init(object(order,1),value(line,(1,1))).")
    steps.write_text("occurs(object(robot,1),action(move,(1,0)),1). occurs(object(robot,1),action(move,(1,0)),2).")
    code, modules, errors = _check_imports([str(instance), str(steps), "--domain", "m"])
    assert (code, errors) == (0, "")
    assert "asprilo.bounds.mapf" in modules
    assert _loaded(modules, [*NEVER, "asprilo.bounds.delivery"]) == []


def test_a_process_that_checks_twice_exits_quietly():
    """The second check hands over parsed statements, kept until exit: they are dropped before
    clingo's modules are torn down (a statement's finalizer needs them)."""
    program = ("from asprilo.checker import check\nfrom asprilo.reader import read_instance, read_plan\n"
               f"instance, plan = read_instance({str(SMALL_A)!r}), read_plan({str(WRONG_OUTCOME)!r})\n"
               "print([len(check(instance, plan).errors) for _ in range(3)])\n")
    done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True, timeout=120)
    assert (done.returncode, done.stdout.strip(), done.stderr) == (0, "[3, 3, 3]", "")


@pytest.mark.parametrize("plan_path", [OUTCOME, WRONG_OUTCOME])
def test_the_checker_loaded_from_its_files_and_handed_over_parsed_derives_the_same_atoms(plan_path, monkeypatch):
    monkeypatch.setattr(programs, "_checked", set())  # as in a fresh process
    instance, plan = read_instance(SMALL_A), read_plan(plan_path)
    facts = programs.instance_facts(instance) + "\n" + programs.plan_facts(instance, plan)
    loaded = sorted(map(str, programs.run_checker(facts, Domain.A)[0]))
    assert programs._checked == {Domain.A}
    parsed = sorted(map(str, programs.run_checker(facts, Domain.A)[0]))
    assert loaded == parsed
    assert (len(loaded) > 0) == (plan_path == WRONG_OUTCOME)
