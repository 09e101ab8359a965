"""``asprilo grade --class``: a folder of submissions graded one by one, each failure the
student's own line, then a table, ``--json`` and ``--csv`` -- and clingo's hints kept.

The class is tests/grade-class/ (five submissions written for these tests, each file's header
says what its student did), graded on the first two instances of the M ladder.  Expected
grades by hand:

- instance 1 (3x2): robot 1 at (3,2), the ordered shelf at (1,1): 3 moves, minimum 3;
- instance 2 (5x2): robots at (1,1) and (2,1), the ordered shelves at (5,1) and (5,2):
  robot 1 needs 4 moves to (5,1), robot 2 4 moves to (5,2) (5 the other way round), so the
  minimum is 4 and every plan of makespan 4 moves both robots right (robot 2 up once) at
  every step: no two robots ever move towards each other, so no plan of makespan 4 swaps.

ada (correct, two files): valid and minimal on both.  bob: clingo stops at line 3, column 45
(the '.' where the ')' of init(...) is missing).  cyd: its occurs(object(robot,R),start(C),0)
atoms are no plan.  dan: the swap constraint reads att/3, which no rule defines (clingo's
hint, line 16, columns 44-55): swaps are allowed, but no plan of makespan 3 or 4 here can
swap, so both plans are valid and minimal.  eve: ten million numbers (about 1.4 GB to
ground) beyond the memory limit of 300 MB.

The class runs in a fresh process (the command as a teacher types it): a child forked from
it starts small, so the memory limit hits eve's numbers only.
"""

from __future__ import annotations

import csv
import json
import re
import subprocess
import sys

import pytest
from helpers import ROOT

from asprilo.cli import main
from asprilo.encodings.grade_class import class_members
from asprilo.errors import InputError

CLASS = ROOT / "tests" / "grade-class"
RELATIVE = "tests/grade-class"
BOB = f"clingo refused the encoding: {CLASS / 'bob.lp'}:3: column 45: syntax error, unexpected ., expecting ) or ;"
DAN = f"{CLASS / 'dan.lp'}:16:44-55: info: atom does not occur in any rule head: att(R2,C,T)"
SHAPE = "its model's occurs/3 atoms are no plan: expected occurs(object(robot,R),action(Name,Args),T), got "
MEMORY = "stopped at the memory limit (300 MB)"
#: the command line of every run (the hang guard: the default time limit, 20 s per instance)
COMMAND = ["grade", "--class", RELATIVE, "--domain", "m", "--first", "2", "--memory-limit", "300"]


def _asprilo(*arguments: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "asprilo.cli", *arguments], cwd=ROOT, capture_output=True,
                          text=True, timeout=600)


def _timeless(line: str) -> str:
    """A grade's line with its seconds blanked (they depend on the machine)."""
    return re.sub(r"\d+\.\d s", "_ s", line)


def _header(files: str, style: str = "single-shot with a horizon constant") -> str:
    return f"grading your encoding ({files}: {style}) on the M ladder: 2 instances, time limit 20 s each"


def _lines(verdicts: list[str]) -> list[str]:
    return [f"1/2  01-x3_y2_r1    3x2, 1 robot       _ s  {verdicts[0]}",
            f"2/2  02-x5_y2_r2    5x2, 2 robots      _ s  {verdicts[1]}"]


@pytest.fixture(scope="module")
def text_run(tmp_path_factory):
    table = tmp_path_factory.mktemp("class") / "class.csv"
    return _asprilo(*COMMAND, "--csv", str(table)), table


