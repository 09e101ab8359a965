"""YAML batch files: the preset tree, the paper's batch files, command-line overrides, errors."""

from __future__ import annotations

import textwrap

import pytest
from conftest import ROOT
from test_gen_layout import PAPER, check_instance

from asprilo.cli import main
from asprilo.errors import InputError
from asprilo.generator import GeneratorConfig, make_plan
from asprilo.generator.batch import load_batch
from asprilo.generator.config import split_values
from asprilo.reader import read_instance

BENCHMARKS = ROOT / "benchmarks"


def batch(write, text: str):
    return write("batch.yml", textwrap.dedent(text))


def test_paper_m_batch_file_is_the_papers_set():
    runs = load_batch(BENCHMARKS / "paper-m.yml")
    assert [run.directory for run in runs] == [f"{size}/r{r:02d}" for size, (_, rs) in PAPER.items() for r in rs]
    for run in runs:
        size, robots = run.path[0], int(run.path[1][1:])
        options = {name: value for name, value in _flags(PAPER[size][0]).items()}
        assert run.values == {**options, "count": 30, "structured": True, "prs_min": 1, "prs_max": 1,
                              "robots": robots, "orders": robots}
        make_plan(GeneratorConfig(**split_values(run.values)[0]))


def _flags(options: dict) -> dict:
    from asprilo.generator.options import BY_FLAG
    return {BY_FLAG[flag].name: value for flag, value in options.items()}


def test_paper_abc_batch_file_has_the_same_tree_and_valid_runs():
    runs = load_batch(BENCHMARKS / "paper-abc.yml")
    assert [run.directory for run in runs] == [run.directory for run in load_batch(BENCHMARKS / "paper-m.yml")]
    for run in runs:
        plan = make_plan(GeneratorConfig(**split_values(run.values)[0]))
        assert plan.order_total == 2 * plan.robot_total and run.values["count"] == 30


def test_generating_a_batch_writes_one_directory_per_leaf(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["gen", "-j", str(BENCHMARKS / "paper-m.yml"), "-N", "1", "-d", str(out)]) == 0
    files = sorted(str(p.relative_to(out)) for p in out.rglob("*.lp"))
    assert len(files) == 12
    assert files[0] == "1x2x4/r02/x11_y6_n66_r2_s16_ps1_pr16_u16_o2_N001.lp"
    assert files[-1] == "4x5x8/r46/x46_y15_n690_r46_s320_ps10_pr320_u320_o46_N001.lp"
    instance = read_instance(out / files[0])
    check_instance(instance)
    # the header's command makes the same file on its own
    header = (out / files[0]).read_text().splitlines()
    command = header[2].removeprefix("% command: ").split()
    assert command[0] == "gen" and "--seed" in command and command[command.index("-N") + 1] == "1"
    assert main([*command, "-d", str(tmp_path / "again")]) == 0
    again, = (tmp_path / "again").iterdir()
    assert again.read_bytes() == (out / files[0]).read_bytes()
    assert capsys.readouterr().err.splitlines()[-3:] == [
        f"[12/12] {out}/{files[-1]}", f"wrote 12 instance files below {out} (12 folders)",
        f"wrote 1 instance file to {tmp_path / 'again'}"]


def test_presets_conf_and_lists(write):
    path = batch(write, """\
        global_settings: { '-N': 2, '-x': 10, '-y': 10 }
        run_configs:
          few:
            args: { '-r': 1, '-s': 5 }
            conf:
              args: { '-p': 2 }
              a: { args: { '-r': 3 } }
            b:
              args:
                - { '-o': 0 }
                - { '-s': 7, '-f': 'more-' }
          plain: {}
        """)
    runs = load_batch(path)
    assert [(run.directory, run.index) for run in runs] == [("few/a", 0), ("few/b", 0), ("few/b", 1), ("plain", 0)]
    common = {"count": 2, "width": 10, "height": 10}
    assert runs[0].values == {**common, "robots": 3, "shelves": 5, "stations": 2}
    assert runs[1].values == {**common, "robots": 1, "shelves": 5, "orders": 0}
    assert runs[2].values == {**common, "robots": 1, "shelves": 7, "prefix": "more-"}
    assert runs[3].values == common


