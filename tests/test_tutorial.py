"""docs/OWN_ENCODINGS.md is run as it is written: every command of its ``sh`` blocks, from a
folder that holds the checkout's docs/ and examples/, with the exit status the page gives
(``# exit N``, else 0); an indented block right after a command block lists lines that the
last command of the block prints."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys

import pytest
from helpers import ROOT

PAGE = ROOT / "docs" / "OWN_ENCODINGS.md"


def _steps() -> list[tuple[list[str], int, list[str]]]:
    """(command, exit status, lines it prints) for every command of the page, in order."""
    steps: list[tuple[list[str], int, list[str]]] = []
    text = PAGE.read_text()
    for block in re.finditer(r"```sh\n(.*?)```\n(?:\n((?:    [^\n]*\n)+))?", text, re.S):
        commands = [line for line in block.group(1).splitlines() if line.strip() and not line.startswith("#")]
        printed = [line[4:] for line in (block.group(2) or "").splitlines()]
        for index, line in enumerate(commands):
            command, _, comment = line.partition("  # ")
            status = int(comment.split()[1]) if comment.startswith("exit ") else 0
            steps.append((shlex.split(command), status, printed if index == len(commands) - 1 else []))
    return steps


def _run(words: list[str], folder) -> subprocess.CompletedProcess:
    program = {"asprilo": [sys.executable, "-m", "asprilo.cli"], "python": [sys.executable]}[words[0]]
    return subprocess.run([*program, *words[1:]], cwd=folder, capture_output=True, text=True, timeout=600,
                          check=False)


def test_the_page_has_the_commands_of_every_step():
    names = [" ".join(words[:2]) for words, _status, _printed in _steps()]
    assert names == ["python -m", "asprilo solve", "asprilo check", "asprilo solve", "asprilo viz", "asprilo grade",
                     "asprilo bench", "asprilo bench"]


@pytest.mark.gui
def test_every_command_of_the_page_runs_as_it_says(tmp_path, monkeypatch):
    monkeypatch.setenv("QT_QPA_PLATFORM", "offscreen")
    for folder in ("docs", "examples"):
        (tmp_path / folder).symlink_to(ROOT / folder)
    (tmp_path / "work").mkdir()
    for words, status, printed in _steps():
        done = _run(words, tmp_path)
        said = done.stdout + done.stderr
        assert done.returncode == status, f"{shlex.join(words)}: exit {done.returncode}\n{said}"
        for line in printed:
            assert line in said.splitlines(), f"{shlex.join(words)} does not print {line!r}:\n{said}"
    assert (tmp_path / "work" / "plan.gif").stat().st_size > 0
    assert (tmp_path / "work" / "bench" / "report" / "scatter-plain-mine.pdf").read_bytes().startswith(b"%PDF")
