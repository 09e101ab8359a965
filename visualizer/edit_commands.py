"""The edited instance and its undo history: every edit is a QUndoCommand on a QUndoStack."""

from __future__ import annotations

from pathlib import Path

from PyQt5.QtCore import QObject, pyqtSignal
from PyQt5.QtWidgets import QUndoCommand, QUndoStack

from asprilo.model import Instance
from asprilo.writer import format_instance, header_lines, write_text

from . import edits
from .edits import Edit

TOOL = "asprilo viz"


class EditCommand(QUndoCommand):
    """One :class:`Edit`, done and undone on a :class:`Document`."""

    def __init__(self, document: Document, edit: Edit):
        super().__init__(edit.text)
        self.document = document
        self.edit = edit

    def redo(self) -> None:
        self.document.apply(self.edit)

    def undo(self) -> None:
        self.document.apply(self.edit, undo=True)


class Document(QObject):
    """The instance being edited (always its initial state), its history and its file."""

    changed = pyqtSignal(object)  # the Edit just done or undone
    modified_changed = pyqtSignal()

    def __init__(self, parent: QObject | None = None):
        super().__init__(parent)
        self.instance = Instance()
        self.stack = QUndoStack(self)
        self.stack.cleanChanged.connect(self._clean_changed)
        self.path: Path | None = None
        self.modified = False  # unsaved edits (kept here: the stack may be gone when asked)

    def reset(self, instance: Instance, path: str | Path | None = None) -> None:
        """Edit ``instance`` from now on (a new history, nothing unsaved)."""
        self.instance = instance
        self.path = Path(path) if path is not None else None
        self.stack.clear()
        self.stack.setClean()

    def _clean_changed(self, clean: bool) -> None:
        self.modified = not clean
        self.modified_changed.emit()

    def perform(self, edit: Edit) -> bool:
        """Do ``edit`` as one undoable step; ``False`` when it changes nothing."""
        if not edit.changes:
            return False
        self.stack.push(EditCommand(self, edit))
        return True

    def apply(self, edit: Edit, undo: bool = False) -> None:
        edits.apply(self.instance, edit, undo)
        self.changed.emit(edit)

    # --- files ----------------------------------------------------------------------------

    def text(self) -> str:
        """The instance in the canonical format, with a header naming the editor."""
        return format_instance(self.instance, header_lines(self.instance, tool=TOOL))

    def save(self, path: str | Path) -> None:
        """Write the instance (atomically) and remember the file."""
        write_text(path, self.text())
        self.path = Path(path)
        self.stack.setClean()

    def save_template(self, path: str | Path) -> None:
        """Write the layout without products and orders, for ``gen -T FILE``."""
        template = edits.template_of(self.instance)
        header = header_lines(template, tool=TOOL)
        header[1:1] = [f"template for the generator: gen -T {Path(path).name} (adds products and orders)"]
        write_text(path, format_instance(template, header))