def test_every_submission_is_graded_one_by_one(text_run):
    done, _table = text_run
    assert done.returncode == 1
    blocks = done.stdout.split("\n\n")
    assert len(blocks) == 6  # five submissions, then the table
    assert [_timeless(line) for line in blocks[0].splitlines()] == [
        _header(f"{RELATIVE}/ada/moves.lp, {RELATIVE}/ada/show.lp"),
        *_lines(["valid    minimal (makespan 3)", "valid    minimal (makespan 4)"]),
        "2/2 valid, 2/2 minimal; _ s"]
    assert [_timeless(line) for line in blocks[1].splitlines()] == [
        _header(f"{RELATIVE}/bob.lp", "refused by clingo"),
        "1/2  01-x3_y2_r1    3x2, 1 robot       _ s  no plan  " + BOB,
        "2/2  02-x5_y2_r2    5x2, 2 robots      _ s  no plan  " + BOB,
        "0/2 valid, 0/2 minimal, 2 without a plan; _ s"]
    assert [_timeless(line) for line in blocks[2].splitlines()] == [
        _header(f"{RELATIVE}/cyd.lp"),
        *_lines(["no plan  " + SHAPE + "occurs(object(robot,1),start((3,2)),0)",
                 "no plan  " + SHAPE + "occurs(object(robot,1),start((1,1)),0)"]),
        "0/2 valid, 0/2 minimal, 2 without a plan; _ s"]
    first, second = _lines(["valid    minimal (makespan 3)", "valid    minimal (makespan 4)"])
    assert [_timeless(line) for line in blocks[3].splitlines()] == [
        _header(f"{RELATIVE}/dan.lp"), first, f"  clingo: {DAN}", second,  # the hint once, where it was first said
        "2/2 valid, 2/2 minimal; _ s"]
    assert [_timeless(line) for line in blocks[4].splitlines()] == [
        _header(f"{RELATIVE}/eve.lp"), *_lines([f"no plan  {MEMORY}"] * 2),
        "0/2 valid, 0/2 minimal, 2 without a plan; _ s"]


def test_the_class_table(text_run):
    done, _table = text_run
    table = done.stdout.split("\n\n")[-1].splitlines()
    assert table[:-1] == [
        "student  valid  minimal  notes",
        "ada        2/2      2/2",
        f"bob        0/2      0/2  {BOB}",
        "cyd        0/2      0/2  2 without a plan",
        "dan        2/2      2/2  1 clingo warning",
        "eve        0/2      0/2  2 without a plan",
        "all       4/10     4/10  6 without a plan",
    ]
    assert _timeless(table[-1]) == "5 submissions: 2 with every plan valid, 1 refused; _ s"
    assert done.stderr.splitlines() == [f"grading {n}/5: {name}" for n, name in
                                        enumerate(["ada", "bob", "cyd", "dan", "eve"], 1)]


def test_the_csv_has_a_row_per_submission(text_run):
    _done, table = text_run
    rows = list(csv.reader(table.read_text().splitlines()))
    assert rows[0] == ["student", "files", "instances", "valid", "minimal", "invalid", "no_plan", "time_outs",
                       "forgot", "refused", "first_failure", "clingo_warnings", "seconds"]
    seconds = [float(row.pop()) for row in rows[1:]]
    assert all(value >= 0 for value in seconds)
    assert rows[1:] == [
        ["ada", f"{RELATIVE}/ada/moves.lp {RELATIVE}/ada/show.lp", "2", "2", "2", "0", "0", "0", "", "", "", ""],
        ["bob", f"{RELATIVE}/bob.lp", "2", "0", "0", "0", "2", "0", "", BOB, f"01-x3_y2_r1: no plan {BOB}", ""],
        ["cyd", f"{RELATIVE}/cyd.lp", "2", "0", "0", "0", "2", "0", "", "",
         f"01-x3_y2_r1: no plan {SHAPE}occurs(object(robot,1),start((3,2)),0)", ""],
        ["dan", f"{RELATIVE}/dan.lp", "2", "2", "2", "0", "0", "0", "", "", "", DAN],
        ["eve", f"{RELATIVE}/eve.lp", "2", "0", "0", "0", "2", "0", "", "", f"01-x3_y2_r1: no plan {MEMORY}", ""],
    ]


