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


class Command:
    """A command of the toolkit running in its own process group, its standard error read as it comes."""

    def __init__(self, arguments: list[str], folder: Path):
        self.process = subprocess.Popen([sys.executable, "-m", "asprilo.cli", *arguments], cwd=folder,
                                        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                        start_new_session=True)
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


@pytest.mark.parametrize("stop", [signal.SIGTERM, signal.SIGHUP])
def test_a_stopped_search_writes_its_best_plan_and_its_children_end(tmp_path, stop):
    plan = tmp_path / "plan.lp"
    command = Command(["solve", str(SMALL_A), "--time-limit", "120", "-o", str(plan)], tmp_path)
    command.wait_until(lambda: command.said("plan: makespan"), "reporting a first plan")
    children = command.busy_with_children()
    os.kill(command.process.pid, stop)
    code, _out, err = command.end()
    assert code == 0, err
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
    assert code == 0, err
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
    assert (code, err) == (0, "asprilo serve solver: stopped\n")
