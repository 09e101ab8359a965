"""Pictures and animations of a plan without a window: the visualizer's public ``render``.

    from asprilo.visualizer import render
    render(instance, plan, "final.png", step=plan.horizon)
    render(instance, plan, "plan.gif", frames=4)

Qt is loaded when ``render`` runs; without a display it draws offscreen.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from pathlib import Path

from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.model import Instance, Plan

#: Qt warnings that say nothing useful to a user of the viewer (headless runs print them)
_QUIET = ("XDG_RUNTIME_DIR not set", "does not support propagateSizeHints")


def application():
    """The running QApplication, or a new one (keep a reference while Qt objects live)."""
    from PyQt5.QtCore import qInstallMessageHandler
    from PyQt5.QtWidgets import QApplication
    app = QApplication.instance()
    if app is None:
        def report(_kind, _context, message: str) -> None:
            if not any(text in message for text in _QUIET):
                print(message, file=sys.stderr)
        qInstallMessageHandler(report)
        app = QApplication(sys.argv[:1])
        app.setApplicationName("asprilo viz")
        app.setOrganizationName("asprilo")
    return app


def render(instance: Instance, plan: Plan, path: str | Path, domain: Domain | None = None,
           step: int | None = None, frames: int = 1, speed: float = 2.0, cell: int | None = None,
           progress: Callable[[int, int], None] | None = None, caption: bool = True) -> str:
    """Write a picture (.png, .jpg, .svg: the state after ``step``, default 0, with a caption
    line saying so unless ``caption`` is false or there is no plan) or an animation (.gif,
    .mp4: the whole plan, ``frames`` per step at ``speed`` steps per second) of ``plan`` on
    ``instance``; returns a short description of what was written."""
    if not os.environ.get("DISPLAY") and not os.environ.get("WAYLAND_DISPLAY"):
        os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from ..scene.animator import Animator
    from ..scene.warehouse import WarehouseScene
    from ..state.track import Track
    from . import images

    suffix = images.export_format(path)  # a bad name fails before any work
    images.check_budget(instance, suffix, cell, plan.horizon, frames)  # a picture too large, before drawing
    app = application()  # noqa: F841 (Qt objects below need it alive)
    track = Track(instance, plan, domain)
    scene = WarehouseScene(instance)
    animator = Animator(scene, track)
    try:
        if suffix in images.ANIMATIONS:
            count = images.save_animation(str(path), animator, frames, speed, cell, progress)
            return f"{count} frames"
        shown = step or 0
        if shown > track.horizon:
            raise InputError(f"--step {shown} lies beyond the plan, whose last step is {track.horizon}")
        animator.show(shown)
        said = images.picture_caption(shown, track.horizon) if caption and track.horizon else None
        size = images.save_picture(str(path), scene, cell, said)
        return f"{size.width()}x{size.height()}"
    finally:
        del animator, scene  # before the application goes
