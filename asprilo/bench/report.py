"""Tables and plots of benchmark results, shaped like the paper's (Table 2 and the appendix),
for comparing encodings in a paper.

A run ends in one of four ways:

- **solved**: a plan that passes the checker; its time counts;
- **out of limits**: a time-out, a mem-out, or no known minimal makespan (its search ran out
  of time): counted at the time limit;
- **invalid**: a plan that the checker rejected (a wrong answer);
- **error**: the run failed (its encoding refused at run time, a crash, no plan at the
  problem's minimum -- an own encoding whose shortest plan is longer...).

Invalid plans and errors are never averaged in as times: the cells count them apart
(``xN``, ``!N``) and the list of failed runs says why.  The time tables give the average run
time over the solved runs and those out of limits (``T(N)``: N out of limits); ``*`` marks
the best encoding of each domain and column: fewest unsolved runs (of any kind), then least
average time.  The table of solved runs gives PAR2 and PAR10: the penalised average run
time, each run out of limits counted at 2 (10) times the time limit.  Every table ends with
a key for the marks it prints, and is written as LaTeX (booktabs) too.

The plots are drawn by :mod:`asprilo.bench.plots`.
"""

from __future__ import annotations

import csv
import io
import math
import textwrap
from collections import defaultdict
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from statistics import mean
from typing import Any

from .results import ERROR, INVALID, OUT_OF_LIMITS, SOLVED

#: what a run came to, for the report
LIMIT, FAILED_RUN = "limit", "failed"
#: the LaTeX columns of the failed runs (run, instance, outcome, reason): shares of the line
FAILED_WIDTHS = (0.17, 0.28, 0.13, 0.42)
#: the failed runs listed at most (all of them are in results.csv)
LISTED = 50


def outcome(record: dict) -> str:
    """``solved``, ``limit`` (out of time or memory, or no known makespan), ``invalid`` or ``error``."""
    status = record.get("status")
    if status == SOLVED:
        return SOLVED
    if status in OUT_OF_LIMITS:
        return LIMIT
    return INVALID if status == INVALID else ERROR


def _timed(record: dict) -> bool:
    """Whether a run has a time for the averages: solved, or out of limits (at the limit)."""
    return outcome(record) in (SOLVED, LIMIT)


def _time(record: dict) -> float:
    return record["time"] if record["status"] == SOLVED else record["time_limit"]


def _seconds(value: float) -> str:
    return f"{value:.1f}" if value < 10 else f"{value:.0f}"


@dataclass
class Cell:
    """The runs of one (domain, encoding) on one group of instances."""

    times: list[float]   # the solved runs' times, and the time limit for each run out of limits
    unsolved: int        # runs out of limits
    invalid: int = 0     # plans the checker rejected
    errors: int = 0      # runs that failed

    @property
    def failed(self) -> int:
        return self.invalid + self.errors

    @property
    def average(self) -> float | None:
        return mean(self.times) if self.times else None

    def rank(self) -> tuple[int, float]:
        """Fewest unsolved runs of any kind, then least average time."""
        return self.unsolved + self.failed, math.inf if self.average is None else self.average

    def text(self, best: bool = False) -> str:
        seconds = "-" if self.average is None else _seconds(self.average)
        flags = (f" !{self.errors}" if self.errors else "") + (f" x{self.invalid}" if self.invalid else "")
        return f"{seconds}({self.unsolved}){flags}{'*' if best else ''}"


def _cell(records: list[dict]) -> Cell:
    kinds = [outcome(r) for r in records]
    return Cell([_time(r) for r in records if _timed(r)], kinds.count(LIMIT), kinds.count(INVALID),
                kinds.count(ERROR))


def _ordered(values: Iterable, order: list) -> list:
    present = set(values)
    return [v for v in order if v in present] + sorted(present - set(order), key=str)


#: row order as in the paper: domains from simple to hard, each without then with assignment
LABELS = ["M", "M_a", "Md", "Md_a", "C", "C_a", "B", "B_a", "A", "A_a"]
#: the reference encodings first, in the paper's order; encodings of one's own after them, by name
ENCODINGS = ["plain", "split", "clingcon", "dl", "plain-inc", "split-inc", "clingcon-inc"]


def _rank(value: str, order: list[str]) -> tuple:
    return (order.index(value), "") if value in order else (len(order), value)


