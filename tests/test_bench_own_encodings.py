"""Bench suites that name encodings of their own: run end to end, refused before the first
run when a name or a file is wrong, failed runs counted apart from time-outs, carried by
the btool export.

The encodings are the tests' own (tests/encodings/, written in the styles people use with
clingo); the instances are tiny: the 2x2 floor of examples/encodings-repo (minimal makespan
1) and tests/encodings/m-tiny.lp (4, by hand).
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from helpers import EXAMPLES, ROOT

from asprilo.bench.results import load_results
from asprilo.bench.suite import load_suite
from asprilo.cli import main
from asprilo.encodings.own import own_encoding
from asprilo.errors import InputError

OWN = ROOT / "tests" / "encodings"
TINY = EXAMPLES / "encodings-repo/x2_y2_n4_r2_s2_ps1_pr2_u4_o2_N1.lp"
M_TINY = OWN / "m-tiny.lp"
BTOOL = shutil.which("btool", path=f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}")


def _suite(folder: Path, encodings: str, runs: str, instances: tuple[Path, ...] = (TINY, M_TINY)) -> Path:
    listed = ", ".join(f'"{path}"' for path in instances)
    path = folder / "suite.yml"
    path.write_text(f"name: own\ntime_limit: 60\nmemory_limit: 2048\nmakespan_time_limit: 60\n{encodings}"
                    f"instances:\n  tiny: {{files: [{listed}]}}\nruns:\n{runs}")
    return path


def _encoding_folder(folder: Path) -> Path:
    """enc/: domain M in two files (moves with the goal, and what is shown) that need the
    constant ``need`` set to 2: without it every horizon is unsatisfiable."""
    enc = folder / "enc"
    enc.mkdir()
    shutil.copy(OWN / "m-moves.lp", enc / "m-moves.lp")
    (enc / "mine.lp").write_text('#const horizon = 1.\n#include "m-moves.lp".\n')
    (enc / "goal.lp").write_text("occurs(object(robot,R),action(move,D),T) :- move(R,D,T).\n#show occurs/3.\n"
                                 ":- need != 2.\n")
    return enc


MINE = ("encodings:\n"
        "  mine: {files: [enc/mine.lp, enc/goal.lp], constants: {need: 2}, options: [\"--configuration=crafty\"]}\n"
        f"  single: {{files: [\"{OWN / 'm-single.lp'}\"]}}\n"
        f"  inc: {{files: \"{OWN / 'm-incmode.lp'}\"}}\n")


def test_a_suite_runs_encodings_of_its_own_end_to_end(tmp_path, capsys):
    _encoding_folder(tmp_path)
    suite = _suite(tmp_path, MINE, "  - {domain: m, encoding: [plain, mine, single, inc]}\n")
    out = tmp_path / "out"
    assert main(["bench", str(suite), "-o", str(out), "--plots", "none"]) == 0
    records = load_results(out)
    assert sorted((Path(r["instance"]).name, r["encoding"], r["status"], r["horizon"]) for r in records) == [
        (name, encoding, "solved", horizon) for name, horizon in (("m-tiny.lp", 4), (TINY.name, 1))
        for encoding in ("inc", "mine", "plain", "single")]
    assert all(r["metrics"]["makespan_ratio"] == 1.0 for r in records)  # plans at the minimal makespan
    report = capsys.readouterr().out
    rows = [line.split()[-2:] for line in report.split("\n\n")[1].splitlines()[2:]]
    assert [encoding for encoding, _cell in rows] == ["plain", "inc", "mine", "single"]  # references first
    assert all(re.fullmatch(r"\d+(\.\d)?\(0\)\*?", cell) for _encoding, cell in rows)  # all solved
    key = " ".join(report.split("\n\n")[2].split())
    # the files named relative to the suite's folder (tmp_path), as its instances are
    assert ("mine enc/mine.lp, enc/goal.lp; single-shot with a horizon constant; "
            "-c need=2; --configuration=crafty") in key
    incmode = os.path.relpath(OWN / "m-incmode.lp", tmp_path.resolve())
    assert incmode.startswith("../") and f"inc {incmode}; incremental (step(t)/check(t), query(t))" in key
    assert json.loads((out / "suite.json").read_text())["encodings"]["inc"] == \
        f"{incmode}; incremental (step(t)/check(t), query(t))"


def test_the_constants_and_the_files_reach_the_run(tmp_path):
    """Without need=2 the encoding has no plan at the problem's minimum: an error, said in words."""
    _encoding_folder(tmp_path)
    suite = _suite(tmp_path, "encodings:\n  mine: {files: [enc/mine.lp, enc/goal.lp]}\n",
                   "  - {domain: m, encoding: mine}\n", (TINY,))
    assert main(["bench", str(suite), "-o", str(tmp_path / "out"), "--plots", "none"]) == 0
    (record,) = load_results(tmp_path / "out")
    assert (record["status"], record["error"]) == ("error", "the encoding has no plan at horizon 1, the problem's "
                                                            "minimum")


