"""Hostile encodings (issue 46, items 2 and 5): deep operator chains, a huge string, huge
comments, includes of what is no file, names that are no file, each through ``solve``,
``grade``, ``bench``, ``check --watch --encoding`` and the viewer's Solve with encoding file
(its job runner, offscreen).  Every answer is clean (one sentence, exit 1 or 2, a plan where
the program is fine) and the command's own process stays under 300 MB at its peak, measured
by ``ru_maxrss`` of that process (tests/helpers/peak.py runs the command in-process).

The big files are made here, at test time.  What clingo does with them was seen by hand, as
the issue reported it: its parser recurses, and a chain of 200,000 unary minus signs (or
``1+1+...`` with 200,000 terms) overflows its stack (SIGSEGV, signal 11) in the process that
parses it; a chain of 20,000 is parsed, and grounding it ends the solver's child process.
``m-single.lp`` (tests/encodings) solves tests/encodings/m-tiny.lp with 4 moves (by hand).
"""

from __future__ import annotations

import io
import os
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import pytest
from helpers import ROOT

ENCODINGS = ROOT / "tests" / "encodings"
M_TINY = ENCODINGS / "m-tiny.lp"
PEAK = ROOT / "tests" / "helpers" / "peak.py"
#: the most memory (MB) the command's own process may take at its peak
MOST_MB = 300
#: a hang guard (seconds): no call comes near it
PATIENCE = 600
CRASH = ("clingo's parser crashed on it (killed by signal 11); a term nested too deep, such as a long chain of "
         "operators, does that")
#: a comment line of 62 characters
COMMENT = "% this is a comment line of about sixty characters, roughly.\n"


