"""The help texts agree: ``asprilo --help`` lists each command with the first line of the
command's own description (``asprilo COMMAND --help``), so the two cannot drift apart."""

from __future__ import annotations

import re

import pytest

from asprilo.cli import COMMANDS, main


def _help(capsys, *argv: str) -> str:
    with pytest.raises(SystemExit) as exit_:
        main([*argv, "--help"])
    assert exit_.value.code == 0
    return capsys.readouterr().out


def _listed(text: str) -> dict[str, str]:
    """The commands of ``asprilo --help`` and their summaries (argparse wraps them: unwrapped)."""
    block = text[text.index("\n  COMMAND\n"):].split("\n\n")[0]
    found = re.findall(r"^ {4}(\w+)\s+(.*?)(?=^ {4}\w|\Z)", block, re.MULTILINE | re.DOTALL)
    return {name: " ".join(summary.split()) for name, summary in found}


def _first_line_of_description(text: str) -> str:
    """The description's first line in ``asprilo COMMAND --help``: after the usage block."""
    return text.split("\n\n")[1].splitlines()[0]


def test_the_command_list_names_every_command_once(capsys):
    assert list(_listed(_help(capsys))) == list(COMMANDS)


@pytest.mark.parametrize("name", list(COMMANDS))
def test_each_command_is_summarised_with_the_first_line_of_its_own_description(capsys, name):
    summary = _listed(_help(capsys))[name]
    line = _first_line_of_description(_help(capsys, name))
    assert line == summary[0].upper() + summary[1:] + ("" if summary.endswith("?") else ".")
