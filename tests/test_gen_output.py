"""Generator output: reproducible files, headers, names, variety, and the output options."""

from __future__ import annotations

import os

from test_gen_layout import FIGURE_1, cells_of, check_instance

from asprilo.cli import main
from asprilo.generator import GeneratorConfig, generate
from asprilo.reader import read_instance

SMALL = ["-x", "11", "-y", "6", "-X", "4", "-Y", "2", "-p", "1", "-s", "12", "-P", "20", "-u", "60",
         "-H", "-r", "3", "-o", "4", "--olmax", "2"]


def gen(*arguments: str) -> int:
    return main(["gen", *arguments])


def test_same_command_and_seed_give_byte_identical_files(tmp_path):
    for run in ("one", "two"):
        assert gen(*SMALL, "-N", "3", "--seed", "42", "-d", str(tmp_path / run)) == 0
    one, two = sorted((tmp_path / "one").iterdir()), sorted((tmp_path / "two").iterdir())
    assert [p.name for p in one] == [p.name for p in two] == \
        [f"x11_y6_n66_r3_s12_ps1_pr20_u60_o4_N00{k}.lp" for k in (1, 2, 3)]
    assert [p.read_bytes() for p in one] == [p.read_bytes() for p in two]
    assert gen(*SMALL, "-N", "1", "--seed", "43", "-d", str(tmp_path / "three")) == 0
    other, = (tmp_path / "three").iterdir()
    assert other.read_bytes() != one[0].read_bytes()


def test_header_names_tool_command_seed_and_counts(tmp_path):
    assert gen(*FIGURE_1_ARGS, "--seed", "7", "-d", str(tmp_path)) == 0
    path, = tmp_path.iterdir()
    lines = path.read_text().splitlines()
    assert lines[:17] == [
        "%" * 60,
        "% asprilo gen 0.1.0",
        "% command: gen -x 19 -y 9 -H -X 5 -Y 2 -p 3 -r 6 -s 45 -P 180 -u 540 -o 12 -N 1 --seed 7",
        "% seed: 7",
        "% instance: 1",
        "% Grid Size X:                       19",
        "% Grid Size Y:                       9",
        "% Number of Nodes:                   171",
        "% Number of Highway Nodes:           102",
        "% Number of Robots:                  6",
        "% Number of Shelves:                 45",
        "% Number of Picking Stations:        3",
        "% Number of Products:                180",
        "% Number of Product Units in Total:  540",
        "% Number of Orders:                  12",
        "%" * 60,
        "",
    ]
    assert lines[17] == "#program base."
    instance = read_instance(path)
    assert path.name == instance.file_name(1) == "x19_y9_n171_r6_s45_ps3_pr180_u540_o12_N001.lp"


FIGURE_1_ARGS = [flag if value is True else f"{flag} {value}" for flag, value in FIGURE_1.items()]
FIGURE_1_ARGS = " ".join(FIGURE_1_ARGS).split()


def test_instances_of_a_run_are_genuinely_different():
    items = generate(GeneratorConfig.from_options(FIGURE_1), count=4, seed=5)
    shelves = [cells_of(item.instance.shelves) for item in items]
    stock = [{(p.id, item.instance.shelves[s].at) for p in item.instance.products.values() for s in p.stock}
             for item in items]
    orders = [{(o.id, tuple(o.lines)) for o in item.instance.orders.values()} for item in items]
    for a in range(4):
        for b in range(a + 1, 4):
            assert len(shelves[a] ^ shelves[b]) >= 10          # 45 of 60 cells: many differ
            assert len(stock[a] & stock[b]) <= len(stock[a]) // 4  # products lie elsewhere
            assert orders[a] != orders[b]
    for item in items:
        check_instance(item.instance)


def test_the_instance_of_a_number_does_not_depend_on_the_count():
    config = GeneratorConfig.from_options(FIGURE_1)
    third = generate(config, count=3, seed=9)[2]
    alone = generate(config, count=1, seed=9, first=3)[0]
    assert third.instance == alone.instance and third.number == alone.number == 3


def test_console_output(capsys):
    assert gen(*SMALL, "-C", "-N", "2") == 0
    out, err = capsys.readouterr()
    assert out.count("#program base.") == 2 and out.count("% instance: ") == 2
    assert err == ""  # a progress bar only for files


