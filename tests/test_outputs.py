"""Outputs only where meant (README "Where outputs go"): every command that writes a file
writes it through ``asprilo.writer.write_bytes``, only to a regular file that is none of its
inputs, whole or not at all; standard output on a full disk or a closed pipe ends cleanly.

Per output kind and command family: a device node, a FIFO, a symbolic link (to a file, and
dangling) as the output are refused with one line and left as they were; an output that is
also an input (the same path, a hard link, a symbolic link, an input found beside another)
is refused; a write that fails mid-way (a file size limit in a child process, as a full disk
would) leaves the old file or none and no temporary file; standard output on ``/dev/full``
gives one line, a closed pipe (``| head -c 10``) none.  The MovingAI pair
``tests/hostile/output-beside.{scen,map}`` is the case of an input found beside another.

No test writes to a system device: device nodes are made in a temporary folder (a copy of
``/dev/full``'s numbers), or, where that is not allowed, ``/dev/full`` is used only by a
user who may not replace it.
"""

from __future__ import annotations

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")  # the viewer's Save and Export, below

import contextlib  # noqa: E402
import errno  # noqa: E402
import resource
import shutil
import signal
import socket
import stat
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

from asprilo import writer
from asprilo.cli import main
from asprilo.errors import InputError

CORPUS = Path(__file__).parent / "hostile"
BASE_INSTANCE, BASE_PLAN = CORPUS / "base-instance.lp", CORPUS / "base-plan.lp"
ROOT_ENCODINGS = Path(__file__).parent / "encodings"
BUDGET = 30.0  # seconds a refusal may take (it comes before any work)
KINDS = ("device", "fifo", "symlink", "dangling", "loop")
SMALL_GEN = ["-x", "4", "-y", "3", "-r", "1", "-s", "1", "-p", "1", "-P", "1", "-u", "1", "-o", "1"]
GEN_NAME = "x4_y3_n12_r1_s1_ps1_pr1_u1_o1_N001.lp"
ROOT = os.geteuid() == 0


def _run(capsys, arguments: list) -> tuple[int, str, str]:
    started = time.perf_counter()
    code = main([str(argument) for argument in arguments])
    assert time.perf_counter() - started < BUDGET
    out, err = capsys.readouterr()
    return code, out, err


def _device(path: Path) -> Path:
    """A character device node at ``path`` (numbers of /dev/full: a write there fails anyway)."""
    try:
        os.mknod(path, stat.S_IFCHR | 0o666, os.makedev(1, 7))
        return path
    except (OSError, AttributeError):
        pass
    full = Path("/dev/full")
    if not ROOT and full.is_char_device():
        return full  # a user who cannot replace it
    pytest.skip("no device node can be made here")


