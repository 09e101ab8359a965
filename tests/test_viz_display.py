"""viz checks for a display and for the system libraries of Qt's xcb plugin before Qt
starts: one line saying what to install or to do instead, exit 2, never Qt's abort."""

from __future__ import annotations

import os
import socket
import subprocess
import sys
from pathlib import Path

import pytest
from helpers import OUTCOME

from asprilo.visualizer.state import display
from asprilo.visualizer.state.display import HEADLESS, INSTALL, window_problem, x_server_answers

NO_DISPLAY = f"no display to open a window on (DISPLAY is not set): {HEADLESS}"
linux = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="Qt uses xcb on Linux only")


def loader(missing: set[str], plugin_error: str = ""):
    """A stand-in for ctypes.CDLL: libraries in ``missing`` and the plugin fail to load."""
    def load(name: str) -> object:
        if name.endswith("libqxcb.so") and plugin_error:
            raise OSError(plugin_error)
        if name in missing:
            raise OSError(f"{name}: cannot open shared object file: No such file or directory")
        return object()
    return load


@linux
def test_without_a_display_viz_says_what_to_do_instead():
    assert window_problem({}, loader(set())) == NO_DISPLAY
    assert window_problem({"QT_QPA_PLATFORM": "xcb"}, loader(set())) == NO_DISPLAY
    for platform in ("offscreen", "wayland", "vnc"):
        assert window_problem({"QT_QPA_PLATFORM": platform}, loader(set())) is None


@linux
def test_missing_libraries_are_named_with_the_line_that_installs_them(monkeypatch):
    monkeypatch.setattr(display, "xcb_plugin", lambda: Path("/somewhere/platforms/libqxcb.so"))
    gone = {"libxcb-icccm.so.4", "libxcb-keysyms.so.1", "libxcb-xinerama.so.0"}  # stock Debian 12 lacks these
    load = loader(gone, "libxcb-icccm.so.4: cannot open shared object file: No such file or directory")
    assert window_problem({"DISPLAY": ":0"}, load) == (
        "Qt cannot open a window: the system lacks libxcb-icccm.so.4, libxcb-keysyms.so.1, libxcb-xinerama.so.0; "
        f"on Debian or Ubuntu: {INSTALL}; or, without a window, {HEADLESS}")
    for package in ("libxcb-icccm4", "libxcb-keysyms1", "libxcb-xinerama0", "libgl1", "libxkbcommon-x11-0"):
        assert f" {package}" in INSTALL
    # a library the table does not know: the one the plugin's loader named
    assert display.missing_libraries(loader(set(), "libfoo.so.3: cannot open shared object file")) == ["libfoo.so.3"]
    monkeypatch.setattr(display, "xcb_plugin", lambda: None)  # not a PyQt5 wheel: nothing to check
    assert display.missing_libraries(loader(gone, "x")) == []


def test_an_x_server_is_looked_for_where_display_points():
    listener = socket.create_server(("127.0.0.1", 0))
    port = listener.getsockname()[1]
    try:
        assert x_server_answers(f"127.0.0.1:{port - 6000}")
        assert x_server_answers(f"127.0.0.1:{port - 6000}.0")
    finally:
        listener.close()
    assert not x_server_answers(f"127.0.0.1:{port - 6000}")
    assert x_server_answers("/private/tmp/com.apple.launchd.x/org.xquartz:0")  # a form it does not know


@linux
def test_viz_without_a_display_exits_2_with_one_line():
    env = {key: value for key, value in os.environ.items() if key not in ("DISPLAY", "QT_QPA_PLATFORM")}
    result = subprocess.run([sys.executable, "-m", "asprilo.cli", "viz", str(OUTCOME)], capture_output=True,
                            text=True, env=env, timeout=60)
    assert (result.returncode, result.stderr) == (2, f"error: {NO_DISPLAY}\n")


def test_a_qt_that_cannot_load_is_one_line_too(tmp_path):
    fake = tmp_path / "PyQt5"  # stands in for a PyQt5 whose Qt lacks libGL, as on a bare server
    fake.mkdir()
    (fake / "__init__.py").write_text("")
    (fake / "QtWidgets.py").write_text("raise ImportError('libGL.so.1: cannot open shared object file: "
                                       "No such file or directory')\n")
    env = {**os.environ, "PYTHONPATH": str(tmp_path)}
    result = subprocess.run([sys.executable, "-m", "asprilo.cli", "viz", str(OUTCOME), "--export",
                             str(tmp_path / "out.png")], capture_output=True, text=True, env=env, timeout=60)
    assert (result.returncode, result.stderr) == (
        2, "error: Qt cannot be loaded (libGL.so.1: cannot open shared object file: No such file or directory); "
           f"on Debian or Ubuntu: {INSTALL}\n")
    assert not (tmp_path / "out.png").exists()