def _rows(records: list[dict]) -> list[tuple[str, str]]:
    """(domain label, encoding) pairs present, in the paper's order."""
    rows = {(record["label"], record["encoding"]) for record in records}
    return sorted(rows, key=lambda row: (_rank(row[0], LABELS), _rank(row[1], ENCODINGS)))


def encodings_of(records: list[dict]) -> list[str]:
    """The encodings of the runs at the minimal makespan, in report order."""
    return sorted({r["encoding"] for r in records if r.get("method") != "anytime"},
                  key=lambda name: _rank(name, ENCODINGS))


def _time_limit(records: list[dict]) -> str:
    limits = {r["time_limit"] for r in records}
    return f" ({limits.pop():g} s)" if len(limits) == 1 else ""


# --- tables ------------------------------------------------------------------------------


@dataclass
class Table:
    """A table: its caption, header and rows, the key of the marks it prints, the columns
    that hold text (the others hold numbers), and where its row groups (domains) start."""

    name: str                      # file name of its LaTeX form: <name>.tex
    caption: str
    header: list[str]
    rows: list[list[str]]
    key: list[tuple[str, str]] = field(default_factory=list)   # (mark, meaning)
    text_columns: int = 1
    groups: list[int] = field(default_factory=list)            # row numbers where a new group starts
    align: str = ""                                            # LaTeX column types (default: l for text, r)
    listing: bool = False                                      # as text: a list, one wrapped entry per row
    #: in LaTeX, columns that wrap: each column's share of the line (adding up to 1), so that
    #: the table is exactly as wide as the page's line (empty: columns as wide as their text)
    widths: tuple[float, ...] = ()

    def text(self, width: int = 100) -> str:
        """The table (or the list), then its key (wrapped at ``width`` characters)."""
        if self.listing:
            entries = ["\n".join(textwrap.wrap(": ".join(row), width, initial_indent="  ", subsequent_indent="      ",
                                               break_on_hyphens=False)) for row in self.rows]
            parts = [f"{self.caption}\n\n" + "\n".join(entries)]
        else:
            parts = [f"{self.caption}\n\n{_text_table(self.header, self.rows)}"]
        if self.key:
            marks = max(len(mark) for mark, _ in self.key)
            lines = []
            for number, (mark, meaning) in enumerate(self.key):
                head = f"{'Key:' if number == 0 else '':4} {mark.ljust(marks)}  "
                lines += textwrap.wrap(meaning, width, initial_indent=head, subsequent_indent=" " * len(head),
                                       break_on_hyphens=False)
            parts.append("\n".join(lines))
        return "\n\n".join(parts)

    def latex(self) -> str:
        """The table as a LaTeX float with booktabs rules (no vertical rules); the key below it.
        With :attr:`widths` its columns wrap (ragged right, names breakable at ``/`` and ``_``)
        and it fills the line exactly, in a smaller type."""
        align = self.align or "l" * self.text_columns + "r" * (len(self.header) - self.text_columns)
        cell, end = _latex_cell, r" \\"
        size: list[str] = []
        if self.widths:
            align, cell, end = _wrapped_columns(self.widths), _wrapped_cell, r" \tabularnewline"
            size = [r"  \footnotesize"]
        lines = [r"\begin{table}[tbp]", r"  \centering", f"  \\caption{{{latex_text(self.caption)}}}",
                 f"  \\label{{tab:{self.name}}}", *size, f"  \\begin{{tabular}}{{{align}}}", r"    \toprule",
                 "    " + " & ".join(latex_text(text) for text in self.header) + end, r"    \midrule"]
        for number, row in enumerate(self.rows):
            if number in self.groups and number > 0:
                lines.append(r"    \addlinespace")
            lines.append("    " + " & ".join(cell(text) for text in row) + end)
        lines += [r"    \bottomrule", r"  \end{tabular}"]
        if self.key:
            key = "; ".join(f"{latex_text(mark)}: {latex_text(meaning)}" for mark, meaning in self.key)
            lines += [r"  \par\smallskip\footnotesize", f"  Key. {key}."]
        lines.append(r"\end{table}")
        return "\n".join(lines) + "\n"


