"""A user's own encoding files for Run > Solve with encoding file…: the file dialog and the
encoding sets used lately (Run > Recent encodings), kept in the viewer's settings like the
recent files.

A set is the list of files of one encoding, in loading order (the main file first, as
``asprilo solve --encoding A --encoding B`` loads them).  A set whose files are gone stays
listed, disabled and marked missing, until newer sets push it out.
"""

from __future__ import annotations

import json
from pathlib import Path

from PyQt5.QtCore import QSettings
from PyQt5.QtWidgets import QFileDialog, QWidget

from asprilo.paths import real

from ..panels.files import start_folder

#: the most encoding sets remembered
RECENT_LIMIT = 10
ENCODING_FILTER = "ASP programs (*.lp *.ilp *.clp *.dlp *.asp);;All files (*)"
_RECENT, _FOLDER = "tools/recent_encodings", "tools/encoding_folder"


def ask_encoding_files(parent: QWidget, settings: QSettings) -> list[str]:
    """The encoding files the user chooses (several: loaded in the order chosen); ``[]``: none."""
    folder = str(settings.value(_FOLDER, "")) or start_folder(settings)
    paths, _ = QFileDialog.getOpenFileNames(parent, "Solve with encoding files (loaded in this order)", folder,
                                            ENCODING_FILTER)
    if paths:
        settings.setValue(_FOLDER, str(Path(paths[0]).parent))
    return list(paths)


def recent_encodings(settings: QSettings) -> list[list[str]]:
    """The encoding sets used lately, newest first, each a list of absolute paths."""
    try:
        entries = json.loads(str(settings.value(_RECENT, "[]")))
    except ValueError:
        return []
    if not isinstance(entries, list):
        return []
    return [entry for entry in entries
            if isinstance(entry, list) and entry and all(isinstance(path, str) for path in entry)]


def remember_encoding(settings: QSettings, paths: list[str]) -> None:
    """Put the set ``paths`` first among the recent encodings."""
    entry = [str(real(path)) for path in paths]
    entries = [entry] + [e for e in recent_encodings(settings) if e != entry]
    settings.setValue(_RECENT, json.dumps(entries[:RECENT_LIMIT]))


def missing(entry: list[str]) -> list[str]:
    """The files of a set that are no longer there."""
    return [path for path in entry if not Path(path).is_file()]


def entry_text(entry: list[str]) -> str:
    """A set as a menu shows it: its files' names joined by ``+``."""
    return " + ".join(Path(path).name for path in entry)
