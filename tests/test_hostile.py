"""Hostile and broken input (tests/hostile/): every command that reads files answers each
bad file with exit 2 and exactly one line ``error: FILE[:LINE]: ...`` on stderr, no
traceback, well within a time budget; odd but valid files (a byte-order mark, CRLF,
Unicode in comments and strings, unknown attributes) are read.

File names say what to expect: ``bad-instance-*`` / ``bad-plan-*`` are refused,
``ok-instance-*`` / ``ok-plan-*`` are read; ``base-instance.lp`` (robot 1 must reach
destination 1 along a corridor of three nodes) and ``base-plan.lp`` (two moves east)
complete the calls.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from asprilo.cli import main

CORPUS = Path(__file__).parent / "hostile"
BASE_INSTANCE, BASE_PLAN = CORPUS / "base-instance.lp", CORPUS / "base-plan.lp"
BUDGET = 30.0  # seconds any call may take (each is refused long before on any machine)


def _files(pattern: str) -> list[Path]:
    return sorted(CORPUS.glob(pattern))


#: command -> its arguments for an instance file, in a fresh folder ``out``
ON_INSTANCE = {
    "info": lambda path, out: ["info", path],
    "check": lambda path, out: ["check", path, BASE_PLAN],
    "solve": lambda path, out: ["solve", path, "-o", out / "plan.lp"],
    "convert-map": lambda path, out: ["convert", path, out / "floor.map"],
    "convert-m": lambda path, out: ["convert", path, out / "m.lp", "--to", "m"],
    "gen": lambda path, out: ["gen", "-T", path, "-d", out / "generated"],
    "viz": lambda path, out: ["viz", path, "--export", out / "state.png"],
}
#: command -> its arguments for a plan file
ON_PLAN = {
    "info": lambda path, out: ["info", BASE_INSTANCE, path],
    "check": lambda path, out: ["check", BASE_INSTANCE, path],
    "convert": lambda path, out: ["convert", path, out / "result.txt", "--from", "plan", "--instance", BASE_INSTANCE],
    "viz": lambda path, out: ["viz", BASE_INSTANCE, path, "--export", out / "plan.gif"],
}


def _run(capsys, arguments: list) -> tuple[int, str, str, float]:
    started = time.perf_counter()
    code = main([str(argument) for argument in arguments])
    seconds = time.perf_counter() - started
    out, err = capsys.readouterr()
    return code, out, err, seconds


def _refused(capsys, arguments: list, path: Path) -> None:
    code, _out, err, seconds = _run(capsys, arguments)
    assert code == 2, err
    assert err.count("\n") == 1 and err.startswith(f"error: {path}"), err
    assert not any(char < " " for char in err[:-1]), err  # control characters are shown escaped
    assert seconds < BUDGET


@pytest.mark.parametrize("command", ON_INSTANCE)
@pytest.mark.parametrize("path", _files("bad-instance-*"), ids=lambda path: path.name)
def test_bad_instances_are_refused_by_every_command(capsys, tmp_path, command, path):
    _refused(capsys, ON_INSTANCE[command](path, tmp_path), path)


@pytest.mark.parametrize("command", ON_PLAN)
@pytest.mark.parametrize("path", _files("bad-plan-*"), ids=lambda path: path.name)
def test_bad_plans_are_refused_by_every_command(capsys, tmp_path, command, path):
    _refused(capsys, ON_PLAN[command](path, tmp_path), path)


@pytest.mark.parametrize("path", _files("bad-map-*") + _files("bad-scen-*") + _files("bad-result-*")
                         + [CORPUS / "far-node.lp"], ids=lambda path: path.name)
def test_bad_movingai_and_lacam_files_are_refused_by_convert(capsys, tmp_path, path):
    target = {".map": "floor.lp", ".scen": "agents.lp", ".txt": "plan.lp", ".lp": "floor.map"}[path.suffix]
    extra = ["--instance", BASE_INSTANCE] if path.suffix == ".txt" else []
    _refused(capsys, ["convert", path, tmp_path / target, *extra], path)


@pytest.mark.parametrize("name, exits", [
    ("invalid-plan-unknown-robot.lp", {"info": 2, "check": 2, "convert": 2, "viz": 2}),  # one sentence, all
    ("invalid-plan-move-not-tuple.lp", {"info": 0, "check": 1, "convert": 2, "viz": 1}),  # viz --export as check
])
def test_invalid_plans_get_the_verdict_or_are_refused(capsys, tmp_path, name, exits):
    path = CORPUS / name
    for command, expected in exits.items():
        code, out, err, seconds = _run(capsys, ON_PLAN[command](path, tmp_path))
        assert code == expected and seconds < BUDGET, (command, err)
        if expected == 2:
            assert err.count("\n") == 1 and err.startswith(f"error: {path}"), (command, err)
        else:
            assert "error" not in err and "Traceback" not in err, (command, err)
    if exits["check"] == 1:
        assert "invalid plan: 2 violations" in _run(capsys, ON_PLAN["check"](path, tmp_path))[1]  # and the goal


@pytest.mark.parametrize("path", [*_files("ok-instance-*"), BASE_INSTANCE], ids=lambda path: path.name)
def test_odd_but_valid_instances_are_read(capsys, tmp_path, path):
    warning = "ok-instance-unknown-attributes" in path.name
    for command in ("info", "check", "convert-map", "viz"):
        code, _out, err, seconds = _run(capsys, ON_INSTANCE[command](path, tmp_path))
        assert (code, err.count("warning: ")) == (0, warning), (command, err)
        assert "error" not in err and "Traceback" not in err and seconds < BUDGET
    code, _out, err, _seconds = _run(capsys, ON_INSTANCE["solve"](path, tmp_path))
    assert code == 0 and "Traceback" not in err
    assert (tmp_path / "plan.lp").read_text() == BASE_PLAN.read_text()


@pytest.mark.parametrize("path", _files("ok-plan-*"), ids=lambda path: path.name)
def test_odd_but_valid_plans_are_read(capsys, tmp_path, path):
    for command in ON_PLAN:
        code, _out, err, seconds = _run(capsys, ON_PLAN[command](path, tmp_path))
        assert code == 0 and "error" not in err and seconds < BUDGET, (command, err)


def test_bench_refuses_a_suite_with_a_bad_instance(capsys, tmp_path):
    bad = CORPUS / "bad-instance-deep-function.lp"
    suite = tmp_path / "suite.yml"
    suite.write_text(f"name: hostile\ntime_limit: 5\ninstances:\n  bad: {{files: [\"{bad}\"]}}\n"
                     "runs:\n  - {domain: md, encoding: plain, sets: [bad]}\n")
    _refused(capsys, ["bench", suite, "-o", tmp_path / "out"], bad)


def test_limits_are_named_and_can_be_raised(capsys, tmp_path):
    code, _out, err, _seconds = _run(capsys, ["info", BASE_INSTANCE, "--limit", "facts=3"])
    assert (code, err) == (2, f"error: {BASE_INSTANCE}: more than 3 facts, beyond the limit facts=3 "
                               "(raise it with --limit facts=N)\n")
    far = CORPUS / "bad-instance-robot-far.lp"
    code, out, err, _seconds = _run(capsys, ["info", far, "--limit", "coordinate=300000"])
    assert (code, err) == (0, "") and "2 robots" in out
    step = CORPUS / "bad-plan-step-1e7.lp"
    code, _out, err, _seconds = _run(capsys, ["check", BASE_INSTANCE, step])
    assert (code, err) == (2, f"error: {step}:1: an action at step 10,000,000, beyond the limit "
                              "robot-steps=500,000 (raise it with --limit robot-steps=N)\n")


def test_rules_when_allowed_are_grounded_under_time_and_memory_limits(capsys, tmp_path):
    endless = CORPUS / "bad-instance-infinite-rule.lp"
    code, _out, err, seconds = _run(capsys, ["info", endless, "--allow-rules", "--limit", "rule-seconds=2"])
    assert (code, err) == (2, f"error: {endless}: grounding the rules takes longer, beyond the limit "
                              "rule-seconds=2.0 (raise it with --limit rule-seconds=N)\n")
    assert seconds < BUDGET  # (the message says the limit stopped it)
    huge = tmp_path / "huge.lp"
    huge.write_text(BASE_INSTANCE.read_text() + "big(1..200000000).\n")
    code, _out, err, _seconds = _run(capsys, ["info", huge, "--allow-rules", "--limit", "rule-mb=400",
                                              "--limit", "rule-seconds=60"])
    assert code == 2 and err.startswith(f"error: {huge}: grounding the rules ") and "rule-mb=400" in err, err
    assert err.count("\n") == 1
    script = CORPUS / "bad-instance-script.lp"
    _refused(capsys, ["info", script, "--allow-rules"], script)


@pytest.mark.parametrize("name", ["bad-instance-deep-function.lp", "bad-instance-syntax-dash.lp",
                                  "bad-instance-nul.lp", "bad-instance-include-binary.lp",
                                  "bad-instance-readme.md", "bad-instance-binary.lp", "bad-instance-power-chain.lp",
                                  "bad-instance-const-power-chain.lp", "bad-instance-int-min-by-minus-one.lp",
                                  "bad-instance-deep-minus-brackets.lp", "bad-instance-const-bomb.lp"])
def test_no_crash_reaches_the_process(name):
    """Files that once ended the process (clingo's PANIC on a cut message, a segfault on a
    deep term or a long chain of operators, SIGFPE on -2147483648/-1), in a process of
    their own."""
    path = CORPUS / name
    for arguments in (["info", path], ["check", path, BASE_PLAN]):
        result = subprocess.run([sys.executable, "-m", "asprilo.cli", *map(str, arguments)],
                                capture_output=True, text=True, timeout=BUDGET)
        assert result.returncode == 2 and result.stderr.count("\n") == 1, result.stderr
        assert result.stderr.startswith(f"error: {path}")


@pytest.mark.parametrize("name", ["ok-instance-minus-20000.lp", "ok-instance-minus-20000-tight.lp",
                                  "ok-instance-tilde-20000.lp", "ok-instance-plus-chain.lp",
                                  "ok-instance-const-minus-20000.lp"])
def test_long_operator_chains_are_read_in_a_process_of_their_own(name):
    """20,000 unary operators, or 20,000 binary ones, in a row (clingo segfaulted on each:
    the parser evaluates them on a stack of its own and clingo sees only the result)."""
    path = CORPUS / name
    for arguments, expected in ((["info", path], "1 robots"), (["check", path, BASE_PLAN], "destinations reached")):
        result = subprocess.run([sys.executable, "-m", "asprilo.cli", *map(str, arguments)],
                                capture_output=True, text=True, timeout=BUDGET)
        assert (result.returncode, result.stderr) == (0, "") and expected in result.stdout, result.stderr


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="FIFOs need a POSIX system")
def test_a_fifo_as_an_input_is_refused_by_every_command(tmp_path):
    """A FIFO nobody writes to: each command answers at once with one line (it used to wait
    for a writer for ever); the hang guard is generous, no measurement."""
    fifo = tmp_path / "fifo.lp"
    os.mkfifo(fifo)
    calls = [make(fifo, tmp_path / command) for command, make in ON_INSTANCE.items()]
    calls += [make(fifo, tmp_path / command) for command, make in ON_PLAN.items()]
    for arguments in calls:
        result = subprocess.run([sys.executable, "-m", "asprilo.cli", *map(str, arguments)],
                                capture_output=True, text=True, timeout=BUDGET, stdin=subprocess.DEVNULL)
        assert result.returncode == 2, (arguments, result.stderr)
        assert result.stderr == f"error: {fifo}: is a FIFO (named pipe), not a regular file (give data on standard " \
                                "input as -)\n", (arguments, result.stderr)


#: a read in a child process under a hard address-space cap
_CAPPED = """
import resource, sys
resource.setrlimit(resource.RLIMIT_AS, (int(sys.argv[1]) * 2**20,) * 2)
from asprilo.cli import main
sys.exit(main(sys.argv[2:]))
"""


def test_a_huge_string_is_read_within_a_hard_memory_cap(tmp_path):
    """A 30 MB string literal (the old screen's regular expression took about 130 bytes per
    byte: 4 GB): refused by string-chars at once, and read within the cap when the limits
    allow it, kept (as an unknown attribute) or not."""
    base = BASE_INSTANCE.read_text()
    dropped, kept = tmp_path / "note.lp", tmp_path / "energy.lp"
    dropped.write_text(base + 'note("' + "x" * 30_000_000 + '").\n')
    kept.write_text(base + 'init(object(robot,1),value(energy,"' + "x" * 30_000_000 + '")).\n')
    cap = "400"  # megabytes of address space: the interpreter, clingo's library, the file and its string
    raised = ["--limit", "string-chars=40000000", "--limit", "fact-chars=40000000"]
    for path, arguments, code, stderr in (
            (dropped, [], 2, f"error: {dropped}:5: a string of more than 100,000 characters, beyond the limit "
                             "string-chars=100,000 (raise it with --limit string-chars=N)\n"),
            (dropped, raised, 0, ""),
            (kept, raised, 0, f"warning: {kept}:5: ignored (and kept when written): attribute 'energy' of robot\n")):
        result = subprocess.run([sys.executable, "-c", _CAPPED, cap, "info", str(path), *arguments],
                                capture_output=True, text=True, timeout=BUDGET)
        assert (result.returncode, result.stderr) == (code, stderr), result.stderr[-500:]


def test_cr_line_ends_are_lines(capsys):
    """A file with CR line ends (old Mac style): lines counted and comments ended at CR (clingo
    ends them at LF only: everything after the first comment was lost, "0 robots")."""
    path = CORPUS / "bad-instance-cr-rule.lp"
    code, _out, err, _seconds = _run(capsys, ["info", path])
    assert (code, err) == (2, f"error: {path}:6: 'p(X) :- q(X).' is a rule; data holds only facts, #const and "
                              "'#program base.' (rules need --allow-rules)\n")
    code, out, err, _seconds = _run(capsys, ["info", CORPUS / "ok-instance-cr-comments.lp"])
    assert (code, err) == (0, "") and "1 robots" in out and "3 nodes" in out


def test_messages_show_control_characters_escaped(capsys):
    path = CORPUS / "bad-instance-escape-sequence-id.lp"
    code, _out, err, _seconds = _run(capsys, ["info", path])
    assert (code, err) == (2, f'error: {path}:5: robot id must be an integer, got "\\x1b]2;owned\\x07\\x1b[2J'
                              '\\x1b[31m"\n')
    plan = CORPUS / "bad-plan-escape-sequence-step.lp"
    code, _out, err, _seconds = _run(capsys, ["check", BASE_INSTANCE, plan])
    assert (code, err) == (2, f"error: {plan}:1: the time step of occurs(object(robot,1),action(move,(1,0)),"
                              '"\\x1b[2J\\x1b[H") must be an integer\n')


def test_outputs_never_destroy_inputs(capsys, tmp_path):
    instance = tmp_path / "instance.lp"
    instance.write_text(BASE_INSTANCE.read_text())
    before = instance.read_text()
    for arguments in (["solve", instance, "-o", instance], ["convert", instance, instance, "--to", "m"],
                      ["convert", BASE_PLAN, instance, "--from", "result", "--instance", instance]):
        code, _out, err, _seconds = _run(capsys, arguments)
        assert (code, err) == (2, f"error: {instance}: is also an input ({instance}); choose another output file\n")
    assert instance.read_text() == before
    code, _out, err, _seconds = _run(capsys, ["solve", instance, "-o", tmp_path])
    assert (code, err) == (2, f"error: {tmp_path}: is a directory, not a file to write\n")
    blocked = tmp_path / "instance.lp" / "plan.lp"  # a folder that cannot exist: a file is in the way
    code, _out, err, _seconds = _run(capsys, ["convert", instance, blocked, "--to", "m"])
    assert code == 2 and err.startswith(f"error: {blocked}: cannot be written (") and err.count("\n") == 1
    (tmp_path / "demo").mkdir()
    (tmp_path / "demo" / "notes.txt").write_text("mine")
    code, _out, err, _seconds = _run(capsys, ["demo", "-o", tmp_path / "demo"])
    assert (code, err) == (2, f"error: {tmp_path / 'demo'}: the folder holds files already; choose another "
                              "(-o DIR) or add --force\n")
    assert (tmp_path / "demo" / "notes.txt").read_text() == "mine"


def test_a_replaced_file_keeps_its_permissions(tmp_path):
    from asprilo.writer import write_text

    path = tmp_path / "private.lp"
    path.write_text("old")
    path.chmod(0o600)
    write_text(path, "new")
    assert (path.read_text(), path.stat().st_mode & 0o777) == ("new", 0o600)


def test_bad_ports_are_refused(capsys):
    for port in ("70000", "-1", "http"):
        with pytest.raises(SystemExit) as exit_:
            main(["serve", "solver", "--port", port])
        assert exit_.value.code == 2
        assert "argument --port" in capsys.readouterr().err


def test_a_clingo_message_cut_inside_a_character_is_read(tmp_path):
    """clingo logs a lexer error next to a multi-byte character with the character cut;
    a program (not data: no screening) with one gives a clean error, not clingo's PANIC."""
    program = tmp_path / "program.lp"
    program.write_text("p :- q — r.\n", encoding="utf-8")
    code = ("from asprilo.solver import Solver\n"
            "from asprilo.errors import InputError\n"
            "try:\n"
            f"    Solver().load({str(program)!r})\n"
            "except InputError as error:\n"
            "    print(error)\n")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=BUDGET)
    assert (result.returncode, result.stdout, result.stderr) == (0, f"{program}:1: lexer error, unexpected —\n", "")