def test_the_suite_keeps_its_encodings_with_their_style(tmp_path):
    _encoding_folder(tmp_path)
    runs = "  - {domain: [m, md], encoding: mine}\n  - {domain: [m, md], encoding: plain, assign: [false, true]}\n"
    suite = load_suite(_suite(tmp_path, MINE, runs))
    mine = suite.encodings["mine"]
    assert mine.files == (str(tmp_path / "enc/mine.lp"), str(tmp_path / "enc/goal.lp"))
    assert (mine.constants, mine.options, mine.style) == (
        (("need", "2"),), ("--configuration=crafty",), "single-shot with a horizon constant")
    assert [(spec.label, spec.encoding, spec.own) for spec in suite.runs] == [
        ("M", "mine", mine), ("Md", "mine", mine),
        ("M", "plain", None), ("M_a", "plain", None), ("Md", "plain", None), ("Md_a", "plain", None)]
    assert suite.encodings["inc"].style == "incremental (step(t)/check(t), query(t))"


# --- refused before the first run --------------------------------------------------------

def _bad(folder: Path, name: str, text: str) -> Path:
    path = folder / "enc" / name
    path.parent.mkdir(exist_ok=True)
    path.write_text(text)
    return path


def _refusal(tmp_path: Path, encodings: str, runs: str = "  - {domain: m, encoding: [plain, mine]}\n") -> str:
    """The error of ``asprilo bench`` on a suite with ``encodings``: exit 2, nothing made."""
    suite = _suite(tmp_path, encodings, runs)
    out = tmp_path / "out"
    assert main(["bench", str(suite), "-o", str(out)]) == 2
    assert not out.exists()
    return str(suite)


def _own_error(*files: Path, constants=(), options=()) -> str:
    """What :func:`own_encoding` (asprilo solve's recognition) says of these files."""
    with pytest.raises(InputError) as raised:
        own_encoding(files, constants, options)
    return str(raised.value)


def test_an_unknown_encoding_name_is_refused_with_its_line(tmp_path, capsys):
    suite = _refusal(tmp_path, "", "  - {domain: m, encoding: plain}\n  - domain: m\n    encoding:\n"
                                   "      - split\n      - mien\n")
    assert capsys.readouterr().err == (
        f"error: {suite}:12: runs[1].encoding: no encoding 'mien' for domain M (reference encodings: plain, "
        f"split, clingcon, dl, plain-inc, split-inc, clingcon-inc; no encodings of the suite's own)\n")


def test_a_reference_name_of_another_domain_is_refused(tmp_path, capsys):
    _encoding_folder(tmp_path)
    suite = _refusal(tmp_path, "encodings:\n  mine: {files: [enc/mine.lp, enc/goal.lp]}\n",
                     "  - {domain: [m, a], encoding: [mine, split]}\n")
    assert capsys.readouterr().err == (
        f"error: {suite}:10: runs[0].encoding: no encoding 'split' for domain A (reference encodings: plain, "
        f"clingcon; the suite's encodings: mine)\n")


def test_a_missing_file_is_refused_at_its_item(tmp_path, capsys):
    _encoding_folder(tmp_path)
    suite = _refusal(tmp_path, "encodings:\n  mine:\n    files:\n      - enc/mine.lp\n      - enc/gaol.lp\n")
    assert capsys.readouterr().err == \
        f"error: {suite}:9: encodings.mine.files[1]: {tmp_path / 'enc/gaol.lp'}: no such file\n"


def test_a_file_clingo_cannot_parse_is_refused_with_clingo_s_place(tmp_path, capsys):
    bad = _bad(tmp_path, "bad.lp", "#const horizon = 1.\np(X :- q.\n")
    suite = _refusal(tmp_path, "encodings:\n  mine: {files: [enc/bad.lp]}\n")
    inner = _own_error(bad)
    assert inner.endswith(":2: column 5: syntax error, unexpected :-, expecting ) or ;")
    assert capsys.readouterr().err == f"error: {suite}:6: encodings.mine.files[0]: {inner}\n"