@pytest.fixture(scope="module")
def corpus(tmp_path_factory) -> Path:
    """The hostile encodings, in one folder."""
    folder = tmp_path_factory.mktemp("corpus")
    single = (ENCODINGS / "m-single.lp").read_text()
    shutil.copy(ENCODINGS / "m-moves.lp", folder / "m-moves.lp")
    (folder / "minus-20k.lp").write_text("p(" + "- " * 20_000 + "1).\n")
    (folder / "minus-200k.lp").write_text("p(" + "- " * 200_000 + "1).\n")
    (folder / "plus-200k.lp").write_text("p(" + "1+" * 200_000 + "1).\n")
    (folder / "string-20mb.lp").write_text(f'{single}note("{"a" * 20_000_000}").\n')
    with open(folder / "comments-200mb.lp", "w") as file:
        file.write(single)
        for _ in range(32):
            file.write(COMMENT * (200_000_000 // len(COMMENT) // 32))
    (folder / "loop.lp").symlink_to("loop.lp")
    os.mkfifo(folder / "pipe")
    (folder / "sub").mkdir()
    for name, target in (("include-loop", "loop.lp"), ("include-fifo", "pipe"), ("include-folder", "sub"),
                         ("include-zero", "/dev/zero")):
        (folder / f"{name}.lp").write_text(f'#include "{target}".\np.\n')
    (folder / os.fsdecode(b"enc_\xff.lp")).write_text(single)
    return folder


#: file -> what every command says of it: (what follows "FILE" in its sentence, or None: a plan is found;
#: whether the file itself is at fault, not what it says: then every command refuses it, exit 2)
ANSWERS = {
    "minus-200k.lp": (f": {CRASH}", False),
    "plus-200k.lp": (f": {CRASH}", False),
    "string-20mb.lp": (None, False),
    "comments-200mb.lp": (None, False),
    "include-loop.lp": (":1: #include of 'loop.lp', which is a loop of symbolic links", False),
    "include-fifo.lp": (":1: #include of 'pipe', which is a FIFO (named pipe), not a regular file", False),
    "include-folder.lp": (":1: #include of 'sub', which is a folder, not a file", False),
    "include-zero.lp": (":1: #include of '/dev/zero', which is a character device, not a regular file", False),
    "loop.lp": (": is a loop of symbolic links", True),
    "pipe": (": is a FIFO (named pipe), not a regular file", True),
    "sub": (": is a folder, not a file", True),
    "enc_\\xff.lp": (": has a name that is not UTF-8 (rename the file)", True),
}


def _path(corpus: Path, name: str) -> Path:
    return corpus / os.fsdecode(b"enc_\xff.lp") if name == "enc_\\xff.lp" else corpus / name


def _run(arguments: list[str | Path], cwd: Path, interrupt_after: tuple[str, ...] = ()) -> tuple[int, str, str]:
    """Exit status, standard output and error of ``python tests/helpers/peak.py ARGUMENTS``,
    the peak line checked and taken off; ``interrupt_after``: Ctrl-C once a line on standard
    output starts with one of these words (a watch)."""
    process = subprocess.Popen([sys.executable, str(PEAK), *map(str, arguments)], cwd=cwd, text=True,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, errors="backslashreplace")
    out = ""
    if interrupt_after:
        assert process.stdout is not None
        for line in process.stdout:
            out += line
            if line.startswith(interrupt_after):
                process.send_signal(signal.SIGINT)
                break
    rest, err = process.communicate(timeout=PATIENCE)
    *said, peak = err.splitlines()
    assert peak.startswith("peak ") and int(peak.split()[1]) < MOST_MB, err
    assert "Traceback" not in err
    return process.returncode, out + rest, "".join(line + "\n" for line in said)


def _suite(folder: Path, encoding: Path) -> Path:
    path = folder / "suite.yml"
    path.write_text(f"name: hostile\ntime_limit: 60\nmemory_limit: 2048\nmakespan_time_limit: 60\n"
                    f"encodings:\n  mine: {{files: [\"{os.fsencode(encoding).decode('utf-8', 'replace')}\"]}}\n"
                    f"instances:\n  tiny: {{files: [\"{M_TINY}\"]}}\nruns:\n  - {{domain: m, encoding: mine}}\n")
    return path


@pytest.mark.parametrize("name", ANSWERS)
def test_solve(corpus, tmp_path, name):
    encoding, (said, _named) = _path(corpus, name), ANSWERS[name]
    code, out, err = _run(["cli", "solve", M_TINY, "--encoding", encoding], tmp_path)
    if said is None:
        assert code == 0 and out.count("occurs(") == 4, out + err
        assert "plan: horizon 4 (proven minimal), 4 actions, checked: valid\n" in err
    else:
        assert (code, err) == (2, f"error: {corpus}/{name}{said}\n")


@pytest.mark.parametrize("name", ANSWERS)
def test_grade(corpus, tmp_path, name):
    encoding, (said, named) = _path(corpus, name), ANSWERS[name]
    code, out, err = _run(["cli", "grade", encoding, "--domain", "m", "--first", "1", "--time-limit", "60"],
                          tmp_path)
    if said is None:
        assert code == 0 and "\n1/1 valid, 1/1 minimal; " in out, out + err
    elif named:  # a mistake of the command line: nothing is graded
        assert (code, out, err) == (2, "", f"error: {corpus}/{name}{said}\n")
    else:  # what the encoding says: graded, no plan
        assert code == 1 and f" no plan  clingo refused the encoding: {corpus}/{name}{said}\n" in out, out


@pytest.mark.parametrize("name", [name for name in ANSWERS if name != "enc_\\xff.lp"])  # (a suite is UTF-8)
def test_bench(corpus, tmp_path, name):
    encoding, (said, _named) = _path(corpus, name), ANSWERS[name]
    suite = _suite(tmp_path, encoding)
    code, out, err = _run(["cli", "bench", suite, "-o", tmp_path / "out"], tmp_path)
    if said is None:
        assert code == 0 and "runs [1/1] solved 1, time-outs 0, failures 0" in err, err
    else:
        assert (code, out, err) == (2, "", f"error: {suite}:6: encodings.mine.files[0]: {corpus}/{name}{said}\n")


@pytest.mark.parametrize("name", ANSWERS)
def test_watch(corpus, tmp_path, name):
    encoding, (said, named) = _path(corpus, name), ANSWERS[name]
    code, out, err = _run(["cli", "check", M_TINY, "--watch", "--encoding", encoding], tmp_path,
                          interrupt_after=("error: ", "valid plan", "no plan", "invalid plan"))
    if named:  # refused before the watch starts
        assert (code, out, err) == (2, "", f"error: {corpus}/{name}{said}\n")
        return
    assert (code, err.splitlines()[-1]) == (130, "interrupted")
    last = out.splitlines()[-1]
    if said is None:
        assert last == "valid plan (domain M (detected), horizon 4)", out
    else:
        assert last == f"error: {corpus}/{name}{said}", out


@pytest.mark.parametrize("name", ANSWERS)
def test_viewer_job_runner(corpus, tmp_path, name):
    encoding, (said, _named) = _path(corpus, name), ANSWERS[name]
    code, out, _err = _run(["viewer", M_TINY, encoding], tmp_path)
    assert (code, out) == (0, "plan 4\n" if said is None else f"{corpus}/{name}{said}\n")


#: command -> its arguments for an encoding, the exit status and the words of its answer there
DEEP_BUT_PARSED = {
    "solve": (lambda encoding, folder: ["cli", "solve", M_TINY, "--encoding", encoding], 1,
              "\nno plan within the limits: "),  # (on standard error, with the search's summary)
    "grade": (lambda encoding, folder: ["cli", "grade", encoding, "--domain", "m", "--first", "1"], 1,
              "\n0/1 valid, 0/1 minimal, 1 without a plan; "),
    "bench": (lambda encoding, folder: ["cli", "bench", _suite(folder, encoding), "-o", folder / "out"], 0,
              "\nM       mine      0/1     "),
    "watch": (lambda encoding, folder: ["cli", "check", M_TINY, "--watch", "--encoding", encoding], 130,
              "\nno plan within the limits (60 s): "),
    "viewer": (lambda encoding, folder: ["viewer", M_TINY, encoding], 0, "minus-20k.lp: no plan within "),
}


@pytest.mark.parametrize("command", DEEP_BUT_PARSED)
def test_a_chain_of_20000_minus_signs_is_parsed_and_ends_the_solvers_child_only(corpus, tmp_path, command):
    """clingo's parser reads it in the reading child; grounding it ends the solver's child: no plan,
    said by each command as for any run that ended early (the reason is the solver's)."""
    arguments, status, words = DEEP_BUT_PARSED[command]
    code, out, err = _run(arguments(corpus / "minus-20k.lp", tmp_path), tmp_path,
                          interrupt_after=("no plan",) if command == "watch" else ())
    assert code == status and words in "\n" + out + err, out + err


def test_a_watched_encoding_that_becomes_a_loop_of_links_is_said_and_the_watch_goes_on(tmp_path):
    """(The watch ended with a RuntimeError traceback here.)"""
    from asprilo.cli.reruns import EncodingSolve
    from asprilo.cli.watching import watch

    single = (ENCODINGS / "m-single.lp").read_text()
    shutil.copy(ENCODINGS / "m-moves.lp", tmp_path / "m-moves.lp")
    program = tmp_path / "mine.lp"
    program.write_text(single)

    def loop() -> None:
        program.unlink()
        program.symlink_to(program.name)

    def mend() -> None:
        program.unlink()
        program.write_text(single)

    actions = [loop, None, mend, None]  # a save, a quiet poll (the run), ...

    def play(_seconds: float) -> None:
        action = actions.pop(0)
        if action is not None:
            action()

    out = io.StringIO()
    rerun = EncodingSolve(M_TINY, None, None, 5, [str(program)], [], [], None, 60.0, out, io.StringIO())
    watch(rerun.paths, rerun, wait=play, stop=lambda: not actions)
    runs = [run.splitlines()[1:] for run in out.getvalue().split("--- ")[1:]]
    valid = ["your encoding: single-shot with a horizon constant", "plan: horizon 4 (proven minimal), 4 actions",
             "valid plan (domain M (detected), horizon 4)"]
    assert runs == [valid, [f"error: {program}: is a loop of symbolic links"], valid], out.getvalue()
