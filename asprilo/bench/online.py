"""Online suites (``asprilo bench online SUITE.yml``): scenarios x planners x budgets, each an
online run (:func:`asprilo.online.run.run_online`), reported as a table of throughput beside
its ceiling, order latency, planner time and waiting steps, and a throughput-over-time plot.

A suite is a YAML file::

    name: online-small
    scenarios: {files: ["../examples/asprilo/dom-a/small/*.lp"]}  # instances (patterns, as bench's)
    every: 3              # optional: release one order every 3 steps (default: the instances' own)
    steps: 200            # steps of each run (default 1000)
    planners: [anytime, asp, multishot]   # multishot: one clingo Control a run (A and M)
    budgets: [0.5, 1]     # seconds a planner call may take
    step_seconds: 1       # seconds of planner time a step of the world takes (default 1)

The runs go one after the other in this process (each is bounded by its steps and budgets);
every run's figures are a line of ``DIR/online.jsonl``; the report (``DIR/report/``) has the
table as text, LaTeX and CSV, and the plot in the formats asked for.
"""

from __future__ import annotations

import csv
import io
import json
import sys
from dataclasses import dataclass
from pathlib import Path
from statistics import mean
from typing import Any

from asprilo.domain import detect_domain
from asprilo.errors import InputError
from asprilo.reader import read_instance
from asprilo.writer import write_text
from asprilo.yamlfile import load_yaml, shown

from .files import matching_files
from .report import Table

#: what a suite may say, and the defaults of what it may leave out
KEYS = {"name", "scenarios", "every", "steps", "planners", "budgets", "step_seconds"}
STEPS, STEP_SECONDS = 1000, 1.0
PLANNERS = ("anytime", "asp", "multishot")
RESULTS = "online.jsonl"
#: the windows of the throughput over time in a run
WINDOWS = 20


@dataclass(frozen=True)
class OnlineSuite:
    """A suite as read (see the module docstring)."""

    path: Path
    name: str
    scenarios: list[Path]
    planners: list[str]
    budgets: list[float]
    every: int | None = None
    steps: int = STEPS
    step_seconds: float = STEP_SECONDS

    def runs(self) -> list[tuple[Path, str, float]]:
        return [(scenario, planner, budget) for scenario in self.scenarios for planner in self.planners
                for budget in self.budgets]


def load_online_suite(path: str | Path) -> OnlineSuite:
    """The suite in ``path``, checked (bad input: :class:`InputError` naming the file)."""
    path = Path(path)
    data = load_yaml(path)
    if not isinstance(data, dict):
        raise InputError("an online suite is a mapping (name, scenarios, planners, budgets, ...)", str(path))
    unknown = sorted(str(key) for key in data if key not in KEYS)
    if unknown:
        raise InputError(f"unknown key {shown(unknown[0])} (an online suite has {', '.join(sorted(KEYS))})", str(path))
    scenarios = data.get("scenarios")
    if not isinstance(scenarios, dict) or not isinstance(scenarios.get("files"), list) \
            or not all(isinstance(pattern, str) for pattern in scenarios["files"]):
        raise InputError("scenarios: give {files: [PATTERN, ...]}", str(path))
    planners = _listed(data.get("planners", ["anytime"]))
    if not planners or any(planner not in PLANNERS for planner in planners):
        raise InputError(f"planners: choose among {', '.join(PLANNERS)}", str(path))
    budgets = _listed(data.get("budgets", [1.0]))
    if not budgets or not all(_seconds(budget) for budget in budgets):
        raise InputError("budgets: seconds a planner call may take, above 0", str(path))
    for key, least in (("every", 1), ("steps", 1)):
        value = data.get(key)
        if value is not None and (type(value) is not int or value < least):
            raise InputError(f"{key}: a whole number of at least {least}, got {shown(value)}", str(path))
    step_seconds = data.get("step_seconds", STEP_SECONDS)
    if not _seconds(step_seconds):
        raise InputError(f"step_seconds: seconds above 0, got {shown(step_seconds)}", str(path))
    name = data.get("name", path.stem)
    if not isinstance(name, str) or not name or "/" in name:
        raise InputError(f"name: a name for the results, got {shown(name)}", str(path))
    return OnlineSuite(path, name, matching_files(path, scenarios["files"], "scenarios"), planners,
                       [float(budget) for budget in budgets], data.get("every"), data.get("steps") or STEPS,
                       float(step_seconds))


def _listed(value: Any) -> list:
    return value if isinstance(value, list) else [value]


def _seconds(value: Any) -> bool:
    return type(value) in (int, float) and 0 < value < 1e6


