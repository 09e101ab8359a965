"""Grade a class (``asprilo grade --class``): every submission graded on the same instances,
one after the other, then a table of the class.

The submissions are named on the command line: a file is one submission; a folder holds
them, each encoding file in it (``.lp``, ``.ilp``, ``.iclp``, ``.clp``) one submission and
each sub-folder one made of its encoding files, loaded in name order.  A submission is named
by its file's stem or its folder's name.  Whatever a submission does is its own grade: a
syntax error, an empty folder, a crash, a limit are its lines, and the next one is graded.

    asprilo grade --class submissions/ --domain m --csv class.csv

Text: each submission's grades as ``asprilo grade`` prints them, then the table (a line per
submission: valid and minimal counts and what went wrong; totals).  ``--json``: an object
per submission and the class summary (docs/GRADING.md).  ``--csv FILE``: a row per
submission, written atomically.
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from asprilo.errors import InputError
from asprilo.writer import check_output, write_text

from .grade import (
    GradeProgress,
    Submission,
    detail,
    grade_submission,
    graded_encoding,
    refused_encoding,
    report,
)
from .grading import VERDICTS, Graded, Summary
from .own import check_options
from .probes import UNDECIDED, Probed, add_probes, probe_report, require_illegal, summary_words
from .probes import summary as probes_summary

if TYPE_CHECKING:
    from .grade import _Setup

#: the files of a folder that are encodings (a submission each, or together a sub-folder's)
ENCODING_SUFFIXES = (".lp", ".ilp", ".iclp", ".clp")
#: the columns of ``--csv``
CSV_COLUMNS = ("student", "files", "instances", "valid", "minimal", "invalid", "no_plan", "time_outs",
               "forgot", "refused", "first_failure", "clingo_warnings", "seconds")


@dataclass(frozen=True)
class Member:
    """One submission of a class: its name and its encoding files (none: an empty folder)."""

    name: str
    path: Path
    files: tuple[Path, ...]


@dataclass
class Result:
    """How one submission did: its encoding (or refusal), its grades and their counts, the
    ladder's probes (``None``: not run)."""

    member: Member
    submission: Submission
    graded: list[Graded]
    summary: Summary
    probed: list[Probed] | None = None

    @property
    def all_valid(self) -> bool:
        return self.summary.valid == self.summary.instances

    @property
    def forgot(self) -> list[str]:
        """The probes it accepted: the rules it forgot."""
        return [item.probe.name for item in self.probed or () if item.forgot]

    @property
    def clean(self) -> bool:
        """Every plan valid, no rule forgotten."""
        return self.all_valid and not self.forgot

    def warnings(self) -> list[str]:
        """clingo's warnings on the encoding, each once."""
        return list(dict.fromkeys(warning for item in self.graded for warning in item.warnings))

    def notes(self) -> str:
        """What went wrong, in a few words: the refusal, or the counts, and how many warnings
        clingo gave (``""``: nothing)."""
        parts = [self.submission.refusal or self.summary.failures()]
        if self.forgot:
            parts.append(f"forgot {', '.join(self.forgot)}")
        undecided = sum(item.result == UNDECIDED for item in self.probed or ())
        if undecided:
            parts.append(f"{undecided} probe{'s' * (undecided != 1)} undecided")
        warnings = len(self.warnings())
        if warnings:
            parts.append(f"{warnings} clingo warning{'s' * (warnings != 1)}")
        return "; ".join(part for part in parts if part)

    def first_failure(self) -> str:
        """The first instance without a valid plan and why, in words (``""``: none)."""
        for item in self.graded:
            if not item.valid:
                return f"{item.rung.name}: {VERDICTS[item.result]} {detail(item)}"
        return ""


def class_members(values: list[str]) -> list[Member]:
    """The submissions that the command line's files and folders name, in order (a folder's
    by name); bad input: :class:`InputError` (a path not there, no submission at all)."""
    members: list[Member] = []
    for value in values:
        path = Path(value)
        if not path.exists():
            raise InputError("no such file or folder", value)
        if path.is_file():
            members.append(Member(path.stem, path, (path,)))
            continue
        for entry in sorted(path.iterdir()):
            if entry.name.startswith("."):
                continue
            if entry.is_dir():
                members.append(Member(entry.name, entry, _encoding_files(entry)))
            elif entry.suffix in ENCODING_SUFFIXES:
                members.append(Member(entry.stem, entry, (entry,)))
    if not members:
        raise InputError(f"no submissions: no encoding files ({', '.join(ENCODING_SUFFIXES)}) or sub-folders",
                         values[0])
    return _unique(members)


def _encoding_files(folder: Path) -> tuple[Path, ...]:
    return tuple(sorted(entry for entry in folder.iterdir()
                        if entry.is_file() and entry.suffix in ENCODING_SUFFIXES and not entry.name.startswith(".")))


def _unique(members: list[Member]) -> list[Member]:
    """The members, those whose names repeat named by their paths instead."""
    names = [member.name for member in members]
    return [member if names.count(member.name) == 1 else Member(str(member.path), member.path, member.files)
            for member in members]


