"""Bad input never takes the viewer down: files that cannot be read (opened, dropped or
reloaded) and online servers that misbehave leave the window, and unsaved edits, as they were."""

from __future__ import annotations

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import socket  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import threading  # noqa: E402

import pytest  # noqa: E402
from helpers import SMALL_A  # noqa: E402
from helpers.viewer import shown_window  # noqa: E402
from PyQt5.QtCore import QMimeData, QPoint, Qt, QUrl  # noqa: E402
from PyQt5.QtGui import QDropEvent  # noqa: E402
from PyQt5.QtWidgets import QMessageBox  # noqa: E402

from asprilo.visualizer.jobs import network  # noqa: E402

pytestmark = pytest.mark.gui
WAIT_MS = 30_000
NODE = "init(object(node,1),value(at,(1,1))).\n"


@pytest.fixture
def window(qtbot, tmp_path_factory, monkeypatch):
    window = shown_window(qtbot, tmp_path_factory)
    window.questions = []  # "discard unsaved edits?" must not be asked for a file that cannot be read
    monkeypatch.setattr(QMessageBox, "question", lambda *args: window.questions.append(args[2]) or QMessageBox.Discard)
    return window


def deep_tuple(depth: int) -> str:
    term = "1"
    for _ in range(depth):
        term = f"({term},1)"
    return term


#: name -> (bytes, what the message says after "FILE")
BAD_FILES = {
    "latin1.lp": (NODE.encode() + "% Gr\u00fc\u00dfe\n".encode("latin-1"),
                  ":2: not a UTF-8 text file (byte 0xfc cannot be read)"),
    "syntax.lp": (NODE.encode() + b"init(object(node,2),value(at,(2,1))\n", ":3: syntax error"),
    "deep.lp": ((NODE + f"init(object(node,2),value(at,{deep_tuple(3000)})).\n").encode(),
                ":2: terms nested more deeply, beyond the limit depth=100"),
}


#: files that once made clingo abort the whole process (PANIC) instead of raising InputError
#: (issue 15): name -> (bytes, what the message says after "FILE"; None: read cleanly, a BOM is
#: no error).  Each is read in a child process first: a reader that aborts again fails the test
#: instead of ending the test run.
ONCE_ABORTING = {
    "bom.lp": ("\ufeff".encode() + NODE.encode(), None),
    "dash.lp": ((NODE + "init(object(node,2),value(at,(2,1)))\u2014\n").encode(),  # the error is at the dash
                ":2: character '\u2014' (U+2014) outside a string or comment"),
    "nul.lp": (NODE.encode() + b"init(object(node,2),\x00value(at,(2,1))).\n",
               ":2: not a text file (it holds a NUL byte)"),
}


def reader_survives(path) -> bool:
    """Whether reading ``path`` ends in the reader (an instance, or InputError), not in an abort."""
    code = ("import sys\nfrom asprilo.errors import InputError\nfrom asprilo.reader import read_instance\n"
            f"try:\n    read_instance({str(path)!r})\nexcept InputError:\n    pass\n")
    return subprocess.run([sys.executable, "-c", code], capture_output=True, timeout=60).returncode == 0


@pytest.fixture
def edited(window, tmp_path):
    """The small example opened and edited (a robot added): unsaved edits."""
    assert window.open_files([str(SMALL_A)])
    assert window.editor.add("robot", (2, 2))
    assert window.state.document.modified
    return window


def kept(window) -> bool:
    """The edited example is still shown, its edit unsaved, and nobody was asked to drop it."""
    return (window.scenario.title == SMALL_A.name and 4 in window.state.document.instance.robots
            and window.state.document.modified and window.track.robot_ids == [1, 2, 3, 4]
            and window.windowTitle().startswith("*") and not window.questions)


@pytest.mark.parametrize("name", sorted(BAD_FILES))
def test_opening_a_bad_file_reports_it_and_keeps_the_unsaved_edits(edited, tmp_path, name):
    data, said = BAD_FILES[name]
    path = tmp_path / name
    path.write_bytes(data)
    assert not edited.open_files([str(path)])
    assert edited.last_error.startswith(f"{path}{said}")
    assert kept(edited)


@pytest.mark.parametrize("name", ["dash.lp", "nul.lp"])
def test_files_the_core_reader_once_aborted_on_are_reported_and_keep_the_window(edited, tmp_path, name):
    data, said = ONCE_ABORTING[name]
    path = tmp_path / name
    path.write_bytes(data)
    assert reader_survives(path), "the core reader aborts on this file again (issue 15)"
    assert not edited.open_files([str(path)])
    assert edited.last_error.startswith(f"{path}{said}")
    assert kept(edited)


def test_a_file_with_a_byte_order_mark_the_core_reader_once_aborted_on_is_opened(edited, tmp_path):
    data, said = ONCE_ABORTING["bom.lp"]
    path = tmp_path / "bom.lp"
    path.write_bytes(data)
    assert said is None and reader_survives(path), "the core reader aborts on this file again (issue 15)"
    assert edited.open_files([str(path)])  # after asking about the unsaved edits
    assert edited.questions == ["The instance has unsaved edits. Discard them?"]
    assert edited.scenario.title == "bom.lp" and edited.state.document.instance.nodes == {1: (1, 1)}


