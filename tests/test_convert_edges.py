"""``asprilo convert`` at its edges (issue 46): passable ``G``/``S`` cells survive a map round
trip, maps beyond ``coordinate`` or ``facts`` are refused after their header and before
anything is written, hostile ``movingai`` facts never break a map, and unknown attributes
keep every leaf."""

from __future__ import annotations

import pytest

from asprilo.cli import main

# 6x3: passable '.', 'G', 'S'; blocked '@', 'T', 'W'; 'G' outnumbers every blocked character
TERRAIN = "type octile\nheight 3\nwidth 6\nmap\nGGG@.T\nS.GGWG\n@@GG.S\n"


def convert(*args) -> int:
    return main(["convert", *map(str, args)])


def test_passable_g_and_s_cells_survive_the_round_trip(tmp_path):
    (tmp_path / "t.map").write_text(TERRAIN)
    assert convert(tmp_path / "t.map", tmp_path / "t.lp") == 0
    facts = (tmp_path / "t.lp").read_text()
    assert facts.count("init(object(node,") == 13  # 3 + 5 + 5 passable cells (by hand)
    assert 'movingai(passable,(1,1),"G").' in facts and 'movingai(passable,(1,2),"S").' in facts
    assert 'movingai(blocked,"@").' in facts and 'movingai(blocked,(6,1),"T").' in facts
    assert convert(tmp_path / "t.lp", tmp_path / "back.map") == 0
    assert (tmp_path / "back.map").read_text() == TERRAIN


def test_files_written_before_keep_their_g_cells(tmp_path):
    # before, a G cell was kept as movingai(blocked,(X,Y),"G") while a node stood on it
    (tmp_path / "old.lp").write_text(
        "init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))).\n"
        'movingai(type,"octile"). movingai(size,(3,1)). movingai(blocked,"@"). movingai(blocked,(1,1),"G").\n')
    assert convert(tmp_path / "old.lp", tmp_path / "old.map") == 0
    assert (tmp_path / "old.map").read_text() == "type octile\nheight 1\nwidth 3\nmap\nG.@\n"


@pytest.mark.parametrize(("width", "height", "message"), [
    (2000, 2000, "a map of 2,000x2,000 = 4,000,000 cells, beyond the limit facts=1,500,000 "
                 "(raise it with --limit facts=N)"),
    (10001, 1, "a map 10,001 cells wide and 1 high, beyond the limit coordinate=10,000 "
               "(raise it with --limit coordinate=N)"),
    (1, 10001, "a map 1 cells wide and 10,001 high, beyond the limit coordinate=10,000 "
               "(raise it with --limit coordinate=N)"),
])
def test_maps_beyond_the_limits_are_refused_after_the_header(tmp_path, capsys, width, height, message):
    path = tmp_path / "big.map"
    # the header alone: refused before its rows are looked at (else: 'the header promises ...')
    path.write_text(f"type octile\nheight {height}\nwidth {width}\nmap\n")
    assert convert(path, tmp_path / "big.lp") == 2
    assert capsys.readouterr().err == f"error: {path}: {message}\n"
    assert not (tmp_path / "big.lp").exists()


def test_a_wide_map_within_the_limit_converts(tmp_path):
    path = tmp_path / "wide.map"
    path.write_text("type octile\nheight 1\nwidth 10000\nmap\n" + "." * 9999 + "@\n")
    assert convert(path, tmp_path / "wide.lp") == 0
    assert main(["info", str(tmp_path / "wide.lp")]) == 0


def test_hostile_movingai_facts_leave_the_defaults(tmp_path, capsys):
    (tmp_path / "h.lp").write_text(
        "init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,2))).\n"
        'movingai(type,"a b\\nc"). movingai(size,(a,b)). movingai(map,5). movingai(blocked,"").\n'
        'movingai(blocked,(1,2),"\\n"). movingai(blocked,(2,1),"G"). movingai(passable,(2,2),"@").\n'
        'movingai(passable,(1,1),"S",x). movingai(blocked,f(1),"W"). movingai. movingai(1,2).\n')
    assert convert(tmp_path / "h.lp", tmp_path / "h.map") == 0
    assert (tmp_path / "h.map").read_text() == "type octile\nheight 2\nwidth 2\nmap\n.@\n@.\n"
    assert "Traceback" not in capsys.readouterr().err


def test_a_map_size_fact_beyond_the_limits_is_refused(tmp_path, capsys):
    (tmp_path / "s.lp").write_text("init(object(node,1),value(at,(1,1))). movingai(size,(20000,1)).\n")
    assert convert(tmp_path / "s.lp", tmp_path / "s.map") == 2
    assert capsys.readouterr().err.endswith("a map 20,000 cells wide and 1 high, beyond the limit "
                                            "coordinate=10,000 (raise it with --limit coordinate=N)\n")
    assert not (tmp_path / "s.map").exists()


def test_unknown_attributes_keep_every_leaf(tmp_path, capsys):
    attributes = ['value(energy,high)', 'value(label,"r 1")', "value(spec,f(1,(a,2)))", "value(top,#sup)",
                  "value(sign,-a)", "value(pair,(b,-(1,2)))"]
    (tmp_path / "robot.lp").write_text(
        "init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))).\n"
        "init(object(robot,1),value(at,(1,1))).\n" + "".join(f"init(object(robot,1),{a}).\n" for a in attributes))
    assert convert(tmp_path / "robot.lp", tmp_path / "out.lp", "--to", "md") == 0
    assert capsys.readouterr().err == (f"warning: {tmp_path / 'robot.lp'}:3: ignored (and kept when written): "
                                       + ", ".join(f"attribute '{name}' of robot"
                                                   for name in ("energy", "label", "spec", "top", "sign", "pair"))
                                       + "\n")
    written = (tmp_path / "out.lp").read_text()
    for attribute in attributes:
        assert f"init(object(robot,1),{attribute}).\n" in written
    assert "#inf" not in written


def test_a_scenario_of_more_rows_than_facts_is_refused_as_it_is_read(tmp_path, capsys):
    (tmp_path / "m.map").write_text("type octile\nheight 1\nwidth 4\nmap\n....\n")
    rows = "".join(f"0\tm.map\t4\t1\t{x}\t0\t{3 - x}\t0\t3\n" for x in range(4))
    (tmp_path / "m.scen").write_text("version 1\n" + rows + "not a row\n")  # line 6: never reached
    assert main(["convert", str(tmp_path / "m.scen"), str(tmp_path / "m.lp"), "--limit", "facts=3"]) == 2
    assert capsys.readouterr().err == (f"error: {tmp_path / 'm.scen'}:5: a scenario of more than 3 rows, beyond "
                                       "the limit facts=3 (raise it with --limit facts=N)\n")
