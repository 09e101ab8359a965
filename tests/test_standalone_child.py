"""asprilo.isolation's standalone children (the benchmark runs): a fresh interpreter in a
session of its own, killed as a whole, its output discarded; and the bench's view of them."""

from __future__ import annotations

import os
import subprocess
import sys
import time

import pytest

from asprilo.bench import limits
from asprilo.errors import InputError
from asprilo.isolation import run_isolated


def _count(n, report):
    print("noise on standard output")  # discarded
    for i in range(n):
        report(i)
    # what a forked or spawned child would have of the parent: the tests' conftest, pytest's main
    parents = sorted(name for name in sys.modules if "conftest" in name)
    return {"parents": parents, "main": getattr(sys.modules["__main__"], "__file__", None), "pid": os.getpid()}


def _start_a_grandchild_and_hang(path, report):
    grandchild = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(600)"])
    with open(path, "w") as stream:
        stream.write(str(grandchild.pid))
    report("started")
    while True:
        time.sleep(1)


def _leave_a_grandchild(path, report):
    grandchild = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(600)"])
    with open(path, "w") as stream:
        stream.write(str(grandchild.pid))
    return "done"


def _ground_for_ever(report):
    import clingo
    control = clingo.Control()
    control.add("base", [], "p(0). p(X+1) :- p(X).")
    control.ground([("base", [])])


def _bad_input(report):
    raise InputError("no such file", "missing.lp", 3)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    with open(f"/proc/{pid}/stat") as stream:  # a zombie is gone too
        return stream.read().split(")")[-1].split()[0] != "Z"


def test_a_standalone_child_is_a_fresh_interpreter_and_reports_as_any_child():
    seen = []
    outcome = run_isolated(_count, (3,), time_limit=60, on_message=seen.append, standalone=True)
    assert (outcome.status, outcome.messages, seen) == ("done", [0, 1, 2], [0, 1, 2])
    assert outcome.value == {"parents": [], "main": None, "pid": outcome.value["pid"]}  # nothing of this process
    assert outcome.value["pid"] != os.getpid()


def test_the_deadline_kills_a_standalone_child_with_whatever_it_started(tmp_path):
    path = tmp_path / "grandchild"
    outcome = run_isolated(_start_a_grandchild_and_hang, (str(path),), time_limit=5, standalone=True)
    assert (outcome.status, outcome.messages) == ("timeout", ["started"])
    grandchild = int(path.read_text())
    deadline = time.time() + 10
    while _alive(grandchild) and time.time() < deadline:
        time.sleep(0.1)
    assert not _alive(grandchild)


def test_nothing_a_standalone_child_started_outlives_it(tmp_path):
    path = tmp_path / "grandchild"
    assert run_isolated(_leave_a_grandchild, (str(path),), time_limit=60, standalone=True).value == "done"
    grandchild = int(path.read_text())
    deadline = time.time() + 10
    while _alive(grandchild) and time.time() < deadline:
        time.sleep(0.1)
    assert not _alive(grandchild)


def test_the_limits_and_errors_of_a_standalone_child():
    assert run_isolated(_ground_for_ever, time_limit=1, standalone=True).status == "timeout"
    assert run_isolated(_ground_for_ever, time_limit=120, memory_mb=300, standalone=True).status == "memout"
    with pytest.raises(InputError) as raised:
        run_isolated(_bad_input, standalone=True)
    assert str(raised.value) == "missing.lp:3: no such file"


def test_a_bench_run_that_fails_is_an_error_with_the_last_line_of_its_error(tmp_path):
    job = {"kind": "run", "instance": str(tmp_path / "missing.lp"), "domain": "m", "encoding": "plain",
           "horizon": 1}
    run = limits.run_limited(job, 30, 2048)
    assert (run.status, run.report, run.detail) == (
        "error", {}, f"{tmp_path / 'missing.lp'}: no such file")


def _where_asprilo_is(report):
    import asprilo
    return asprilo.__file__


def test_a_standalone_child_imports_its_parents_asprilo_whatever_the_current_folder_holds(tmp_path, monkeypatch):
    """``python -c`` puts the current folder first on the path: a folder holding another
    ``asprilo`` (a checkout's, say) must not give the child another package than its parent's."""
    import asprilo
    (tmp_path / "asprilo").mkdir()
    (tmp_path / "asprilo" / "__init__.py").write_text("raise ImportError('the wrong asprilo')\n")
    monkeypatch.chdir(tmp_path)
    outcome = run_isolated(_where_asprilo_is, (), time_limit=60, standalone=True)
    assert outcome.status == "done" and outcome.value == asprilo.__file__


def test_a_standalone_child_that_cannot_start_says_why(monkeypatch):
    """A child that ends without a result is said with its last words (its standard error's last line)."""
    import asprilo.isolation as isolation
    monkeypatch.setattr(isolation, "_standalone_command", lambda: "import asprilo_nowhere")
    outcome = run_isolated(_where_asprilo_is, (), time_limit=60, standalone=True)
    assert outcome.status == "crashed"
    assert outcome.detail == "exit status 1: ModuleNotFoundError: No module named 'asprilo_nowhere'"
