"""Memory limits of users' encodings (issue 46, item 3): a default everywhere they run, never
above the limit the process has (``ulimit -v``), and values no child could honour refused in
words before anything starts.  The outer limits are set here (``RLIMIT_AS`` of the command's
process, as ``ulimit -v`` sets it); the expected figures are worked out from them."""

from __future__ import annotations

import resource
import subprocess
import sys
from pathlib import Path

import pytest
from helpers import EXAMPLES

from asprilo import isolation

ENCODINGS = Path(__file__).parent / "encodings"
SMALL_M = EXAMPLES / "paper-m/1x2x4/x11_y6_n66_r11_s16_ps1_pr16_u16_o11_N001.lp"
#: ``ulimit -v 4000000`` (kB), a cluster's 4 GB address-space limit
OUTER_KB = 4_000_000


def asprilo(arguments: list[str], folder: Path, outer_kb: int | None = None) -> subprocess.CompletedProcess:
    """Run a command of the toolkit, under an address-space limit of ``outer_kb`` kB if given."""
    def limit() -> None:
        if outer_kb is not None:
            resource.setrlimit(resource.RLIMIT_AS, (outer_kb * 1024, outer_kb * 1024))

    return subprocess.run([sys.executable, "-m", "asprilo.cli", *arguments], cwd=folder, capture_output=True,
                          text=True, timeout=300, preexec_fn=limit)


def _python(code: str, outer_kb: int | None = None) -> str:
    def limit() -> None:
        if outer_kb is not None:
            resource.setrlimit(resource.RLIMIT_AS, (outer_kb * 1024, outer_kb * 1024))

    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=60,
                          preexec_fn=limit).stdout.strip()


def test_the_default_is_half_the_machine_or_8_gb():
    with open("/proc/meminfo") as meminfo:
        total_kb = int(next(line for line in meminfo if line.startswith("MemTotal:")).split()[1])
    expected = min(8192, total_kb // 1024 // 2)
    assert _python("from asprilo.memory import default_memory_mb; print(default_memory_mb())") == str(expected)


def test_the_default_never_exceeds_the_limit_the_process_has():
    shown = _python("from asprilo.memory import default_memory_mb; print(default_memory_mb())", outer_kb=1_000_000)
    assert shown == "976"  # 1,000,000 kB in whole MB


@pytest.mark.parametrize("command", [["solve", str(SMALL_M), "--encoding", str(ENCODINGS / "m-single.lp")],
                                     ["grade", str(ENCODINGS / "m-single.lp"), "--domain", "m"],
                                     ["bench", "suite.yml"]])
def test_a_memory_limit_too_small_to_start_is_refused(tmp_path, command):
    result = asprilo([*command, "--memory-limit", "50"], tmp_path)
    assert result.returncode == 2
    assert result.stderr.splitlines()[-1] == (f"asprilo {command[0]}: error: argument --memory-limit: 50 MB is too "
                                              "small: a solver process needs at least 256 MB to start")


@pytest.mark.parametrize("command", [["solve", str(SMALL_M), "--encoding", str(ENCODINGS / "m-single.lp")],
                                     ["grade", str(ENCODINGS / "m-single.lp"), "--domain", "m"],
                                     ["bench", "suite.yml"]])
def test_a_memory_limit_above_the_outer_one_is_refused(tmp_path, command):
    result = asprilo([*command, "--memory-limit", "5000"], tmp_path, outer_kb=OUTER_KB)
    assert result.returncode == 2
    assert result.stderr.splitlines()[-1] == (
        f"asprilo {command[0]}: error: argument --memory-limit: 5000 MB is above the memory limit this process "
        "has (3906 MB, ulimit -v): a child process cannot be given more")


def test_an_encoding_that_eats_memory_stops_at_the_default_limit_and_says_it(tmp_path):
    hog = tmp_path / "hog.lp"
    hog.write_text(f'#include "{ENCODINGS / "m-single.lp"}".\nhog(X,Y) :- X = 1..100000, Y = 1..100000.\n')
    result = asprilo(["solve", str(SMALL_M), "--encoding", str(hog)], tmp_path, outer_kb=600_000)
    assert result.returncode == 1, result.stderr
    assert "no plan within the limits: stopped at the memory limit (585 MB)\n" in result.stderr  # 600,000 kB


def test_grading_under_an_outer_limit_grades(tmp_path):
    result = asprilo(["grade", str(ENCODINGS / "m-single.lp"), "--domain", "m", "--first", "2"], tmp_path,
                     outer_kb=OUTER_KB)
    assert result.returncode == 0, result.stderr
    assert "Traceback" not in result.stderr
    assert result.stdout.splitlines()[-1].startswith("2/2 valid, 2/2 minimal;")


def test_a_benchmark_under_an_outer_limit_lowers_the_suite_default_once(tmp_path):
    suite = tmp_path / "suite.yml"
    suite.write_text(f"name: capped\ntime_limit: 60\ninstances:\n  small: {{files: ['{SMALL_M}']}}\n"
                     "runs:\n  - {domain: m, encoding: [plain]}\n")
    result = asprilo(["bench", str(suite), "-o", str(tmp_path / "out"), "--plots", "none"], tmp_path,
                     outer_kb=OUTER_KB)
    assert result.returncode == 0, result.stderr
    note = "note: the memory limit 8192 MB is lowered to 3906 MB, the limit this process has (ulimit -v)\n"
    assert result.stderr.count(note) == 1
    assert "runs [1/1] solved 1, time-outs 0, failures 0" in result.stderr


def _spin(report=None) -> None:
    while True:
        pass


def test_a_child_ends_by_itself_past_its_time_limit(monkeypatch):
    """A parent that never stops its child (stopped itself, or hung): the child's own time limit
    ends it, said as a time-out."""
    monkeypatch.setattr(isolation, "BACKSTOP", 0.5)
    child = isolation.start_isolated(_spin, time_limit=0.5)
    outcome = child.wait(time_limit=60)  # (a hang guard: the parent would kill it then, said otherwise)
    assert (outcome.status, outcome.detail) == ("timeout", "its own time limit")


def test_a_child_whose_memory_limit_is_below_what_it_maps_says_so():
    mapped = isolation._mapped_mb()
    assert mapped is not None
    outcome = isolation.run_isolated(_spin, memory_mb=mapped - 1, time_limit=60)
    assert outcome.status == "memout"
    assert outcome.detail.startswith("too little memory to start: it needs at least ")
