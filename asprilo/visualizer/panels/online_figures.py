"""The Online panel: the figures of an online run after the step shown.

From the instance's release steps (``value(release,Step)``) and the plan: the order lines
released and done so far, the throughput beside its ceiling (asprilo/online/ceiling.py),
the latency of the orders done; from a run record (``viz SCENARIO PLAN --record RUN.json``,
written by ``asprilo online --record``): the planner's calls, their time and the waiting
steps up to the step shown.  The deliveries are found once per plan; each step only counts.
"""

from __future__ import annotations

from html import escape

from PyQt5.QtCore import Qt
from PyQt5.QtWidgets import QLabel

from asprilo.domain import Goal
from asprilo.online.ceiling import ceiling, earliest_steps
from asprilo.online.metrics import PlannerCall, counted, deliveries, figures

from ..state.track import Track


class OnlineFigures(QLabel):
    """The figures after the step shown (see the module docstring)."""

    def __init__(self, parent=None):
        super().__init__(parent)
        self.setTextFormat(Qt.RichText)
        self.setAlignment(Qt.AlignTop | Qt.AlignLeft)
        self.setWordWrap(True)
        self.setMargin(8)
        self.track: Track | None = None
        self.record: dict | None = None
        self.delivered: tuple[dict, dict] = ({}, {})
        self.earliest: dict = {}
        self.releases: dict[int, int] = {}
        self.setText("no warehouse")

    def set_record(self, record: dict | None) -> None:
        """A run record (``asprilo online --record``), or none."""
        self.record = record

    def set_track(self, track: Track | None) -> None:
        self.track = track
        if track is not None:
            self.delivered = deliveries(track.instance, track.plan, track.domain, track.horizon, track.timeline)
            self.releases = {order.id: order.release or 0 for order in track.instance.orders.values()}
            self.earliest = {} if track.domain.goal is Goal.DESTINATIONS else \
                earliest_steps(track.instance, track.domain, self.releases)

    def show_step(self, step: int) -> None:
        track = self.track
        if track is None:
            self.setText("no warehouse")
            return
        releases = self.releases
        calls, waiting = self._planner(step)
        shown = figures(track.instance, releases, self.delivered, step, calls, waiting) if step else None
        lines = [self._releases(step)]
        if shown is not None:
            bound = ceiling(track.instance, track.domain, releases, step, self.earliest)
            beside = "" if bound is None else f" (ceiling {bound.lines_per_100:.1f})"
            lines.append(f"done by step {step}: {shown.lines_done} of {counted(shown.lines, 'line')} released, "
                         f"{counted(shown.units_done, 'unit')}; {shown.lines_per_100:.1f} lines per 100 steps{beside}")
            latency = shown.latency
            lines.append("no order done yet" if not latency.orders else
                         f"latency of {counted(latency.orders, 'order')} done: mean {latency.mean:.1f}, "
                         f"p95 {latency.p95}, max {latency.most} steps")
        if self.record is not None:
            said = f"planner: {counted(len(calls), 'call')} by step {step}"
            if calls:
                seconds = [call.seconds for call in calls]
                said += f", {sum(seconds) / len(seconds):.2f} s on average, {max(seconds):.2f} s at most"
            lines.append(f"{said}; {counted(waiting, 'waiting step')}")
        self.setText("<br>".join(escape(line) for line in lines))

    def _releases(self, step: int) -> str:
        releases = self.releases
        released = sorted(set(releases.values()))
        if released in ([], [0]):
            return f"{len(releases)} orders, every one known from the start"
        known = sum(release <= step for release in releases.values())
        return (f"{len(releases)} orders released over steps {released[0]}–{released[-1]}: "
                f"{known} known after step {step}")

    def _planner(self, step: int) -> tuple[list[PlannerCall], int]:
        """The record's planner calls made by ``step`` and its waiting steps up to it."""
        if self.record is None:
            return [], 0
        calls = [PlannerCall(call["step"], call["seconds"], call["found"]) for call in self.record.get("calls", [])
                 if call["step"] <= step]
        return calls, sum(waited <= step for waited in self.record.get("waiting", []))
