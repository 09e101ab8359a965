"""Run benchmark suites under time and memory limits, report tables and plots, export for btool.

  asprilo bench SUITE.yml [-o DIR] [--jobs N] [--time-limit S] [--memory-limit MB] [--domain D]
      make the suite's instances, find their minimal makespans, run every (instance,
      domain, encoding, assignment) under OS-enforced limits, check every plan, append
      one JSON line per run to DIR/results.jsonl and print the summary table;
      rerunning resumes where a previous run stopped (with the same limits: results of
      other limits are not mixed in; --restart discards them)
  asprilo bench report DIR | RESULTS.xml [--plots png,pdf] [--scatter A:B ...] [--no-latex]
      print the paper's summary table, solved runs with PAR2/PAR10, the tables by robot
      count and the failed runs with their reasons, each with a key of its marks, and
      write DIR/report/: summary.txt, results.csv, each table as LaTeX (<table>.tex), and
      the plots (cactus, time-by-robots, scatter-A-B) in each format of --plots; reads
      DIR/results.jsonl, or what `btool eval` printed (RESULTS.xml, written to
      RESULTS-report/)
  asprilo bench online SUITE.yml [-o DIR] [--plots png,pdf]
      run an online suite (scenarios x planners x budgets, asprilo/bench/online.py): each
      an online run (asprilo online); DIR/online.jsonl, and DIR/report/: the table of
      throughput beside its ceiling, latency, planner time and waiting steps (text,
      LaTeX, CSV) and the throughput-over-time plot
  asprilo bench export-btool SUITE.yml DIR
      write a runscript, run templates and a result parser for potassco's
      benchmark-tool (btool 2.x), to run the suite on a cluster (benchmarks/README.md);
      the runs find the minimal makespans themselves

Examples:
  asprilo bench benchmarks/smoke.yml -o out/smoke
  asprilo bench benchmarks/paper.yml -o out/paper --jobs 2 --time-limit 60
  asprilo bench online benchmarks/online-small.yml -o out/online
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from asprilo.arguments import domain_argument, megabytes_argument
from asprilo.errors import InputError
from asprilo.generator.output import check_output_folder
from asprilo.writer import write_text

from . import btool, plots, report
from .plots import FORMATS
from .results import RESULTS, load_results
from .runner import Runner, forget_unknown_makespans, ticking
from .suite import MOST_SECONDS, load_suite

SUITE_ORDER = "suite.json"


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("words", nargs="+", metavar="SUITE.yml | report DIR | export-btool SUITE.yml DIR")
    parser.add_argument("-o", "--output", metavar="DIR", help="output folder (default: out/<suite name>)")
    parser.add_argument("--jobs", type=int, default=1, metavar="N", help="runs at the same time (default 1)")
    parser.add_argument("--time-limit", type=float, metavar="S", help="seconds per run (default: the suite's)")
    parser.add_argument("--memory-limit", type=megabytes_argument, metavar="MB",
                        help="MB per run (default: the suite's, at most ulimit -v)")
    parser.add_argument("--domain", type=domain_argument, action="append", metavar="D",
                        help="only the runs of this domain (a|b|c|m|md, its variants included; may be repeated)")
    parser.add_argument("--restart", action="store_true",
                        help="discard the output folder's results (e.g. to run again with other limits)")
    shown = parser.add_argument_group("the report (also after a run)")
    shown.add_argument("--plots", type=_formats, default=("png", "pdf"), metavar="FORMATS",
                       help=f"plot formats, comma-separated ({', '.join(FORMATS)}; default png,pdf; none: no plots)")
    shown.add_argument("--scatter", type=_pair, action="append", metavar="A:B",
                       help="a scatter plot of encoding A (x) against B (y), per instance; may be repeated "
                            "(default: the first encoding, plain where it ran, against every other)")
    shown.add_argument("--latex", action=argparse.BooleanOptionalAction, default=True,
                       help="write every table as LaTeX (booktabs) too (default: yes)")


def _formats(text: str) -> tuple[str, ...]:
    words = [word.strip().lower() for word in text.split(",") if word.strip()]
    if words == ["none"]:
        return ()
    unknown = [word for word in words if word not in FORMATS]
    if unknown or not words:
        raise argparse.ArgumentTypeError(f"{unknown[0] if unknown else text!r}: choose among "
                                         f"{', '.join(FORMATS)} (comma-separated), or none")
    return tuple(dict.fromkeys(words))


def _pair(text: str) -> tuple[str, str]:
    first, colon, second = text.partition(":")
    if not colon or not first or not second:
        raise argparse.ArgumentTypeError(f"{text!r}: expected ENCODING:ENCODING, e.g. plain:mine")
    return first, second


def run(args: argparse.Namespace) -> int:
    words = args.words
    if words[0] == "report":
        if len(words) != 2:
            raise InputError("usage: asprilo bench report DIR")
        return _report(Path(words[1]), args)
    if words[0] == "online":
        if len(words) != 2:
            raise InputError("usage: asprilo bench online SUITE.yml")
        return _online(words[1], args)
    if words[0] == "export-btool":
        if len(words) != 3:
            raise InputError("usage: asprilo bench export-btool SUITE.yml DIR")
        return _export(words[1], Path(words[2]), args)
    if len(words) != 1:
        raise InputError("give one suite file (or: report DIR, export-btool SUITE.yml DIR)")
    suite = load_suite(words[0])
    folder = Path(args.output or Path("out") / suite.name)
    check_output_folder(folder, "-o")
    runner = _runner(suite, folder, args)
    limits = {"time_limit": runner.time_limit, "memory_limit": runner.memory_limit,
              "makespan_time_limit": suite.makespan_time_limit}
    _same_limits(folder, limits, args.restart)
    folder.mkdir(parents=True, exist_ok=True)
    write_text(folder / SUITE_ORDER, json.dumps({"name": suite.name, "sets": [s.name for s in suite.sets],
                                                  "limits": limits, "encodings": _described(suite)}) + "\n")
    runner.run()
    return _report(folder, args)


def _online(path: str, args: argparse.Namespace) -> int:
    """An online suite: its runs, then the report (asprilo/bench/online.py)."""
    from .online import load_online_suite, report_online, run_suite

    suite = load_online_suite(path)
    folder = Path(args.output or Path("out") / suite.name)
    check_output_folder(folder, "-o")
    folder.mkdir(parents=True, exist_ok=True)
    records = run_suite(suite, folder)
    for written in report_online(records, folder / "report", args.plots):
        print(f"wrote {written}", file=sys.stderr)
    return 0


def _described(suite) -> dict[str, str]:
    """The suite's own encodings in words (files relative to the suite's folder, style,
    constants, options), for the report's key."""
    folder = suite.path.resolve().parent
    return {name: own.describe(folder).partition(": ")[2] for name, own in suite.encodings.items()}