def test_the_class_as_json():
    done = _asprilo(*COMMAND, "--json", "--quiet")
    assert (done.returncode, done.stderr) == (1, "")
    report = json.loads(done.stdout)
    assert isinstance(report["summary"].pop("seconds"), float)
    assert {key: report[key] for key in ("version", "domain", "ladder", "time_limit", "class", "summary")} == {
        "version": 1, "domain": "m", "ladder": "m", "time_limit": 20.0, "class": True,
        "summary": {"submissions": 5, "all_valid": 2, "clean": 2, "refused": 1, "instances": 10, "valid": 4,
                    "minimal": 4, "invalid": 0, "no_plan": 6, "time_outs": 0}}
    submissions = {entry["name"]: entry for entry in report["submissions"]}
    assert list(submissions) == ["ada", "bob", "cyd", "dan", "eve"]
    assert {name: (entry["files"], entry["refused"], entry["warnings"], entry["encoding"]["style"])
            for name, entry in submissions.items()} == {
        "ada": ([f"{RELATIVE}/ada/moves.lp", f"{RELATIVE}/ada/show.lp"], None, [],
                "single-shot with a horizon constant"),
        "bob": ([f"{RELATIVE}/bob.lp"], BOB, [], "refused by clingo"),
        "cyd": ([f"{RELATIVE}/cyd.lp"], None, [], "single-shot with a horizon constant"),
        "dan": ([f"{RELATIVE}/dan.lp"], None, [DAN], "single-shot with a horizon constant"),
        "eve": ([f"{RELATIVE}/eve.lp"], None, [], "single-shot with a horizon constant"),
    }
    assert [(item["result"], item["makespan"], item["reason"], item["warnings"])
            for item in submissions["dan"]["instances"]] == [("valid", 3, None, [DAN]), ("valid", 4, None, [DAN])]
    assert [(item["result"], item["reason"]) for item in submissions["eve"]["instances"]] == [
        ("no-plan", MEMORY)] * 2
    assert {key: value for key, value in submissions["cyd"]["summary"].items() if key != "seconds"} == {
        "instances": 2, "valid": 0, "minimal": 0, "invalid": 0, "no_plan": 2, "time_outs": 0}


def test_a_hint_of_clingo_stays_with_the_grade_of_one_encoding(capsys):
    code = main(["grade", str(CLASS / "dan.lp"), "--domain", "m", "--first", "2"])
    lines = capsys.readouterr().out.splitlines()
    assert code == 0
    first, second = _lines(["valid    minimal (makespan 3)", "valid    minimal (makespan 4)"])
    assert [_timeless(line) for line in lines[1:4]] == [first, f"  clingo: {DAN}", second]


def test_the_rule_of_a_class_folder(tmp_path):
    (tmp_path / "zoe.lp").write_text("a.")
    (tmp_path / "notes.txt").write_text("not an encoding")
    (tmp_path / ".hidden.lp").write_text("a.")
    for name in ("b.lp", "a.ilp", "c.txt"):
        (tmp_path / "kim" / name).parent.mkdir(exist_ok=True)
        (tmp_path / "kim" / name).write_text("a.")
    (tmp_path / "empty").mkdir()
    other = tmp_path / "other"
    other.mkdir()
    (other / "zoe.lp").write_text("a.")
    members = class_members([str(tmp_path), str(other / "zoe.lp")])
    assert [(member.name, [file.name for file in member.files]) for member in members] == [
        ("empty", []), ("kim", ["a.ilp", "b.lp"]), ("other", ["zoe.lp"]),
        (str(tmp_path / "zoe.lp"), ["zoe.lp"]), (str(other / "zoe.lp"), ["zoe.lp"])]
    with pytest.raises(InputError) as refused:
        class_members([str(tmp_path / "nobody")])
    assert str(refused.value) == f"{tmp_path / 'nobody'}: no such file or folder"
    with pytest.raises(InputError) as refused:
        class_members([str(tmp_path / "empty")])
    assert str(refused.value) == f"{tmp_path / 'empty'}: no submissions: no encoding files (.lp, .ilp, .iclp, .clp) " \
                                 "or sub-folders"


def test_an_empty_submission_folder_is_a_graded_line(tmp_path, capsys):
    (tmp_path / "ann").mkdir()
    (tmp_path / "ben.lp").write_text((CLASS / "ada" / "moves.lp").read_text() + (CLASS / "ada" / "show.lp").read_text())
    code = main(["grade", "--class", str(tmp_path), "--domain", "m", "--first", "1", "--quiet"])
    out = capsys.readouterr().out
    assert code == 1
    why = f"no encoding files (.lp, .ilp, .iclp, .clp) in the folder {tmp_path / 'ann'}"
    assert out.splitlines()[:2] == [
        f"grading your encoding ({tmp_path / 'ann'}: no encoding files) on the M ladder: 1 instance, time limit 20 s "
        "each", f"1/1  01-x3_y2_r1    3x2, 1 robot       0.0 s  no plan  {why}"]
    table = out.split("\n\n")[-1].splitlines()
    assert table[1:4] == [f"ann        0/1      0/1  {why}", "ben        1/1      1/1",
                          "all        1/2      1/2  1 without a plan"]


