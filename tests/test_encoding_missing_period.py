"""A missing ``.`` in an encoding: clingo reports the statement after it; the message adds
the line that lacks its ``.`` (issue 47, item 7), as the reader does for instance and plan
files.  The lines and columns below are counted by hand in each text."""

from __future__ import annotations

import pytest

from asprilo.cli import main
from asprilo.errors import InputError
from asprilo.solver import Solver
from asprilo.syntax_hint import missing_period

CORRIDOR = """\
init(object(node,1),value(at,(1,1))).
init(object(node,2),value(at,(2,1))).
init(object(robot,1),value(at,(1,1))).
init(object(shelf,1),value(at,(2,1))).
init(object(product,1),value(on,(1,1))).
init(object(order,1),value(line,(1,1))).
"""


@pytest.mark.parametrize("text, said", [
    # the rule on line 1 lacks its '.': clingo stops at the name starting line 2
    ("at(C) :- cell(C)\nmoved.\n",
     "2: column 1: syntax error, unexpected <IDENTIFIER> (a missing '.' at the end of line 1?)"),
    # comments and a blank line between: the code line before is line 3
    ("cell(1).\n% a comment\nat(C) :- cell(C)   % no period\n\n#show at/1.\n",
     "5: column 1: syntax error, unexpected #showsig (a missing '.' at the end of line 3?)"),
    # the last statement lacks its '.': clingo reaches the end of the text
    ("cell(1).\nat(C) :- cell(C)\n", "3: column 1: syntax error, unexpected EOF (a missing '.' at the end of line 2?)"),
    # an indented statement after it, and a constraint
    ("at(C) :- cell(C)\n    moved.\n",
     "2: column 5: syntax error, unexpected <IDENTIFIER> (a missing '.' at the end of line 1?)"),
    ("at(C) :- cell(C)\n:- at(3).\n",
     "2: column 1: syntax error, unexpected :-, expecting : or \",\" or . or ; (a missing '.' at the end of line 1?)"),
    # no hint: the line before ends with ',' (the rule goes on), the error is inside a line
    ("at(C) :- cell(C),\n#show at/1.\n", "2: column 1: syntax error, unexpected #showsig"),
    ("at(C) :- cell(C) moved.\n", "1: column 18: syntax error, unexpected <IDENTIFIER>"),
])
def test_solve_names_the_line_that_lacks_its_period(tmp_path, capsys, text, said):
    (tmp_path / "corridor.lp").write_text(CORRIDOR)
    encoding = tmp_path / "mine.lp"
    encoding.write_text(text)
    assert main(["solve", str(tmp_path / "corridor.lp"), "--encoding", str(encoding)]) == 2
    out, err = capsys.readouterr()
    assert (out, err) == ("", f"error: {encoding}:{said}\n")


def test_a_program_file_loaded_by_the_driver_gets_the_hint_too(tmp_path):
    program = tmp_path / "rules.lp"
    program.write_text("a :- b\nc.\n")
    with pytest.raises(InputError) as raised:
        Solver().load(program)
    assert str(raised.value) == (f"{program}:2: syntax error, unexpected <IDENTIFIER> "
                                 "(a missing '.' at the end of line 1?)")


@pytest.mark.parametrize("text, line, column, hint", [
    ("a :- b\nc.\n", 2, 1, " (a missing '.' at the end of line 1?)"),
    ("a :- b\nc.\n", 2, 2, None),                      # not where a statement starts
    ("a :- b.\nc d.\n", 2, 3, None),
    ("p(\"50%\")\nq.\n", 2, 1, " (a missing '.' at the end of line 1?)"),  # '%' in a string is no comment
    ("a :- b;\nc.\n", 2, 1, None),                     # ';' goes on
    ("% only a comment\nc.\n", 2, 1, None),            # no code line before
])
def test_the_hint_by_hand(text, line, column, hint):
    assert missing_period(text, line, column) == hint
