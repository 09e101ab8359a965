"""The scanner of program files (asprilo/encodings/program_scan.py) against clingo's own
parser: random texts made of comments, strings, directives and code read the same with the
comments and includes blanked as clingo reads the original; the pieces the file is read in
change nothing; its memory stays bounded on huge files.  And the path resolver
(asprilo/paths.py): one sentence for each kind of path that is no file."""

from __future__ import annotations

import os
import random
import re
import subprocess
import sys

import clingo.ast
import pytest

from asprilo.encodings import program_scan
from asprilo.encodings.program_scan import Include, scan
from asprilo.errors import InputError
from asprilo.paths import PathError, included_file, input_file, output_folder, real, shown

#: pieces of programs, each a few tokens of clingo's syntax (the odd ones too)
PIECES = ['p(1).', 'q("a%b").', '% line "c" #include "x.lp".\n', '%* blk %* in *% "q" *%', '\n', ' ', 'r("\\"").',
          '#include "inc.lp".', '#include <incmode>.', 's :- t.', '"', '%', '*%', '%*', '$x', '#const a=1.',
          '#script (python)\nx = "%*"\n#end.\n']


def _statements(text: str) -> list[str] | str:
    """What clingo's parser reads in ``text`` (comments left out), or ``error``."""
    read: list[str] = []
    try:
        clingo.ast.parse_string(text, lambda s: read.append(str(s)) if s.ast_type != clingo.ast.ASTType.Comment
                                else None, logger=lambda _code, _message: None)
    except RuntimeError:
        return "error"
    return read


def _harmless(text: str) -> str:
    """``text`` with its includes blanked (clingo would open the files), by hand."""
    for directive in ('#include "inc.lp".', "#include <incmode>."):
        text = text.replace(directive, re.sub(r"[^\n]", " ", directive))
    return text


def test_random_programs_read_as_clingo_reads_them_in_pieces_of_any_size(tmp_path, monkeypatch):
    rng = random.Random(46)
    path = tmp_path / "random.lp"
    for _ in range(300):
        text = "".join(rng.choice(PIECES) for _ in range(rng.randint(1, 20)))
        path.write_text(text)
        results = []
        for size in (1 << 16, 1, 2, 3, 7, 13):
            monkeypatch.setattr(program_scan, "CHUNK", size)
            found = scan(path, keep_code=True)
            assert found.code is not None
            code = re.sub(r" +\n", "\n", found.code).rstrip(" ")  # blanks at a line's end say nothing
            results.append((found.includes, found.csp3_line, code))
        assert all(result == results[0] for result in results), text
        includes, _line, code = results[0]
        assert code.count("\n") == text.count("\n")
        assert _statements(code) == _statements(_harmless(text)), text


def test_what_a_scan_finds_by_hand(tmp_path):
    path = tmp_path / "enc.lp"
    path.write_text('p. % #include "no.lp".\n%* "#include" *% #include "a.lp".\n#include\n  <incmode>  .\n'
                    'q("#include \\"no.lp\\".").\n#include "b\\\\c.lp" % here\n.\n#includes "no.lp".\n'
                    '#script (python)\n#include "no.lp".\n#end.\nr :- $X$<=3.\n')
    found = scan(path)
    assert found.includes == [Include("a.lp", 2), Include("incmode", 3, True), Include("b\\c.lp", 6)]
    assert (found.csp3_line, found.code) == (12, None)


def test_a_file_that_is_not_utf8_is_refused(tmp_path):
    path = tmp_path / "latin.lp"
    path.write_bytes(b"p(\"\xe9\").\n")
    with pytest.raises(InputError) as refused:
        scan(path)
    assert str(refused.value) == f"{path}: not a UTF-8 text file"


SCAN_PEAK = """
import resource, sys
from pathlib import Path
from asprilo.encodings.program_scan import scan
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
found = scan(Path(sys.argv[1]))
print(len(found.includes), (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before) // 1024)
"""


@pytest.mark.parametrize("content", ["string", "comments"])
def test_a_scan_of_a_huge_file_takes_no_more_memory_than_a_few_pieces(tmp_path, content):
    """A 20 MB string, 50 MB of one-character comments: the scan's memory stays within 20 MB
    (the regular expressions it replaced took 2.35 GB on the string)."""
    path = tmp_path / "huge.lp"
    with open(path, "w") as file:
        file.write('#include "a.lp".\n')
        if content == "string":
            file.write(f'p("{"a" * 20_000_000}").\n')
        else:
            for _ in range(25):
                file.write("%\n" * 1_000_000)
        file.write('#include "b.lp".\n')
    answer = subprocess.run([sys.executable, "-c", SCAN_PEAK, str(path)], capture_output=True, text=True, check=True)
    includes, grown = map(int, answer.stdout.split())
    assert includes == 2 and grown < 20, answer.stdout


# --- the path resolver --------------------------------------------------------------------------

def test_each_kind_of_path_that_is_no_file_is_one_sentence(tmp_path):
    (tmp_path / "loop").symlink_to("loop")
    (tmp_path / "gone").symlink_to("nothing")
    os.mkfifo(tmp_path / "pipe")
    (tmp_path / "folder").mkdir()
    (tmp_path / "file.lp").write_text("p.\n")
    odd = tmp_path / os.fsdecode(b"enc_\xff.lp")
    odd.write_text("p.\n")
    said = {}
    for name in ("loop", "gone", "pipe", "folder", "/dev/zero", "file.lp/x", "missing.lp", odd.name):
        with pytest.raises(PathError) as refused:
            input_file(tmp_path / name)
        said[name] = refused.value.message
    assert said == {"loop": "is a loop of symbolic links", "gone": "no such file",
                    "pipe": "is a FIFO (named pipe), not a regular file", "folder": "is a folder, not a file",
                    "/dev/zero": "is a character device, not a regular file",
                    "file.lp/x": "no such file (a part of its path is a file, not a folder)",
                    "missing.lp": "no such file", odd.name: "has a name that is not UTF-8 (rename the file)"}
    assert shown(odd) == f"{tmp_path}/enc_\\xff.lp"
    assert input_file(tmp_path / "file.lp") == tmp_path / "file.lp"
    assert real(tmp_path / "loop") == tmp_path / "loop"  # (Path.resolve raises RuntimeError here)


def test_an_include_is_located_at_its_directive(tmp_path):
    includer = tmp_path / "enc.lp"
    (tmp_path / "loop").symlink_to("loop")
    with pytest.raises(InputError) as refused:
        included_file("loop", includer, 3)
    assert str(refused.value) == f"{includer}:3: #include of 'loop', which is a loop of symbolic links"
    with pytest.raises(InputError) as refused:
        included_file("none.lp", includer, 4)
    assert str(refused.value) == f"{includer}:4: #include of a missing file 'none.lp'"


def test_an_output_folder_that_is_no_folder_is_refused(tmp_path):
    (tmp_path / "loop").symlink_to("loop")
    (tmp_path / "file").write_text("")
    os.mkfifo(tmp_path / "pipe")
    said = {}
    for name in ("loop", "file", "pipe"):
        with pytest.raises(PathError) as refused:
            output_folder(tmp_path / name, "-o")
        said[name] = refused.value.message
    assert said == {"loop": "is a loop of symbolic links (-o names the output folder)",
                    "file": "is a file, not a folder (-o names the output folder)",
                    "pipe": "is a FIFO (named pipe), not a folder (-o names the output folder)"}
    output_folder(tmp_path / "new", "-o")  # not there yet: made later
    output_folder(tmp_path, "-o")

