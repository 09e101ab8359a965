"""Menu commands from tables: each part of the window names its commands, their menu texts
and shortcuts in one table, and gets back one QAction per command, shortcut active."""

from __future__ import annotations

from collections.abc import Callable
from html import escape

from PyQt5.QtCore import Qt
from PyQt5.QtGui import QKeySequence
from PyQt5.QtWidgets import QAction, QMainWindow, QMessageBox, QWidget

#: name -> (menu text, shortcuts); the first shortcut is the one menus show
Table = dict[str, tuple[str, tuple[str, ...]]]


def make_actions(owner: QWidget, table: Table, slots: dict[str, Callable[[], object]]) -> dict[str, QAction]:
    """One action per entry of ``table``, calling ``slots[name]``, its shortcuts active in ``owner``."""
    actions = {}
    for name, (text, keys) in table.items():
        action = QAction(text, owner)
        action.setShortcuts([QKeySequence(key) for key in keys])
        action.setToolTip(f"{plain(text)} ({keys[0]})" if keys else plain(text))
        action.triggered.connect(lambda _checked=False, slot=slots[name]: slot())
        owner.addAction(action)
        actions[name] = action
    return actions


def plain(text: str) -> str:
    """A menu text without its mnemonic ``&`` and its trailing ``…``."""
    return text.replace("&", "").rstrip("…")


def shortcut_rows(window: QMainWindow) -> list[tuple[str, str]]:
    """``(command, keys)`` of every command of the window that has a shortcut, menu order aside."""
    rows = {}
    for action in window.findChildren(QAction):
        keys = [key.toString() for key in action.shortcuts()]
        if keys and action.text():
            rows.setdefault(plain(action.text()), ", ".join(keys))
    return list(rows.items())


def show_shortcuts(window: QMainWindow) -> None:
    """A window listing every command with its keys, and what the mouse does."""
    rows = "".join(f"<tr><td>{escape(text)}</td><td><b>{escape(keys)}</b></td></tr>"
                   for text, keys in shortcut_rows(window))
    box = QMessageBox(QMessageBox.Information, "Keyboard shortcuts",
                      f"<table cellspacing=4>{rows}</table>"
                      "<p>Mouse: wheel zooms, drag pans, click selects a robot "
                      "(Ctrl+click: several), hover shows details.</p>", QMessageBox.Ok, window)
    box.setAttribute(Qt.WA_DeleteOnClose)
    box.open()
