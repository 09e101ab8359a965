"""``check --watch``: the polling loop (stepped poll by poll, no clock), the re-check and the
re-solve it runs, and the command in a process of its own (its output read line by line
under a hang guard, ended by SIGINT)."""

from __future__ import annotations

import io
import os
import queue
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path

import pytest

from asprilo.cli import main
from asprilo.cli.reruns import EncodingSolve, PlanCheck
from asprilo.cli.watching import Stamps, watch

ROOT = Path(__file__).resolve().parent.parent
OWN = ROOT / "docs" / "own-encoding"
#: on a 3x3 floor robot 1 goes two cells down to the ordered shelf (domain M)
DOWN = (OWN / "down.lp").read_text()
GOOD_PLAN = "occurs(object(robot,1),action(move,(0,1)),1).\noccurs(object(robot,1),action(move,(0,1)),2).\n"
BAD_PLAN = GOOD_PLAN.replace("(0,1)),1", "(0,-1)),1")       # up, off the floor, and back: 2 violations
#: seconds a process may take to say its next line before the test gives up (a hang guard, not a timing)
PATIENCE = 120


def replace(path: Path, text: str) -> None:
    """Save as many editors do: write a new file and rename it over the old one."""
    fresh = path.with_name(f".{path.name}.new")
    fresh.write_text(text)
    os.replace(fresh, path)


class Script:
    """A ``wait`` for :func:`watch` that plays one action per poll (``None``: a quiet poll)
    and a ``stop`` that ends the loop when the script is played."""

    def __init__(self, *actions: Callable[[], object] | None, before: Callable[[], object] | None = None):
        self.actions, self.before, self.polls = list(actions), before, 0

    def wait(self, _seconds: float) -> None:
        if self.before is not None:
            self.before()
        self.polls += 1
        action = self.actions.pop(0) if self.actions else None
        if action is not None:
            action()

    def stop(self) -> bool:
        return not self.actions


# --- the loop -------------------------------------------------------------------------------------


def test_a_save_is_acted_on_after_one_quiet_poll(tmp_path):
    a, b = tmp_path / "a.lp", tmp_path / "b.lp"
    a.write_text("a.\n")
    b.write_text("b.\n")
    calls: list[tuple[int, list[str]]] = []
    script = Script(None, lambda: a.write_text("a(1).\n"), None, lambda: b.write_text("b(1).\n"),
                    lambda: b.write_text("b(1). b(2).\n"),     # an editor writing in two steps: one change
                    None, None)
    watch(lambda: [a, b], lambda changed: calls.append((script.polls, [p.name for p in changed])),
          wait=script.wait, stop=script.stop)
    assert calls == [(0, []), (3, ["a.lp"]), (6, ["b.lp"])]


def test_rename_replace_and_a_moment_without_the_file_are_saves(tmp_path):
    plan = tmp_path / "plan.lp"
    plan.write_text("x.\n")
    before = os.stat(plan)
    calls: list[list[str]] = []

    def same_size_and_time() -> None:  # only the inode tells this save apart
        replace(plan, "y.\n")
        os.utime(plan, ns=(before.st_atime_ns, before.st_mtime_ns))

    script = Script(same_size_and_time, None, plan.unlink, lambda: plan.write_text("z.\n"), None, None)
    watch(lambda: [plan], lambda changed: calls.append([p.name for p in changed]), wait=script.wait,
          stop=script.stop)
    assert calls == [[], ["plan.lp"], ["plan.lp"]]


def test_the_files_are_asked_for_again_after_each_run(tmp_path):
    main_file, included = tmp_path / "main.lp", tmp_path / "part.lp"
    main_file.write_text("a.\n")
    files = [main_file]
    calls: list[list[str]] = []

    def include() -> None:
        main_file.write_text('#include "part.lp".\n')
        files.append(included)                                 # what the next run will read

    script = Script(include, None, lambda: included.write_text("b.\n"), None)
    watch(lambda: list(files), lambda changed: calls.append([p.name for p in changed]), wait=script.wait,
          stop=script.stop)
    assert calls == [[], ["main.lp"], ["part.lp"]]