#: how each limit is set, for messages
LIMIT_NAMES = {"time_limit": "--time-limit", "memory_limit": "--memory-limit",
               "makespan_time_limit": "the suite's makespan_time_limit"}


def _same_limits(folder: Path, limits: dict, restart: bool) -> None:
    """Results of runs under other limits are not mixed with this run's: refuse, or with
    ``restart`` discard them (and the makespans not found, to search them again)."""
    results = folder / RESULTS
    if not results.exists():
        return
    if restart:
        results.unlink()
        forget_unknown_makespans(folder)
        print(f"{folder}: earlier results discarded (--restart)", file=sys.stderr)
        return
    earlier = _recorded_limits(folder)
    changed = [f"{LIMIT_NAMES[key]} {earlier[key]} (this run: {value})" for key, value in limits.items()
               if key in earlier and earlier[key] != value]
    if changed:
        raise InputError(f"its results were run with {', '.join(changed)}; give --restart to discard them "
                         f"and run again, or -o ANOTHER_FOLDER", str(folder))


def _recorded_limits(folder: Path) -> dict:
    """The limits of a folder's runs: from suite.json, or (older folders) the time limit of its records."""
    try:
        recorded = json.loads((folder / SUITE_ORDER).read_text(encoding="utf-8")).get("limits")
    except (OSError, ValueError, AttributeError):
        recorded = None
    if isinstance(recorded, dict):
        return recorded
    limits = {record.get("time_limit") for record in load_results(folder)}
    return {"time_limit": limits.pop()} if len(limits) == 1 else {}


