"""Windows and dialogs that fit the screen, frame included: a 1366x768 laptop, a projector.

Sizes come from the available area of the widget's screen (``QScreen.availableGeometry``:
the screen less panels and docks), less the room the window manager's frame takes (a title
bar of 20 pixels).  Dialogs taller than that room scroll.
"""

from __future__ import annotations

from PyQt5.QtCore import QMargins, QRect, QSize, Qt
from PyQt5.QtWidgets import QAbstractScrollArea, QApplication, QScrollArea, QScrollBar, QWidget

#: room left around a window for the window manager's frame (a title bar of 20 pixels)
FRAME = QMargins(0, 20, 0, 0)


def available(widget: QWidget | None = None) -> QRect:
    """The available area of the screen ``widget`` is on (or will open on), frame not taken off."""
    screen = None
    if widget is not None:
        parent = widget.parentWidget()
        top = parent.window() if parent is not None else widget
        screen = top.screen() if top is not None else None
    if screen is None:
        screen = QApplication.primaryScreen()
    return screen.availableGeometry() if screen is not None else QRect(0, 0, 1366, 768)


def room(widget: QWidget | None = None) -> QRect:
    """Where a window's contents may go on its screen: the available area less the frame."""
    return available(widget).marginsRemoved(FRAME)


def fit(widget: QWidget, width: int, height: int) -> QSize:
    """Resize ``widget`` to ``width`` x ``height``, or less where its screen has less room."""
    space = room(widget)
    size = QSize(min(width, space.width()), min(height, space.height()))
    widget.resize(size)
    return size


def fit_dialog(dialog: QWidget) -> QSize:
    """Give a dialog the size it asks for, but no more than its screen's room (its scroll
    areas take the rest); Qt opens it centred on its parent and moves it onto the screen."""
    hint = dialog.sizeHint().expandedTo(dialog.minimumSizeHint())
    return fit(dialog, hint.width(), hint.height())


def scrolling(body: QWidget, parent: QWidget | None = None) -> QScrollArea:
    """``body`` in a scroll area that asks for the whole of ``body`` (``fit_dialog`` then
    takes what the screen lacks from it)."""
    area = _WholeScrollArea(parent)
    area.setWidget(body)
    area.setWidgetResizable(True)
    return area


def own_scroll_bar(area: QAbstractScrollArea) -> QScrollBar:
    """A vertical scroll bar for ``area`` made here, for the reason ``commands.submenu`` gives
    for menus: Qt deletes the bar it made without telling Python, and a wrapper Python kept
    may be handed out again for another object at the same address (CI crashed once asking
    a note's bar for its width while a new window was laid out); a bar made here tells its
    wrapper (``area.verticalScrollBar()`` then hands out the same)."""
    bar = QScrollBar(Qt.Orientation.Vertical, area)
    area.setVerticalScrollBar(bar)
    return bar


class _WholeScrollArea(QScrollArea):
    """A scroll area whose size hint is its contents' whole size (Qt's stops at 36 lines)."""

    def __init__(self, *args) -> None:
        super().__init__(*args)
        self.bar = own_scroll_bar(self)

    def sizeHint(self) -> QSize:
        inner = self.widget()
        if inner is None:
            return super().sizeHint()
        frame = 2 * self.frameWidth()
        hint = inner.sizeHint()
        return QSize(hint.width() + frame + self.bar.sizeHint().width(), hint.height() + frame)