def test_a_clingcon3_program_is_refused_naming_why(tmp_path, capsys):
    suite = _refusal(tmp_path, f"encodings:\n  mine:\n    files: [\"{OWN / 'm-clingcon3.clp'}\"]\n")
    inner = _own_error(OWN / "m-clingcon3.clp")
    assert "written for clingcon 3" in inner
    assert capsys.readouterr().err == f"error: {suite}:7: encodings.mine.files[0]: {inner}\n"


def test_an_include_of_a_missing_file_is_refused(tmp_path, capsys):
    main_file = _bad(tmp_path, "main.lp", '#const horizon = 1.\n#include "nope.lp".\n')
    suite = _refusal(tmp_path, "encodings:\n  mine: {files: enc/main.lp}\n")
    assert capsys.readouterr().err == f"error: {suite}:6: encodings.mine.files[0]: {_own_error(main_file)}\n"


def test_an_option_clingo_refuses_is_refused_at_the_options(tmp_path, capsys):
    _encoding_folder(tmp_path)
    suite = _refusal(tmp_path, "encodings:\n  mine:\n    files: [enc/mine.lp, enc/goal.lp]\n"
                               "    options: [--frobnicate=3]\n")
    assert capsys.readouterr().err == (f"error: {suite}:8: encodings.mine.options: clingo refuses the option "
                                       f"--frobnicate=3: unknown option: 'frobnicate'\n")


@pytest.mark.parametrize("entry, message", [
    ("  plain: {files: [enc/mine.lp]}\n",
     "6: encodings.plain: 'plain' is the name of a reference encoding; give yours another name"),
    ("  my encoding: {files: [enc/mine.lp]}\n",
     "6: encodings.my encoding: an encoding's name is letters, digits and _ . + - (it names its runs in "
     "results, tables and files)"),
    ("  mine: {file: enc/mine.lp}\n", "6: encodings.mine: needs 'files': the encoding's files, relative to the suite"),
    ("  mine: {files: [enc/mine.lp], colour: red}\n",
     "6: encodings.mine.colour: unknown key (known: files, constants, options, stage)"),
    ("  mine:\n    files: [enc/mine.lp]\n    constants: {horizon: 3}\n",
     "8: encodings.mine.constants.horizon: the runs are at each instance's minimal makespan: a suite sets no horizon"),
    ("  mine:\n    files: [enc/mine.lp]\n    constants:\n      lanes: 2\n      need: 1 +\n",
     "10: encodings.mine.constants.need: clingo cannot read '1 +' as a term"),
    ("  mine: {files: [enc/mine.lp], constants: [need]}\n",
     "6: encodings.mine.constants: must map names to values, e.g. {lanes: 2}"),
    ("  mine: {files: [enc/mine.lp], options: [3]}\n",
     "6: encodings.mine.options: must be clingo options, e.g. [\"--configuration=crafty\"]"),
    ("  mine: {files: []}\n", "6: encodings.mine.files: must be a file or a list of files"),
])
def test_bad_encoding_entries_are_refused_with_their_line(tmp_path, capsys, entry, message):
    _encoding_folder(tmp_path)
    suite = _refusal(tmp_path, "encodings:\n" + entry)
    assert capsys.readouterr().err == f"error: {suite}:{message}\n"


def test_encodings_must_be_a_mapping(tmp_path, capsys):
    suite = _refusal(tmp_path, "encodings: [enc/mine.lp]\n")
    assert capsys.readouterr().err == (f"error: {suite}:5: encodings: must map names to {{files: [FILE, ...], "
                                       f"constants: {{NAME: VALUE}}, options: [OPTION, ...]}}\n")


# --- failed runs are not time-outs -------------------------------------------------------

