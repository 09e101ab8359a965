"""Tables and plots of benchmark results, shaped like the paper's (Table 2 and the appendix).

Average run times count every unsolved run (time-out, mem-out, no known makespan,
invalid plan, error) at the time limit; the number in parentheses counts the unsolved
runs, and ``!N`` flags N of them that failed (invalid plan or error) rather than ran out of
time or memory.  ``*`` marks the best encoding of each domain and instance set: fewest
unsolved runs, then least average time.
"""

from __future__ import annotations

import csv
import io
from collections import defaultdict
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from statistics import mean

from .results import FAILED, SOLVED


@dataclass
class Cell:
    """The runs of one (domain, encoding) on one group of instances."""

    times: list[float]
    unsolved: int
    failed: int

    @property
    def average(self) -> float:
        return mean(self.times) if self.times else 0.0

    def text(self, best: bool = False) -> str:
        seconds = f"{self.average:.1f}" if self.average < 10 else f"{self.average:.0f}"
        flag = f" !{self.failed}" if self.failed else ""
        return f"{seconds}({self.unsolved}){flag}{'*' if best else ''}"


def _cell(records: list[dict]) -> Cell:
    times = [r["time"] if r["status"] == SOLVED else r["time_limit"] for r in records]
    unsolved = sum(r["status"] != SOLVED for r in records)
    return Cell(times, unsolved, sum(r["status"] in FAILED for r in records))


def _ordered(values: Iterable, order: list) -> list:
    present = set(values)
    return [v for v in order if v in present] + sorted(present - set(order), key=str)


#: row order as in the paper: domains from simple to hard, each without then with assignment
LABELS = ["M", "M_a", "Md", "Md_a", "C", "C_a", "B", "B_a", "A", "A_a"]
ENCODINGS = ["plain", "split", "clingcon", "dl"]


def _rank(value: str, order: list[str]) -> tuple:
    return (order.index(value), "") if value in order else (len(order), value)


def _rows(records: list[dict]) -> list[tuple[str, str]]:
    """(domain label, encoding) pairs present, in the paper's order."""
    rows = {(record["label"], record["encoding"]) for record in records}
    return sorted(rows, key=lambda row: (_rank(row[0], LABELS), _rank(row[1], ENCODINGS)))


def _table(header: list[str], rows: list[list[str]]) -> str:
    widths = [max(len(row[i]) for row in [header, *rows]) for i in range(len(header))]
    lines = ["  ".join(text.ljust(width) for text, width in zip(row, widths, strict=True)).rstrip()
             for row in [header, *rows]]
    lines.insert(1, "  ".join("-" * width for width in widths))
    return "\n".join(lines)


def _makespans(records: list[dict], label: str, sets: list[str]) -> str:
    parts = []
    for name in sets:
        spans = {(r["instance"], r["horizon"]) for r in records
                 if r["label"] == label and r["set"] == name and r.get("horizon") is not None}
        parts.append(f"{mean(h for _i, h in spans):.0f}" if spans else "-")
    return "/".join(parts)


def grouped_table(records: list[dict], column_of, columns: list, caption: str,
                  set_order: list[str] | None = None) -> str:
    """Rows (domain, encoding), one column per value of ``column_of(record)``."""
    groups: dict[tuple, list[dict]] = defaultdict(list)
    for record in records:
        groups[(record["label"], record["encoding"], column_of(record))].append(record)
    rows = _rows(records)
    cells = {key: _cell(runs) for key, runs in groups.items()}
    best = set()
    for label in {label for label, _e in rows}:
        for column in columns:
            candidates = [(cells[(label, e, column)].unsolved, cells[(label, e, column)].average, e)
                          for row_label, e in rows if row_label == label and (label, e, column) in cells
                          and e != "anytime"]  # its time is the time to a first plan: not comparable
            if len(candidates) > 1:
                best.add((label, min(candidates)[2], column))
    sets = _ordered({r["set"] for r in records}, set_order or [])
    body, previous = [], None
    for label, encoding in rows:
        first = label != previous
        previous = label
        makespan = _makespans(records, label, sets) if first else ""
        body.append([label if first else "", makespan, encoding] +
                    [cells[(label, encoding, c)].text((label, encoding, c) in best)
                     if (label, encoding, c) in cells else "-" for c in columns])
    header = ["domain", "makespan", "encoding", *map(str, columns)]
    return f"{caption}\n\n{_table(header, body)}"


def summary(records: list[dict], set_order: list[str] | None = None) -> str:
    """The paper's summary table: average time (unsolved runs) per domain x encoding x set."""
    sets = _ordered({r["set"] for r in records}, set_order or [])
    return grouped_table(records, lambda r: r["set"], sets,
                         "Average run time in seconds (unsolved runs); unsolved runs count at the time limit",
                         sets)