def test_prefix_instance_directories_and_progress(tmp_path, capsys):
    assert gen(*SMALL, "-N", "2", "-f", "pre_", "--instance-dir", "-d", str(tmp_path)) == 0
    names = sorted(str(p.relative_to(tmp_path)) for p in tmp_path.rglob("*.lp"))
    assert names == [f"pre_x11_y6_n66_r3_s12_ps1_pr20_u60_o4_N00{k}/pre_x11_y6_n66_r3_s12_ps1_pr20_u60_o4_N00{k}.lp"
                     for k in (1, 2)]
    err = capsys.readouterr().err
    assert err.splitlines()[-2:] == [f"[2/2] {tmp_path}/{names[1]}", f"wrote 2 instance files to {tmp_path}"]


def test_skip_existing_keeps_files_and_fills_gaps(tmp_path):
    assert gen(*SMALL, "-N", "3", "-d", str(tmp_path)) == 0
    first, second, third = sorted(tmp_path.iterdir())
    second.unlink()
    os.utime(first, (1, 1))
    assert gen(*SMALL, "-N", "3", "-d", str(tmp_path), "--skip-existing") == 0
    assert sorted(tmp_path.iterdir()) == [first, second, third]
    assert first.stat().st_mtime == 1  # kept, not written again


def test_one_closing_line_says_where_the_files_went_and_q_silences_it(tmp_path, capsys):
    assert gen(*SMALL, "-d", str(tmp_path)) == 0
    assert capsys.readouterr().err == f"wrote 1 instance file to {tmp_path}\n"
    assert gen(*SMALL, "-N", "3", "-d", str(tmp_path), "--se") == 0
    assert capsys.readouterr().err.splitlines()[-1] == f"wrote 2 instance files to {tmp_path}, kept 1 that existed"
    assert gen(*SMALL, "-N", "4", "-d", str(tmp_path), "--se", "-q") == 0
    assert capsys.readouterr() == ("", "")
    assert len(list(tmp_path.iterdir())) == 4
    assert gen(*SMALL, "-C") == 0
    assert capsys.readouterr().err == ""  # the instance on stdout is what was made



def test_existing_files_are_replaced_only_with_force(tmp_path, capsys):
    assert gen(*SMALL, "-N", "2", "-d", str(tmp_path)) == 0
    first, second = sorted(tmp_path.iterdir())
    second.write_text("% my own file\n")
    capsys.readouterr()
    assert gen(*SMALL, "-N", "2", "-d", str(tmp_path)) == 2
    assert capsys.readouterr().err == \
        f"error: {first}: exists already; give --force to replace it or --skip-existing to keep it\n"
    assert second.read_text() == "% my own file\n"
    assert gen(*SMALL, "-N", "2", "-d", str(tmp_path), "--force") == 0
    assert "% instance: 2" in second.read_text() and read_instance(second).counts()["robots"] == 3


def test_template_from_stdin(tmp_path, monkeypatch, capsys):
    import io
    layout = "".join(f"init(object(node,{y * 4 + x + 1}),value(at,({x + 1},{y + 1}))).\n"
                     for y in range(4) for x in range(4))
    monkeypatch.setattr("sys.stdin", io.StringIO(layout))
    assert gen("-T", "-", "-r", "2", "-s", "3", "-p", "1", "-C") == 0
    out = capsys.readouterr().out
    assert "% command: gen -T - -p 1 -r 2 -s 3 -N 1 --seed 123456789" in out
    instance = read_instance(_written(tmp_path, out))
    assert len(instance.nodes) == 16 and len(instance.robots) == 2 and len(instance.shelves) == 3
    check_instance(instance)


def _written(tmp_path, text):
    path = tmp_path / "out.lp"
    path.write_text(text)
    return path


def test_domains_b_and_c_write_quantity_free_facts(capsys):
    assert gen(*SMALL, "--domain", "b", "-C") == 0
    out = capsys.readouterr().out
    assert "value(on,(" not in out and "value(line,(" not in out
    assert "init(object(product,1),value(on," in out and "init(object(order,1),value(line," in out
