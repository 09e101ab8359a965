"""The viewer's main window for GUI tests (import after QT_QPA_PLATFORM is set)."""

from __future__ import annotations

from PyQt5.QtCore import QSettings

from asprilo.visualizer.window import MainWindow


def shown_window(qtbot, tmp_path_factory, size: tuple[int, int] | None = None) -> MainWindow:
    """A main window with settings of its own (a fresh ini file), shown and exposed."""
    settings = QSettings(str(tmp_path_factory.mktemp("settings") / "viz.ini"), QSettings.IniFormat)
    window = MainWindow(settings)
    qtbot.addWidget(window)
    if size is not None:
        window.resize(*size)
    window.show()
    qtbot.waitExposed(window)
    return window
