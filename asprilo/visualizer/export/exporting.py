"""File > Export picture / animation: the warehouse as shown, or every state of the plan."""

from __future__ import annotations

from PyQt5.QtCore import QObject, QSettings, Qt
from PyQt5.QtWidgets import QFileDialog, QInputDialog, QProgressDialog, QWidget

from asprilo.errors import InputError
from asprilo.writer import check_output

from ..panels.files import start_folder
from ..scene.player import Player
from ..scene.stage import Stage
from ..state.viewer import ViewerState
from . import images


class ExportActions(QObject):
    """Asks where to save, renders the stage's scene, and says what was saved."""

    def __init__(self, state: ViewerState, stage: Stage, player: Player, settings: QSettings, parent: QWidget):
        super().__init__(parent)
        self.state, self.stage, self.player, self.settings, self.parent_widget = state, stage, player, settings, parent

    def ask_picture(self) -> None:
        if self.stage.animator is None:
            return
        path, _ = QFileDialog.getSaveFileName(self.parent_widget, "Export picture", start_folder(self.settings),
                                              "PNG image (*.png);;SVG drawing (*.svg);;JPEG image (*.jpg)")
        if path:
            self.picture(path)

    def ask_animation(self) -> None:
        if self.stage.animator is None:
            return
        path, _ = QFileDialog.getSaveFileName(self.parent_widget, "Export animation", start_folder(self.settings),
                                              "GIF animation (*.gif);;MP4 video (*.mp4)")
        if not path:
            return
        frames, ok = QInputDialog.getInt(self.parent_widget, "Export animation",
                                         "Frames per step (1: only the states):", 4, 1, 30)
        if ok:
            self.animation(path, frames)

    def picture(self, path: str) -> bool:
        """Save the warehouse as shown now (time, selection, paths), the state's caption below it."""
        try:
            check_output(path, self.state.document.loaded())
            caption = images.picture_caption(self.player.time, self.player.horizon) if self.player.horizon else None
            images.save_picture(path, self.stage.scene, caption=caption)  # the state shown, said below it
        except InputError as error:
            self.state.report_error(str(error))
            return False
        self.state.say(f"saved {path}")
        return True

    def animation(self, path: str, frames_per_step: int = 4) -> bool:
        """Save every state of the plan (with in-between frames) as a GIF or MP4."""
        self.player.pause()
        progress = QProgressDialog("Rendering frames…", "", 0, 1, self.parent_widget)
        progress.setCancelButton(None)
        progress.setWindowModality(Qt.WindowModal)

        def advance(done: int, total: int) -> None:
            progress.setMaximum(total)
            progress.setValue(done)

        try:
            check_output(path, self.state.document.loaded())
            images.save_animation(path, self.stage.animator, frames_per_step, self.player.speed, progress=advance)
        except InputError as error:
            self.state.report_error(str(error))
            return False
        finally:
            progress.close()
        self.state.say(f"saved {path}")
        return True
