"""Budgets for everything accepted, and special inputs (issue 34, items 2 and 4).

``gen`` sizes and counts within ``coordinate``, ``gen-cells`` and ``gen-objects`` (refused
before any grounding); YAML files (``gen -j`` batch files, ``bench`` suites) within the
``yaml-*`` budgets: alias bombs, an alias inside what it names, 3,000-deep nesting, one line
each and little memory under a hard cap; a suite's time limits finite, its ``files:``
patterns walking folders only below its folder; a bench run that could not start recorded
as an error with its reason, apart from the time-outs; exports within ``pixels``, ``frames``
and ``animation-pixels``; ``--speed nan``; control characters escaped; README lists every
limit.  Expected messages and sizes are derived by hand in the comments.

The YAML files are corpus files: ``tests/hostile/bad-suite-*.yml`` (``bench``) and
``tests/hostile/bad-batch-*.yml`` (``gen -j``).
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

from asprilo.bench import runner as runner_module
from asprilo.bench.results import load_results
from asprilo.bench.runner import Runner
from asprilo.bench.suite import existing_files, load_suite
from asprilo.cli import main
from asprilo.errors import InputError
from asprilo.generator.plan import check_budgets
from asprilo.limits import NAMES, Limits
from asprilo.yamlfile import load_yaml

ROOT = Path(__file__).parent.parent
CORPUS = Path(__file__).parent / "hostile"
EXAMPLES = ROOT / "examples"
TINY = EXAMPLES / "encodings-repo/x2_y2_n4_r2_s2_ps1_pr2_u4_o2_N1.lp"
MAPF = ROOT / "docs/own-encoding/mapf.lp"
BUDGET = 30.0  # seconds any refusal may take (each comes long before on any machine)
QUICK = 5.0    # seconds a refusal "before any grounding" takes at most (about 0.2 s here)
MB = 2**20


def _run(capsys, arguments: list) -> tuple[int, str, str, float]:
    started = time.perf_counter()
    code = main([str(argument) for argument in arguments])
    seconds = time.perf_counter() - started
    out, err = capsys.readouterr()
    return code, out, err, seconds


def _one_line(err: str) -> None:
    assert err.count("\n") == 1 and err.startswith("error: "), err
    assert not any(char < " " or char == "\x7f" for char in err[:-1]), err  # control characters escaped
    assert "Traceback" not in err


def _beyond(name: str, value: str, what: str) -> str:
    """The message of ``Limits.exceeded``."""
    return f"{what}, beyond the limit {name}={value} (raise it with --limit {name}=N)"


# --- gen: sizes and counts within the limits, before any grounding --------------------------------

GEN_REFUSED = [
    (["-x", "10001", "-y", "1"], _beyond("coordinate", "10,000", "-x 10,001")),
    (["-x", "1", "-y", "20000"], _beyond("coordinate", "10,000", "-y 20,000")),
    (["-x", "4", "-y", "4", "-H", "-X", "10001"], _beyond("coordinate", "10,000", "-X 10,001")),
    (["-x", "4", "-y", "4", "-H", "-Y", "10001"], _beyond("coordinate", "10,000", "-Y 10,001")),
    (["-x", "4", "-y", "4", "-H", "-B", "10001"], _beyond("coordinate", "10,000", "-B 10,001")),
    # 2,000 x 1,000 = 2,000,000 cells (this hung at 2.9 GB before gen had budgets)
    (["-x", "2000", "-y", "1000"], _beyond("gen-cells", "700,000", "-x 2,000 -y 1,000: a floor of 2,000,000 cells")),
    (["-x", "1001", "-y", "1000"], _beyond("gen-cells", "700,000", "-x 1,001 -y 1,000: a floor of 1,001,000 cells")),
    *[(["-x", "4", "-y", "4", flag, "100001"], _beyond("gen-objects", "100,000", f"{flag} 100,001"))
      for flag in ("-n", "--gs", "-p", "-r", "-s", "-P", "-u", "-o", "--pusmin", "--pusmax", "--prsmin",
                   "--prsmax", "--sprmin", "--sprmax", "--olmin", "--olmax", "--split-threshold")],
    # the shorthands set both ends: the first one checked is named
    (["-x", "4", "-y", "4", "--prs", "100001"], _beyond("gen-objects", "100,000", "--prsmin 100,001")),
    (["-x", "4", "-y", "4", "--ol", "2000000"], _beyond("gen-objects", "100,000", "--olmin 2,000,000")),
    (["-x", "4", "-y", "4", "-w", "inf"], "-w must be a finite number, got inf"),
    (["-x", "4", "-y", "4", "-w", "nan"], "-w must be positive, got nan"),
    # limits lowered: the bound is the limit itself (4 x 4 = 16 cells)
    (["-x", "4", "-y", "4", "--limit", "gen-cells=15"], _beyond("gen-cells", "15", "-x 4 -y 4: a floor of 16 cells")),
    (["-x", "4", "-y", "4", "-r", "3", "--limit", "gen-objects=2"], _beyond("gen-objects", "2", "-r 3")),
    (["-x", "6", "-y", "1", "--limit", "coordinate=5"], _beyond("coordinate", "5", "-x 6")),
]


@pytest.mark.parametrize("arguments, message", GEN_REFUSED, ids=lambda value: " ".join(value)
                         if isinstance(value, list) else "")
def test_gen_sizes_beyond_the_limits_are_refused_at_once(capsys, tmp_path, arguments, message):
    code, out, err, seconds = _run(capsys, ["gen", *arguments, "-d", tmp_path / "out"])
    assert (code, err) == (2, f"error: {message}\n")
    assert out == "" and seconds < QUICK  # no grounding started
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("arguments", [
    ["-x", "4", "-y", "4", "--limit", "gen-cells=16"],                  # exactly the limit
    ["-x", "4", "-y", "4", "-r", "2", "--limit", "gen-objects=2"],
    ["-x", "10001", "-y", "1", "-r", "1", "--limit", "coordinate=10001"],  # raised beyond the default
], ids=lambda value: " ".join(value))
def test_gen_limits_moved_with_limit_let_the_sizes_through(capsys, arguments):
    one_of_each = ["-r", "1", "-p", "1", "-s", "1", "-P", "1", "-o", "1"]  # (the arguments' own counts come after)
    code, out, err, _seconds = _run(capsys, ["gen", *one_of_each, *arguments, "-C", "-w", "60"])
    assert (code, err) == (0, ""), err
    assert "init(object(node," in out


def test_gen_budgets_bound_every_size_and_count():
    """check_budgets on its own: at the limit accepted, one beyond refused."""
    class Config:
        width = height = zone_x = zone_y = border = None

        def __getattr__(self, name):  # every count not given
            return None

    limits = Limits(coordinate=10, gen_cells=50, gen_objects=7)
    config = Config()
    config.width, config.height = 10, 5  # 50 cells
    check_budgets(config, limits)
    config.height = 6
    with pytest.raises(InputError, match=r"^-x 10 -y 6: a floor of 60 cells, beyond the limit gen-cells=50 "):
        check_budgets(config, limits)
    config.height, config.robots = 5, 7
    check_budgets(config, limits)
    config.robots = 8
    with pytest.raises(InputError, match=r"^-r 8, beyond the limit gen-objects=7 "):
        check_budgets(config, limits)


#: a command in a child process under a hard address-space cap (megabytes), which prints its
#: own peak memory (KB) on standard output when it ends: VmHWM, the peak of this program's
#: memory (``ru_maxrss`` would keep the peak of the test process it was forked from, which
#: Linux carries across exec)
_CAPPED = """
import resource, sys
resource.setrlimit(resource.RLIMIT_AS, (int(sys.argv[1]) * 2**20,) * 2)
from asprilo.cli import main
code = main(sys.argv[2:])
with open("/proc/self/status") as status:
    print(next(line.split()[1] for line in status if line.startswith("VmHWM:")))
