"""Pictures (PNG, JPEG, SVG) and animations (GIF, MP4) of the scene, with or without a window.

Files are rendered in memory and written atomically (``asprilo.writer.write_bytes``), so
an interrupted export never leaves half a file.  MP4 needs PyAV (``pip install av``).

Exports stay within the budgets of :mod:`asprilo.limits` (``--limit NAME=N``), checked
before anything is drawn: ``pixels`` for a picture and for each frame of an animation,
``frames`` and ``animation-pixels`` (all frames together: a GIF keeps every frame until it
is encoded) for an animation.
"""

from __future__ import annotations

import importlib.util
import io
import math
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from fractions import Fraction
from pathlib import Path

from PyQt5.QtCore import QBuffer, QIODevice, QRectF, QSize, Qt
from PyQt5.QtGui import QFontMetricsF, QImage, QPainter

from asprilo.errors import InputError
from asprilo.limits import current
from asprilo.model import Instance
from asprilo.writer import write_bytes

from ..panels.controls import time_text
from ..scene import style
from ..scene.animator import Animator
from ..scene.style import CELL
from ..scene.warehouse import WarehouseScene

PICTURES = (".png", ".jpg", ".jpeg", ".svg")
ANIMATIONS = (".gif", ".mp4")
#: Largest side of an export in pixels when no cell size is given.
MAX_SIDE = 2000
#: Pixels per cell of an animation (every frame is kept until the file is encoded).
DEFAULT_CELL_PX = 48
#: Pixels per cell of a picture, for slides and projectors: an 11x6 floor 1472 px wide, its
#: labels (a fifth of a cell) 26 px high; big floors get less (``MAX_SIDE``).
PICTURE_CELL_PX = 128
#: The caption line's height in pixels at most.
MAX_CAPTION_PX = 48
#: Cells of margin around the floor in a picture (``WarehouseScene.picture_rect``'s default).
PICTURE_MARGIN = 0.25
#: The longest side of a JPEG picture Qt writes (libjpeg's limit).
JPEG_SIDE = 65_500

Progress = Callable[[int, int], None]


def export_format(path: str | Path) -> str:
    """The export's format from the file name; unknown suffixes are bad input."""
    suffix = Path(path).suffix.lower()
    if suffix not in PICTURES + ANIMATIONS:
        raise InputError(f"cannot export '{suffix or 'no suffix'}': use .png, .jpg, .svg, .gif or .mp4",
                         str(path))
    return suffix


def default_cell_px(scene: WarehouseScene, largest: int = DEFAULT_CELL_PX) -> int:
    """Pixels per cell: ``largest`` (48 for animations, ``PICTURE_CELL_PX`` for pictures),
    less for big warehouses so the longest side stays under 2000 px."""
    rect = scene.picture_rect()
    return _cell_px_for(max(rect.width(), rect.height()) / CELL, largest)


def _cell_px_for(cells: float, largest: int) -> int:
    """Pixels per cell for a picture ``cells`` cells long at its longest side."""
    return max(2, min(largest, int(MAX_SIDE / cells)))


def image_size(scene: WarehouseScene, cell_px: int, caption: bool = False) -> QSize:
    """The picture's size at ``cell_px`` pixels per cell: at most ``pixels`` pixels (the
    limit; else :class:`InputError`, before anything is drawn)."""
    rect = scene.picture_rect()
    return QSize(*_picture_size(rect.width() / CELL, rect.height() / CELL, cell_px, caption))


def _picture_size(width_cells: float, height_cells: float, cell_px: int, caption: bool) -> tuple[int, int]:
    """The size in pixels of a picture ``width_cells`` x ``height_cells`` cells large, within
    the limit ``pixels`` (else :class:`InputError`)."""
    width = round(width_cells * cell_px)
    height = round(height_cells * cell_px) + (caption_height(cell_px) if caption else 0)
    limits = current()
    if width * height > limits.pixels:
        raise limits.exceeded("pixels", f"a picture of {width:,}x{height:,} pixels ({cell_px:,} per cell; "
                                        f"a smaller --cell makes it smaller)")
    return width, height


def check_budget(instance: Instance, suffix: str, cell_px: int | None, horizon: int, frames_per_step: int) -> None:
    """Refuse an export beyond the limits ``pixels``, ``frames`` and ``animation-pixels``
    from the instance alone, before its scene and floor image are made (a floor of
    10000x10000 cells takes most of a GB to draw): the floor with the margins of
    ``WarehouseScene.picture_rect`` is the least a picture of it shows."""
    cells = [*instance.nodes.values(), *instance.highways.values()]
    if not cells:
        return
    width = max(x for x, _ in cells) + 2 * PICTURE_MARGIN
    height = max(y for _, y in cells) + 2 * PICTURE_MARGIN
    animation = suffix in ANIMATIONS
    cell_px = cell_px or _cell_px_for(max(width, height), DEFAULT_CELL_PX if animation else PICTURE_CELL_PX)
    size = _picture_size(width, height, cell_px, caption=animation)
    if animation:
        check_animation(animation_frames(horizon, frames_per_step), QSize(*size))


