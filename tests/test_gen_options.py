"""The gen command: inconsistent options are rejected before solving (exit 2, a message naming
the options); an unsatisfiable request or a time-out is reported (exit 1) and writes nothing."""

from __future__ import annotations

import pytest

from asprilo.cli import main

REJECTED = [
    ("-y 5", "give the grid size (-x) or a template (-T)"),
    ("-x 5 -y 5 -n 30", "-n 30 nodes do not fit into the grid of -x 5 x -y 5 = 25 cells"),
    ("-x 5 -y 5 -H -n 20", "-H uses the full grid; leave out -n"),
    ("-x 5 -y 5 -X 2 -Y 3", "-X, -Y only apply to the structured layout (-H)"),
    ("-x 5 -y 5 --gs 2", "--gs only applies to a partial grid (-n)"),
    ("-x 5 -y 5 -s 3 --sc 10", "give either -s or --sc, not both"),
    ("-x 5 -y 5 --sc 120", "--sc is a percentage (0..100), got 120.0"),
    ("-x 5 -y 5 -p 10 -r 10 -s 10",
     "-s 10 shelves do not fit: room for 5 more on the nodes left by picking stations and robots "
     "(-x, -y, -n, -p, -r)"),
    ("-x 11 -y 6 -H -s 20", "-s 20 shelves do not fit: room for 12 more in the storage zones (-H with -X 2 -Y 2)"),
    ("-x 11 -y 6 -H -p 12", "-H: -p 12 picking stations do not fit into the top row (-x 11)"),
    ("-x 11 -y 6 -H -X 4 -r 12", "-H: -r 12 robots do not fit below the storage zones (room for 11); -y 7 gives "
                                 "room for 22"),
    ("-x 3 -y 3 -H", "-H: no storage zone of -X 2 x -Y 2 fits into -x 3 x -y 3 with border -B 1"),
    ("-x 5 -y 5 -s 4 -P 3 -u 2",
     "-u 2: with -P 3, -s 4, --sprmin/--sprmax 1/4, --prsmin/--prsmax 0/20, --pusmin/--pusmax 1/10 "
     "the shelves hold 3..120 units"),
    ("-x 5 -y 5 -s 4 -P 3 --pusmin 4 --pusmax 2", "--pusmin 4 exceeds --pusmax 2"),
    ("-x 5 -y 5 -P 3", "-P 3 products need shelves (-s or --sc)"),
    ("-x 5 -y 5 -s 2 -P 3 --prs 1",
     "the products do not fit on the shelves: -P 3, -s 2, --sprmin/--sprmax 1/4, --prsmin/--prsmax 1/1"),
    ("-x 5 -y 5 -u 5", "-u 5: there are no new products (-P) to hold the units"),
    ("-x 5 -y 5 -s 3 -P 3 -o 2", "-o 2 orders need picking stations (-p)"),
    ("-x 5 -y 5 -s 3 -P 3 -u 3 -p 1 -o 4",
     "-o 4 orders with --olmin 1 lines each ask for more units than the shelves hold (3, -u)"),
    ("-x 5 -y 5 -s 3 -P 5 -p 1 -o 2 --oap",
     "--oap: -o 2 orders with --olmax 1 lines cannot ask for all -P 5 products"),
    ("-x 5 -y 5 -s 3 -r 2 --domain m -P 4", "--domain m: as many products as shelves (3); got -P 4"),
    ("-x 5 -y 5 -s 3 -r 2 --domain m -o 3", "--domain m: as many orders as robots (2); got -o 3"),
    ("-x 5 -y 5 --prs 1 --prsmin 0", "give either --prs or --prsmin, not both"),
    ("-x 5 -y 5 --one-shot -I", "--one-shot solves once: it cannot be combined with -I/--split-threshold"),
    ("-x 5 -y 5 -t 0", "-t must be at least 1, got 0"),
    ("-x 5 -y 5 -r -1", "-r must be at least 0, got -1"),
    ("-x 5 -y 5 --domain md", "--domain md is not generated; generate m and convert it"),
    ("-x 4 -y 4 -T layout.lp", "-T: the template fixes the floor; leave out -x, -y"),
    ("-x 5 -y 5 -t 1000", "-t must be at most 14, got 1000"),
    ("-x 5 -y 5 -w 0", "-w must be positive, got 0.0"),
    ("-x 5 -y 5 -f ../x-", "-f must be part of a file name (no '/'), got '../x-'"),
    ("-x 5 -y 5 --force --se", "give either --force (replace files) or --skip-existing (keep them), not both"),
    ("-x 5 -y 5 -d layout.lp", "layout.lp: is a file, not a folder (-d names the output folder)"),
    ("-x 5 -y 5 -d layout.lp/out", "layout.lp/out: cannot make the output folder (-d): "
                                    "{tmp}/layout.lp is a file"),
]


@pytest.mark.parametrize("arguments,message", REJECTED)
def test_inconsistent_options_are_rejected_before_solving(arguments, message, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "layout.lp").write_text("init(object(node,1),value(at,(1,1))).\n")
    assert main(["gen", *arguments.split()]) == 2
    assert capsys.readouterr().err == f"error: {message.format(tmp=tmp_path)}\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["layout.lp"]  # nothing written


def test_unknown_values_are_argparse_errors(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["gen", "-x", "5", "-y", "5", "--domain", "q"])
    assert exit_.value.code == 2
    assert "argument --domain: unknown domain 'q' (choose one of a, b, c, m, md)" in capsys.readouterr().err


def test_unsatisfiable_request_exits_1_and_writes_nothing(tmp_path, capsys):
    # 20 shelves that all touch a shelf-free path to the station: impossible on 5 x 5
    arguments = ["gen", "-x", "5", "-y", "5", "-s", "20", "-R", "-p", "1", "-r", "1", "-d", str(tmp_path / "out")]
    assert main(arguments) == 1
    assert capsys.readouterr().err == \
        "error: no instance 1: the request is unsatisfiable (stage shelves)\n"
    assert not (tmp_path / "out").exists()
    arguments.remove("-R")
    assert main(arguments) == 0


def test_time_limit_exits_1(tmp_path, capsys):
    arguments = ["gen", "-x", "60", "-y", "60", "-n", "3000", "-s", "500", "-w", "0.01", "-d", str(tmp_path)]
    assert main(arguments) == 1
    err = capsys.readouterr().err
    assert err.startswith("error: no instance 1: the time limit ran out (stage ")
    assert list(tmp_path.iterdir()) == []


def test_missing_template_file(capsys):
    assert main(["gen", "-T", "no/such/layout.lp", "-r", "2"]) == 2
    assert capsys.readouterr().err == "error: no/such/layout.lp: no such file\n"


def test_bad_template_names_file_and_line(tmp_path, capsys):
    bad = tmp_path / "bad.lp"
    bad.write_text("init(object(node,1),value(at,(1,1))).\ninit(object(robot,1),value(at,foo)).\n")
    assert main(["gen", "-T", str(bad), "-r", "2"]) == 2
    assert capsys.readouterr().err == \
        f"error: {bad}:2: robot 1: value of 'at' must be a cell (X,Y), got foo\n"