def test_stamps_follow_new_files_without_calling_them_changed(tmp_path):
    a = tmp_path / "a.lp"
    stamps = Stamps([a])
    assert stamps.changed() == []
    a.write_text("a.\n")
    assert stamps.changed() == [a] and stamps.changed() == []
    stamps.follow([a, tmp_path / "b.lp"])
    assert stamps.changed() == []


# --- the re-check ---------------------------------------------------------------------------------


def test_a_fixed_plan_is_valid_and_a_syntax_error_does_not_end_the_watch(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    instance, plan = Path("down.lp"), Path("plan.lp")
    instance.write_text(DOWN)
    plan.write_text(BAD_PLAN)
    out = io.StringIO()
    rerun = PlanCheck(instance, plan, None, 1, out)
    script = Script(lambda: replace(plan, GOOD_PLAN + "occurs(object(robot,1),action(move,(0,1)),3)\n"), None,
                    lambda: plan.write_text(GOOD_PLAN), None)
    watch(rerun.paths, rerun, wait=script.wait, stop=script.stop)
    runs = out.getvalue().split("--- ")[1:]
    assert len(runs) == 3
    first, broken, fixed = (run.splitlines() for run in runs)
    assert first[0].endswith("watching down.lp, plan.lp (Ctrl-C ends): checking ---")
    assert first[1] == "step 1: robot 1 moves to (2,0), which is not a floor node"   # one violation of two
    assert first[2] == "... and 1 more (check without --watch lists them all)"
    assert first[3] == "invalid plan: 2 violations (domain M (detected), horizon 2)"
    assert broken[0].endswith("plan.lp changed: checking ---")
    assert broken[1].startswith("error: plan.lp:") and len(broken) == 2   # one line, and the watch goes on
    assert fixed[1:] == ["valid plan (domain M (detected), horizon 2)"]


def test_a_missing_file_is_one_line_too(tmp_path):
    instance, plan = tmp_path / "down.lp", tmp_path / "plan.lp"
    instance.write_text(DOWN)
    plan.write_text(GOOD_PLAN)
    out = io.StringIO()
    rerun = PlanCheck(instance, plan, None, 5, out)
    script = Script(plan.unlink, None, lambda: plan.write_text(GOOD_PLAN), None)
    watch(rerun.paths, rerun, wait=script.wait, stop=script.stop)
    lines = out.getvalue().splitlines()
    assert [line for line in lines if not line.startswith("---")] == [
        "valid plan (domain M (detected), horizon 2)", f"error: {plan}: no such file",
        "valid plan (domain M (detected), horizon 2)"]


# --- the re-solve ---------------------------------------------------------------------------------


def solver(tmp_path: Path, encoding: str, **options) -> tuple[EncodingSolve, io.StringIO, Path]:
    instance, program = tmp_path / "down.lp", tmp_path / "mine.lp"
    instance.write_text(DOWN)
    program.write_text(encoding)
    out = io.StringIO()
    rerun = EncodingSolve(instance, tmp_path / "plan.lp", None, 5, [str(program)], options.pop("const", []),
                          [], None, options.pop("time_limit", 60.0), out, io.StringIO())
    return rerun, out, program


def test_a_changed_encoding_is_solved_again(tmp_path):
    rerun, out, program = solver(tmp_path, (OWN / "mapf-upside-down.lp").read_text())
    script = Script(lambda: replace(program, "this is no program"), None,
                    lambda: replace(program, (OWN / "mapf.lp").read_text()), None)
    watch(rerun.paths, rerun, wait=script.wait, stop=script.stop)
    runs = [run.splitlines() for run in out.getvalue().split("--- ")[1:]]
    assert len(runs) == 3
    upside_down, broken, fixed = runs
    assert upside_down[0].endswith(": solving ---") and "mine.lp" in upside_down[0]
    assert upside_down[-1] == "invalid plan: 3 violations (domain M (detected), horizon 2)"
    assert broken[0].endswith("mine.lp changed: solving ---")
    assert broken[1].startswith(f"error: {program.resolve()}:1: column") and len(broken) == 2
    assert fixed[1] == "your encoding: single-shot with a horizon constant"
    assert fixed[2] == "plan: horizon 2 (proven minimal), 2 actions, written to " + str(tmp_path / "plan.lp")
    assert fixed[3] == "valid plan (domain M (detected), horizon 2)"
    assert (tmp_path / "plan.lp").read_text() == GOOD_PLAN


def test_a_save_cancels_the_solve_still_running(tmp_path):
    endless = "p(0).\np(X+1) :- p(X).\n#const horizon=1.\n"       # grounds for ever
    rerun, out, program = solver(tmp_path, endless)
    saved = threading.Event()

    def save_while_grounding() -> None:   # an editor, while the watch waits for the child
        if until(lambda: "grounding" in rerun.err.getvalue()):
            replace(program, (OWN / "mapf.lp").read_text())
            saved.set()

    editor = threading.Thread(target=save_while_grounding, daemon=True)
    editor.start()
    script = Script(None, None, None)
    watch(rerun.paths, rerun, wait=script.wait, stop=script.stop)
    editor.join(PATIENCE)
    assert saved.is_set(), rerun.err.getvalue()
    runs = [run.splitlines() for run in out.getvalue().split("--- ")[1:]]
    assert len(runs[0]) == 2 and runs[0][1].startswith("(cancelled: ") and runs[0][1].endswith("mine.lp changed)")
    assert runs[1][0].endswith("mine.lp changed: solving ---")
    assert runs[1][-1] == "valid plan (domain M (detected), horizon 2)"


def until(condition: Callable[[], bool]) -> bool:
    """Whether ``condition`` comes true within :data:`PATIENCE` seconds (looked at every 50 ms)."""
    deadline = time.monotonic() + PATIENCE
    while not condition():
        if time.monotonic() > deadline:
            return False
        time.sleep(0.05)
    return True


def test_the_watch_refuses_what_no_save_can_mend(tmp_path, capsys):
    instance, plan = tmp_path / "down.lp", tmp_path / "plan.lp"
    instance.write_text(DOWN)
    plan.write_text(GOOD_PLAN)
    program = OWN / "mapf.lp"
    cases = [
        ([str(instance), str(plan), "--watch", "--json"], "--json and --watch do not go together"),
        ([str(instance), "-", "--watch"], "standard input (-) is never saved"),
        ([str(instance), "--watch"], "no plan given"),
        ([str(instance), str(tmp_path / "nothing.lp"), "--watch"], "nothing.lp: no such file"),
        ([str(instance), str(plan), "--watch", "-c", "a=1"], "-c goes with --encoding"),
        ([str(instance), str(plan), "-c", "a=1"], "-c goes with --watch --encoding"),
        ([str(instance), str(plan), "--violations", "3"], "--violations goes with --watch"),
        ([str(instance), str(plan), "--nonsense=1"], "unrecognized arguments: --nonsense=1"),
        ([str(instance), str(instance), "--watch", "--encoding", str(program)], "is also an input"),
        ([str(instance), "--watch", "--encoding", str(program), "-c", "lanes"], "-c lanes: expected NAME=VALUE"),
        ([str(instance), "--watch", "--encoding", str(program), "--no-such-clingo-option=1"], "clingo refuses"),
    ]
    for arguments, message in cases:
        assert main(["check", *arguments]) == 2, arguments
        assert message in capsys.readouterr().err, arguments


# --- the command ----------------------------------------------------------------------------------


class Command:
    """``asprilo check ...`` in a process of its own, its output read line by line."""

    def __init__(self, arguments: list[str], cwd: Path):
        self.process = subprocess.Popen([sys.executable, "-m", "asprilo.cli", "check", *arguments], cwd=cwd,
                                        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.lines: queue.Queue[str | None] = queue.Queue()
        self.seen: list[str] = []
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        assert self.process.stdout is not None
        for line in self.process.stdout:
            self.lines.put(line.rstrip("\n"))
        self.lines.put(None)

    def until(self, wanted: Callable[[str], bool]) -> str:
        """The next line that is ``wanted`` (the lines before it are kept in ``seen``)."""
        while True:
            try:
                line = self.lines.get(timeout=PATIENCE)
            except queue.Empty:
                self.process.kill()
                raise AssertionError(f"no line wanted within {PATIENCE} s; seen: {self.seen}") from None
            if line is None:
                raise AssertionError(f"the watch ended; seen: {self.seen}; stderr: {self.stop()[1]}")
            self.seen.append(line)
            if wanted(line):
                return line

    def interrupt(self) -> tuple[int, str]:
        """Ctrl-C: the exit status and standard error."""
        self.process.send_signal(signal.SIGINT)
        return self.stop()

    def stop(self) -> tuple[int, str]:
        try:
            _out, err = self.process.communicate(timeout=PATIENCE)
        except subprocess.TimeoutExpired:
            self.process.kill()
            raise
        return self.process.returncode, err


def test_the_command_checks_again_on_every_save_and_ends_on_ctrl_c(tmp_path):
    (tmp_path / "down.lp").write_text(DOWN)
    plan = tmp_path / "plan.lp"
    plan.write_text(BAD_PLAN)
    command = Command(["down.lp", "plan.lp", "--watch"], tmp_path)
    try:
        assert command.until(lambda line: not line.startswith("---")).startswith("step 1: robot 1 moves")
        command.until(lambda line: line.startswith("invalid plan: 2 violations"))
        replace(plan, GOOD_PLAN + "occurs(")                  # a syntax error: one line, the watch goes on
        assert command.until(lambda line: line.startswith("error:")).startswith("error: plan.lp:")
        replace(plan, GOOD_PLAN)
        command.until(lambda line: line.startswith("valid plan"))
        status, err = command.interrupt()
    finally:
        command.process.kill()
    assert status == 130
    assert "Traceback" not in err and err.strip().endswith("interrupted")
    headings = [line for line in command.seen if line.startswith("---")]
    assert [heading.split(" ", 2)[2] for heading in headings] == [
        "watching down.lp, plan.lp (Ctrl-C ends): checking ---", "plan.lp changed: checking ---",
        "plan.lp changed: checking ---"]


def test_the_command_solves_again_when_the_encoding_is_saved(tmp_path):
    (tmp_path / "down.lp").write_text(DOWN)
    program = tmp_path / "mine.lp"
    program.write_text((OWN / "mapf-upside-down.lp").read_text())
    command = Command(["down.lp", "plan.lp", "--watch", "--encoding", "mine.lp", "-c", "unused=1",
                       "--configuration=crafty", "--time-limit", "100"], tmp_path)
    try:
        command.until(lambda line: line.startswith("invalid plan: 3 violations"))
        replace(program, (OWN / "mapf.lp").read_text())
        assert command.until(lambda line: line.startswith("plan:")) == \
            "plan: horizon 2 (proven minimal), 2 actions, written to plan.lp"
        command.until(lambda line: line.startswith("valid plan"))
        status, err = command.interrupt()
    finally:
        command.process.kill()
    assert status == 130 and "Traceback" not in err
    assert (tmp_path / "plan.lp").read_text() == GOOD_PLAN


@pytest.mark.parametrize("arguments", [["--help"]])
def test_the_help_says_how_to_watch(arguments, capsys):
    with pytest.raises(SystemExit):
        main(["check", *arguments])
    text = capsys.readouterr().out
    assert "check INSTANCE PLAN --watch" in text and "--violations N" in text and "--encoding" in text


def test_the_watch_checks_under_the_variants_given(tmp_path):
    """tests/variants/corridor.lp (robot 1 at (2,1), energy 2): a detour of four moves runs out
    at step 3 under --variant energy, and is valid without it (the energy fact then ignored)."""
    from asprilo.domain.variants import load_variant

    corridor = Path(__file__).parent / "variants" / "corridor.lp"
    plan = tmp_path / "detour.lp"
    plan.write_text("".join(f"occurs(object(robot,1),action(move,({dx},0)),{step}).\n"
                            for step, dx in enumerate((-1, 1, 1, 1), 1)))
    verdicts = []
    for variants in ([], [load_variant("energy")]):
        out = io.StringIO()
        rerun = PlanCheck(corridor, plan, None, 5, out)
        rerun.variants = variants
        rerun([])
        verdicts.append([line for line in out.getvalue().splitlines()[1:] if not line.startswith("warning")])
    assert verdicts == [["valid plan (domain M (detected), horizon 4)"],
                        ["step 3: robot 1 runs out of energy: its level would be -1",
                         "invalid plan: 1 violation (domain M+energy (detected), horizon 4)"]]
