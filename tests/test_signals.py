"""Stopping a long command from outside: SIGTERM and SIGHUP are handled as Ctrl-C is (what was
found so far is kept, the children end), and no child process outlives its parent, whatever
ended the parent (SIGKILL included).

Each test starts a real command, waits until it is busy (a child process runs, or its progress
says so), signals it and then counts, by the process tree read from /proc, which of the
processes it had started are still alive.  The waits are hang guards, not measurements."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
from helpers import EXAMPLES

pytestmark = pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads the process tree from /proc")

SMALL_A = EXAMPLES / "asprilo/dom-a/small/x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp"
#: hang guards (seconds): for a command to become busy, to end after a signal, for its children to go
BUSY, END, GONE = 60.0, 30.0, 2.0


def _state(pid: int) -> str | None:
    """The process's state letter (``Z`` for a zombie), ``None`` when there is no such process."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    return stat[stat.rindex(")") + 2]


def descendants(pid: int) -> set[int]:
    """Every live process below ``pid`` in the process tree."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            parent = int(stat[stat.rindex(")") + 2:].split()[1])
            children.setdefault(parent, []).append(int(entry.name))
    found: set[int] = set()
    todo = [pid]
    while todo:
        for child in children.get(todo.pop(), ()):
            if child not in found and _state(child) not in (None, "Z"):
                found.add(child)
                todo.append(child)
    return found


def alive(pids: set[int]) -> set[int]:
    return {pid for pid in pids if _state(pid) not in (None, "Z")}


def marked(mark: str) -> set[int]:
    """Every live process whose environment holds ``mark`` (a command's and all it started,
    inherited: found even once reparented, when the tree below the command no longer shows them)."""
    found = set()
    needle = f"{MARK}={mark}".encode()
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                environment = (entry / "environ").read_bytes()
            except OSError:
                continue
            if needle in environment.split(b"\0") and _state(int(entry.name)) not in (None, "Z"):
                found.add(int(entry.name))
    return found


#: the environment variable that marks the processes of one command
MARK = "ASPRILO_SIGNAL_TEST"


class Command:
    """A command of the toolkit running in its own process group, its standard error read as it
    comes; every process it starts carries its mark (:func:`marked`)."""

    def __init__(self, arguments: list[str], folder: Path):
        self.mark = f"{os.getpid()}-{time.monotonic_ns()}"
        self.process = subprocess.Popen([sys.executable, "-m", "asprilo.cli", *arguments], cwd=folder,
                                        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                        start_new_session=True, env={**os.environ, MARK: self.mark})
        self.lines: list[str] = []
        self.output: list[str] = []
        self.readers = [threading.Thread(target=self._read, args=(stream, into), daemon=True)
                        for stream, into in ((self.process.stderr, self.lines), (self.process.stdout, self.output))]
        for reader in self.readers:
            reader.start()

    @staticmethod
    def _read(stream, into: list[str]) -> None:
        for line in stream:
            into.append(line)

    def wait_until(self, condition, what: str) -> None:
        deadline = time.monotonic() + BUSY
        while not condition():
            assert self.process.poll() is None, f"ended before {what}: {''.join(self.lines)}"
            assert time.monotonic() < deadline, f"not {what} within {BUSY} s: {''.join(self.lines)}"
            time.sleep(0.05)

    def busy_with_children(self) -> set[int]:
        self.wait_until(lambda: descendants(self.process.pid), "running a child process")
        return descendants(self.process.pid)

    def said(self, text: str) -> bool:
        return any(text in line for line in self.lines)

    def end(self) -> tuple[int, str, str]:
        self.process.wait(END)
        for reader in self.readers:
            reader.join(END)
        return self.process.returncode, "".join(self.output), "".join(self.lines)


def assert_gone(pids: set[int]) -> None:
    """Every one of ``pids`` ends within the hang guard (they are killed at once, not waited for)."""
    deadline = time.monotonic() + GONE
    while alive(pids) and time.monotonic() < deadline:
        time.sleep(0.02)
    assert not alive(pids), f"still running: {sorted(alive(pids))}"


def assert_none_left(command: Command) -> None:
    """No process the command started, the command included, runs ``GONE`` seconds after it ended."""
    deadline = time.monotonic() + GONE
    while marked(command.mark) and time.monotonic() < deadline:
        time.sleep(0.02)
    assert not marked(command.mark), f"still running: {sorted(marked(command.mark))}"


@pytest.mark.parametrize("stop", [signal.SIGTERM, signal.SIGHUP])
def test_a_stopped_search_writes_its_best_plan_and_its_children_end(tmp_path, stop):
    plan = tmp_path / "plan.lp"
    command = Command(["solve", str(SMALL_A), "--time-limit", "120", "-o", str(plan)], tmp_path)
    command.wait_until(lambda: command.said("plan: makespan"), "reporting a first plan")
    children = command.busy_with_children()
    os.kill(command.process.pid, stop)
    code, _out, err = command.end()
    assert code == 130, err  # interrupted (README, Exit status), the plan kept all the same
    assert "the search ended: cancelled" in err and "checked: valid" in err
    assert plan.read_text().count("occurs(") > 0
    assert_gone(children)


def test_a_search_stopped_as_timeout_stops_it_keeps_its_plan(tmp_path):
    """``timeout`` signals the whole process group: the children ignore it, the parent stops them."""
    plan = tmp_path / "plan.lp"
    command = Command(["solve", str(SMALL_A), "--time-limit", "120", "-o", str(plan)], tmp_path)
    command.wait_until(lambda: command.said("plan: makespan"), "reporting a first plan")
    children = command.busy_with_children()
    os.killpg(command.process.pid, signal.SIGTERM)
    code, _out, err = command.end()
    assert code == 130, err
    assert plan.read_text().count("occurs(") > 0
    assert_gone(children)


def test_the_children_of_a_killed_parent_end_with_it(tmp_path):
    command = Command(["solve", str(SMALL_A), "--time-limit", "120", "-o", str(tmp_path / "plan.lp")], tmp_path)
    children = command.busy_with_children()
    assert len(children) >= 2  # method auto: the anytime planner and the exact search, side by side
    os.kill(command.process.pid, signal.SIGKILL)
    command.end()
    assert_gone(children)
    assert not (tmp_path / "plan.lp").exists()


def _suite(folder: Path) -> Path:
    suite = folder / "suite.yml"
    suite.write_text("name: stopped\ntime_limit: 120\nmakespan_time_limit: 120\n"
                     f"instances:\n  small: {{files: [{str(SMALL_A)!r}]}}\n"
                     "runs:\n  - {domain: a, encoding: [plain]}\n")
    return suite


@pytest.mark.parametrize("stop", [signal.SIGTERM, signal.SIGHUP, signal.SIGKILL])
def test_a_stopped_benchmark_leaves_no_run_behind(tmp_path, stop):
    """The runs live in sessions of their own: a signal to the runner's group does not reach
    them, so the runner ends them (or, killed, the kernel does)."""
    command = Command(["bench", str(_suite(tmp_path)), "-o", str(tmp_path / "out")], tmp_path)
    children = command.busy_with_children()
    os.killpg(command.process.pid, stop)
    code, _out, err = command.end()
    assert code == (-signal.SIGKILL if stop == signal.SIGKILL else 130), err
    assert_gone(children)


@pytest.mark.parametrize("stop", [signal.SIGTERM, signal.SIGKILL])
def test_a_stopped_grading_leaves_no_solver_behind(tmp_path, stop):
    encoding = Path(__file__).parent / "encodings" / "m-single.lp"
    command = Command(["grade", str(encoding), "--domain", "m", "--time-limit", "120"], tmp_path)
    children = command.busy_with_children()
    os.kill(command.process.pid, stop)
    code, _out, err = command.end()
    assert code == (-signal.SIGKILL if stop == signal.SIGKILL else 130), err
    assert_gone(children)


def test_a_stopped_generation_keeps_the_instances_it_made(tmp_path):
    out = tmp_path / "out"
    command = Command(["gen", "-x", "11", "-y", "6", "-X", "4", "-Y", "2", "-H", "-p", "1", "-s", "16", "-r", "5",
                       "--domain", "m", "-N", "100000", "-d", str(out), "--seed", "7"], tmp_path)
    command.wait_until(lambda: out.is_dir() and len(list(out.glob("*.lp"))) >= 3, "writing instances")
    os.kill(command.process.pid, signal.SIGTERM)
    code, _out, err = command.end()
    assert code == 130, err
    made = sorted(out.glob("*.lp"))
    assert 3 <= len(made) < 100000
    assert all(path.read_text().rstrip().endswith(").") for path in made)  # each one whole
    assert not list(out.glob(".*"))  # no half-written temporary file left


@pytest.mark.parametrize("stop", [signal.SIGINT, signal.SIGTERM, signal.SIGHUP])
def test_a_stopped_online_run_keeps_what_ran(tmp_path, stop):
    """asprilo online (no child processes: its planners run in it) ends after the step under way
    and writes the plan carried out; with --steps far away it is still running when told."""
    plan = tmp_path / "plan.lp"
    command = Command(["online", str(SMALL_A), "--every", "3", "--steps", "1000000", "-o", str(plan), "--live"],
                      tmp_path)
    command.wait_until(plan.exists, "writing its plan so far")
    os.kill(command.process.pid, stop)
    code, _out, err = command.end()
    assert code == 130, err
    assert "(interrupted)" in err and plan.read_text().count("occurs(") > 0
    assert_none_left(command)


@pytest.mark.parametrize("stop", [signal.SIGTERM, signal.SIGINT, signal.SIGHUP])
def test_the_viewer_window_ends_on_a_stop_signal(tmp_path, stop):
    """Qt's event loop ran no Python: the window ignored Ctrl-C, SIGTERM and SIGHUP until
    SIGKILL.  A signal that comes before the handlers are in place ends it as the default
    action does; one that comes after, as Ctrl-C (exit status 130)."""
    env = {**os.environ, "QT_QPA_PLATFORM": "offscreen"}
    process = subprocess.Popen([sys.executable, "-m", "asprilo.cli", "viz", str(SMALL_A),
                                str(EXAMPLES / "asprilo/dom-a/small/outcome.txt")], cwd=tmp_path, env=env,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    time.sleep(3)  # most of the time the window is up by then; either way it must end
    os.kill(process.pid, stop)
    assert process.wait(END) in (130, -stop)


@pytest.mark.parametrize("stop", [signal.SIGTERM, signal.SIGHUP])
def test_a_stopped_server_ends_and_says_so(tmp_path, stop):
    command = Command(["serve", "solver", "--port", "0"], tmp_path)
    command.wait_until(lambda: any("listening on" in line for line in command.output), "listening")
    os.kill(command.process.pid, stop)
    code, _out, err = command.end()
    assert (code, err) == (130, "asprilo serve solver: stopped\n")


#: an encoding of domain M whose every solve runs until stopped: the plans of m-single.lp, and
#: 21 pigeons in 20 holes (no answer; clingo's search takes far longer than any test)
HARD = (f'#include "{Path(__file__).parent / "encodings" / "m-single.lp"}".\n'
        "{ pigeon(P,H) : H = 1..20 } = 1 :- P = 1..21.\n"
        ":- pigeon(P,H), pigeon(Q,H), P < Q.\n")
SMALL_M = EXAMPLES / "paper-m/1x2x4/x11_y6_n66_r11_s16_ps1_pr16_u16_o11_N001.lp"


def _long_command(name: str, folder: Path) -> list[str]:
    """The arguments of a command that runs child processes until it is stopped."""
    hard = folder / "hard.lp"
    hard.write_text(HARD)
    return {
        "solve": ["solve", str(SMALL_M), "--encoding", str(hard), "--time-limit", "120"],
        "grade": ["grade", str(hard), "--domain", "m", "--time-limit", "120"],
        "watch": ["check", str(SMALL_M), "--watch", "--encoding", str(hard), "--time-limit", "120"],
        "gen": ["gen", "-x", "200", "-y", "150", "-r", "5", "-s", "20", "-p", "2", "-N", "100000",
                "-d", str(folder / "out"), "--seed", "3"],
        "bench": ["bench", str(_suite(folder)), "-o", str(folder / "bench")],
    }[name]


@pytest.mark.parametrize("stop", [signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGKILL])
@pytest.mark.parametrize("name", ["solve", "grade", "watch", "gen", "bench"])
def test_no_process_outlives_a_stopped_command(tmp_path, name, stop):
    """The signal goes to the command alone (not its group): whatever it started ends with it,
    SIGKILL included; stopped by Ctrl-C (SIGINT), SIGTERM or SIGHUP it exits as interrupted
    (130, README: Exit status)."""
    command = Command(_long_command(name, tmp_path), tmp_path)
    command.busy_with_children()
    os.kill(command.process.pid, stop)
    code, _out, err = command.end()
    assert code == (-signal.SIGKILL if stop == signal.SIGKILL else 130), err
    assert_none_left(command)