def run_suite(suite: OnlineSuite, folder: Path) -> list[dict]:
    """Every run of ``suite``, one after the other, each recorded in ``folder``; progress on stderr."""
    from asprilo.online.ceiling import ceiling
    from asprilo.online.metrics import measure
    from asprilo.online.planner import encodings_planner, release_steps
    from asprilo.online.planning import FromScratch, OnlinePlanning, multishot
    from asprilo.online.record import figures
    from asprilo.online.run import run_online, scenario_of

    records = []
    runs = suite.runs()
    for number, (scenario, planner, budget) in enumerate(runs, 1):
        instance = read_instance(str(scenario))
        domain = detect_domain(instance)
        releases = release_steps(instance, suite.every)
        instance = scenario_of(instance, releases)

        def planner_for(seconds: float, method: str = planner):
            return encodings_planner(time_limit=seconds, method=method)

        online: OnlinePlanning = multishot(instance, domain) if planner == "multishot" else \
            FromScratch(instance, domain, planner_for)
        outcome = run_online(instance, domain, online, releases, budget=budget,
                             steps=suite.steps, step_seconds=suite.step_seconds)
        metrics = measure(instance, outcome.plan, domain, releases, outcome.steps, outcome.calls,
                          len(outcome.waiting), window=max(1, suite.steps // WINDOWS))
        shown_path = str(scenario.relative_to(suite.path.parent)) if scenario.is_relative_to(suite.path.parent) \
            else str(scenario)
        record = {"scenario": shown_path, "method": planner, "budget": budget, "ended": outcome.ended,
                  **figures(metrics, ceiling(instance, domain, releases, outcome.steps))}
        records.append(record)
        print(f"[{number}/{len(runs)}] {shown_path} {planner} {budget:g} s: {metrics.lines_per_100:.1f} lines per "
              f"100 steps, {metrics.waiting_steps} waiting steps", file=sys.stderr, flush=True)
    write_text(folder / RESULTS, "".join(json.dumps(record) + "\n" for record in records))
    return records


def online_table(records: list[dict]) -> Table:
    """One row per planner and budget, averaged over the scenarios."""
    rows = []
    for planner, budget in dict.fromkeys((r["method"], r["budget"]) for r in records):
        mine = [r for r in records if (r["method"], r["budget"]) == (planner, budget)]
        shares = [r["lines_done"] / r["ceiling_lines"] for r in mine if r.get("ceiling_lines")]
        latencies = [r["latency"]["mean"] for r in mine if r["latency"]["mean"] is not None]
        calls = [r["planner"]["mean_seconds"] for r in mine if r["planner"]["mean_seconds"] is not None]
        most = [r["planner"]["max_seconds"] for r in mine if r["planner"]["max_seconds"] is not None]
        rows.append([planner, f"{budget:g}", f"{mean(r['lines_per_100'] for r in mine):.1f}",
                     f"{100 * mean(shares):.0f}" if shares else "-", f"{mean(latencies):.1f}" if latencies else "-",
                     str(max((r["latency"]["p95"] or 0) for r in mine)), f"{mean(calls):.2f}" if calls else "-",
                     f"{max(most):.2f}" if most else "-", str(sum(r["waiting_steps"] for r in mine))])
    header = ["planner", "budget (s)", "lines/100 steps", "% of ceiling", "latency", "p95", "s/call", "max s",
              "waiting"]
    key = [("lines/100 steps", "order lines done per 100 steps, the mean over the scenarios"),
           ("% of ceiling", "lines done over the most any planner could do (asprilo/online/ceiling.py)"),
           ("latency, p95", "steps from an order's release to its last line done: the mean of the means, the "
                            "largest 95th percentile"),
           ("s/call, max s", "the planner's seconds per call: the mean of the means, the largest"),
           ("waiting", "steps robots stood while the planner thought, all scenarios together")]
    return Table("online", "Online runs: throughput, latency and planner time", header, rows, key, text_columns=1)


def online_csv(records: list[dict]) -> str:
    stream = io.StringIO()
    fields = ["scenario", "method", "budget", "ended", "steps", "lines", "lines_done", "units_done",
              "lines_per_100", "ceiling_lines", "waiting_steps"]
    writer = csv.DictWriter(stream, fields, extrasaction="ignore", lineterminator="\n")
    writer.writeheader()
    for record in records:
        writer.writerow(record)
    return stream.getvalue()


def throughput_figure(records: list[dict]):
    """Order lines done in each window of steps (a twentieth of a run), one line per planner
    and budget (the mean over the scenarios)."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(6.4, 3.8), layout="constrained")
    axis = figure.subplots()
    for planner, budget in dict.fromkeys((r["method"], r["budget"]) for r in records):
        windows: dict[int, list[int]] = {}
        for record in records:
            if (record["method"], record["budget"]) == (planner, budget):
                for window in record["windows"]:
                    windows.setdefault(window["last"], []).append(window["lines"])
        ends = sorted(windows)
        axis.plot(ends, [mean(windows[end]) for end in ends], marker="o", markersize=3, label=f"{planner} {budget:g} s")
    width = records[0]["windows"][0]["last"] if records and records[0]["windows"] else 1
    axis.set(xlabel="step", ylabel=f"order lines done in {width} steps", title="Throughput over time")
    axis.grid(alpha=0.3)
    axis.legend(fontsize="small")
    return figure


def report_online(records: list[dict], folder: Path, formats: tuple[str, ...]) -> list[Path]:
    """The table (text, LaTeX, CSV) and the plot in ``folder``; the files written."""
    from .plots import save

    table = online_table(records)
    written = [folder / "online.txt", folder / "online.tex", folder / "online.csv"]
    write_text(written[0], table.text() + "\n")
    write_text(written[1], table.latex())
    write_text(written[2], online_csv(records))
    print(table.text())
    figure = throughput_figure(records) if formats else None
    return written + [save(figure, folder / f"throughput.{kind}") for kind in formats]
