"""Flags of the original asprilo generator that old command lines and batch files use: each is
taken with its meaning, or refused with one line saying what to use instead (exit 2)."""

from __future__ import annotations

import textwrap

import pytest

from asprilo.cli import main
from asprilo.generator.options import REFUSED
from asprilo.reader import read_instance

SMALL = ["-x", "6", "-y", "5", "-p", "1", "-r", "2", "-s", "4", "-P", "4", "-u", "8"]


@pytest.mark.parametrize("flag", [flag for flags in REFUSED for flag in flags])
def test_every_refused_flag_is_one_line_and_exit_2(flag, tmp_path, capsys):
    assert main(["gen", *SMALL, flag, "3", "-d", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {flag}: ") and err.count("\n") == 1 and "Traceback" not in err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("words, message", [
    ("--ph-robots 3", "--ph-robots: not needed: -H keeps the bottom row for robots whatever -r is (give -r)"),
    ("--ph-pickstas 2",
     "--ph-pickstas: not needed: -H keeps the top row for picking stations whatever -p is (give -p)"),
    ("--prj-orders", "--prj-orders: add orders to an existing warehouse with -T FILE -o N"),
    ("--split 2 3", "--split: make the warehouses without orders (-N W, no -o), then the orders of each with "
                    "-T FILE -o O -N K"),
    ("-D", "-D: there is no debug output (use -V for each stage's rounds and seconds)"),
    ("--su", "--su: use --skip-existing: it keeps every instance file that exists, so an interrupted batch resumes"),
])
def test_refusals_say_what_to_use_instead(words, message, capsys):
    assert main(["gen", *SMALL, *words.split(), "-C"]) == 2
    assert capsys.readouterr() == ("", f"error: {message}\n")


def test_refused_flags_in_a_batch_file_name_file_and_line(write, capsys):
    path = write("old.yml", textwrap.dedent("""\
        run_configs:
          a:
            args:
              '-x': 6
              '--instance-dir-suffix': /orders
        """))
    assert main(["gen", "-j", str(path)]) == 2
    assert capsys.readouterr().err == \
        f"error: {path}:5: --instance-dir-suffix: use --instance-dir (one directory per instance) or -f PREFIX\n"


def test_options_directly_under_a_directory_key_say_where_they_go(write, capsys):
    path = write("old.yml", "run_configs:\n  a:\n    '-x': 6\n")
    assert main(["gen", "-j", str(path)]) == 2
    assert capsys.readouterr().err == (f"error: {path}:3: '-x': an option where a sub-directory is expected; "
                                       f"options go under 'args:' (see asprilo/generator/README.md)\n")


def test_random_is_taken_and_changes_nothing(write, capsys):
    assert main(["gen", *SMALL, "-C"]) == 0
    plain = capsys.readouterr().out
    assert main(["gen", *SMALL, "--random", "-C"]) == 0
    assert capsys.readouterr().out == plain
    path = write("batch.yml", "run_configs:\n  a: {args: {'-x': 4, '-y': 4, '--random': true}}\n")
    assert main(["gen", "-j", str(path), "-d", str(path.parent / "out")]) == 0


def test_instance_count_numbers_the_instances(tmp_path):
    assert main(["gen", *SMALL, "-N", "3", "-d", str(tmp_path / "all")]) == 0
    assert main(["gen", *SMALL, "--instance-count", "3", "-d", str(tmp_path / "third")]) == 0
    third, = (tmp_path / "third").iterdir()
    assert third.name == "x6_y5_n30_r2_s4_ps1_pr4_u8_o0_N003.lp"
    same = tmp_path / "all" / third.name  # the third of -N 3: the same facts
    assert read_instance(third) == read_instance(same)
    assert "% command: gen -x 6 -y 5 -p 1 -r 2 -s 4 -P 4 -u 8 -N 1 --seed 123456789 --instance-count 3" \
        in third.read_text()


def test_the_advice_for_prj_orders_works(tmp_path):
    warehouse = tmp_path / "w"
    assert main(["gen", *SMALL, "-d", str(warehouse)]) == 0
    layout, = warehouse.iterdir()
    assert main(["gen", "-T", str(layout), "-o", "3", "-d", str(tmp_path / "orders")]) == 0
    made, = (tmp_path / "orders").iterdir()
    instance = read_instance(made)
    assert len(instance.orders) == 3 and instance.robots == read_instance(layout).robots


def test_version(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["gen", "-v"])
    assert exit_.value.code == 0 and capsys.readouterr().out == "gen (asprilo) 0.1.0\n"
