"""Grade your encoding on a ladder of instances: is each plan valid, is it minimal?

ENCODING is one or several files of your own encoding (as asprilo solve --encoding takes
them: single-shot with a horizon constant, incremental, clingcon, clingo-dl; -c NAME=VALUE
and clingo's --name=value options go to clingo), or the name of a reference encoding.  It
runs on the bundled ladder of the domain: instances from one robot on a few cells up to
11x6 floors with 3 to 5 robots, each with its minimal makespan established independently
(max-flow for M/Md, the reference encodings' proven minimum for A/B/C, cross-checked by
a breadth-first search over joint states where the instance is tiny; --list shows them).

Each instance is solved from a lower bound up in a child process under --time-limit
(default 20 s; so the whole run takes at most about that times the number of instances)
and its plan checked.  A line per instance: valid or not, minimal or "makespan 9,
minimum 7", the time, and the first violation in words or why there is no plan (time
limit and where, no answer set, occurs/3 atoms that are no plan, clingo refusing the
encoding, a crash), clingo's warnings under it; then a summary line.  --json: the same
as JSON for course tools (docs/GRADING.md).  Progress goes to stderr.

Against a model solution: --reference TEACHER.lp --instances DIR (and --variant V for
changed rules) takes each minimum from the teacher's encoding, searched from the lower
bound up under the same time limit ("minimum unknown" where it proved none), and checks
the plans under the variant's rules; --exercise FILE bundles all of it (docs/GRADING.md).

--class grades a class one by one: each ENCODING a submission's file or a folder of them
(each sub-folder one), then a table; --csv FILE writes a row per submission.

Exit status: 0 every instance got a valid plan, 1 some did not, 2 bad input (the command
line; an encoding that clingo refuses is graded).

Examples:
  asprilo grade my.lp --domain m
  asprilo grade main.lp goal.lp --domain a -c lanes=2 --configuration=crafty
  asprilo grade my.lp --domain m --json --time-limit 10 > grades.json
  asprilo grade my.lp --ladder course/week3/ladder.yml
  asprilo grade --list --domain c
  asprilo grade student.lp --variant visit-anytime --reference teacher.lp --instances exercise/
  asprilo grade student.lp --exercise week5/exercise.yml --json
  asprilo grade --class submissions/ --domain m --csv class.csv
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, TextIO

from asprilo.arguments import (
    add_variant_option,
    chosen_domain,
    domain_argument,
    loaded_variants,
    megabytes_argument,
    seconds_argument,
)
from asprilo.domain import Domain, detect_domain
from asprilo.errors import InputError
from asprilo.paths import PathError
from asprilo.reader import read_instance

from .choice import choose_encoding, stage_encoding
from .exercise import Exercise, instance_files, instance_ladder, read_exercise
from .grading import (
    JSON_VERSION,
    VALID,
    VERDICTS,
    Graded,
    Summary,
    grade_ladder,
    horizons,
    refusal_words,
    refused,
    too_strong,
    warning_lines,
)
from .ladder import Ladder, Rung, bundled_ladder, read_ladder
from .probes import REFUSED, Probe, add_probes, probe_report, require_illegal, summary_words
from .reference import Reference
from .registry import Encoding, find_encoding
from .solving import Phase
from .solving.minimality import sentence

#: options asprilo does not know are clingo's (the command line passes them on)
CLINGO_OPTIONS = True
#: seconds per instance unless told otherwise
DEFAULT_TIME_LIMIT = 20.0


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("encoding", metavar="ENCODING", nargs="*",
                        help="files of your own encoding (loaded in this order), or a reference encoding's name")
    parser.add_argument("--domain", type=domain_argument, help="a|b|c|m|md: grade on this domain's ladder")
    parser.add_argument("--ladder", metavar="FILE", help="a ladder of your own (ladder.yml; docs/GRADING.md)")
    parser.add_argument("-c", "--const", action="append", default=[], metavar="NAME=VALUE",
                        help="a constant for your encoding, as clingo's -c (-c horizon=H solves at H only)")
    parser.add_argument("--time-limit", type=seconds_argument, metavar="S",
                        help=f"seconds per instance, grounding and check included (default {DEFAULT_TIME_LIMIT:g})")
    parser.add_argument("--memory-limit", type=megabytes_argument, metavar="MB",
                        help="megabytes per instance (default: half the machine's memory or 8192, whichever is "
                             "less, and at most ulimit -v)")
    parser.add_argument("--first", type=_count, metavar="N", help="grade only the first N instances of the ladder")
    parser.add_argument("--json", action="store_true", help="print the grades as JSON (docs/GRADING.md)")
    parser.add_argument("--class", dest="class_", action="store_true",
                        help="grade a class: each ENCODING is a submission (a file), or a folder of submissions "
                             "(each encoding file in it one, each sub-folder one of its encoding files), graded "
                             "one by one, then a table of the class")
    parser.add_argument("--csv", metavar="FILE", help="with --class: write a row per submission to FILE (CSV)")
    parser.add_argument("--list", action="store_true", help="list the ladder's instances and their minima, and exit")
    parser.add_argument("-q", "--quiet", action="store_true", help="no progress on stderr")
    parser.add_argument("--stage", action="extend", nargs="+", metavar="FILE",
                        help="a first stage of the encoding (e.g. a task assignment), solved once with each instance "
                             "and the same -c constants: the shown atoms of its first answer become facts of the "
                             "encoding (as asprilo solve --stage)")
    add_variant_option(parser)
    group = parser.add_argument_group("against a model solution", "the minima from a teacher's encoding, the "
                                      "plans checked under the exercise's rules (docs/GRADING.md)")
    group.add_argument("--reference", nargs="+", action="extend", metavar="FILE",
                       help="the model solution's files (or a reference encoding's name; default: the variant's "
                            "model solution): each minimum is what its search proves")
    group.add_argument("--instances", nargs="+", action="extend", metavar="DIR|FILE",
                       help="the instances to grade on: a folder (its .lp files, by name) or files")
    group.add_argument("--exercise", metavar="FILE",
                       help="an exercise file (exercise.yml) naming the domain, variants, reference, instances and "
                            "time limit")


def _count(text: str) -> int:
    try:
        number = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
    if number < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {number}")
    return number


@dataclass(frozen=True)
class _Setup:
    """What a run grades on: the instances (a ladder), the reference that computes their
    minima (``None``: they are stored), the time limit and the exercise file, if any."""

    ladder: Ladder
    reference: Reference | None
    time_limit: float
    exercise: Exercise | None = None


def run(args: argparse.Namespace) -> int:
    setup = _setup(args)
    ladder, reference = setup.ladder, setup.reference
    if args.list:
        _list(ladder, reference)
        return 0
    if not args.encoding:
        raise InputError("no encoding given (asprilo grade ENCODING... --domain D)")
    if args.csv is not None and not args.class_:
        raise InputError("--csv writes the table of a class: grade one with --class")
    if args.class_:
        from .grade_class import grade_class
        return grade_class(args, setup)
    submission = graded_encoding(args, args.encoding, ladder)
    out = sys.stdout
    progress = GradeProgress(sys.stderr, quiet=args.quiet)
    # no probes on a part of the ladder, or where a first stage's answer could rule a plan out
    probing = bool(ladder.probes) and args.first is None and submission.stage is None and not submission.refusal
    for probe in ladder.probes if probing else ():  # a legal plan is a mistake of the ladder: before any grade
        require_illegal(probe, ladder.domain)
    graded, summary = grade_submission(submission, args, setup, out, progress)
    probed = probe_report(submission.encoding, ladder.probes, ladder.domain, time_limit=setup.time_limit,
                          memory_limit=args.memory_limit, out=None if args.json else out, on_start=progress.probe,
                          on_done=progress.clear, checked=True) if probing else None
    if args.json:
        answer = report(submission.encoding, submission.horizon, ladder, setup.time_limit, graded, summary,
                        reference, setup.exercise)
        add_probes(answer, probed)
        _say(out, json.dumps(answer, indent=2))
    else:
        _say(out, summary.line() + ("" if probed is None else f"; {summary_words(probed)}"))
    clean = probed is None or all(item.result == REFUSED for item in probed)
    return 0 if summary.valid == summary.instances and clean else 1


@dataclass(frozen=True)
class Submission:
    """An encoding to grade: the one its files make, its horizon (``-c horizon=H``) and first
    stage (``--stage``); for files clingo refuses, a stand-in and the ``refusal`` in words."""

    encoding: Encoding
    horizon: int | None = None
    stage: Encoding | None = None
    refusal: str = ""


def graded_encoding(args: argparse.Namespace, values: list[str], ladder: Ladder) -> Submission:
    """The encoding that ``values`` name, with the command line's constants, options and
    first stage: an encoding clingo refuses is graded (the refusal comes back), a mistake of
    the command line (a missing file, an option) is :class:`InputError`."""
    try:
        encoding, horizon = choose_encoding(values, args.const, getattr(args, "clingo_options", None) or (),
                                            ladder.domain)
        stage = stage_encoding(args.stage, encoding.constants) if args.stage else None
    except InputError as error:
        if not _in_encoding(error):
            raise
        return Submission(refused_encoding(values), refusal=refusal_words(error))
    return Submission(encoding, horizon, stage)


def grade_submission(submission: Submission, args: argparse.Namespace, setup: _Setup, out: TextIO,
                     progress: GradeProgress) -> tuple[list[Graded], Summary]:
    """Grade one submission on the setup's instances; without ``--json`` its header, a line
    per instance and clingo's warnings (each the first time it is said) go to ``out``."""
    ladder, reference, time_limit = setup.ladder, setup.reference, setup.time_limit
    started = time.perf_counter()
    graded: list[Graded] = []
    said: list[str] = []
    steps = len(ladder.rungs) if args.first is None else min(args.first, len(ladder.rungs))
    if submission.refusal:
        grades = refused(ladder, submission.refusal, args.first)
    else:
        grades = grade_ladder(submission.encoding, ladder, time_limit=time_limit, horizon=submission.horizon,
                              stage=submission.stage, memory_limit=args.memory_limit, first=args.first,
                              reference=reference, on_start=progress.start, on_phase=progress.phase,
                              on_reference_phase=progress.reference_phase)
    try:
        for item in grades:
            progress.clear()
            if not args.json and not graded:  # after the first grade: a bad reference is an error alone
                _say(out, _header(submission.encoding, ladder, steps, time_limit, reference))
            graded.append(item)
            if not args.json:
                _say(out, "\n".join([line(item, steps), *warning_lines(item, said)]))
    finally:
        progress.clear()
    return graded, Summary.of(graded, time.perf_counter() - started)