sys.exit(code)
"""


def _capped(cap_mb: int, arguments: list) -> tuple[int, str, float, float]:
    """(exit status, stderr, peak MB, seconds) of ``asprilo ARGUMENTS`` under ``cap_mb`` of address space."""
    started = time.perf_counter()
    result = subprocess.run([sys.executable, "-c", _CAPPED, str(cap_mb), *map(str, arguments)],
                            capture_output=True, text=True, timeout=BUDGET, stdin=subprocess.DEVNULL)
    peak = int(result.stdout.split()[-1]) / 1024 if result.stdout.split() else float("nan")
    return result.returncode, result.stderr, peak, time.perf_counter() - started


def test_a_huge_floor_is_refused_under_a_hard_memory_cap(tmp_path):
    """gen -x 2000 -y 1000 once ground until it had 2.9 GB; now one line, in a fraction of
    a second, within 1 GB of address space (about 30 MB used)."""
    code, err, peak, _seconds = _capped(1024, ["gen", "-x", "2000", "-y", "1000", "-d", tmp_path / "out"])
    assert (code, err) == (2, "error: " + _beyond("gen-cells", "700,000",
                                                  "-x 2,000 -y 1,000: a floor of 2,000,000 cells") + "\n")
    assert peak < 300


# --- YAML files: aliases, nesting, size ----------------------------------------------------------

#: corpus file -> (line, message): the lines and node counts derived in the comments
YAML_REFUSED = {
    # the suite's name is a list of a0..a8 (before the budgets: 2.4 GB and a minute to run out
    # of memory).  Line 2: the document's mapping and "name" (2 nodes); line 3: the list (1)
    # and a0 (its list and 9 strings: 10): 13; a1 (line 4): 1 + 9 x 10 = 91, 104 in all; a2:
    # 1 + 9 x 91 = 820, 924; a3: 7,381, 8,305; a4 (line 7): 8,306 + 7,381 per alias passes
    # 50,000 at its 6th alias
    "bad-suite-alias-bomb.yml": (7, _beyond("yaml-nodes", "50,000", "more than 50,000 values, lists and mappings "
                                                                   "(aliases counted as what they stand for)")),
    # the same as gen's -f (a file name prefix) one line further down: "-f:" and its mapping
    # come first (4 nodes), a4 is on line 8
    "bad-batch-alias-bomb.yml": (8, _beyond("yaml-nodes", "50,000", "more than 50,000 values, lists and mappings "
                                                                   "(aliases counted as what they stand for)")),
    "bad-suite-alias-in-itself.yml": (2, "the alias *loop stands for a value that contains it"),
    "bad-batch-alias-in-itself.yml": (4, "the alias *g stands for a value that contains it"),
    # 1,001 aliases of one number are 1,001 nodes, well within yaml-nodes
    "bad-suite-many-aliases.yml": (4, _beyond("yaml-aliases", "1,000", "more than 1,000 aliases")),
    # the document's mapping is depth 1: the 50th "[" opens depth 51
    "bad-suite-deep-3000.yml": (3, _beyond("yaml-depth", "50", "lists and mappings nested more than 50 deep")),
    "bad-batch-deep-3000.yml": (3, _beyond("yaml-depth", "50", "lists and mappings nested more than 50 deep")),
    "bad-suite-time-limit-inf.yml": (3, "time_limit: must be a finite number of seconds, at most 31,536,000 (a year), "
                                        "got inf"),
    "bad-suite-time-limit-huge.yml": (3, "time_limit: must be a finite number of seconds, at most 31,536,000 "
                                         "(a year), got inf"),
    "bad-suite-makespan-time-limit-inf.yml": (3, "makespan_time_limit: must be a finite number of seconds, at most "
                                                 "31,536,000 (a year), got inf"),
    "bad-suite-time-limit-nan.yml": (3, "time_limit: must be a positive number of seconds"),
    "bad-suite-files-root.yml": (3, "instances.x.files: '/**/*.lp' walks folders outside the suite's folder: only "
                                    "below it may a pattern walk folders (** or a wildcard in a folder's name); "
                                    "elsewhere only a file name may hold wildcards"),
    "bad-suite-files-up.yml": (5, "instances.x.files: '../*/*.lp' walks folders outside the suite's folder: only "
                                  "below it may a pattern walk folders (** or a wildcard in a folder's name); "
                                  "elsewhere only a file name may hold wildcards"),
    "bad-suite-files-up-after-wildcard.yml": (3, "instances.x.files: '*/../../*.lp': '..' after a wildcard (a "
                                                 "pattern walks only below the suite's folder)"),
    "bad-suite-control-key.yml": (3, "\\x1b[2J\\x1b[31mkey: unknown key (known: name, time_limit, memory_limit, "
                                     "makespan_time_limit, encodings, instances, runs)"),
    "bad-suite-control-set-name.yml": (3, "instances.\\x1b]0;title\\x07.first: must be a positive number of files "
                                          "per folder"),
    "bad-batch-control-key.yml": (4, "'\\x1b[2J' cannot name a directory"),
    "bad-batch-x-beyond.yml": (4, _beyond("coordinate", "10,000", "-x 20,000")),
    "bad-batch-cells-beyond.yml": (4, _beyond("gen-cells", "700,000", "-x 2,000 -y 1,000: a floor of "
                                                                      "2,000,000 cells")),
    "bad-batch-wait-inf.yml": (4, "-w must be a finite number, got inf"),
}


def _yaml_command(path: Path, out: Path) -> list:
    return ["bench", path, "-o", out] if path.name.startswith("bad-suite-") else ["gen", "-j", path, "-d", out]


def test_every_yaml_corpus_file_has_its_message():
    assert sorted(YAML_REFUSED) == sorted(p.name for p in [*CORPUS.glob("bad-suite-*"), *CORPUS.glob("bad-batch-*")])


@pytest.mark.parametrize("name", sorted(YAML_REFUSED))
def test_hostile_yaml_files_are_refused_in_one_line(capsys, tmp_path, name):
    path = CORPUS / name
    line, message = YAML_REFUSED[name]
    code, out, err, seconds = _run(capsys, _yaml_command(path, tmp_path / "out"))
    assert (code, err) == (2, f"error: {path}:{line}: {message}\n")
    _one_line(err)
    assert seconds < BUDGET and not (tmp_path / "out").exists()


@pytest.mark.parametrize("name", ["bad-suite-alias-bomb.yml", "bad-batch-alias-bomb.yml",
                                  "bad-suite-deep-3000.yml", "bad-batch-deep-3000.yml"])
def test_alias_bombs_and_deep_nesting_stay_small_under_a_hard_cap(tmp_path, name):
    """About 570 bytes of aliases took 2.4 GB and a minute (then out of memory, under a 3 GB
    cap) in gen -j and bench before the budgets; 3,000-deep nesting was a RecursionError.
    Now one line under 1 GB of address space, in about 30 MB and half a second."""
    path = CORPUS / name
    line, message = YAML_REFUSED[name]
    code, err, peak, seconds = _capped(1024, _yaml_command(path, tmp_path / "out"))
    assert (code, err) == (2, f"error: {path}:{line}: {message}\n")
    assert peak < 300 and seconds < BUDGET


def test_yaml_budgets_count_as_derived(tmp_path):
    """``a: &a [1, 2, 3]`` / ``b: [*a, *a]``: nodes 1 (the mapping) + 1 (a) + 4 (the list and
    its items) + 1 (b) + 1 (its list) + 2 x 4 (each alias stands for 4) = 16, the second
    alias reaching 16 on line 2; 2 aliases; depth 2 (the mapping, a list)."""
    path = tmp_path / "counts.yml"
    path.write_text("a: &a [1, 2, 3]\nb: [*a, *a]\n")
    assert load_yaml(path, Limits(yaml_nodes=16, yaml_aliases=2, yaml_depth=2)) == {"a": [1, 2, 3],
                                                                                      "b": [[1, 2, 3], [1, 2, 3]]}
    for limits, line, message in (
            (Limits(yaml_nodes=15), 2, _beyond("yaml-nodes", "15", "more than 15 values, lists and mappings "
                                                                   "(aliases counted as what they stand for)")),
            (Limits(yaml_aliases=1), 2, _beyond("yaml-aliases", "1", "more than 1 aliases")),
            (Limits(yaml_depth=1), 1, _beyond("yaml-depth", "1", "lists and mappings nested more than 1 deep"))):
        with pytest.raises(InputError) as refused:
            load_yaml(path, limits)
        assert str(refused.value) == f"{path}:{line}: {message}"


def test_a_yaml_file_beyond_yaml_kb_is_refused_before_it_is_parsed(tmp_path):
    path = tmp_path / "big.yml"
    path.write_text("# " + "x" * 1021 + "\n")  # 1,024 bytes: 1 kB exactly
    assert load_yaml(path, Limits(yaml_kb=1)) is None
    path.write_text("# " + "x" * 1022 + "\n")
    with pytest.raises(InputError) as refused:
        load_yaml(path, Limits(yaml_kb=1))
    assert str(refused.value) == f"{path}: " + _beyond("yaml-kb", "1", "a YAML file of more than 1 kB")


def test_yaml_limits_can_be_raised_within_their_ceiling(capsys, tmp_path):
    with pytest.raises(SystemExit) as refused:  # (argparse's usage and error lines)
        main(["bench", str(CORPUS / "bad-suite-deep-3000.yml"), "--limit", "yaml-depth=201"])
    assert refused.value.code == 2
    assert "--limit yaml-depth=201: the limit must be positive and at most 200" in capsys.readouterr().err
    many = CORPUS / "bad-suite-many-aliases.yml"  # 1,001 aliases allowed: the suite's own first fault is said
    code, _out, err, _seconds = _run(capsys, ["bench", many, "-o", tmp_path / "out", "--limit", "yaml-aliases=1001"])
    assert (code, err) == (2, f"error: {many}:3: one: unknown key (known: name, time_limit, memory_limit, "
                              "makespan_time_limit, encodings, instances, runs)\n")


# --- bench: time limits, patterns, runs that could not start -------------------------------------

@pytest.mark.parametrize("value", ["nan", "inf", "-1", "0", "1e300"])
def test_bench_time_limit_on_the_command_line_is_finite(capsys, tmp_path, value):
    suite = tmp_path / "suite.yml"
    suite.write_text(f"name: t\ninstances: {{x: {{files: ['{TINY}']}}}}\nruns: [{{domain: m}}]\n")
    code, _out, err, _seconds = _run(capsys, ["bench", suite, "-o", tmp_path / "out", "--time-limit", value])
    shown = f"{float(value):g}"
    assert (code, err) == (2, "error: --time-limit must be a positive finite number of seconds, at most 31,536,000 "
                              f"(a year), got {shown}\n")


def _suite_in(folder: Path, files: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    suite = folder / "suite.yml"
    suite.write_text(f"name: t\ninstances: {{x: {{files: {files}}}}}\nruns: [{{domain: m}}]\n")
    return suite


def test_patterns_walk_only_below_the_suite_and_never_through_links(tmp_path):
    """``**`` below the suite's folder, with links back up and to itself: each file once, at
    once (glob.glob followed such links: 200,000 matches in 19 s and counting)."""
    folder = tmp_path / "suite"
    (folder / "sub" / "deeper").mkdir(parents=True)
    (folder / ".hidden").mkdir()
    for name in ("sub/a.lp", "sub/deeper/b.lp", "c.lp", ".hidden/d.lp", "sub/.e.lp"):  # hidden ones as glob has it
        (folder / name).write_text("")
    (folder / "sub" / "self").symlink_to(".")
    (folder / "sub" / "up").symlink_to("..")
    (folder / "sub" / "root").symlink_to("/")
    suite = load_suite(_suite_in(folder, "['**/*.lp']"))
    started = time.perf_counter()
    found = existing_files(suite, suite.sets[0])
    assert [str(path.relative_to(folder)) for path in found] == ["c.lp", "sub/a.lp", "sub/deeper/b.lp"]
    assert time.perf_counter() - started < QUICK
    # a link to a folder outside, as the start of a walk: refused at its line
    with pytest.raises(InputError) as refused:
        load_suite(_suite_in(folder, "['sub/root/**/*.lp']"))
    assert str(refused.value) == (f"{folder / 'suite.yml'}:2: instances.x.files: 'sub/root/**/*.lp' walks folders "
                                  "outside the suite's folder: only below it may a pattern walk folders (** or a "
                                  "wildcard in a folder's name); elsewhere only a file name may hold wildcards")


def test_outside_the_suite_a_pattern_lists_one_folder_and_keeps_its_regular_files(tmp_path):
    """``../*`` lists the folder above (its regular files: not the suite's own folder); a file
    named as it is may be anywhere (the bundled smoke suite names ../examples/... files)."""
    (tmp_path / "one.lp").write_text("")
    (tmp_path / "two.txt").write_text("")
    suite = load_suite(_suite_in(tmp_path / "suite", f"['../*', '{TINY}', '../../{tmp_path.name}/one.lp']"))
    found = existing_files(suite, suite.sets[0])
    assert found == [tmp_path / "suite" / "../one.lp", tmp_path / "suite" / "../two.txt", TINY,
                     tmp_path / "suite" / f"../../{tmp_path.name}/one.lp"]
    for bundled in (ROOT / "benchmarks/smoke.yml", ROOT / "docs/own-encoding/suite.yml"):
        suite = load_suite(bundled)
        assert all(existing_files(suite, s) for s in suite.sets if not s.batch)


def _own_suite(folder: Path) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "a.lp").write_text(TINY.read_text())
    (folder / "mine.lp").write_text(MAPF.read_text())
    suite = folder / "suite.yml"
    suite.write_text("name: t\ntime_limit: 20\nmakespan_time_limit: 20\nencodings: {mine: {files: [mine.lp]}}\n"
                     "instances: {x: {files: [a.lp]}}\nruns: [{domain: m, encoding: [plain, mine]}]\n")
    return suite


def _statuses(records: list[dict]) -> list[tuple]:
    return sorted((r["encoding"], r["status"], r.get("error")) for r in records)


def _report(capsys, folder: Path) -> str:
    capsys.readouterr()
    assert main(["bench", "report", str(folder), "--plots", "none", "--no-latex"]) == 0
    return " ".join(capsys.readouterr().out.split())


def test_a_run_whose_encoding_is_gone_is_an_error_not_a_time_out(capsys, tmp_path):
    """The suite's own encoding deleted after the suite was checked: its run cannot start;
    an error with the reason, after the fraction of a second it took (not the 20 s limit)."""
    suite = load_suite(_own_suite(tmp_path / "s"))
    mine = tmp_path / "s" / "mine.lp"
    mine.unlink()
    records = Runner(suite, tmp_path / "out").run()
    assert _statuses(records) == [("mine", "error", f"{mine}: no such file"),
                                  ("plain", "solved", None)]
    assert next(r for r in records if r["encoding"] == "mine")["time"] < 20
    report = _report(capsys, tmp_path / "out")
    assert "mine -(0) !1" in report  # no time, not out of limits: one error
    # the suite names a.lp beside itself: so does the report
    assert f"M mine: x a.lp: error: {mine}: no such file" in report


def test_a_run_whose_instance_is_gone_is_an_error(capsys, tmp_path, monkeypatch):
    """The instance deleted after its minimal makespan was found, before the runs."""
    suite = load_suite(_own_suite(tmp_path / "s"))
    instance = tmp_path / "s" / "a.lp"
    run_limited = runner_module.run_limited

    def deleting(job, *limits):
        if job["kind"] == "run" and instance.exists():
            instance.unlink()
        return run_limited(job, *limits)

    monkeypatch.setattr(runner_module, "run_limited", deleting)
    records = Runner(suite, tmp_path / "out").run()
    assert [(e, s) for e, s, _why in _statuses(records)] == [("mine", "error"), ("plain", "error")]
    assert all(r["error"].endswith(f"{instance}: no such file") and r["time"] < 20 for r in records)
    # known by the instance's name in the suite (a.lp, beside it)
    assert json.loads((tmp_path / "out" / "makespans.json").read_text()) == {"a.lp": {"M": 1}}


def test_a_makespan_search_that_could_not_run_makes_errors_not_time_outs(capsys, tmp_path, monkeypatch):
    """The instance deleted after it was read, before the search for its minimal makespan:
    the search fails at once.  Its runs were recorded as 'no-makespan ... (its search timed
    out)' at the 20 s limit and counted with the time-outs; now errors that say why, time 0,
    and the failed search is not cached (it runs again on resume)."""
    suite = load_suite(_own_suite(tmp_path / "s"))
    instance = tmp_path / "s" / "a.lp"
    instances = Runner.instances

    def then_deleted(self):
        found = instances(self)
        instance.unlink()
        return found

    monkeypatch.setattr(Runner, "instances", then_deleted)
    stream = tmp_path / "progress.txt"
    with stream.open("w") as progress:
        records = Runner(suite, tmp_path / "out", stream=progress).run()
    why = f"no minimal makespan to run at: its search failed ({instance}: no such file)"
    assert _statuses(records) == [("mine", "error", why), ("plain", "error", why)]
    assert [r["time"] for r in records] == [0.0, 0.0]
    assert not (tmp_path / "out" / "makespans.json").exists()
    lines = stream.read_text().splitlines()
    assert lines[0].startswith("makespans [1/1] solved 0, time-outs 0, failures 1 |")
    assert lines[-1].startswith("runs [2/2] solved 0, time-outs 0, failures 2 |")
    report = _report(capsys, tmp_path / "out")
    assert "plain -(0) !1" in report and "mine -(0) !1" in report
    assert "Failed runs (2; not in the averages, not in PAR)" in report
    assert load_results(tmp_path / "out") == records


# --- exports: pixels and frames ------------------------------------------------------------------

SMALL = "init(object(node,1),value(at,(1,1))).\ninit(object(node,2),value(at,(2,1))).\n" \
        "init(object(robot,1),value(at,(1,1))).\n"
#: pictures show the floor with a quarter cell around it: 2 x 1 nodes are 2.5 x 1.5 cells


@pytest.fixture
def small(tmp_path) -> Path:
    path = tmp_path / "small.lp"
    path.write_text(SMALL)
    return path


@pytest.mark.gui
@pytest.mark.parametrize("arguments, message", [
    # 2.5 x 1.5 cells at 100,000 px (it used to say "wrote" and write 0 bytes)
    (["--cell", "100000"], _beyond("pixels", "40,000,000", "a picture of 250,000x150,000 pixels (100,000 per cell; "
                                                          "a smaller --cell makes it smaller)")),
    (["--cell", "100", "--limit", "pixels=37499"],  # 250 x 150 = 37,500
     _beyond("pixels", "37,499", "a picture of 250x150 pixels (100 per cell; a smaller --cell makes it smaller)")),
    (["--cell", "3000000000"], _beyond("pixels", "40,000,000", "a picture of 7,500,000,000x4,500,000,000 pixels "
                                                              "(3,000,000,000 per cell; a smaller --cell makes it "
                                                              "smaller)")),  # beyond what Qt's sizes hold
], ids=["cell-100000", "pixels-lowered", "cell-beyond-int"])
def test_pictures_beyond_the_pixel_budget_are_refused(capsys, tmp_path, small, arguments, message):
    out = tmp_path / "state.png"
    code, _out, err, seconds = _run(capsys, ["viz", small, "--export", out, *arguments])
    assert (code, err) == (2, f"error: {message}\n")
    assert seconds < BUDGET and not out.exists()


@pytest.mark.gui
def test_pictures_at_the_pixel_budget_are_written(capsys, tmp_path, small):
    out = tmp_path / "state.png"
    code, _out, err, _seconds = _run(capsys, ["viz", small, "--export", out, "--cell", "100",
                                              "--limit", "pixels=37500"])
    assert (code, err) == (0, f"wrote {out}: 250x150\n")
    assert out.read_bytes().startswith(b"\x89PNG")


@pytest.mark.gui
def test_a_jpeg_wider_than_libjpeg_allows_is_refused_not_written_empty(capsys, tmp_path):
    """Nodes at (1,1) and (3000,1): 3,000.5 cells at 24 px = 72,012 px wide, 36 high (2.6
    million pixels, within the budget): a PNG is written, a JPEG (65,500 a side) refused."""
    wide = tmp_path / "wide.lp"
    wide.write_text("init(object(node,1),value(at,(1,1))).\ninit(object(node,2),value(at,(3000,1))).\n")
    code, _out, err, _seconds = _run(capsys, ["viz", wide, "--export", tmp_path / "w.jpg", "--cell", "24"])
    assert (code, err) == (2, "error: a JPEG picture is at most 65,500 pixels a side, this one would be 72,012x36: "
                              "write a .png, or give a smaller --cell\n")
    assert not (tmp_path / "w.jpg").exists()
    code, _out, err, _seconds = _run(capsys, ["viz", wide, "--export", tmp_path / "w.png", "--cell", "24"])
    assert (code, err) == (0, f"wrote {tmp_path / 'w.png'}: 72012x36\n")


@pytest.mark.gui
def test_a_far_node_is_refused_in_one_line_with_bounded_memory(tmp_path):
    """Three facts, one node at (10000,10000): the floor's 10,000.5 cells at the smallest
    default cell (2 px) are 20,001 px a side, 400 million pixels.  The export took 2.1 GB
    (PNG) or ran out of memory (GIF), then 0.9 GB to refuse (the scene's floor image of the
    10,000 x 10,000 box was made first); now one line, said from the instance alone before
    any scene exists: the process stays at what Python and Qt's libraries take."""
    far = tmp_path / "far.lp"
    far.write_text("init(object(node,1),value(at,(1,1))).\ninit(object(node,2),value(at,(10000,10000))).\n"
                   "init(object(robot,1),value(at,(1,1))).\n")
    for name, height in (("far.png", 20001), ("far.gif", 20001 + 18), ("far.svg", 20001)):  # GIF frames: a caption
        out = tmp_path / name
        code, err, peak, seconds = _capped(4096, ["viz", far, "--export", out])
        assert (code, err) == (2, "error: " + _beyond("pixels", "40,000,000", f"a picture of 20,001x{height:,} pixels "
                                                      "(2 per cell; a smaller --cell makes it smaller)") + "\n")
        assert peak < 250 and seconds < BUDGET and not out.exists()


@pytest.mark.gui
def test_an_animation_beyond_the_frame_budget_is_refused_before_any_frame(capsys, tmp_path, small):
    """One action at step 20,000: 20,001 frames (a plan at step 1,000,000 rendered a million)."""
    late = tmp_path / "late.lp"
    late.write_text("occurs(object(robot,1),action(move,(1,0)),20000).\n")
    for out in (tmp_path / "late.gif", tmp_path / "late.mp4"):
        code, _out, err, seconds = _run(capsys, ["viz", small, late, "--export", out])
        assert (code, err) == (2, "error: " + _beyond("frames", "10,000", "an animation of 20,001 frames") + "\n")
        assert seconds < BUDGET and not out.exists()


@pytest.mark.gui
def test_animation_budgets_are_exact(capsys, tmp_path):
    """The corridor's plan (horizon 2) with --frames 4: 2 x 4 + 1 = 9 frames of 3.5 x 1.5
    cells at 48 px (168 x 72) and a caption band of 24 px: 168 x 96 = 16,128 pixels each,
    145,152 in all."""
    instance, plan = CORPUS / "base-instance.lp", CORPUS / "base-plan.lp"
    out = tmp_path / "plan.gif"
    calls = [
        (["--limit", "frames=8"], 2, "error: " + _beyond("frames", "8", "an animation of 9 frames") + "\n"),
        (["--limit", "animation-pixels=145151"], 2, "error: " + _beyond(
            "animation-pixels", "145,151", "an animation of 9 frames of 168x96 pixels (145,152 in all; a smaller "
                                           "--cell or fewer --frames make it smaller)") + "\n"),
        (["--limit", "pixels=16127"], 2, "error: " + _beyond(
            "pixels", "16,127", "a picture of 168x96 pixels (48 per cell; a smaller --cell makes it smaller)") + "\n"),
        (["--limit", "frames=9", "--limit", "animation-pixels=145152", "--limit", "pixels=16128"], 0,
         "rendering frame 9/9\n" f"wrote {out}: 9 frames\n"),
    ]
    for limits, code, err in calls:
        result = _run(capsys, ["viz", instance, plan, "--export", out, "--frames", "4", *limits])
        assert result[0] == code and result[2].replace("\r", "") == err, result[2]
        assert out.exists() == (code == 0)


@pytest.mark.gui
@pytest.mark.parametrize("speed", ["nan", "inf", "-inf", "0", "-2"])
def test_speed_must_be_a_positive_finite_number(capsys, tmp_path, small, speed):
    code, _out, err, _seconds = _run(capsys, ["viz", small, "--export", tmp_path / "a.gif", f"--speed={speed}"])
    assert (code, err) == (2, f"error: --speed must be a positive number of steps per second, got {float(speed):g}\n")


@pytest.mark.gui
def test_a_strip_beyond_the_pixel_budget_is_refused(capsys, tmp_path, small):
    """A strip's panel is a picture with its caption band (48 px at big cells)."""
    out = tmp_path / "strip.png"
    code, _out, err, _seconds = _run(capsys, ["viz", small, "--export", out, "--strip", "0-0", "--cell", "100000"])
    assert (code, err) == (2, "error: " + _beyond("pixels", "40,000,000", "a picture of 250,000x150,048 pixels "
                                                  "(100,000 per cell; a smaller --cell makes it smaller)") + "\n")
    assert not out.exists()


# --- the docs ------------------------------------------------------------------------------------

def test_readme_lists_every_limit_with_its_default():
    text = (ROOT / "README.md").read_text()
    rows = {}
    for names, defaults in re.findall(r"^\| (`[^|]*) \| ([^|]+) \|", text, re.M):
        for name, default in zip(re.findall(r"`([a-z-]+)`", names), defaults.split(", "), strict=True):
            rows[name] = default.strip()
    defaults = Limits()
    for field in NAMES:
        value = getattr(defaults, field)
        written = f"{value:g}" if isinstance(value, float) else f"{value:,}"
        assert rows.get(field.replace("_", "-")) in (written, written.replace(",", "")), field