_LATEX = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_", "{": r"\{",
          "}": r"\}", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}"}


def latex_text(text: str) -> str:
    """``text`` with LaTeX's special characters escaped."""
    return "".join(_LATEX.get(char, char) for char in text)


def _latex_cell(text: str) -> str:
    return "--" if text == "-" else latex_text(text)


def _wrapped_columns(widths: tuple[float, ...]) -> str:
    """Paragraph columns of ``widths`` (shares of the line, adding up to 1), each less the
    space between columns (none at the outer edges), so that they fill the line exactly."""
    last = len(widths) - 1
    columns = []
    for number, width in enumerate(widths):
        gaps = (number > 0) + (number < last)  # a \tabcolsep on each inner side
        space = f"-{gaps}\\tabcolsep" if gaps else ""
        columns.append(f"p{{\\dimexpr {width:g}\\linewidth{space}\\relax}}")
    return "@{}" + "".join(columns) + "@{}"


def _wrapped_cell(text: str) -> str:
    """A cell of a wrapping column: ragged right, a path or a name breakable after ``/``
    and ``_`` (a file name is one long word otherwise)."""
    shown = _latex_cell(text).replace("/", r"/\allowbreak{}").replace(r"\_", r"\_\allowbreak{}")
    return r"\raggedright " + shown


def _text_table(header: list[str], rows: list[list[str]]) -> str:
    widths = [max(len(row[i]) for row in [header, *rows]) for i in range(len(header))]
    lines = ["  ".join(text.ljust(width) for text, width in zip(row, widths, strict=True)).rstrip()
             for row in [header, *rows]]
    lines.insert(1, "  ".join("-" * width for width in widths))
    return "\n".join(lines)


def _makespans(records: list[dict], label: str, sets: list[str]) -> str:
    parts = []
    for name in sets:
        spans = {(r["instance"], r["horizon"]) for r in records
                 if r["label"] == label and r["set"] == name and r.get("horizon") is not None
                 and r.get("method") != "anytime"}
        parts.append(f"{mean(h for _i, h in spans):.1f}" if spans else "-")
    return "/".join(parts)


def _dashes(rows: list[list[str]], first: int) -> bool:
    """Whether a cell from column ``first`` on is ``-``."""
    return any(text == "-" for row in rows for text in row[first:])


def _time_key(records: list[dict], cells: dict[tuple, Cell], best: set, makespans: list[str], sets: list[str],
              described: dict[str, str], empty: bool) -> list[tuple[str, str]]:
    """The key of a time table (``cells`` by (label, encoding, column)): a line for every mark it prints."""
    shown = list(cells.values())
    key = [("T(N)", f"T: average run time in seconds over the solved runs and the runs out of limits, these at "
                    f"the time limit{_time_limit(records)}; N: how many ran out of limits (time-out, mem-out, or "
                    f"no known minimal makespan)")]
    if any(cell.errors for cell in shown):
        key.append(("!N", "N runs ended in an error: not in the average (why: under Failed runs)"))
    if any(cell.invalid for cell in shown):
        key.append(("xN", "N plans the checker rejected: not in the average (why: under Failed runs)"))
    if best:
        key.append(("*", "the best encoding of the domain in this column: fewest unsolved runs of any kind, "
                         "then least average time (never one with an invalid plan)"))
    if any(cell.average is None for cell in shown):
        key.append(("-(0)", "no run solved or ran out of limits: every run failed"))
    if len(sets) > 1 and any("/" in text for text in makespans):
        key.append(("a/b", f"makespan: the average minimal makespan of the instances of each set "
                           f"({'/'.join(sets)}); - unknown"))
    else:
        key.append(("makespan", "the average minimal makespan of the instances; - unknown"))
    if empty:
        key.append(("-", "no runs"))
    key += [(name, described[name]) for name in sorted({e for _l, e, _c in cells}, key=lambda e: _rank(e, ENCODINGS))
            if name in described]
    return key


def grouped_table(records: list[dict], column_of: Callable[[dict], Any], columns: list, caption: str,
                  set_order: list[str] | None = None, name: str = "table",
                  described: dict[str, str] | None = None) -> Table:
    """Rows (domain, encoding), one column per value of ``column_of(record)``."""
    groups: dict[tuple, list[dict]] = defaultdict(list)
    for record in records:
        groups[(record["label"], record["encoding"], column_of(record))].append(record)
    rows = _rows(records)
    cells = {key: _cell(runs) for key, runs in groups.items()}
    best = _best_cells(rows, columns, cells)
    sets = _ordered({r["set"] for r in records}, set_order or [])
    body: list[list[str]] = []
    starts: list[int] = []
    makespans: list[str] = []
    previous = None
    for label, encoding in rows:
        first = label != previous
        previous = label
        makespan = _makespans(records, label, sets) if first else ""
        if first:
            starts.append(len(body))
            makespans.append(makespan)
        body.append([label if first else "", makespan, encoding] +
                    [cells[(label, encoding, c)].text((label, encoding, c) in best)
                     if (label, encoding, c) in cells else "-" for c in columns])
    header = ["domain", "makespan", "encoding", *map(str, columns)]
    key = _time_key(records, cells, best, makespans, sets, (described or {}) if name == "summary" else {},
                    _dashes(body, 3))
    return Table(name, caption, header, body, key, text_columns=3, groups=starts)


def _best_cells(rows: list[tuple[str, str]], columns: list, cells: dict[tuple, Any]) -> set[tuple]:
    """The cells marked ``*``: per domain and column the best of two or more encodings (the
    anytime method's time is to a first plan: not compared; a wrong answer is never the best)."""
    best = set()
    for label in {label for label, _e in rows}:
        for column in columns:
            compared = [e for row_label, e in rows
                        if row_label == label and (label, e, column) in cells and e != "anytime"]
            candidates = [(cells[(label, e, column)].rank(), e) for e in compared
                          if not cells[(label, e, column)].invalid]
            if len(compared) > 1 and candidates:
                best.add((label, min(candidates)[1], column))
    return best


def summary(records: list[dict], set_order: list[str] | None = None,
            described: dict[str, str] | None = None) -> Table:
    """The paper's summary table: average time (runs out of limits) per domain x encoding x set."""
    sets = _ordered({r["set"] for r in records}, set_order or [])
    return grouped_table(records, lambda r: r["set"], sets,
                         "Average run time in seconds (runs out of limits); runs out of limits count at the "
                         "time limit, failed runs apart", sets, "summary", described)


def by_robots(records: list[dict], set_order: list[str] | None = None) -> list[Table]:
    """One table per instance set with a column per robot count (the paper's appendix)."""
    tables = []
    for name in _ordered({r["set"] for r in records}, set_order or []):
        runs = [r for r in records if r["set"] == name]
        counts = sorted({r["robots"] for r in runs})
        tables.append(grouped_table(runs, lambda r: r["robots"], counts,
                                    f"Instance set {name}: average run time (runs out of limits) by number "
                                    f"of robots", None, f"robots-{name}"))
    return tables


def par(records: list[dict], factor: int) -> float | None:
    """The penalised average run time (PAR-``factor``) of the runs that solved or ran out of
    limits: a solved run counts its time, one out of limits ``factor`` times its time limit;
    invalid plans and errors are left out (``None``: no such run)."""
    scored = [r["time"] if r["status"] == SOLVED else factor * r["time_limit"] for r in records if _timed(r)]
    return sum(scored) / len(scored) if scored else None


def solved_table(records: list[dict]) -> Table | None:
    """Per domain and encoding over all instances: runs solved, out of limits, invalid and
    failed, PAR2 and PAR10 (``None`` without runs at the minimal makespan)."""
    runs = [r for r in records if r.get("method") != "anytime"]
    if not runs:
        return None
    body: list[list[str]] = []
    starts: list[int] = []
    previous = None
    for label, encoding in _rows(runs):
        group = [r for r in runs if (r["label"], r["encoding"]) == (label, encoding)]
        kinds = [outcome(r) for r in group]
        if label != previous:
            starts.append(len(body))
        scores = [par(group, factor) for factor in (2, 10)]
        body.append([label if label != previous else "", encoding, f"{kinds.count(SOLVED)}/{len(group)}",
                     str(kinds.count(LIMIT)), str(kinds.count(INVALID)), str(kinds.count(ERROR)),
                     *("-" if score is None else f"{score:.1f}" for score in scores)])
        previous = label
    header = ["domain", "encoding", "solved", "out of limits", "invalid", "errors", "PAR2", "PAR10"]
    limit = _time_limit(runs)
    key = [("solved", "runs with a plan that passes the checker, of all runs"),
           ("out of limits", "time-outs, mem-outs and runs without a known minimal makespan: the unsolved runs "
                             "of PAR"),
           ("invalid", "plans the checker rejected; errors: runs that failed; neither is in PAR"),
           ("PAR2, PAR10", f"penalised average run time in seconds over the solved runs and the unsolved runs, "
                           f"each unsolved run counted at 2 (10) times the time limit{limit}")]
    if _dashes(body, 6):
        key.append(("-", "no run solved or ran out of limits"))
    return Table("solved", "Solved runs and penalised average run time (PAR2, PAR10) over all instances",
                 header, body, key, text_columns=2, groups=starts)


def anytime_table(records: list[dict], set_order: list[str] | None = None) -> Table | None:
    """The anytime runs: per domain and instance set, how many found a plan, the average time
    to the first plan, and the average makespan at the end over its lower bound and over
    the minimal makespan (where another run of the suite knows it); ``None`` without such runs."""
    runs = [r for r in records if r.get("method") == "anytime"]
    if not runs:
        return None
    minimal = {(r["instance"], r["label"]): r["horizon"] for r in records
               if r.get("method") != "anytime" and r.get("horizon") is not None}
    body: list[list[str]] = []
    starts: list[int] = []
    for label in _ordered({r["label"] for r in runs}, LABELS):
        starts.append(len(body))
        for name in _ordered({r["set"] for r in runs if r["label"] == label}, set_order or []):
            group = [r for r in runs if r["label"] == label and r["set"] == name]
            body.append([label, name, *_anytime_row(group, minimal, label)])
    header = ["domain", "set", "plans", "first plan (s)", "makespan/bound", "makespan/minimal"]
    key = [("plans", "runs that returned a plan passing the checker, of all runs"),
           ("first plan (s)", "average seconds to the first plan of those runs"),
           ("makespan/bound", "average makespan at the end over the instance's lower bound"),
           ("makespan/minimal", "the same over the minimal makespan (where a run at the minimal makespan knows it)")]
    if _dashes(body, 2):
        key.append(("-", "none"))
    return Table("anytime", "Anytime runs: plans found, time to the first plan, makespan at the end",
                 header, body, key, text_columns=2, groups=starts)


def _anytime_row(group: list[dict], minimal: dict[tuple, int], label: str) -> list[str]:
    """Plans found, time to the first plan, makespan over the bound and over the minimum."""
    solved = [r for r in group if r["status"] == SOLVED]
    bound = [r["horizon"] / r["lower_bound"] for r in solved if r.get("lower_bound")]
    optimum = [r["horizon"] / minimal[(r["instance"], label)] for r in solved if minimal.get((r["instance"], label))]
    return [f"{len(solved)}/{len(group)}", f"{mean(r['time'] for r in solved):.1f}" if solved else "-",
            f"{mean(bound):.2f}" if bound else "-", f"{mean(optimum):.2f}" if optimum else "-"]


def failed_runs(records: list[dict]) -> Table | None:
    """The runs that failed (invalid plans and errors) with the reason in words (the first
    :data:`LISTED`; ``None`` if none failed)."""
    failed = sorted((r for r in records if not _timed(r)),
                    key=lambda r: (_rank(r["label"], LABELS), _rank(r["encoding"], ENCODINGS), r["set"],
                                   r["instance"]))
    if not failed:
        return None
    words = {INVALID: "invalid plan", ERROR: "error"}
    body = [[f"{r['label']} {r['encoding']}", f"{r['set']} {r['instance']}", words[outcome(r)],
             " ".join(str(r.get("error") or "no reason recorded").split())] for r in failed[:LISTED]]
    caption = f"Failed runs ({len(failed)}; not in the averages, not in PAR): domain encoding, set instance, why"
    key = []
    if len(failed) > LISTED:
        key.append(("...", f"and {len(failed) - LISTED} more: every run's reason is in results.csv (column error)"))
    return Table("failed", caption, ["run", "instance", "outcome", "reason"], body, key,
                 text_columns=4, listing=True, widths=FAILED_WIDTHS)


def tables(records: list[dict], set_order: list[str] | None = None,
           described: dict[str, str] | None = None) -> list[Table]:
    """Every table of the report, in order: the summary, solved runs and PAR, by robots, the
    anytime runs, the failed runs."""
    found = [summary(records, set_order, described), solved_table(records), *by_robots(records, set_order),
             anytime_table(records, set_order), failed_runs(records)]
    return [table for table in found if table is not None]


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