def _setup(args: argparse.Namespace) -> _Setup:
    """The ladder, or the instances with the reference that computes their minima."""
    if args.exercise is not None:
        return _exercise_setup(args)
    time_limit = args.time_limit or DEFAULT_TIME_LIMIT
    if args.instances is None:
        if args.reference is not None or args.variant:
            what = "--reference" if args.reference is not None else "--variant"
            raise InputError(f"{what} grades against a model solution: name the instances (--instances DIR) or an "
                             "exercise (--exercise FILE); a ladder's minima hold for the plain rules only")
        return _Setup(_ladder(args), None, time_limit)
    if args.ladder is not None:
        raise InputError("grade on a ladder (--ladder) or on instances (--instances), not both")
    variants = loaded_variants(args)  # before reading: the attributes they declare are data
    files = instance_files(args.instances)
    if args.domain is not None:
        base = args.domain
    elif variants and len(variants[0].domains) == 1:  # the one domain the variant changes
        base = Domain.parse(variants[0].domains[0])
    else:
        base = detect_domain(read_instance(files[0]))
    domain = chosen_domain(args, base) or base
    shown = ", ".join(args.instances)
    ladder = instance_ladder(domain, files, Path(args.instances[0]), f"the instances {shown}", "the reference")
    return _Setup(ladder, _reference(args.reference, domain, time_limit, args.memory_limit), time_limit)


