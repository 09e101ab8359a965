"""Benchmark suites, the results file and the report tables (no solving here)."""

from __future__ import annotations

import pytest

from asprilo.bench import plots, report
from asprilo.bench.results import append_result, load_results
from asprilo.bench.suite import load_suite
from asprilo.cli import main
from asprilo.domain import Domain
from asprilo.errors import InputError


def record(key, label="M", encoding="plain", status="solved", time=1.0, robots=2, set_="small", horizon=6):
    return {"key": key, "set": set_, "instance": key, "robots": robots, "domain": "m", "label": label,
            "encoding": encoding, "assign": label.endswith("_a"), "status": status, "time": time,
            "time_limit": 60.0, "horizon": horizon}


def test_suite_expands_every_combination(write):
    write("batch.yml", "run_configs: {}\n")
    path = write("suite.yml", """
name: demo
time_limit: 30
memory_limit: 1024
instances:
  small: {batch: batch.yml, select: 1x2x4}
  tiny: {files: ["*.lp"]}
runs:
  - {domain: m, encoding: [plain, split], assign: [false, true]}
  - {domain: [a, b], sets: tiny}
""")
    suite = load_suite(path)
    assert (suite.name, suite.time_limit, suite.memory_limit) == ("demo", 30.0, 1024)
    assert [s.name for s in suite.sets] == ["small", "tiny"]
    assert [(r.domain, r.encoding, r.assign) for r in suite.runs] == [
        (Domain.M, "plain", False), (Domain.M, "plain", True), (Domain.M, "split", False),
        (Domain.M, "split", True), (Domain.A, "plain", False), (Domain.B, "plain", False)]
    assert suite.runs[1].label == "M_a"
    assert [r.runs_on("small") for r in suite.runs] == [True] * 4 + [False] * 2
    assert suite.runs[4].runs_on("tiny")


def test_first_keeps_the_first_files_of_each_folder(write):
    path = write("suite.yml", "instances: {some: {files: ['*/*.lp'], first: 2}}\nruns: [{domain: m}]\n")
    for folder in ("r02", "r05"):
        (path.parent / folder).mkdir()
        for number in (3, 1, 2):
            write(f"{folder}/N{number}.lp", "")
    suite = load_suite(path)
    picked = suite.sets[0].pick(sorted(path.parent.glob("*/*.lp")))
    assert [f"{p.parent.name}/{p.name}" for p in picked] == ["r02/N1.lp", "r02/N2.lp", "r05/N1.lp", "r05/N2.lp"]


SUITE_HEAD = "name: t\ninstances:\n  x: {files: [a]}\nruns:\n"


@pytest.mark.parametrize("text, message", [
    ("runs: [\n  - a\n", "2: not valid YAML: expected the node content, but found '-'"),
    (SUITE_HEAD + "  - {domain: m}\n  - {domain: z}\n",
     "6: runs[1].domain: unknown domain 'z' (choose one of a, b, c, m, md)"),
    ("instances: {}\nruns: []\n",
     "1: instances: must map set names to {batch: FILE, select: DIR} or {files: [GLOB, ...]}"),
    ("name: t\ninstances:\n  x: {batch: nope.yml}\nruns: [{domain: m}]\n", "3: instances.x.batch: no such file "),
    ("name: t\ntime_limit: -1\n", "2: time_limit: must be a positive number of seconds"),
    ("colour: red\n",
     "1: colour: unknown key (known: name, time_limit, memory_limit, makespan_time_limit, encodings, instances, "
     "runs)"),
    ("instances:\n  x:\n    files: [a]\n    first: 0\nruns: [{domain: m}]\n",
     "4: instances.x.first: must be a positive number of files per folder"),
    (SUITE_HEAD + "  - domain: m\n    sets: [y]\n", "6: runs[0].sets: no instance set 'y'"),
    (SUITE_HEAD + "  - domain: m\n    colour: red\n",
     "6: runs[0].colour: unknown key (known: domain, encoding, assign, sets, method, variant)"),
    (SUITE_HEAD + "  - {domain: m}\ninstances: {}\n", "6: duplicate key 'instances'"),
    ("name: t\nname: u\n", "2: duplicate key 'name'"),
    ("name: t\ninstances:\n  x: {files: [a]}\n  x: {files: [b]}\n", "4: duplicate key 'x'"),
])
def test_bad_suites_name_file_and_line(write, text, message):
    path = write("suite.yml", text)
    with pytest.raises(InputError) as error:
        load_suite(path)
    assert str(error.value).startswith(f"{path}:{message}")