def caption_height(cell_px: int) -> int:
    return max(18, min(MAX_CAPTION_PX, cell_px // 2))


@contextmanager
def _detail_for(scene: WarehouseScene, cell_px: int) -> Iterator[None]:
    """Give the scene the look that suits ``cell_px`` while exporting (outlines, the labels
    that can be read), then the one it had."""
    fine, labels, label_px = scene.fine, scene.labels_on, scene.label_cell_px
    scene.set_detail(cell_px >= style.FINE_DETAIL_PX)
    scene.show_labels(labels, cell_px)
    try:
        yield
    finally:
        scene.set_detail(fine)
        scene.show_labels(labels, label_px)


def render(scene: WarehouseScene, cell_px: int, caption: str | None = None) -> QImage:
    """The scene as an image, ``cell_px`` pixels per cell, with an optional caption line below."""
    size = image_size(scene, cell_px, caption is not None)
    image = QImage(size, QImage.Format_ARGB32_Premultiplied)
    if image.isNull():  # Qt could not allocate it
        raise InputError(f"a picture of {size.width():,}x{size.height():,} pixels cannot be made "
                         f"(not enough memory); give a smaller --cell")
    image.fill(style.BACKGROUND)
    painter = QPainter(image)
    _paint(painter, scene, cell_px, size.width(), size.height(), caption)
    painter.end()
    return image


def _paint(painter: QPainter, scene: WarehouseScene, cell_px: int, width: int, height: int,
           caption: str | None) -> None:
    painter.setRenderHints(QPainter.Antialiasing | QPainter.TextAntialiasing)
    floor_height = height - (caption_height(cell_px) if caption is not None else 0)
    scene.render(painter, QRectF(0, 0, width, floor_height), scene.picture_rect(), Qt.IgnoreAspectRatio)
    if caption is not None:
        room = QRectF(cell_px * 0.25, floor_height, width - cell_px * 0.5, height - floor_height)
        font = style.font(caption_height(cell_px) * 0.6)
        wide = QFontMetricsF(font).horizontalAdvance(caption)
        if wide > room.width() > 0:  # a narrow floor: smaller letters, the whole caption
            font = style.font(max(1.0, font.pixelSize() * room.width() / wide))
        painter.setPen(style.CAPTION)
        painter.setFont(font)
        painter.drawText(room, Qt.AlignLeft | Qt.AlignVCenter, caption)


def step_caption(step: float, horizon: int) -> str:
    whole = math.floor(step + 1e-9)
    if step - whole > 1e-9:
        return f"step {whole} \u2192 {whole + 1} / {horizon}"
    return f"step {whole} / {horizon}"


def picture_caption(time: float, horizon: int) -> str:
    """The caption of a picture of the state at ``time``, as the window's time display says it:
    ``initial state (step 0 of 29)``, ``state after step 12 of 29``, ``step 12 → 13 of 29``
    (the one caption of pictures: ``save_picture``, File > Export picture)."""
    return time_text(time, horizon)


def save_picture(path: str | Path, scene: WarehouseScene, cell_px: int | None = None,
                 caption: str | None = None) -> QSize:
    """Write the scene as it stands to a PNG, JPEG or SVG file, with ``caption`` on a line
    below it if given; returns the picture's size."""
    suffix = export_format(path)
    if suffix not in PICTURES:
        raise InputError(f"{suffix} is an animation format; pictures are .png, .jpg or .svg", str(path))
    cell_px = cell_px or default_cell_px(scene, PICTURE_CELL_PX)
    size = image_size(scene, cell_px, caption is not None)
    with _detail_for(scene, cell_px):
        if suffix == ".svg":
            data = _svg(scene, cell_px, size, caption)
        else:
            data = _encoded(render(scene, cell_px, caption), "PNG" if suffix == ".png" else "JPEG")
    write_bytes(path, data)
    return size


def _encoded(image: QImage, form: str) -> bytes:
    """``image`` as a PNG or JPEG file's bytes (never none: :class:`InputError` if Qt cannot)."""
    if form == "JPEG" and max(image.width(), image.height()) > JPEG_SIDE:
        raise InputError(f"a JPEG picture is at most {JPEG_SIDE:,} pixels a side, this one would be "
                         f"{image.width():,}x{image.height():,}: write a .png, or give a smaller --cell")
    buffer = QBuffer()
    buffer.open(QIODevice.WriteOnly)
    if not image.save(buffer, form) or not buffer.size():
        raise InputError(f"a picture of {image.width():,}x{image.height():,} pixels cannot be written as {form}; "
                         f"give a smaller --cell")
    return bytes(buffer.data())


def _svg(scene: WarehouseScene, cell_px: int, size: QSize, caption: str | None = None) -> bytes:
    from PyQt5.QtSvg import QSvgGenerator
    buffer = QBuffer()
    generator = QSvgGenerator()
    generator.setOutputDevice(buffer)
    generator.setSize(size)
    generator.setResolution(96)  # so that viewers show it at its pixel size
    generator.setViewBox(QRectF(0, 0, size.width(), size.height()))
    generator.setTitle("asprilo warehouse")
    painter = QPainter(generator)
    painter.fillRect(QRectF(0, 0, size.width(), size.height()), style.BACKGROUND)
    _paint(painter, scene, cell_px, size.width(), size.height(), caption)
    painter.end()
    return bytes(buffer.data())


def animation_frames(horizon: int, frames_per_step: int) -> int:
    """How many frames :func:`animation_times` gives."""
    return max(0, horizon) * max(1, frames_per_step) + 1


def check_frames(frames: int) -> None:
    """Refuse an animation of ``frames`` frames beyond the limit ``frames`` (:class:`InputError`)."""
    limits = current()
    if frames > limits.frames:
        raise limits.exceeded("frames", f"an animation of {frames:,} frames")


def check_animation(frames: int, size: QSize) -> None:
    """Refuse an animation of ``frames`` frames of ``size`` beyond the limits ``frames`` and
    ``animation-pixels`` (:class:`InputError`), before any frame is drawn."""
    check_frames(frames)
    limits = current()
    pixels = frames * size.width() * size.height()
    if pixels > limits.animation_pixels:
        raise limits.exceeded("animation_pixels", f"an animation of {frames:,} frames of {size.width():,}x"
                                                  f"{size.height():,} pixels ({pixels:,} in all; a smaller --cell "
                                                  f"or fewer --frames make it smaller)")


def animation_times(horizon: int, frames_per_step: int) -> list[float]:
    """The times of the frames: every state, with ``frames_per_step - 1`` in-between frames."""
    frames = max(1, frames_per_step)
    return [step + k / frames for step in range(horizon) for k in range(frames)] + [float(horizon)]


def save_animation(path: str | Path, animator: Animator, frames_per_step: int = 1, speed: float = 2.0,
                   cell_px: int | None = None, progress: Progress | None = None) -> int:
    """Write all states of the plan as a GIF or MP4 (``speed`` in steps per second).

    Returns the number of frames.  The animator is left showing the time it showed before.
    """
    suffix = export_format(path)
    if suffix not in ANIMATIONS:
        raise InputError(f"{suffix} is a picture format; animations are .gif or .mp4", str(path))
    if suffix == ".mp4" and importlib.util.find_spec("av") is None:
        raise InputError("MP4 export needs PyAV (pip install av); .gif works without it", str(path))
    if not 0 < speed < math.inf:
        raise InputError(f"the speed must be a positive number of steps per second, got {speed:g}")
    scene, horizon = animator.scene, animator.track.horizon
    cell_px = cell_px or default_cell_px(scene)
    check_animation(animation_frames(horizon, frames_per_step), image_size(scene, cell_px, caption=True))
    times = animation_times(horizon, frames_per_step)
    frame_ms = 1000.0 / (max(speed, 0.01) * max(1, frames_per_step))
    shown = animator.time

    def frames() -> Iterator[QImage]:
        for number, time in enumerate(times):
            animator.show(time)
            yield render(scene, cell_px, step_caption(time, horizon))
            if progress is not None:
                progress(number + 1, len(times))

    try:
        with _detail_for(scene, cell_px):
            data = (_gif if suffix == ".gif" else _mp4)(frames(), frame_ms)
    finally:
        animator.show(shown)
    write_bytes(path, data)
    return len(times)


def _pillow(image: QImage):
    from PIL import Image
    image = image.convertToFormat(QImage.Format_RGBA8888)
    data = image.constBits().asstring(image.sizeInBytes())
    return Image.frombuffer("RGBA", (image.width(), image.height()), data, "raw", "RGBA",
                            image.bytesPerLine(), 1).convert("RGB")


def _gif(frames: Iterator[QImage], frame_ms: float) -> bytes:
    pictures = [_pillow(frame).quantize(colors=255, method=2, dither=0) for frame in frames]
    durations = [max(20, int(round(frame_ms / 10)) * 10)] * len(pictures)
    durations[-1] += 1000  # hold the final state a moment before looping
    out = io.BytesIO()
    pictures[0].save(out, format="GIF", save_all=True, append_images=pictures[1:],
                     duration=durations, loop=0, optimize=False, disposal=1)
    return out.getvalue()


def _mp4(frames: Iterator[QImage], frame_ms: float) -> bytes:
    import av
    rate = Fraction(round(1000.0 / frame_ms * 100), 100)
    out = io.BytesIO()
    with av.open(out, mode="w", format="mp4") as container:
        stream = None
        for frame in frames:
            picture = _pillow(frame)
            if stream is None:
                stream = container.add_stream("libx264", rate=rate)
                stream.width, stream.height = picture.width // 2 * 2, picture.height // 2 * 2
                stream.pix_fmt = "yuv420p"
                stream.options = {"crf": "20"}
            picture = picture.crop((0, 0, stream.width, stream.height))
            for packet in stream.encode(av.VideoFrame.from_image(picture)):
                container.mux(packet)
        if stream is not None:
            for packet in stream.encode():
                container.mux(packet)
    return out.getvalue()
