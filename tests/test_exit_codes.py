"""One table of exit statuses for every command (README: "Exit status"; issue 46, item 8):
a refusal is 2 and one sentence, the same in every command.  Interrupts (130) are tested per
command in tests/test_signals.py, where the processes they leave are counted too."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

#: a command per entry, each given an input that does not exist: (arguments, the file named)
REFUSALS = [
    (["info", "nope.lp"], "nope.lp"),
    (["check", "inst.lp", "nope.lp"], "nope.lp"),
    (["gen", "-j", "nope.yml"], "nope.yml"),
    (["viz", "nope.lp", "--export", "out.png"], "nope.lp"),
    (["bench", "nope.yml"], "nope.yml"),
    (["convert", "nope.map", "out.lp"], "nope.map"),
    (["solve", "nope.lp"], "nope.lp"),
    (["grade", "nope.lp", "--domain", "m"], "nope.lp"),
    (["serve", "simulator", "nope.lp", "--port", "0"], "nope.lp"),
]


@pytest.mark.parametrize(("arguments", "missing"), REFUSALS, ids=[words[0] for words, _ in REFUSALS])
def test_a_missing_input_is_refused_with_status_2_in_every_command(tmp_path, arguments, missing):
    (tmp_path / "inst.lp").write_text("init(object(node,1),value(at,(1,1))).\n")
    result = subprocess.run([sys.executable, "-m", "asprilo.cli", *arguments], cwd=tmp_path, capture_output=True,
                            text=True, timeout=120)
    assert (result.returncode, result.stderr) == (2, f"error: {missing}: no such file\n")
    assert not (tmp_path / "out.png").exists() and not (tmp_path / "out.lp").exists()


def test_demo_refuses_a_folder_that_holds_files_with_status_2(tmp_path):
    folder = tmp_path / "full"
    folder.mkdir()
    (folder / "kept.txt").write_text("kept\n")
    result = subprocess.run([sys.executable, "-m", "asprilo.cli", "demo", "-o", str(folder)], cwd=tmp_path,
                            capture_output=True, text=True, timeout=120)
    assert (result.returncode, result.stderr) == (
        2, f"error: {folder}: the folder holds files already; choose another (-o DIR) or add --force\n")
    assert [path.name for path in folder.iterdir()] == ["kept.txt"]


def test_the_table_is_the_readme_s():
    readme = (Path(__file__).parent.parent / "README.md").read_text(encoding="utf-8")
    section = readme.split("### Exit status\n", 1)[1].split("\n### ", 1)[0]
    rows = [line.split("|")[1].strip() for line in section.splitlines() if line.startswith("| ") and "---" not in line]
    assert rows == ["status", "0", "1", "2", "130"]