def test_command_line_options_override_the_file(write, tmp_path):
    path = batch(write, """\
        global_settings: { '-N': 30, '-x': 6, '-y': 6 }
        run_configs:
          r1: { args: { '-r': 1, '--prs': 2 } }
        """)
    assert main(["gen", "-j", str(path), "-N", "2", "--prsmax", "3", "-d", str(tmp_path / "out")]) == 0
    assert len(list((tmp_path / "out" / "r1").iterdir())) == 2


def test_templates_are_relative_to_the_batch_file(write, tmp_path):
    write("layout.lp", "".join(f"init(object(node,{i}),value(at,({i},1)))).\n" for i in range(1, 6)))
    path = batch(write, """\
        run_configs:
          t: { args: { '-T': layout.lp, '-r': 2 } }
        """)
    run, = load_batch(path)
    assert run.values == {"templates": (str(tmp_path / "layout.lp"),), "robots": 2}


BAD = [
    ("run_configs: [1, 2]\n", 1, "run_configs must be a mapping"),
    ("global_settings: {}\n", 1, "no run_configs"),
    ("run_configs:\n  a: {args: {'-x': 3\n", 3, "not valid YAML: expected ',' or '}', but got '<stream end>'"),
    ("run_configs:\n  a:\n    args: {'-x': 3, '--nope': 1}\n", 3, "unknown option '--nope'"),
    ("run_configs:\n  a:\n    args:\n      '-x': three\n", 4, "-x needs an integer, got 'three'"),
    ("run_configs:\n  a:\n    args: [{'-x': 3}]\n    b: {}\n", 3,
     "a list of args (one run each) belongs to a leaf, not to a node with sub-configurations"),
    ("run_configs:\n  a:\n  b: {}\n", 2, "a is empty"),
    ("run_configs:\n  ../up: {}\n", 2, "'../up' cannot name a directory"),
    ("runs: {}\n", 1, "unknown key 'runs' (expected global_settings, run_configs)"),
    ("run_configs:\n  a: {}\n  a: {}\n", 3, "duplicate key 'a'"),
    ("run_configs:\n  a:\n    args:\n      '-f': ../../x-\n", 4,
     "-f must be part of a file name (no '/'), got '../../x-'"),
]


@pytest.mark.parametrize("text,line,message", BAD)
def test_bad_batch_files_name_file_and_line(write, text, line, message):
    path = write("bad.yml", text)
    with pytest.raises(InputError) as error:
        load_batch(path)
    assert str(error.value) == f"{path}:{line}: {message}"


def test_bad_batch_file_through_the_command(write, capsys):
    path = write("bad.yml", "run_configs:\n  a:\n    args: {'-x': 5, '-y': 5, '-s': 99}\n")
    assert main(["gen", "-j", str(path)]) == 2
    assert capsys.readouterr().err == \
        f"error: {path}:3: -s 99 shelves do not fit: room for 25 more on the nodes left by picking " \
        f"stations and robots (-x, -y, -n, -p, -r)\n"
    assert main(["gen", "-j", str(path.parent / "missing.yml")]) == 2
    assert capsys.readouterr().err == f"error: {path.parent / 'missing.yml'}: no such file\n"


@pytest.mark.parametrize("data, message", [
    (b"run_configs:\n  a: {args: {'-f': 'caf\xe9'}}\n", "2: not UTF-8 text (byte 0xe9)"),
    (b"\x89PNG\r\n\x1a\n\x00\x00", "3: a binary file, not YAML text"),  # the NUL follows two line ends
])
def test_batch_files_that_are_not_utf8_text_are_bad_input(tmp_path, capsys, data, message):
    path = tmp_path / "bad.yml"
    path.write_bytes(data)
    assert main(["gen", "-j", str(path), "-d", str(tmp_path / "out")]) == 2
    assert capsys.readouterr().err == f"error: {path}:{message}\n"
    assert not (tmp_path / "out").exists()

