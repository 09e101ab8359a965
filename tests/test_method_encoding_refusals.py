"""Combinations that would silently mean nothing are refused in words (issue 47, item 7):
``--method anytime`` (or ``flow``) with ``--encoding`` -- in solve, in the solving API, in
bench suites, in the viewer's Run menu -- and ``assign: true`` on a bench suite's own encoding."""

from __future__ import annotations

import json
import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from pathlib import Path  # noqa: E402

import pytest  # noqa: E402
from helpers.viewer import shown_window  # noqa: E402

from asprilo.cli import main  # noqa: E402
from asprilo.encodings import solve  # noqa: E402
from asprilo.encodings.own import own_encoding  # noqa: E402
from asprilo.errors import InputError  # noqa: E402

ENCODINGS = Path(__file__).parent / "encodings"
M_TINY = ENCODINGS / "m-tiny.lp"
MINE = ENCODINGS / "m-single.lp"


def refusal(method: str) -> str:
    return (f"--method {method} runs no encoding, so --encoding would be ignored: leave out --method to run the "
            f"encoding with the exact search, or --encoding to run the {method} method")


@pytest.mark.parametrize("method", ["anytime", "flow"])
@pytest.mark.parametrize("encoding", [str(MINE), "plain"])
def test_solve_refuses_a_method_that_runs_no_encoding_with_an_encoding(capsys, method, encoding):
    assert main(["solve", str(M_TINY), "--encoding", encoding, "--method", method]) == 2
    assert capsys.readouterr() == ("", f"error: {refusal(method)}\n")
    assert main(["solve", str(M_TINY), "--encoding", encoding, "--method", method, "--json"]) == 2
    out, err = capsys.readouterr()
    assert json.loads(out) == {"error": refusal(method), "exit": 2} and err == f"error: {refusal(method)}\n"


def test_the_api_refuses_an_own_encoding_for_the_anytime_planner():
    with pytest.raises(InputError) as raised:
        solve(M_TINY, encoding=own_encoding([MINE]), method="anytime")
    assert str(raised.value) == refusal("anytime")


def _suite(tmp_path: Path, runs: str) -> Path:
    (tmp_path / "enc").mkdir()
    (tmp_path / "enc" / "mine.lp").write_text(MINE.read_text())
    (tmp_path / "enc" / "m-moves.lp").write_text((ENCODINGS / "m-moves.lp").read_text())  # it includes this
    (tmp_path / "m-tiny.lp").write_text(M_TINY.read_text())
    suite = tmp_path / "suite.yml"
    suite.write_text("name: t\nencodings:\n  mine: {files: [enc/mine.lp]}\ninstances:\n  tiny: {files: [m-tiny.lp]}\n"
                     f"runs:\n  - {{domain: m, encoding: plain}}\n{runs}")
    return suite


def test_a_suite_refuses_assign_on_its_own_encoding(tmp_path, capsys):
    # line 8 of the suite: the second run entry
    suite = _suite(tmp_path, "  - {domain: m, encoding: [plain, mine], assign: [false, true]}\n")
    assert main(["bench", str(suite), "-o", str(tmp_path / "out")]) == 2
    assert capsys.readouterr().err == (
        f"error: {suite}:8: runs[1].assign: assign: true hands a task assignment to the reference encodings, which "
        "are written to follow it; 'mine' is the suite's own encoding, which nothing makes follow it, so its row "
        "would mean nothing: run 'mine' in an entry without assign\n")
    assert not (tmp_path / "out").exists()


def test_a_suite_refuses_an_encoding_for_the_anytime_method(tmp_path, capsys):
    suite = _suite(tmp_path, "  - {domain: m, method: anytime, encoding: mine}\n")
    assert main(["bench", str(suite), "-o", str(tmp_path / "out")]) == 2
    assert capsys.readouterr().err == f"error: {suite}:8: runs[1]: method anytime takes no encoding and no assignment\n"


@pytest.mark.gui
def test_the_run_menu_offers_no_encoding_to_the_anytime_planner(qtbot, tmp_path_factory):
    window = shown_window(qtbot, tmp_path_factory)
    window.open_files([str(M_TINY)])
    jobs = window.jobs

    def entries() -> list[tuple[str, bool]]:
        jobs._fill_encodings()  # what the menu does when it opens
        return [(action.text(), action.isEnabled()) for action in jobs.encoding_menu.actions()]

    offered = entries()
    assert offered and all(enabled for _text, enabled in offered) and offered[0][0] == "plain"
    window.settings.setValue("tools/method", "anytime")
    assert entries() == [("(Solve method Anytime only runs no encoding)", False),
                         *((text, False) for text, _enabled in offered)]