def _exercise_setup(args: argparse.Namespace) -> _Setup:
    given = [flag for flag, value in (("--ladder", args.ladder), ("--instances", args.instances),
                                      ("--reference", args.reference), ("--variant", args.variant)) if value]
    if given:
        raise InputError(f"{given[0]} and --exercise: the exercise file names its own instances, variants and "
                         "reference")
    exercise = read_exercise(args.exercise)
    if args.domain is not None and args.domain is not exercise.domain:
        raise InputError(f"the exercise is of domain {exercise.domain.label}, not {args.domain.label}",
                         str(exercise.path))
    from asprilo.domain.variants import with_variants
    domain = with_variants(exercise.domain, exercise.variants)  # loads them before the instances are read
    time_limit = args.time_limit or exercise.time_limit or DEFAULT_TIME_LIMIT
    title = f"the exercise {exercise.name} ({exercise.path})"
    ladder = replace(instance_ladder(domain, exercise.instances, exercise.path, title, "the reference"),
                     probes=exercise.probes)
    reference = _reference(list(exercise.reference) or None, domain, time_limit, args.memory_limit)
    return _Setup(ladder, reference, time_limit, exercise)


def _reference(values: list[str] | None, domain: Domain, time_limit: float, memory_limit: int | None) -> Reference:
    """The teacher's encoding: ``values`` as ``--reference`` names it, else the domain's model
    solution (a varied domain's: its variant's)."""
    if values is None:
        if not domain.encodings:
            raise InputError(f"no model solution for {domain.label}: name the teacher's encoding "
                             "(--reference FILE, or 'reference:' in the exercise file)")
        encoding = find_encoding(domain, domain.encodings[0].name)
    else:
        encoding, _ = choose_encoding(values, (), (), domain)
    return Reference(encoding, domain, time_limit=time_limit, memory_limit=memory_limit)