def test_bad_command_lines_of_a_class_exit_2(tmp_path, capsys):
    assert main(["grade", str(CLASS / "dan.lp"), "--domain", "m", "--csv", str(tmp_path / "x.csv")]) == 2
    assert capsys.readouterr().err == "error: --csv writes the table of a class: grade one with --class\n"
    assert main(["grade", "--class", str(CLASS), "--domain", "m", "--csv", str(tmp_path)]) == 2
    assert capsys.readouterr().err.startswith(f"error: {tmp_path}: ")
    assert main(["grade", "--class", str(CLASS), "--domain", "m", "--frobnicate=3"]) == 2
    assert capsys.readouterr().err == "error: clingo refuses the option --frobnicate=3: unknown option: 'frobnicate'\n"
    assert not (tmp_path / "x.csv").exists()


def test_a_class_on_a_ladder_with_a_probe_names_the_rule_a_student_forgot(tmp_path, capsys):
    """A ladder of the first M instance and the M ladder's swap probe (robots 1 and 2
    exchange (1,1) and (2,1) at step 1): ada's swap constraint refuses it; dan's reads att/3,
    which never holds, so dan's encoding accepts the swap."""
    from asprilo.domain import Domain
    from asprilo.encodings.ladder import bundled_ladder

    m = bundled_ladder(Domain.M)
    for name in ("swap.lp", "swap-plan.lp"):
        (tmp_path / name).write_text((m.manifest.parent / "probes" / name).read_text())
    (tmp_path / "01.lp").write_text(m.rungs[0].file.read_text())
    ladder = tmp_path / "ladder.yml"
    ladder.write_text("domain: m\ninstances:\n  - {file: 01.lp, minimum: 3, established: by hand}\n"
                      "probes:\n  - name: swap\n    rule: robots may not swap cells\n"
                      "    case: robots 1 and 2 between (1,1) and (2,1) at step 1\n"
                      "    instance: swap.lp\n    plan: swap-plan.lp\n    horizon: 1\n")
    pupils = tmp_path / "pupils"
    (pupils / "ada").mkdir(parents=True)
    for path in (CLASS / "ada" / "moves.lp", CLASS / "ada" / "show.lp", CLASS / "dan.lp"):
        (pupils / path.relative_to(CLASS)).write_text(path.read_text())
    table = tmp_path / "class.csv"
    code = main(["grade", "--class", str(pupils), "--ladder", str(ladder), "--csv", str(table), "--quiet"])
    out = capsys.readouterr().out
    assert code == 1  # a rule forgotten
    ada, dan, summary = out.split("\n\n")
    assert [_timeless(line) for line in ada.splitlines()[1:]] == [
        "1/1  01             3x2, 1 robot       _ s  valid    minimal (makespan 3)",
        "kept: robots may not swap cells (swap probe refused)",
        "1/1 valid, 1/1 minimal; _ s; probes: 1/1 refused"]
    assert [_timeless(line) for line in dan.splitlines()[1:]] == [
        "1/1  01             3x2, 1 robot       _ s  valid    minimal (makespan 3)",
        f"  clingo: {pupils / 'dan.lp'}:16:44-55: info: atom does not occur in any rule head: att(R2,C,T)",
        "forgot: robots may not swap cells (swap probe: robots 1 and 2 between (1,1) and (2,1) at step 1)",
        "1/1 valid, 1/1 minimal; _ s; probes: 0/1 refused, forgot 1 rule (swap)"]
    assert [_timeless(line) for line in summary.splitlines()] == [
        "student  valid  minimal  notes",
        "ada        1/1      1/1",
        "dan        1/1      1/1  forgot swap; 1 clingo warning",
        "all        2/2      2/2  1 forgot a rule",
        "2 submissions: 1 with every plan valid and no rule forgotten; _ s"]
    rows = list(csv.reader(table.read_text().splitlines()))
    assert [(row[0], row[8]) for row in rows] == [("student", "forgot"), ("ada", ""), ("dan", "swap")]
    code = main(["grade", "--class", str(pupils), "--ladder", str(ladder), "--json", "--quiet"])
    report = json.loads(capsys.readouterr().out)
    assert (report["summary"]["clean"], report["summary"]["probes"]) == (
        1, {"probes": 2, "refused": 1, "forgotten": 1, "undecided": 0})
    assert [[(probe["name"], probe["result"]) for probe in entry["probes"]] for entry in report["submissions"]] == [
        [("swap", "refused")], [("swap", "accepted")]]
