"""The banner above the map that says how the last online session ended, until dismissed."""

from __future__ import annotations

from html import escape

from PyQt5.QtWidgets import QFrame, QHBoxLayout, QLabel, QPushButton, QWidget

from ..state.viewer import Session

_STYLE = "QFrame#session_banner { background: #fff3bf; border-bottom: 1px solid #f59f00; }"


class SessionBanner(QFrame):
    """Shown while the session's end (and its reason) has not been dismissed."""

    def __init__(self, session: Session, parent: QWidget | None = None):
        super().__init__(parent)
        self.session = session
        self.setObjectName("session_banner")
        self.setStyleSheet(_STYLE)
        self.text = QLabel(self)
        self.text.setWordWrap(True)
        self.dismiss = QPushButton("Dismiss", self)
        self.dismiss.clicked.connect(session.dismiss)
        layout = QHBoxLayout(self)
        layout.setContentsMargins(8, 4, 8, 4)
        layout.addWidget(self.text, 1)
        layout.addWidget(self.dismiss)
        session.changed.connect(self._show)
        self._show()

    def _show(self) -> None:
        reason = self.session.ended_because
        self.setVisible(reason is not None)
        if reason is not None:
            self.text.setText(f"<b>Online session ended:</b> {escape(reason)}")