def _in_encoding(error: InputError) -> bool:
    """Whether ``error`` is about what an encoding's files say (a syntax error, a missing
    #include: a grade), not about the command line (a file not there, an option)."""
    return error.file is not None and not isinstance(error, PathError)


def refused_encoding(values: list[str], summary: str = "refused by clingo") -> Encoding:
    """A stand-in for an encoding clingo refuses outright: its files, no style (``summary``
    says why)."""
    files = [Path(value) for value in values]
    return Encoding("+".join(file.stem for file in files), None, files[0], None, False, summary,
                    extra=tuple(files[1:]), own=True)


def _ladder(args: argparse.Namespace) -> Ladder:
    if args.ladder is None:
        if args.domain is None:
            raise InputError("name the domain (--domain a|b|c|m|md) or a ladder (--ladder FILE)")
        return bundled_ladder(args.domain)
    ladder = read_ladder(args.ladder)
    if args.domain is not None and args.domain is not ladder.domain:
        raise InputError(f"the ladder is of domain {ladder.domain.label}, not {args.domain.label}", args.ladder)
    return ladder


def _list(ladder: Ladder, reference: Reference | None) -> None:
    print(f"{ladder.label}: {len(ladder.rungs)} instances" + ("" if ladder.title else f" ({ladder.manifest})"))
    if reference is not None:
        print(f"  rules: {ladder.domain.label}; minima: {_reference_words(reference.encoding)}")
    width = max(len(rung.name) for rung in ladder.rungs)
    for step, rung in enumerate(ladder.rungs, 1):
        instance = read_instance(rung.file)
        if reference is not None:
            rung = reference.rung(rung, instance)
        (x, y), robots = instance.size, len(instance.robots)
        size = f"{x}x{y}, {robots} robot{'s' * (robots != 1)}"
        minimum = "unknown" if rung.minimum is None else rung.minimum
        print(f"{step:>2}  {rung.name:<{width}}  {size:<15}  minimum {minimum}")
        print(f"      established: {rung.established if rung.reference is None else rung.reference.words()}")
        for method in rung.cross_checked:
            print(f"      cross-checked: {method}")


def _header(encoding: Encoding, ladder: Ladder, count: int, time_limit: float,
            reference: Reference | None = None) -> str:
    if encoding.own:
        what = f"your encoding ({', '.join(str(file) for file in encoding.files)}: {encoding.summary})"
    else:
        what = f"the reference encoding {encoding.name}"
    lines = [f"grading {what} on {ladder.label}: {count} instance{'s' * (count != 1)}, "
             f"time limit {time_limit:g} s each"]
    lines += [f"  assumed: {note}" for note in encoding.assumed]
    if reference is not None:
        lines.append(f"  rules: {ladder.domain.label}; minima: {_reference_words(reference.encoding)}")
    return "\n".join(lines)


def _reference_words(encoding: Encoding) -> str:
    """Who computes the minima, in words."""
    name = ", ".join(str(file) for file in encoding.files) if encoding.own else encoding.name
    how = "solved once" if encoding.fixed else "searched from the lower bound up"
    return f"the reference encoding {name} ({encoding.summary}), {how}"


def line(graded: Graded, steps: int) -> str:
    """One instance's grade in a line: step, name, size, time, result and what to know."""
    number = f"{graded.step:>{len(str(steps))}}/{steps}"
    return (f"{number}  {graded.rung.name:<14} {graded.size:<15} {graded.seconds:6.1f} s  "
            f"{VERDICTS[graded.result]:<8} {detail(graded)}")


def detail(graded: Graded) -> str:
    """What to know about one grade, in words."""
    rung = graded.rung
    minimum = rung.minimum
    if graded.result == VALID:
        if minimum is not None and graded.makespan == minimum:
            return f"minimal (makespan {minimum})"
        floor = minimum if minimum is not None else rung.reference.at_least if rung.reference else None
        if graded.makespan is not None and floor is not None and graded.makespan < floor:
            return _below(graded, floor)
        notes = [rung.reference.words()] if minimum is None and rung.reference is not None else []
        if graded.too_strong:
            notes.append(f"{horizons(graded.too_strong)} refuted{too_strong(graded)}")
        said = f" ({'; '.join(notes)})" if notes else ""
        if graded.encoding_minimal and graded.makespan is not None:  # it refuted every shorter horizon
            return sentence(graded.makespan, minimum) + said
        return f"makespan {graded.makespan}, minimum {'unknown' if minimum is None else minimum}{said}"
    if graded.violation is not None:
        more = graded.violations - 1
        others = f" (and {more} more violation{'s' * (more != 1)})" if more else ""
        return f"makespan {graded.makespan}: {graded.violation.message}{others}"
    return graded.reason