def test_invalid_plans_and_errors_are_counted_apart_and_said(tmp_path, capsys):
    """m-wrong.lp's plans break the rules (the checker says which); unsafe.lp is read but
    cannot be grounded: the run fails at run time.  Neither is a time: the cells count them."""
    unsafe = _bad(tmp_path, "unsafe.lp", "#const horizon = 1.\noccurs(object(robot,1),action(move,(X,0)),1) :- "
                                         "horizon > 0.\n")
    suite = _suite(tmp_path, f"encodings:\n  wrong: {{files: [\"{OWN / 'm-wrong.lp'}\"]}}\n"
                             f"  unsafe: {{files: [enc/unsafe.lp]}}\n",
                   "  - {domain: m, encoding: [plain, wrong, unsafe]}\n")
    out = tmp_path / "out"
    assert main(["bench", str(suite), "-o", str(out), "--plots", "none"]) == 0
    records = {(Path(r["instance"]).name, r["encoding"]): r for r in load_results(out)}
    assert sorted((name, encoding, r["status"]) for (name, encoding), r in records.items()) == [
        ("m-tiny.lp", "plain", "solved"), ("m-tiny.lp", "unsafe", "error"), ("m-tiny.lp", "wrong", "invalid"),
        (TINY.name, "plain", "solved"), (TINY.name, "unsafe", "error"), (TINY.name, "wrong", "invalid")]
    assert records[("m-tiny.lp", "wrong")]["error"] == (
        "the plan breaks the rules: step 4 (the horizon): order 1 is not fulfilled: no robot stands under a shelf "
        "holding product 1; step 4: robot 1 moves to (4,0), which is not a floor node")
    assert records[("m-tiny.lp", "wrong")]["violations"] == ["err(goal,unfilledOrder,(1,1,1,4))",
                                                              "err(move,offFloor,(1,4))"]
    assert records[("m-tiny.lp", "unsafe")]["error"] == (
        f"{unsafe}:2: unsafe variables in: "
        "occurs(object(robot,1),action(move,(X,0)),1):-[#inc_base];4>0. 'X' is unsafe")
    text = capsys.readouterr().out
    parts = text.split("\n\n")  # caption, table, key, caption, table, key...
    summary, solved = parts[1], parts[4]
    assert [line.split()[-3:] for line in summary.splitlines()[3:]] == [["unsafe", "-(0)", "!2"],
                                                                        ["wrong", "-(0)", "x2"]]
    assert [line.split()[-7:] for line in solved.splitlines()[2:]][1:] == [
        ["unsafe", "0/2", "0", "0", "2", "-", "-"], ["wrong", "0/2", "0", "2", "0", "-", "-"]]
    failed = " ".join(text[text.index("Failed runs (4;"):].split())
    for (_name, encoding), record in sorted(records.items()):
        if record["status"] != "solved":
            outcome = "invalid plan" if record["status"] == "invalid" else "error"
            assert f"M {encoding}: tiny {record['instance']}: {outcome}: {record['error']}" in failed


SITECUSTOMIZE = "import os\nos._exit(3)\n"


def test_a_run_that_crashes_is_an_error_with_the_reason(tmp_path, monkeypatch, capsys):
    """Every child process dies at start-up (a sitecustomize on the PYTHONPATH of the runs'
    fresh interpreters); the minimal makespan is known beforehand, so only runs start."""
    crash = tmp_path / "crash"
    crash.mkdir()
    (crash / "sitecustomize.py").write_text(SITECUSTOMIZE)
    suite = _suite(tmp_path, "", "  - {domain: m, encoding: plain}\n", (TINY,))
    out = tmp_path / "out"
    out.mkdir()
    (out / "makespans.json").write_text(json.dumps({str(TINY): {"M": 1}}))
    monkeypatch.setenv("PYTHONPATH", str(crash))
    assert main(["bench", str(suite), "-o", str(out), "--plots", "none"]) == 0
    (record,) = load_results(out)
    assert (record["status"], record["error"]) == ("error", "the run's process ended without a result (exit status 3)")
    text = capsys.readouterr().out
    assert "M       1.0       plain     -(0) !1\n" in text
    assert "     !N        N runs ended in an error: not in the average (why: under Failed runs)\n" in text
    assert f"Failed runs (1; not in the averages, not in PAR): domain encoding, set instance, why M plain: tiny " \
           f"{TINY}: error: the run's process ended without a result (exit status 3)" in " ".join(text.split())


# --- the btool export carries the encodings ----------------------------------------------