def grade_class(args: argparse.Namespace, setup: _Setup) -> int:
    """Grade every submission that ``args.encoding`` names on the setup's instances (and the
    ladder's probes, as for one encoding); print the grades and the table (or ``--json``),
    write ``--csv``.  Exit status 0 when every submission got a valid plan on every
    instance and forgot no rule, else 1."""
    members = class_members(args.encoding)
    check_options(getattr(args, "clingo_options", None) or ())  # the command line's, once for all
    ladder = setup.ladder
    # no probes on a part of the ladder, or where a first stage's answer could rule a plan out
    probing = bool(ladder.probes) and args.first is None and not args.stage
    for probe in ladder.probes if probing else ():  # a legal plan is a mistake of the ladder: before any grade
        require_illegal(probe, ladder.domain)
    if args.csv is not None:
        check_output(args.csv, [file for member in members for file in member.files])
    out = sys.stdout
    progress = GradeProgress(sys.stderr, quiet=args.quiet, instance_lines=False)
    started = time.perf_counter()
    results = []
    for number, member in enumerate(members, 1):
        if not args.quiet and not progress.live:
            sys.stderr.write(f"grading {number}/{len(members)}: {member.name}\n")
        progress.prefix = f"{member.name} ({number}/{len(members)}) "
        submission = _submission(args, member, setup)
        graded, summary = grade_submission(submission, args, setup, out, progress)
        probed = probe_report(submission.encoding, ladder.probes, ladder.domain, time_limit=setup.time_limit,
                              memory_limit=args.memory_limit, out=None if args.json else out, on_start=progress.probe,
                              on_done=progress.clear, checked=True) if probing and not submission.refusal else None
        if not args.json:
            out.write(summary.line() + ("" if probed is None else f"; {summary_words(probed)}") + "\n\n")
        results.append(Result(member, submission, graded, summary, probed))
    seconds = time.perf_counter() - started
    if args.json:
        out.write(json.dumps(class_report(results, setup, seconds), indent=2) + "\n")
    else:
        out.write("\n".join(table(results, seconds)) + "\n")
    out.flush()
    if args.csv is not None:
        write_text(args.csv, csv_text(results))
    return 0 if all(result.clean for result in results) else 1


def _submission(args: argparse.Namespace, member: Member, setup: _Setup) -> Submission:
    """The member's encoding; whatever refuses it (clingo, an empty folder, a constant it
    cannot take) is the member's grade."""
    if not member.files:
        return Submission(refused_encoding([str(member.path)], "no encoding files"),
                          refusal=f"no encoding files ({', '.join(ENCODING_SUFFIXES)}) in the folder {member.path}")
    values = [str(file) for file in member.files]
    try:
        return graded_encoding(args, values, setup.ladder)
    except InputError as error:  # the command line's constants or options do not fit this encoding
        return Submission(refused_encoding(values, "not graded"), refusal=f"not graded: {' '.join(str(error).split())}")


def table(results: list[Result], seconds: float) -> list[str]:
    """The class in a table: a line per submission (valid and minimal counts, what went
    wrong, clingo's warnings), the totals, and how many submissions got a valid plan everywhere."""
    total = Summary.of([item for result in results for item in result.graded], seconds)
    width = max(len("student"), len("all"), *(len(result.member.name) for result in results))
    rows = [("student", "valid", "minimal", "notes")]
    for result in results:
        n = result.summary.instances
        rows.append((result.member.name, f"{result.summary.valid}/{n}", f"{result.summary.minimal}/{n}",
                     result.notes()))
    n = total.instances
    forgetful = sum(bool(result.forgot) for result in results)
    notes = [total.failures()] + [f"{forgetful} forgot a rule"] * bool(forgetful)
    rows.append(("all", f"{total.valid}/{n}", f"{total.minimal}/{n}", ", ".join(note for note in notes if note)))
    lines = [f"{name:<{width}}  {valid:>5}  {minimal:>7}  {notes}".rstrip() for name, valid, minimal, notes in rows]
    refused = sum(bool(result.submission.refusal) for result in results)
    count = len(results)
    probed = any(result.probed is not None for result in results)
    lines.append(f"{count} submission{'s' * (count != 1)}: {sum(r.clean for r in results)} with every plan "
                 f"valid{' and no rule forgotten' if probed else ''}" + (f", {refused} refused" if refused else "")
                 + f"; {seconds:.1f} s")
    return lines


def class_report(results: list[Result], setup: _Setup, seconds: float) -> dict[str, Any]:
    """The class as plain data (``--json``; the shape is docs/GRADING.md's): the keys of one
    grade's report that the class shares, an object per submission, the class summary."""
    shared: dict[str, Any] = {}
    submissions = []
    for result in results:
        graded = report(result.submission.encoding, result.submission.horizon, setup.ladder, setup.time_limit,
                        result.graded, result.summary, setup.reference, setup.exercise)
        entry = {"name": result.member.name, "files": [str(file) for file in result.member.files],
                 "refused": result.submission.refusal or None, "warnings": result.warnings()}
        add_probes(graded, result.probed)
        for key, value in graded.items():
            if key in ("encoding", "instances", "probes", "summary"):
                entry[key] = value
            else:
                shared[key] = value
        submissions.append(entry)
    total = Summary.of([item for result in results for item in result.graded], seconds)
    summary = {"submissions": len(results), "all_valid": sum(result.all_valid for result in results),
               "clean": sum(result.clean for result in results),
               "refused": sum(bool(result.submission.refusal) for result in results), **total.as_json()}
    probed = [item for result in results for item in result.probed or ()]
    if any(result.probed is not None for result in results):
        summary["probes"] = probes_summary(probed)
    return {**shared, "class": True, "submissions": submissions, "summary": summary}


def csv_text(results: list[Result]) -> str:
    """A header row and a row per submission (:data:`CSV_COLUMNS`)."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(CSV_COLUMNS)
    for result in results:
        summary = result.summary
        writer.writerow([result.member.name, " ".join(str(file) for file in result.member.files), summary.instances,
                         summary.valid, summary.minimal, summary.invalid, summary.no_plan, summary.time_outs,
                         " ".join(result.forgot), result.submission.refusal, result.first_failure(),
                         " | ".join(result.warnings()), f"{summary.seconds:.3f}"])
    return buffer.getvalue()