def _make(kind: str, path: Path, mine: Path) -> Path:
    """The hostile output ``kind`` at ``path`` (a link points to ``mine``, a file of the user's)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if kind == "device":
        return _device(path)
    if kind == "fifo":
        os.mkfifo(path)
    elif kind == "symlink":
        path.symlink_to(mine)
    elif kind == "dangling":
        path.symlink_to(mine.parent / "nowhere.lp")
    elif kind == "loop":  # a link to itself
        path.symlink_to(path.name)
    return path


def _state(path: Path) -> str:
    """What is at ``path``, without following a link."""
    mode = os.lstat(path).st_mode
    if stat.S_ISLNK(mode):
        return f"link to {os.readlink(path)}"
    return "device" if stat.S_ISCHR(mode) else "fifo" if stat.S_ISFIFO(mode) else \
        "file" if stat.S_ISREG(mode) else "other"


#: command -> (its arguments writing to TARGET in folder ``tmp``, where TARGET lies relative to ``tmp``)
WRITERS = {
    "solve -o": (lambda tmp, target: ["solve", tmp / "i.lp", "-o", target], "plan.lp"),
    "convert": (lambda tmp, target: ["convert", tmp / "i.lp", target, "--to", "m"], "m.lp"),
    "viz --export": (lambda tmp, target: ["viz", tmp / "i.lp", "--export", target], "state.png"),
    "gen --force": (lambda tmp, target: ["gen", *SMALL_GEN, "-d", tmp / "out", "--force", "-q"], f"out/{GEN_NAME}"),
    "demo --force": (lambda tmp, target: ["demo", "-o", tmp / "demo", "--no-pictures", "--force"], "demo/plan.lp"),
}
#: the start of each refusal, by kind
REFUSAL = {"device": "is a character device, not a regular file: outputs go only to regular files",
           "fifo": "is a FIFO (named pipe), not a regular file: outputs go only to regular files",
           "symlink": "is a symbolic link (to ", "dangling": "is a dangling symbolic link (to ",
           "loop": "is a loop of symbolic links (to "}


@pytest.fixture
def folder(tmp_path) -> Path:
    shutil.copy(BASE_INSTANCE, tmp_path / "i.lp")
    shutil.copy(BASE_PLAN, tmp_path / "p.lp")
    (tmp_path / "mine.lp").write_text("mine\n")
    return tmp_path


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("command", WRITERS)
def test_only_regular_files_are_written(capsys, folder, command, kind):
    arguments, name = WRITERS[command]
    target = _make(kind, folder / name, folder / "mine.lp")
    before = _state(target)
    reader = os.open(target, os.O_RDONLY | os.O_NONBLOCK) if kind == "fifo" else None  # hang guard
    try:
        code, _out, err = _run(capsys, arguments(folder, target))
    finally:
        if reader is not None:
            with contextlib.suppress(BlockingIOError):  # nothing to read: nothing was written into it
                assert os.read(reader, 1) == b""
            os.close(reader)
    assert code == 2 and err.count("\n") == 1, err
    assert err.startswith(f"error: {target}: {REFUSAL[kind]}"), err
    assert _state(target) == before
    assert (folder / "mine.lp").read_text() == "mine\n"
    assert not (folder / "nowhere.lp").exists()


def test_a_device_refusal_says_how_to_discard_output(capsys, folder):
    device = _device(folder / "null")
    code, _out, err = _run(capsys, ["solve", folder / "i.lp", "-o", device])
    assert (code, err) == (2, f"error: {device}: is a character device, not a regular file: outputs go only to "
                              "regular files (-o - writes to standard output, which you may redirect)\n")
    code, _out, err = _run(capsys, ["convert", folder / "i.lp", device, "--to", "m"])
    assert code == 2 and err.endswith("(- as OUT writes to standard output, which you may redirect)\n")


def test_dash_is_standard_output(capsys, folder, monkeypatch):
    monkeypatch.chdir(folder)
    code, out, _err = _run(capsys, ["solve", "i.lp", "-o", "-"])
    assert code == 0 and out == BASE_PLAN.read_text()
    assert not (folder / "-").exists()  # not a file named '-'
    code, out, _err = _run(capsys, ["convert", "i.lp", "-", "--to", "m"])
    assert code == 0 and "#program base." in out and not (folder / "-").exists()


# --- an output that is also an input ------------------------------------------------------------

def _inputs_intact(folder: Path, names: list[str], before: list[bytes]) -> bool:
    return [(folder / name).read_bytes() for name in names] == before


def test_no_output_is_also_an_input(capsys, folder):
    os.link(folder / "i.lp", folder / "hard.lp")
    (folder / "soft.lp").symlink_to("i.lp")
    shutil.copy(folder / "i.lp", folder / "i.png")  # an instance with a picture's name: viz X --export X
    os.link(folder / "i.png", folder / "hard.png")
    shutil.copy(ROOT_ENCODINGS / "m-fixed.lp", folder / "e.lp")
    names = ["i.lp", "p.lp", "i.png", "e.lp"]
    before = [(folder / name).read_bytes() for name in names]
    cases = [
        (["solve", "i.lp", "-o", "i.lp"], "i.lp", "i.lp"),
        (["solve", "i.lp", "-o", "hard.lp"], "hard.lp", "i.lp"),
        (["solve", "i.lp", "-o", "soft.lp"], "soft.lp", "i.lp"),
        (["solve", "i.lp", "--encoding", "e.lp", "-o", "e.lp"], "e.lp", "e.lp"),
        (["convert", "i.lp", "i.lp", "--to", "m"], "i.lp", "i.lp"),
        (["convert", "i.lp", "hard.lp", "--to", "md"], "hard.lp", "i.lp"),
        (["convert", "p.lp", "i.lp", "--to", "result", "--instance", "i.lp"], "i.lp", "i.lp"),
        (["viz", "i.png", "--export", "i.png"], "i.png", "i.png"),
        (["viz", "i.png", "p.lp", "--export", "hard.png"], "hard.png", "i.png"),
        (["viz", "i.lp", "p.lp", "--export", "p.lp"], "p.lp", "p.lp"),
    ]
    old = Path.cwd()
    os.chdir(folder)
    try:
        for arguments, output, given in cases:
            code, _out, err = _run(capsys, arguments)
            assert (code, err) == (2, f"error: {output}: is also an input ({given}); choose another output "
                                      "file\n"), arguments
    finally:
        os.chdir(old)
    assert _inputs_intact(folder, names, before)


def test_the_map_found_beside_a_scenario_is_an_input(capsys, tmp_path):
    for name in ("output-beside.scen", "output-beside.map"):
        shutil.copy(CORPUS / name, tmp_path / name)
    before = (tmp_path / "output-beside.map").read_text()
    target = tmp_path / "output-beside.map"
    code, _out, err = _run(capsys, ["convert", tmp_path / "output-beside.scen", target, "--to", "md"])
    assert (code, err) == (2, f"error: {target}: is also an input ({target}); choose another output file\n")
    assert target.read_text() == before
    code, _out, err = _run(capsys, ["convert", tmp_path / "output-beside.scen", tmp_path / "agents.lp"])
    assert (code, err) == (0, "")


def test_gen_never_replaces_its_template(capsys, tmp_path):
    template = tmp_path / "layout.lp"
    template.write_text("".join(f"init(object(node,{n}),value(at,({x},{y}))).\n"
                                for n, (x, y) in enumerate(((1, 1), (2, 1), (3, 1), (1, 2), (2, 2), (3, 2)), 1)))
    layout = ["-r", "1", "-s", "1", "-p", "1", "-P", "1", "-u", "1", "-o", "1", "-q"]
    code, _out, _err = _run(capsys, ["gen", "-T", template, *layout, "-d", tmp_path / "out"])
    made, = (tmp_path / "out").iterdir()
    made.unlink()
    template.rename(made)  # the template now has the name of the instance gen makes of it
    before = made.read_text()
    code, _out, err = _run(capsys, ["gen", "-T", made, *layout, "-d", tmp_path / "out", "--force"])
    assert (code, err) == (2, f"error: {made}: is also an input ({made}); choose another output file\n")
    assert made.read_text() == before


# --- failed writes ----------------------------------------------------------------------------------

def _command(*arguments) -> list[str]:
    return [sys.executable, "-m", "asprilo.cli", *map(str, arguments)]


def _limited(size: int):
    """For a child: files may grow to ``size`` bytes; beyond, a write fails (EFBIG) instead of a signal."""
    def limit() -> None:
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (size, size))
    return limit


def _big_map(folder: Path, side: int = 200) -> Path:
    """An open square map: its instance has ``side**2`` nodes (about 1.6 MB of facts for 200)."""
    path = folder / "big.map"
    path.write_text(f"type octile\nheight {side}\nwidth {side}\nmap\n" + ("." * side + "\n") * side)
    return path


def _no_traceback(err: str) -> None:
    assert "Traceback" not in err and "Exception ignored" not in err, err


def test_a_write_failing_midway_leaves_the_old_file_or_none(tmp_path):
    big = _big_map(tmp_path)
    old = tmp_path / "old.lp"
    old.write_text("old\n")
    for target in (old, tmp_path / "new.lp"):
        done = subprocess.run(_command("convert", big, target), capture_output=True, text=True, timeout=120,
                              preexec_fn=_limited(100_000))
        _no_traceback(done.stderr)
        assert (done.returncode, done.stderr) == (2, f"error: {target}: cannot be written (File too large)\n")
    assert old.read_text() == "old\n" and not (tmp_path / "new.lp").exists()
    assert sorted(path.name for path in tmp_path.iterdir()) == ["big.map", "old.lp"]  # no temporary file left


def test_gen_and_viz_writes_failing_midway_leave_nothing(tmp_path):
    done = subprocess.run(_command("gen", *SMALL_GEN, "-d", tmp_path / "out"), capture_output=True, text=True,
                          timeout=120, preexec_fn=_limited(500))
    _no_traceback(done.stderr)
    assert done.returncode == 2 and done.stderr == \
        f"error: {tmp_path / 'out' / GEN_NAME}: cannot be written (File too large)\n"
    assert list((tmp_path / "out").iterdir()) == []
    picture = tmp_path / "state.png"
    done = subprocess.run(_command("viz", BASE_INSTANCE, BASE_PLAN, "--export", picture), capture_output=True,
                          text=True, timeout=120, preexec_fn=_limited(300),
                          env={**os.environ, "QT_QPA_PLATFORM": "offscreen"})
    _no_traceback(done.stderr)
    assert done.returncode == 2 and done.stderr.endswith(f"error: {picture}: cannot be written (File too large)\n")
    assert list(tmp_path.iterdir()) == [tmp_path / "out"]


@pytest.mark.parametrize("number, words", [(errno.ENOSPC, "No space left on device"),
                                           (errno.EROFS, "Read-only file system"),
                                           (errno.EACCES, "Permission denied")])
def test_a_failed_write_is_one_line_naming_the_file(tmp_path, monkeypatch, number, words):
    path = tmp_path / "plan.lp"
    path.write_text("old")

    def fails(*_args, **_kwargs):
        raise OSError(number, os.strerror(number))

    monkeypatch.setattr(os, "fsync", fails)
    with pytest.raises(InputError) as error:
        writer.write_text(path, "new")
    assert str(error.value) == f"{path}: cannot be written ({words})"
    assert path.read_text() == "old" and [p.name for p in tmp_path.iterdir()] == ["plan.lp"]
    monkeypatch.undo()
    monkeypatch.setattr(tempfile, "mkstemp", fails)
    with pytest.raises(InputError) as error:
        writer.write_text(tmp_path / "new.lp", "new")
    assert str(error.value) == f"{tmp_path / 'new.lp'}: cannot be written ({words})"


def test_a_file_that_may_not_be_written_is_not_replaced(tmp_path, monkeypatch):
    path = tmp_path / "plan.lp"
    path.write_text("old")
    path.chmod(0o444)
    if ROOT:  # root may write anything: say it may not
        monkeypatch.setattr(os, "access", lambda *_args, **_kwargs: False)
    with pytest.raises(InputError) as error:
        writer.write_text(path, "new")
    assert str(error.value) == f"{path}: cannot be written (Permission denied)"
    assert path.read_text() == "old"


@pytest.mark.skipif(ROOT, reason="root may write into any folder")
def test_a_folder_that_may_not_be_written_gives_one_line(capsys, tmp_path):
    (tmp_path / "locked").mkdir(mode=0o555)
    target = tmp_path / "locked" / "plan.lp"
    code, _out, err = _run(capsys, ["solve", BASE_INSTANCE, "-o", target])
    assert (code, err) == (2, f"error: {target}: cannot be written (Permission denied)\n")


def test_a_path_that_turns_into_a_link_meanwhile_is_not_replaced(tmp_path, monkeypatch):
    path, mine = tmp_path / "plan.lp", tmp_path / "mine.lp"
    mine.write_text("mine")
    synced = os.fsync

    def swap(descriptor):  # between the check and the rename, someone puts a link there
        synced(descriptor)
        path.symlink_to(mine)

    monkeypatch.setattr(os, "fsync", swap)
    with pytest.raises(InputError, match="is a symbolic link"):
        writer.write_text(path, "new")
    assert path.is_symlink() and mine.read_text() == "mine"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine.lp", "plan.lp"]


# --- standard output -------------------------------------------------------------------------------

FULL = Path("/dev/full")
needs_full = pytest.mark.skipif(not FULL.is_char_device(), reason="no /dev/full here")

#: commands whose output goes to standard output, in a folder holding i.lp and p.lp
PRINTING = {
    "solve": ["solve", "i.lp"],
    "solve -o -": ["solve", "i.lp", "-o", "-"],
    "convert -": ["convert", "i.lp", "-", "--to", "m"],
    "info": ["info", "i.lp"],
    "check --json": ["check", "i.lp", "p.lp", "--json"],
    "gen -C": ["gen", *SMALL_GEN, "-C"],
}


@needs_full
@pytest.mark.parametrize("command", PRINTING)
def test_a_full_disk_on_standard_output_is_one_line(folder, command):
    with open(FULL, "w") as full:
        done = subprocess.run(_command(*PRINTING[command]), cwd=folder, stdout=full, stderr=subprocess.PIPE,
                              text=True, timeout=120)
    _no_traceback(done.stderr)
    assert done.returncode == 2
    assert done.stderr.endswith("error: standard output: cannot be written (No space left on device)\n")
    assert done.stderr.count("error:") == 1
    assert not (folder / "-").exists()


def test_a_long_write_that_standard_output_takes_in_part_is_an_error(tmp_path):
    """Python's text stream drops the rest of a long write the system takes only in part."""
    big = _big_map(tmp_path)
    with open(tmp_path / "out.txt", "w") as out:
        done = subprocess.run(_command("convert", big, "-", "--to", "md"), stdout=out, stderr=subprocess.PIPE,
                              text=True, timeout=120, preexec_fn=_limited(100_000))
    _no_traceback(done.stderr)
    assert (done.returncode, done.stderr) == (2, "error: standard output: cannot be written (File too large)\n")