def test_the_btool_export_carries_the_encoding_files(tmp_path):
    enc = _encoding_folder(tmp_path)
    (enc / "lib").mkdir()
    (enc / "lib" / "show.lp").write_text("#show occurs/3.\n")
    (enc / "goal.lp").write_text('occurs(object(robot,R),action(move,D),T) :- move(R,D,T).\n'
                                 '#include "lib/show.lp".\n:- need != 2.\n')
    suite = _suite(tmp_path, "encodings:\n  mine: {files: [enc/mine.lp, enc/goal.lp], constants: {need: 2, "
                             "word: '\"a b\"'}, options: [\"--configuration=crafty\"]}\n",
                   "  - {domain: m, encoding: [plain, mine]}\n", (TINY,))
    cluster = tmp_path / "cluster"
    assert main(["bench", "export-btool", str(suite), str(cluster)]) == 0
    copied = sorted(str(path.relative_to(cluster)) for path in (cluster / "encodings").rglob("*") if path.is_file())
    assert copied == ["encodings/mine.json", "encodings/mine/goal.lp", "encodings/mine/lib/show.lp",
                      "encodings/mine/m-moves.lp", "encodings/mine/mine.lp"]
    assert json.loads((cluster / "encodings/mine.json").read_text()) == {
        "files": ["mine/mine.lp", "mine/goal.lp"], "constants": [["need", "2"], ["word", '"a b"']],
        "options": ["--configuration=crafty"], "style": "single-shot with a horizon constant"}
    runscript = (cluster / "runscripts/own.xml").read_text()
    assert '<setting name="M-mine" tag="set0" cmdline="--domain m --encoding mine --own-encoding ' \
           'encodings/mine.json" dist_template="templates/single.dist"/>' in runscript
    shutil.rmtree(tmp_path / "enc")  # the exported runs use the copies
    elsewhere = tmp_path / "run"
    elsewhere.mkdir()
    done = subprocess.run([str(cluster / f"programs/{next((cluster / 'programs').glob('asprilo-*')).name}"),
                           "--domain", "m", "--encoding", "mine", "--own-encoding", "encodings/mine.json",
                           "--time-limit", "60", str(cluster / "benchmarks/tiny" / TINY.name)],
                          cwd=elsewhere, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    record = json.loads(done.stdout.splitlines()[-1])
    assert (record["encoding"], record["status"], record["horizon"]) == ("mine", "solved", 1)


RUNLIM_STAND_IN = """#!/bin/sh
# runlim's stand-in for the test: runs the command without limits (its options dropped)
while [ "${1#--}" != "$1" ]; do shift; done
exec "$@"
"""


@pytest.mark.skipif(BTOOL is None, reason="btool is not installed (pip install -e '.[test]')")
def test_the_btool_round_trip_runs_the_suite_s_own_encodings(tmp_path, capsys):
    """export-btool, btool gen, the sequential job (runlim replaced by a stand-in, as the
    export's programs/runlim allows), btool eval, the report: the own encodings' runs are
    there, the invalid plans with their reasons."""
    _encoding_folder(tmp_path)
    suite = _suite(tmp_path, "encodings:\n  mine: {files: [enc/mine.lp, enc/goal.lp], constants: {need: 2}}\n"
                             f"  wrong: {{files: [\"{OWN / 'm-wrong.lp'}\"]}}\n",
                   "  - {domain: m, encoding: [plain, mine, wrong]}\n", (TINY,))
    cluster = tmp_path / "cluster"
    assert main(["bench", "export-btool", str(suite), str(cluster)]) == 0
    (cluster / "programs/runlim").write_text(RUNLIM_STAND_IN)
    for command in ([BTOOL, "gen", "runscripts/own.xml"], [sys.executable, "output/own-seq/cluster/start.py"]):
        done = subprocess.run(command, cwd=cluster, capture_output=True, text=True, timeout=300)
        assert done.returncode == 0, done.stderr
    evaluated = subprocess.run([BTOOL, "eval", "runscripts/own.xml"], cwd=cluster, capture_output=True, text=True,
                               timeout=300)
    assert evaluated.returncode == 0, evaluated.stderr
    (cluster / "results.xml").write_text(evaluated.stdout)
    capsys.readouterr()
    assert main(["bench", "report", str(cluster / "results.xml"), "--plots", "none"]) == 0
    text = capsys.readouterr().out
    solved = text.split("\n\n")[4]
    assert [line.split()[-7:-2] for line in solved.splitlines()[2:]] == [
        ["plain", "1/1", "0", "0", "0"], ["mine", "1/1", "0", "0", "0"], ["wrong", "0/1", "0", "1", "0"]]
    assert (f"M wrong: tiny {TINY.name}: invalid plan: the plan breaks the rules: step 1 (the horizon): order 1 "
            f"is not fulfilled") in " ".join(text.split())