def test_dropping_a_bad_file_reports_it_and_keeps_the_unsaved_edits(edited, tmp_path):
    path = tmp_path / "latin1.lp"
    path.write_bytes(BAD_FILES["latin1.lp"][0])
    data = QMimeData()
    data.setUrls([QUrl.fromLocalFile(str(path))])
    edited.dropEvent(QDropEvent(QPoint(100, 100), Qt.CopyAction, data, Qt.LeftButton, Qt.NoModifier))
    assert edited.last_error == f"{path}:2: not a UTF-8 text file (byte 0xfc cannot be read)"
    assert kept(edited)


def test_reloading_a_file_that_went_bad_keeps_what_is_shown(window, tmp_path):
    path = tmp_path / "instance.lp"
    path.write_text(SMALL_A.read_text())
    assert window.open_files([str(path)])
    window.go_to(0)
    path.write_bytes(BAD_FILES["syntax.lp"][0])
    assert not window.files.reload()
    assert window.last_error.startswith(f"{path}:3: syntax error")
    assert window.scenario.title == "instance.lp" and window.track.robot_ids == [1, 2, 3]


def test_a_huge_error_message_is_shortened_in_the_dialog(window):
    window.state.report_error("x" * 5000)
    box = next(w for w in window.findChildren(QMessageBox) if w.isVisible())
    assert len(box.text()) == 600 + len(" … ") and window.last_error == "x" * 5000


# --- servers that misbehave ----------------------------------------------------------------------------

class BadServer:
    """A real local socket server: it accepts one client, reads its lines until the client
    asks for step 1 (``%$done(0).``), then sends ``answer`` and keeps the connection open."""

    def __init__(self, answer: bytes):
        self.answer = answer
        self.listener = socket.create_server(("127.0.0.1", 0))
        self.port = self.listener.getsockname()[1]
        self.received: list[str] = []
        self.done = threading.Event()
        self.thread = threading.Thread(target=self._serve, daemon=True)
        self.thread.start()

    def _serve(self) -> None:
        self.listener.settimeout(WAIT_MS / 1000)
        connection, _ = self.listener.accept()
        with connection, connection.makefile("rb") as lines:
            for line in lines:
                self.received.append(line.decode())
                if line.startswith(b"%$done(0)."):
                    connection.sendall(self.answer)
                    break
            self.done.wait(WAIT_MS / 1000)

    def close(self) -> None:
        self.done.set()
        self.thread.join(WAIT_MS / 1000)
        self.listener.close()


def session_with(window, qtbot, answer: bytes) -> str:
    """Run a session against a server that answers ``answer``; why it ended."""
    window.editor.new_instance(2, 1)
    window.editor.add("robot", (1, 1))
    server = BadServer(answer)
    try:
        assert window.live.connect_to("127.0.0.1", server.port) is not None
        qtbot.waitUntil(lambda: window.live.session is None, timeout=WAIT_MS)
    finally:
        server.close()
    assert server.received[0] == "%$RESET.\n" and server.received[-1] == "%$done(0).\n"
    assert window.isVisible() and window.track.robot_ids == [1]  # the window and its world live on
    assert window.editor.palette.isEnabled() and window.live.commands["connect"].isEnabled()
    return window.live.last_reason


def test_a_byte_that_is_not_utf8_ends_the_session_not_the_window(window, qtbot):
    reason = session_with(window, qtbot, b"occurs(object(robot,1),action(move,(1,0)),1). \xff\n")
    assert reason.endswith("sent bytes that are not UTF-8 (0xFF at byte 47 of a line)")  # 46 ASCII bytes before
    assert reason.startswith("the solver at 127.0.0.1:")


def test_an_answer_the_reader_refuses_ends_the_session(window, qtbot):
    reason = session_with(window, qtbot, b"occurs(object(robot,1),action(move,(1,0))),1).\n")
    assert reason.startswith("the solver sent no actions: <solver>:1: syntax error")


def test_a_deep_term_ends_the_session(window, qtbot):
    reason = session_with(window, qtbot, f"occurs(object(robot,1),action(move,{deep_tuple(3000)}),1).\n".encode())
    assert reason.startswith("the solver sent no actions: ")


def test_a_huge_line_ends_the_session_before_it_ends(window, qtbot, monkeypatch):
    monkeypatch.setattr(network, "MAX_LINE_BYTES", 2**20)
    reason = session_with(window, qtbot, b"a" * (3 * 2**20))
    assert reason.endswith(" sent a line longer than 1 MB")


def test_a_malformed_control_word_ends_the_session(window, qtbot):
    reason = session_with(window, qtbot, b"%$done(x).\n")
    assert reason.endswith(" sent a bad message: unknown control word in '%$done(x).'")


def test_an_unexpected_error_is_reported_and_the_window_goes_on(window, capsys):
    from asprilo.visualizer.cli import report_exceptions_to
    try:
        raise ValueError("boom")
    except ValueError as error:
        report_exceptions_to(window)(ValueError, error, error.__traceback__)
    assert window.last_error == ("Something went wrong inside the viewer (ValueError: boom). "
                                 "It goes on; the details are on standard error.")
    assert capsys.readouterr().err.startswith("Traceback (most recent call last):")
