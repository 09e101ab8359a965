"""The status bar's words: what is shown (title, domain, size, plan) and the verdict at the
step shown (valid plan, or how many rules it breaks)."""

from __future__ import annotations

from PyQt5.QtWidgets import QLabel, QSizePolicy, QStatusBar

from ..state.viewer import ViewerState


class StatusLine:
    """A summary on the left, the verdict on the right, passing messages in between."""

    def __init__(self, state: ViewerState, bar: QStatusBar):
        self.state, self.bar = state, bar
        self.summary = QLabel(bar)
        self.summary.setSizePolicy(QSizePolicy.Ignored, QSizePolicy.Preferred)  # clipped, never overlapping
        self.verdict = QLabel(bar)
        bar.addWidget(self.summary, 1)
        bar.addPermanentWidget(self.verdict)
        state.shown.connect(lambda _keep: self._show_track())
        state.track_changed.connect(lambda _change: self._show_track())
        state.step_changed.connect(self._show_verdict)
        state.said.connect(bar.showMessage)

    def _show_track(self) -> None:
        self._show_summary()
        self._show_verdict(self.state.step)

    def _show_summary(self) -> None:
        scenario, track = self.state.document.scenario, self.state.track
        if scenario is None:
            self.summary.setText("No instance open.")
            return
        counts = scenario.instance.counts()
        plan = (f"plan: {len(scenario.plan)} actions, horizon {track.horizon}" if len(scenario.plan)
                else "no plan")
        self.summary.setText(
            f"{scenario.title}   ·   domain {track.domain.label}   ·   {counts['x']}×{counts['y']}, "
            f"{counts['robots']} robots, {counts['shelves']} shelves, {counts['orders']} orders   ·   {plan}")

    def _show_verdict(self, step: int) -> None:
        scenario, track = self.state.document.scenario, self.state.track
        if track is None or not len(scenario.plan):
            self.verdict.setText("")
            return
        total = len(track.violations)
        here = len(track.violations_at.get(step, []))
        if not total:
            verdict = "no rule broken so far" if scenario.unfinished else "valid plan"
            self.verdict.setText(f"<span style='color:#2b8a3e'>{verdict} \u2713</span>")
            return
        text = f"\u26a0 {total} rule violation{'s' if total > 1 else ''}"
        if here:
            text += f", {here} at step {step}"
        self.verdict.setText(f"<span style='color:#e03131'><b>{text}</b></span>")