def _below(graded: Graded, floor: int) -> str:
    """A valid plan shorter than what the ladder stores or the reference proved."""
    if graded.rung.reference is None:
        return (f"makespan {graded.makespan}, below the stored minimum {floor}: the ladder is wrong, "
                "please report it")
    said = f"the reference's minimum {floor}" if graded.rung.minimum is not None else \
        f"what the reference proved (none shorter than {floor})"
    return f"makespan {graded.makespan}, below {said}: the reference encoding misses plans"


def report(encoding: Encoding, horizon: int | None, ladder: Ladder, time_limit: float, graded: list[Graded],
           summary: Summary, reference: Reference | None = None, exercise: Exercise | None = None) -> dict[str, Any]:
    """The grades as plain data (``--json``; the shape is docs/GRADING.md's).  Graded against
    a reference, the report, each instance and the summary have a few keys more."""
    against = reference is not None
    answer: dict[str, Any] = {"version": JSON_VERSION, "domain": ladder.domain.value}
    if against:
        answer["variants"] = list(ladder.domain.variants)
    answer["ladder"] = None if against else ladder.domain.value if ladder.bundled else str(ladder.manifest)
    if against:
        answer["exercise"] = None if exercise is None else {"name": exercise.name, "file": str(exercise.path),
                                                            "summary": exercise.summary or None}
    answer["encoding"] = {**_encoding_json(encoding), "assumed": list(encoding.assumed),
                          "constants": dict(encoding.constants), "horizon": horizon,
                          "options": list(encoding.options)}
    if reference is not None:
        answer["reference"] = _encoding_json(reference.encoding)
    answer["time_limit"] = time_limit
    answer["instances"] = [_instance_json(item, against) for item in graded]
    answer["summary"] = summary.as_json()
    if against:
        answer["summary"]["minima_unknown"] = summary.unknown
    return answer


def _instance_json(graded: Graded, against: bool) -> dict[str, Any]:
    entry = graded.as_json()
    if against:
        found = graded.rung.reference
        entry["reference"] = None if found is None else found.as_json()
    return entry


def _encoding_json(encoding: Encoding) -> dict[str, Any]:
    return {"name": encoding.name, "own": encoding.own,
            "files": [str(file) for file in encoding.files] if encoding.own else [], "style": encoding.summary}


def _say(stream: TextIO, text: str) -> None:
    stream.write(text + "\n")
    stream.flush()


class GradeProgress:
    """Says on stderr which instance is being graded: on a terminal one line redrawn as the
    search goes (the horizon and phase, after ``prefix``), otherwise a line per instance
    (unless ``instance_lines`` is false: a class says a line per submission instead)."""

    def __init__(self, stream: TextIO, quiet: bool = False, instance_lines: bool = True):
        self.stream, self.quiet = stream, quiet
        self.live = stream.isatty() and not quiet
        self.instance_lines = instance_lines
        self.prefix = ""
        self.current = ""

    def start(self, step: int, steps: int, rung: Rung) -> None:
        if self.quiet:
            return
        minimum = "the reference's minimum first" if rung.minimum is None else f"minimum {rung.minimum}"
        self.current = f"{self.prefix}[{step}/{steps}] {rung.name} ({minimum})"
        if self.live:
            self.stream.write(f"\r\033[K{self.current}")
        elif self.instance_lines:
            self.stream.write(f"grading {self.current}\n")
        self.stream.flush()

    def probe(self, number: int, count: int, probe: Probe) -> None:
        """Before the ``number``-th of ``count`` probes."""
        self.current = f"{self.prefix}probe [{number}/{count}] {probe.name} ({probe.rule})"
        if self.live or (self.instance_lines and not self.quiet):
            self.stream.write(f"\r\033[K{self.current}" if self.live else f"probing {self.current}\n")
            self.stream.flush()

    def phase(self, phase: Phase, who: str = "") -> None:
        if self.live and phase.name in ("grounding", "solving"):
            self.stream.write(f"\r\033[K{self.current}: {who}horizon {phase.horizon}, {phase.name}")
            self.stream.flush()

    def reference_phase(self, phase: Phase) -> None:
        self.phase(phase, "the reference, ")

    def clear(self) -> None:
        if self.live:
            self.stream.write("\r\033[K")
            self.stream.flush()
