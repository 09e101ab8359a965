"""Under the violations list: the checker rule that finds the violation clicked, as text
(its file, line and the rule as written), so that students see the ASP behind the words.

The rule is looked up by the violation's ``err(Module,Check,_)`` in the checker of the
domain shown (:mod:`asprilo.checker.rules`); where several rules derive the check, the
note lists them all (the presentation mode, short of room, shows the first and says how
many there are).
"""

from __future__ import annotations

from html import escape

from PyQt5.QtCore import Qt
from PyQt5.QtWidgets import QLabel

from asprilo.checker.rules import one_line, rules_of
from asprilo.domain import Domain
from asprilo.simulate import Violation

from ..state.viewer import ViewerState
from .tables import TablePanel

HINT = "Click a violation to see the checker rule that finds it."


def rule_note(domain: Domain, violation: Violation) -> str:
    """The note as rich text: where the rule is, and the rule (escaped)."""
    rules = rules_of(domain, violation.module, violation.check)
    if not rules:
        return (f"No rule of domain {escape(domain.label)}'s checker derives "
                f"<code>err({escape(violation.module)},{escape(violation.check)},_)</code>.")
    if len(rules) == 1:
        return (f"<b>{escape(violation.atom)}</b> is found by <b>{escape(rules[0].where)}</b>:"
                f"<br><code>{escape(one_line(rules[0].text))}</code>")
    return (f"<b>{escape(violation.atom)}</b> is found by one of {len(rules)} rules:"
            + "".join(f"<br><b>{escape(rule.where)}</b>: <code>{escape(one_line(rule.text))}</code>"
                      for rule in rules))


class RuleNote(QLabel):
    """A note at the foot of the violations panel; a click on a violation fills it."""

    def __init__(self, state: ViewerState, panel: TablePanel):
        super().__init__(HINT, panel)
        self.state = state
        self.setObjectName("checker_rule")
        self.setWordWrap(True)
        self.setTextFormat(Qt.TextFormat.RichText)
        self.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.setMargin(4)
        self.setStyleSheet("#checker_rule { color: #495057; }")
        layout = panel.layout()
        assert layout is not None
        layout.addWidget(self)
        panel.row_activated.connect(self.show_rule)
        state.shown.connect(lambda _keep: self.setText(HINT))
        state.track_changed.connect(lambda _change: self.setText(HINT))

    def show_rule(self, violation: Violation) -> None:
        track = self.state.track
        if track is not None:
            self.setText(rule_note(track.domain, violation))