@pytest.mark.parametrize("data, message", [
    (b"name: caf\xe9\n", "1: not UTF-8 text (byte 0xe9)"),
    (b"name: t\ninstances: {}\n\x00\x01\x02", "3: a binary file, not YAML text"),
])
def test_suites_that_are_not_utf8_text_are_bad_input(tmp_path, capsys, data, message):
    path = tmp_path / "suite.yml"
    path.write_bytes(data)
    assert main(["bench", str(path), "-o", str(tmp_path / "out")]) == 2
    assert capsys.readouterr().err == f"error: {path}:{message}\n"
    assert not (tmp_path / "out").exists()


def test_a_byte_order_mark_is_fine(write, tmp_path):
    path = tmp_path / "suite.yml"
    path.write_bytes(b"\xef\xbb\xbfname: bom\ninstances: {x: {files: [a]}}\nruns: [{domain: m}]\n")
    assert load_suite(path).name == "bom"


def test_results_survive_a_torn_line(tmp_path):
    append_result(tmp_path, record("a"))
    with open(tmp_path / "results.jsonl", "a") as stream:
        stream.write('{"key": "b", "sta')  # a runner killed while writing
    append_result(tmp_path, record("c"))
    assert [r["key"] for r in load_results(tmp_path)] == ["a", "c"]


def test_summary_table_counts_unsolved_runs_at_the_limit():
    records = [record("1", time=2.0), record("2", time=4.0),
               record("3", encoding="split", status="timeout", time=60.0),
               record("4", encoding="split", time=1.0),
               record("5", label="A", encoding="plain", status="invalid", time=3.0, horizon=20),
               record("6", label="A", encoding="plain", status="solved", time=5.0, horizon=20, set_="medium")]
    text = report.summary(records, ["small", "medium"]).text()
    assert text.splitlines()[2:7] == [
        "domain  makespan   encoding  small    medium",
        "------  ---------  --------  -------  ------",
        "M       6.0/-      plain     3.0(0)*  -",
        "                   split     30(1)    -",
        "A       20.0/20.0  plain     -(0) x1  5.0(0)",  # the invalid plan is not a time
    ]
    assert [line[:10] for line in text.splitlines()[8:] if line[5:6] != " "] == [
        "Key: T(N) ", "     xN   ", "     *    ", "     -(0) ", "     a/b  ", "     -    "]


def test_tables_by_robot_count_and_csv():
    records = [record("1", robots=2, time=1.0), record("2", robots=5, time=3.0)]
    (table,) = report.by_robots(records)
    assert table.text().splitlines()[2:5] == [
        "domain  makespan  encoding  2       5",
        "------  --------  --------  ------  ------",
        "M       6.0       plain     1.0(0)  3.0(0)",
    ]
    rows = report.to_csv(records).splitlines()
    assert rows[0].startswith("key,set,instance,robots,domain,label,encoding,assign,status,time")
    assert rows[1].startswith("1,small,1,2,m,M,plain,False,solved,1.0,60.0,")


def test_plots_are_written(tmp_path):
    records = [record("1"), record("1", encoding="split", status="timeout", time=60.0)]  # one instance
    paths = plots.plot(records, tmp_path)
    assert [p.name for p in paths] == ["cactus.png", "time-by-robots.png", "scatter-plain-split.png"]
    assert all(p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" for p in paths)