def _export(suite_file: str, folder: Path, args: argparse.Namespace) -> int:
    suite = load_suite(suite_file)
    check_output_folder(folder, "export-btool DIR")
    runner = _runner(suite, folder / "prepared", args)
    runscript = btool.export(suite, folder, runner, args.jobs)
    write_text(folder / SUITE_ORDER, json.dumps({"name": suite.name, "sets": [s.name for s in suite.sets],
                                                  "encodings": _described(suite)}) + "\n")
    print(f"wrote {runscript.relative_to(folder.resolve())} and what it needs below {folder}; run it with:\n"
          f"  cd {folder} && btool gen {runscript.relative_to(folder.resolve())}\n"
          f"  ./output/{suite.name}-seq/cluster/start.py     # here, or on Slurm: "
          f"./output/{suite.name}-dist/cluster/start.sh\n"
          f"  btool eval {runscript.relative_to(folder.resolve())} > results.xml && "
          f"asprilo bench report results.xml")
    return 0


def _runner(suite, folder: Path, args: argparse.Namespace) -> Runner:
    if args.domain:
        suite.runs = [spec for spec in suite.runs if (spec.base or spec.domain) in args.domain]
        if not suite.runs:
            raise InputError(f"the suite has no runs of domain {', '.join(d.label for d in args.domain)}",
                             str(suite.path))
    if args.jobs < 1:
        raise InputError(f"--jobs must be at least 1, got {args.jobs}")
    if args.time_limit is not None and not 0 < args.time_limit <= MOST_SECONDS:  # (nan too)
        raise InputError(f"--time-limit must be a positive finite number of seconds, at most {MOST_SECONDS:,} "
                         f"(a year), got {args.time_limit:g}")
    return Runner(suite, folder, args.jobs, args.time_limit, args.memory_limit)


def _report(path: Path, args: argparse.Namespace | None = None) -> int:
    """The report of a results folder (results.jsonl), or of the XML that ``btool eval`` printed."""
    if path.is_file():
        records, folder = btool.read_results(path), path.parent / f"{path.stem}-report"
    elif path.is_dir():
        records, folder = load_results(path), path
        if not records and (path / "results.xml").is_file():
            records = btool.read_results(path / "results.xml")
    else:
        raise InputError("no such folder or file", str(path))
    if not records:
        raise InputError("no results here (neither results.jsonl nor btool eval's results.xml)", str(path))
    formats = getattr(args, "plots", ("png", "pdf"))
    pairs = getattr(args, "scatter", None)
    _known_pairs(records, pairs)
    order, described = _suite_facts((path if path.is_dir() else path.parent) / SUITE_ORDER)
    tables = report.tables(records, order, described)
    text = "\n\n".join(table.text() for table in tables)
    print(text)
    out = folder / "report" if path.is_dir() else folder
    write_text(out / "summary.txt", text + "\n")
    write_text(out / "results.csv", report.to_csv(records))
    if getattr(args, "latex", True):
        for table in tables:
            write_text(out / f"{table.name}.tex", table.latex())
        print(f"wrote {len(tables)} LaTeX tables (booktabs) to {out}", file=sys.stderr)
    if formats:
        with ticking(sys.stderr, "drawing the plots (matplotlib)…"):
            pictures = plots.plot(records, out, order, formats, pairs)
        for picture in pictures:
            print(f"wrote {picture}", file=sys.stderr)
    return 0


def _suite_facts(path: Path) -> tuple[list[str] | None, dict[str, str]]:
    """The set order and the own encodings in words that the run of the suite recorded."""
    try:
        facts = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None, {}
    if not isinstance(facts, dict):
        return None, {}
    described = facts.get("encodings")
    return facts.get("sets"), described if isinstance(described, dict) else {}


def _known_pairs(records: list[dict], pairs: list[tuple[str, str]] | None) -> None:
    names = report.encodings_of(records)
    for pair in pairs or []:
        unknown = [name for name in pair if name not in names]
        if unknown:
            raise InputError(f"--scatter {':'.join(pair)}: no runs of encoding '{unknown[0]}' in these results "
                             f"(encodings: {', '.join(names)})")