def by_robots(records: list[dict], set_order: list[str] | None = None) -> list[str]:
    """One table per instance set with a column per robot count (the paper's appendix)."""
    tables = []
    for name in _ordered({r["set"] for r in records}, set_order or []):
        runs = [r for r in records if r["set"] == name]
        counts = sorted({r["robots"] for r in runs})
        tables.append(grouped_table(runs, lambda r: r["robots"], counts,
                                    f"Instance set {name}: average run time (unsolved runs) by number of robots"))
    return tables


def anytime_table(records: list[dict], set_order: list[str] | None = None) -> str | None:
    """The anytime runs: per domain and instance set, how many found a plan, the average time
    to the first plan, and the average makespan at the end over its lower bound and over
    the minimal makespan (where another run of the suite knows it); ``None`` without such runs."""
    runs = [r for r in records if r.get("method") == "anytime"]
    if not runs:
        return None
    minimal = {(r["instance"], r["label"]): r["horizon"] for r in records
               if r.get("method") != "anytime" and r.get("horizon") is not None}
    body = []
    for label in _ordered({r["label"] for r in runs}, LABELS):
        for name in _ordered({r["set"] for r in runs if r["label"] == label}, set_order or []):
            group = [r for r in runs if r["label"] == label and r["set"] == name]
            solved = [r for r in group if r["status"] == SOLVED]
            bound = [r["horizon"] / r["lower_bound"] for r in solved if r.get("lower_bound")]
            optimum = [r["horizon"] / minimal[(r["instance"], label)] for r in solved
                       if minimal.get((r["instance"], label))]
            body.append([label, name, f"{len(solved)}/{len(group)}",
                         f"{mean(r['time'] for r in solved):.1f}" if solved else "-",
                         f"{mean(bound):.2f}" if bound else "-", f"{mean(optimum):.2f}" if optimum else "-"])
    header = ["domain", "set", "plans", "first plan (s)", "makespan/bound", "makespan/minimal"]
    return "Anytime runs: plans found, time to the first plan, makespan at the end\n\n" + _table(header, body)


CSV_FIELDS = ["key", "set", "instance", "robots", "domain", "label", "encoding", "assign", "status",
              "time", "time_limit", "memory_mb", "horizon", "ground_time", "solve_time", "rules", "atoms",
              "choices", "conflicts", "error"]


def to_csv(records: list[dict]) -> str:
    stream = io.StringIO()
    writer = csv.DictWriter(stream, CSV_FIELDS, extrasaction="ignore", lineterminator="\n")
    writer.writeheader()
    for record in records:
        writer.writerow(record)
    return stream.getvalue()


def plot(records: list[dict], folder: Path, set_order: list[str] | None = None) -> list[Path]:
    """A cactus plot (solved runs over time, one line per encoding, one panel per domain)
    and a plot of average time by number of robots (one panel per instance set)."""
    import matplotlib
    import matplotlib.ticker
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    written = []
    labels = _ordered({r["label"] for r in records}, LABELS)
    figure, axes = plt.subplots(1, len(labels), figsize=(4.5 * len(labels), 3.8), squeeze=False)
    for axis, label in zip(axes[0], labels, strict=True):
        for _l, encoding in [row for row in _rows(records) if row[0] == label]:
            times = sorted(r["time"] for r in records
                           if r["label"] == label and r["encoding"] == encoding and r["status"] == SOLVED)
            axis.plot(range(1, len(times) + 1), times, marker="o", markersize=3, label=encoding)
        axis.set(title=label, xlabel="solved runs", ylabel="time (s)")
        axis.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
        axis.grid(alpha=0.3)
        axis.legend(fontsize="small")
    figure.tight_layout()
    written.append(_save(figure, folder / "cactus.png"))
    plt.close(figure)

    sets = _ordered({r["set"] for r in records}, set_order or [])
    figure, axes = plt.subplots(1, len(sets), figsize=(4.5 * len(sets), 3.8), squeeze=False)
    for axis, name in zip(axes[0], sets, strict=True):
        runs = [r for r in records if r["set"] == name]
        for label, encoding in _rows(runs):
            points = defaultdict(list)
            for r in runs:
                if (r["label"], r["encoding"]) == (label, encoding):
                    points[r["robots"]].append(r["time"] if r["status"] == SOLVED else r["time_limit"])
            robots = sorted(points)
            axis.plot(robots, [mean(points[n]) for n in robots], marker="o", label=f"{label} {encoding}")
        axis.set(title=name, xlabel="robots", ylabel="average time (s)")
        axis.grid(alpha=0.3)
        axis.legend(fontsize="x-small")
    figure.tight_layout()
    written.append(_save(figure, folder / "time-by-robots.png"))
    plt.close(figure)
    return written


def _save(figure, path: Path) -> Path:
    """Save a figure atomically (render to memory, then replace the file)."""
    from asprilo.writer import write_bytes
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=110)
    write_bytes(path, buffer.getvalue())
    return path