@pytest.mark.parametrize("arguments", [["convert", "big.map", "-", "--to", "md"],
                                       ["gen", *SMALL_GEN, "-N", "40", "-C"]], ids=["convert", "gen"])
def test_a_closed_pipe_ends_quietly(tmp_path, arguments):
    _big_map(tmp_path)
    process = subprocess.Popen(_command(*arguments), cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert process.stdout is not None and process.stderr is not None
    head = process.stdout.read(10)  # | head -c 10
    process.stdout.close()
    err = process.stderr.read().decode()
    assert process.wait(timeout=120) == 0
    assert len(head) == 10 and err == ""


# --- the writer's rules --------------------------------------------------------------------------

def test_check_output_refuses_what_is_no_regular_file(tmp_path):
    writer.check_output(None)
    writer.check_output("-")
    writer.check_output(tmp_path / "new.lp")  # a new file
    (tmp_path / "old.lp").write_text("x")
    writer.check_output(tmp_path / "old.lp")  # an existing regular file
    with pytest.raises(InputError, match="is a directory, not a file to write"):
        writer.check_output(tmp_path)
    os.mkfifo(tmp_path / "fifo")
    with pytest.raises(InputError, match=r"is a FIFO \(named pipe\), not a regular file"):
        writer.check_output(tmp_path / "fifo")
    with socket.socket(socket.AF_UNIX) as server:
        server.bind(str(tmp_path / "sock"))
        with pytest.raises(InputError, match="is a socket, not a regular file"):
            writer.check_output(tmp_path / "sock")
    device = next((Path(name) for name in ("/dev/null", "/dev/zero", "/dev/full") if Path(name).is_char_device()),
                  None)
    if device is not None:  # only looked at
        with pytest.raises(InputError, match="is a character device"):
            writer.check_output(device)
    (tmp_path / "link").symlink_to(tmp_path / "old.lp")
    with pytest.raises(InputError, match=r"is a symbolic link \(to .*old.lp\)"):
        writer.check_output(tmp_path / "link")
    with pytest.raises(InputError, match=r"is also an input \(.*old.lp\)"):
        writer.check_output(tmp_path / "link", [tmp_path / "old.lp"])


def test_dash_is_no_file_name(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(InputError, match="is standard output, not a file to write"):
        writer.write_text("-", "text")
    writer.write_output("-", "text\n")
    assert capsys.readouterr().out == "text\n" and list(tmp_path.iterdir()) == []


def test_file_names_in_messages_show_control_characters_escaped(tmp_path):
    link = tmp_path / "plan\x1b[2J.lp"
    link.symlink_to(tmp_path / "nowhere")
    with pytest.raises(InputError) as error:
        writer.write_text(link, "x")
    assert "\x1b" not in str(error.value) and "plan\\x1b[2J.lp" in str(error.value)


def test_bench_results_are_appended_to_a_regular_file_only(tmp_path):
    from asprilo.bench.results import RESULTS, append_result, load_results
    append_result(tmp_path, {"key": "a"})
    assert load_results(tmp_path) == [{"key": "a"}]
    (tmp_path / "elsewhere").mkdir()
    mine = tmp_path / "mine.jsonl"
    mine.write_text("mine\n")
    (tmp_path / "elsewhere" / RESULTS).symlink_to(mine)
    with pytest.raises(InputError, match="is a symbolic link"):
        append_result(tmp_path / "elsewhere", {"key": "b"})
    (tmp_path / "piped").mkdir()
    os.mkfifo(tmp_path / "piped" / RESULTS)
    with pytest.raises(InputError, match="is a FIFO"):  # refused at once: opening it would wait
        append_result(tmp_path / "piped", {"key": "c"})
    assert mine.read_text() == "mine\n"


# --- the viewer's Save and Export ---------------------------------------------------------------

@pytest.mark.gui
def test_the_viewer_saves_and_exports_by_the_same_rule(qtbot, tmp_path_factory, folder):
    from helpers.viewer import shown_window
    window = shown_window(qtbot, tmp_path_factory)
    instance, plan = folder / "i.lp", folder / "p.lp"
    assert window.open_files([str(instance)], [str(plan)])
    before = instance.read_text(), plan.read_text()
    editor, exports = window.editor, window.exports
    for write, path, given in ((editor.save_plan, instance, instance), (editor.save_as, plan, plan),
                               (editor.save_template, instance, instance), (exports.picture, plan, plan),
                               (lambda path: exports.animation(path, 1), instance, instance)):
        assert not write(str(path))
        assert window.last_error == f"{path}: is also an input ({given}); choose another output file"
    assert (instance.read_text(), plan.read_text()) == before
    for kind in ("fifo", "symlink", "dangling"):
        target = _make(kind, folder / f"{kind}.png", folder / "mine.lp")
        assert not exports.picture(str(target))
        assert window.last_error.startswith(f"{target}: {REFUSAL[kind]}")
        target = _make(kind, folder / f"{kind}.lp", folder / "mine.lp")
        assert not editor.save_as(str(target))
        assert window.last_error.startswith(f"{target}: {REFUSAL[kind]}")
        assert _state(target) != "file"
    assert (folder / "mine.lp").read_text() == "mine\n"
    assert editor.save_as(str(instance))  # Save of the instance may replace its own file
    assert editor.save_plan(str(plan))    # and Save plan the plan's
    assert exports.picture(str(folder / "state.png"))
