"""A strip of states for slides and exam sheets: the states after steps FIRST..LAST side by
side, each captioned (``state after step 12 of 29``), wrapping into rows.

    viz INSTANCE PLAN --export strip.png --strip 3-8 [--columns 3] [--cell 40]

Every panel is the picture a PNG export of that state would be (``cell`` pixels per cell,
a quarter-cell margin) with its caption band below it, captioned as picture exports are
(:func:`~.images.picture_caption`, the window's time display); panels are ``gap`` pixels
apart on white.  By default as many panels go in a row as fit in
:data:`~.images.MAX_SIDE` pixels (at least one), and a cell has the animations' 48 pixels
(less for big warehouses; a picture's 128 would put one panel in a row), fewer where the
whole strip would exceed :data:`STRIP_PIXELS`; a strip that cannot fit (a cell size given,
or even 2-pixel cells too big) is refused in words.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from PyQt5.QtCore import QObject, QSettings, QSize, Qt
from PyQt5.QtGui import QImage, QPainter
from PyQt5.QtWidgets import QDialog, QDialogButtonBox, QFileDialog, QFormLayout, QSpinBox, QWidget

from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.model import Instance, Plan
from asprilo.writer import write_bytes

from ..panels.files import start_folder
from ..scene.animator import Animator
from ..scene.stage import Stage
from ..scene.warehouse import WarehouseScene
from ..state.viewer import ViewerState
from . import images

#: the most pixels a strip may have (width x height)
STRIP_PIXELS = 16_000_000
#: the formats a strip is written in
STRIP_FORMATS = (".png", ".jpg", ".jpeg")
#: the smallest cell size a strip is shrunk to
SMALLEST_CELL_PX = 2

Progress = Callable[[int, int], None]


@dataclass(frozen=True)
class StripLayout:
    """Where the panels of a strip go: ``columns`` x ``rows`` panels of ``panel`` pixels
    (the picture and its caption band), ``gap`` pixels apart, filled row by row."""

    panel_width: int
    panel_height: int
    columns: int
    rows: int
    gap: int

    @property
    def width(self) -> int:
        return self.columns * self.panel_width + (self.columns - 1) * self.gap

    @property
    def height(self) -> int:
        return self.rows * self.panel_height + (self.rows - 1) * self.gap

    def origin(self, index: int) -> tuple[int, int]:
        """The top-left pixel of panel ``index`` (0: the first step)."""
        row, column = divmod(index, self.columns)
        return column * (self.panel_width + self.gap), row * (self.panel_height + self.gap)


def gap_px(cell_px: int) -> int:
    """Pixels between two panels: a quarter cell, at least 4."""
    return max(4, cell_px // 4)


def strip_layout(scene: WarehouseScene, cell_px: int, count: int, columns: int | None = None) -> StripLayout:
    """The layout of ``count`` panels of ``scene`` at ``cell_px`` (``columns``: as many as
    fit in ``MAX_SIDE`` pixels when not given)."""
    panel = images.image_size(scene, cell_px, caption=True)
    gap = gap_px(cell_px)
    if columns is None:
        columns = max(1, (images.MAX_SIDE + gap) // (panel.width() + gap))
    columns = max(1, min(columns, count))
    return StripLayout(panel.width(), panel.height(), columns, math.ceil(count / columns), gap)


def strip_cell_px(scene: WarehouseScene, count: int, columns: int | None = None) -> int:
    """The picture export's cell size, lowered a pixel at a time until the strip fits in
    ``STRIP_PIXELS`` (down to ``SMALLEST_CELL_PX``)."""
    cell_px = images.default_cell_px(scene)
    while cell_px > SMALLEST_CELL_PX and _pixels(strip_layout(scene, cell_px, count, columns)) > STRIP_PIXELS:
        cell_px -= 1
    return cell_px


def _pixels(layout: StripLayout) -> int:
    return layout.width * layout.height


def render_strip(animator: Animator, steps: list[int], cell_px: int | None = None, columns: int | None = None,
                 progress: Progress | None = None) -> QImage:
    """The states after ``steps`` side by side, captioned, in rows.  The animator is left
    showing the time it showed before."""
    if not steps:
        raise InputError("a strip needs at least one step")
    scene, horizon = animator.scene, animator.track.horizon
    cell_px = cell_px or strip_cell_px(scene, len(steps), columns)
    layout = strip_layout(scene, cell_px, len(steps), columns)
    if _pixels(layout) > STRIP_PIXELS:
        raise InputError(f"a strip of {len(steps)} states at {cell_px} pixels per cell would be "
                         f"{layout.width}x{layout.height} pixels, more than {STRIP_PIXELS:,} in all: "
                         "give fewer steps, more --columns or a smaller --cell")
    image = QImage(QSize(layout.width, layout.height), QImage.Format_RGB32)
    image.fill(Qt.GlobalColor.white)
    painter = QPainter(image)
    shown = animator.time
    try:
        with images._detail_for(scene, cell_px):
            for index, step in enumerate(steps):
                animator.show(float(step))
                x, y = layout.origin(index)
                painter.drawImage(x, y, images.render(scene, cell_px, images.picture_caption(float(step), horizon)))
                if progress is not None:
                    progress(index + 1, len(steps))
    finally:
        painter.end()
        animator.show(shown)
    return image


def strip_steps(first: int, last: int, horizon: int) -> list[int]:
    """Steps ``first``..``last``, checked against the plan (else :class:`InputError`)."""
    if first > last:
        raise InputError(f"--strip {first}-{last}: the first step comes after the last")
    if last > horizon:
        raise InputError(f"--strip {first}-{last} lies beyond the plan, whose last step is {horizon}")
    return list(range(first, last + 1))


def save_strip(path: str | Path, animator: Animator, first: int, last: int, cell_px: int | None = None,
               columns: int | None = None, progress: Progress | None = None) -> QSize:
    """Write the strip of the states after ``first``..``last`` to a PNG or JPEG file; its size."""
    suffix = Path(path).suffix.lower()
    if suffix not in STRIP_FORMATS:
        raise InputError(f"a strip is a picture: use .png or .jpg, not '{suffix or 'no suffix'}'", str(path))
    image = render_strip(animator, strip_steps(first, last, animator.track.horizon), cell_px, columns, progress)
    write_bytes(path, images._encoded(image, "PNG" if suffix == ".png" else "JPEG"))
    return image.size()


# --- File > Export strip in the window ----------------------------------------------------------

class StripDialog(QDialog):
    """Asks for the first and the last step of a strip, and the panels per row."""

    def __init__(self, horizon: int, step: int, parent: QWidget | None = None):
        super().__init__(parent)
        self.setWindowTitle("Export strip")
        self.first, self.last, self.columns = QSpinBox(self), QSpinBox(self), QSpinBox(self)
        self.first.setRange(0, horizon)
        self.last.setRange(0, horizon)
        self.first.setValue(min(step, horizon))
        self.last.setValue(min(step + 5, horizon))
        self.first.valueChanged.connect(lambda value: self.last.setValue(max(self.last.value(), value)))
        self.last.valueChanged.connect(lambda value: self.first.setValue(min(self.first.value(), value)))
        self.columns.setRange(0, 50)
        self.columns.setSpecialValueText("as many as fit")
        form = QFormLayout(self)
        form.addRow("From the state after step", self.first)
        form.addRow("to the state after step", self.last)
        form.addRow("Panels per row", self.columns)
        buttons = QDialogButtonBox(QDialogButtonBox.Ok | QDialogButtonBox.Cancel, self)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        form.addRow(buttons)

    def choice(self) -> tuple[int, int, int | None]:
        return self.first.value(), self.last.value(), self.columns.value() or None


class StripExport(QObject):
    """File > Export strip: asks for the steps and the file, renders the stage's scene."""

    def __init__(self, state: ViewerState, stage: Stage, settings: QSettings, parent: QWidget):
        super().__init__(parent)
        self.state, self.stage, self.settings, self.parent_widget = state, stage, settings, parent

    def ask(self) -> None:
        track = self.state.track
        if self.stage.animator is None or track is None:
            return
        dialog = StripDialog(track.horizon, self.state.step, self.parent_widget)
        if dialog.exec_() != QDialog.Accepted:
            return
        first, last, columns = dialog.choice()
        path, _ = QFileDialog.getSaveFileName(self.parent_widget, "Export strip", start_folder(self.settings),
                                              "PNG image (*.png);;JPEG image (*.jpg)")
        if path:
            self.save(path, first, last, columns)

    def save(self, path: str, first: int, last: int, columns: int | None = None) -> bool:
        """Save the strip of the states after ``first``..``last`` as the window shows them
        (goals, selection, highlighted violation)."""
        if self.stage.animator is None:
            return False
        try:
            size = save_strip(path, self.stage.animator, first, last, columns=columns)
        except InputError as error:
            self.state.report_error(str(error))
            return False
        self.state.say(f"saved {path}: steps {first}–{last}, {size.width()}x{size.height()}")
        return True


# --- without a window ---------------------------------------------------------------------------

def export_strip(instance: Instance, plan: Plan, path: str | Path, first: int, last: int,
                 domain: Domain | None = None, columns: int | None = None, cell: int | None = None) -> str:
    """Write the strip of the states after ``first``..``last`` of ``plan`` on ``instance``
    (PNG or JPEG) without a window; returns a short description of what was written."""
    if not os.environ.get("DISPLAY") and not os.environ.get("WAYLAND_DISPLAY"):
        os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from ..state.track import Track
    from .render import application

    app = application()  # noqa: F841 (Qt objects below need it alive)
    track = Track(instance, plan, domain)
    scene = WarehouseScene(instance)
    animator = Animator(scene, track)
    try:
        size = save_strip(path, animator, first, last, cell, columns)
        return f"{size.width()}x{size.height()}, the states after steps {first} to {last}"
    finally:
        del animator, scene  # before the application goes
