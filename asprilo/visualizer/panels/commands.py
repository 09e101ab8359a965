"""Menu commands from tables: each part of the window names its commands, their menu texts
and shortcuts in one table, and gets back one QAction per command, shortcut active."""

from __future__ import annotations

from collections.abc import Callable
from html import escape
from itertools import zip_longest

from PyQt5.QtCore import Qt
from PyQt5.QtGui import QKeySequence
from PyQt5.QtWidgets import (
    QAction,
    QDialog,
    QDialogButtonBox,
    QLabel,
    QMainWindow,
    QMenu,
    QMenuBar,
    QVBoxLayout,
    QWidget,
)

from .screen import fit_dialog, scrolling

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


def submenu(parent: QMenu | QMenuBar, title: str) -> QMenu:
    """A menu in ``parent`` made here, not by ``parent.addMenu(title)``: Qt deletes the menus
    it makes without telling Python, and the wrapper Python keeps may then be handed out for
    a new menu at the same address (a crash); a menu made here tells its wrapper."""
    menu = QMenu(title, parent)
    parent.addMenu(menu)
    return menu


def menu_entry(menu: QMenu, text: str) -> QAction:
    """An entry of ``menu`` made here, for the reason :func:`submenu` gives (entries of menus
    filled again each time they open are deleted by ``clear()``)."""
    action = QAction(text, menu)
    menu.addAction(action)
    return action


def plain(text: str) -> str:
    """A menu text without its mnemonic ``&`` and its trailing ``…``."""
    return text.replace("&", "").rstrip("…")


def shortcut_rows(window: QMainWindow) -> list[tuple[str, str]]:
    """``(command, keys)`` of every command of the window that has a shortcut, menu order aside.

    The window's own actions (``make_actions`` adds each to its owner), not every QAction in its
    tree: Qt's internal ones (a text field's menu, a dialog being deleted) are none of ours."""
    rows: dict[str, str] = {}
    for action in window.actions():
        keys = [key.toString() for key in action.shortcuts()]
        if keys and action.text():
            rows.setdefault(plain(action.text()), ", ".join(keys))
    return list(rows.items())


def shortcuts_dialog(window: QMainWindow) -> QDialog:
    """A dialog listing every command with its keys in two columns, and what the mouse does;
    as tall as the screen allows (the list scrolls on a smaller one), OK always in view."""
    rows = shortcut_rows(window)
    half = (len(rows) + 1) // 2

    def cells(row: tuple[str, str] | None) -> str:
        return f"<td>{escape(row[0])}</td><td><b>{escape(row[1])}</b></td>" if row else "<td></td><td></td>"

    lines = "".join(f"<tr>{cells(left)}<td width=20></td>{cells(right)}</tr>"
                    for left, right in zip_longest(rows[:half], rows[half:]))
    text = QLabel(f"<table cellspacing=3>{lines}</table>"
                  "<p>Mouse: wheel zooms, drag pans, click selects a robot "
                  "(Ctrl+click: several), hover shows details.</p>")
    text.setTextFormat(Qt.TextFormat.RichText)
    text.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
    text.setContentsMargins(8, 8, 8, 8)
    dialog = QDialog(window)
    dialog.setWindowTitle("Keyboard shortcuts")
    layout = QVBoxLayout(dialog)
    layout.addWidget(scrolling(text, dialog), 1)
    buttons = QDialogButtonBox(QDialogButtonBox.Ok, dialog)
    buttons.accepted.connect(dialog.accept)
    layout.addWidget(buttons)
    fit_dialog(dialog)
    return dialog


def show_shortcuts(window: QMainWindow) -> None:
    """Open the list of every command with its keys (not blocking)."""
    dialog = shortcuts_dialog(window)
    dialog.setAttribute(Qt.WidgetAttribute.WA_DeleteOnClose)
    dialog.open()
