"""The generator's Python API, its modes (staged, split, one-shot) and the inventory ranges."""

from __future__ import annotations

from collections import Counter

import pytest
from helpers import ROOT
from helpers.generated import FIGURE_1, check_instance, one

from asprilo.errors import InputError
from asprilo.generator import GenerationFailed, GeneratorConfig, RunOptions, generate, make_plan


def test_generate_returns_instances_and_headers_and_prints_nothing(capsys):
    config = GeneratorConfig.from_options({"-x": 8, "-y": 8, "-p": 2, "-r": 3, "-s": 10, "-P": 5, "-u": 20, "-o": 4})
    items = generate(config, count=2, seed=11)
    assert [item.number for item in items] == [1, 2] and {item.seed for item in items} == {11}
    assert items[0].header[:4] == ["asprilo gen 0.1.0",
                                   "command: gen -x 8 -y 8 -p 2 -r 3 -s 10 -P 5 -u 20 -o 4 -N 2 --seed 11",
                                   "seed: 11", "instance: 1"]
    assert items[1].file_name("p-") == "p-x8_y8_n64_r3_s10_ps2_pr5_u20_o4_N002.lp"
    assert capsys.readouterr() == ("", "")


def test_config_from_options_and_its_command_line():
    config = GeneratorConfig.from_options({"-x": 11, "--grid-y": 6, "--prs": 1, "structured": True})
    assert (config.width, config.height, config.prs_min, config.prs_max, config.structured) == (11, 6, 1, 1, True)
    assert config.command_line(RunOptions(count=3, seed=5)) == "gen -x 11 -y 6 -H --prs 1 -N 3 --seed 5"
    with pytest.raises(InputError, match=r"-N: not a generator setting \(a run option\)"):
        GeneratorConfig.from_options({"-N": 3})
    with pytest.raises(InputError, match="-x needs an integer, got '11'"):
        GeneratorConfig.from_options({"-x": "11"})


def test_inconsistent_options_raise_input_error_and_unsat_raises_generation_failed():
    with pytest.raises(InputError, match="give either -s or --sc, not both"):
        generate(GeneratorConfig(width=5, height=5, shelves=3, shelf_coverage=50))
    with pytest.raises(GenerationFailed) as failure:
        generate(GeneratorConfig(width=5, height=5, shelves=20, stations=1, robots=1, reachable=True))
    assert (failure.value.stage, failure.value.timed_out) == ("shelves", False)
    assert str(failure.value) == "the request is unsatisfiable (stage shelves)"


def test_split_threshold_places_objects_in_rounds():
    item = generate(GeneratorConfig.from_options({**FIGURE_1, "--split-threshold": 10}), seed=3)[0]
    rounds = {stage: rounds for stage, (rounds, _) in item.stages.items()}
    assert rounds == {"stations": 1, "robots": 1, "shelves": 5, "stock": 18, "units": 1, "lines": 2,
                      "quantities": 1}
    counts = item.instance.counts()
    assert (counts["shelves"], counts["products"], counts["units"], counts["orders"]) == (45, 180, 540, 12)
    check_instance(item.instance)
    assert make_plan(GeneratorConfig(width=5, height=5, incremental=True)).split == 100


def test_one_shot_mode_solves_everything_at_once():
    options = {"-x": 11, "-y": 6, "-X": 4, "-Y": 2, "-H": True, "-p": 1, "-s": 12, "-r": 3, "-P": 20,
               "-u": 50, "-o": 4, "--olmax": 2}
    item = generate(GeneratorConfig.from_options({**options, "--one-shot": True}), seed=2)[0]
    counts = item.instance.counts()
    assert (counts["shelves"], counts["products"], counts["units"], counts["orders"]) == (12, 20, 50, 4)
    check_instance(item.instance)


def test_shelf_coverage_counts_the_shelf_sites():
    # random layout: 100 nodes - 2 stations - 3 robots = 95 sites; 40 % of them
    assert len(one({"-x": 10, "-y": 10, "-p": 2, "-r": 3, "--sc": 40}).shelves) == 38
    # structured: the zones (2 x 2 zones of 4 x 2 cells in 11 x 9)
    assert len(one({"-x": 11, "-y": 9, "-X": 4, "-Y": 2, "-H": True, "--sc": 50}).shelves) == 16


def test_inventory_ranges_are_kept():
    instance = one({"-x": 10, "-y": 10, "-s": 12, "-P": 12, "--prs": 2, "--spr": 2, "--pus": 3, "-u": 72,
                    "-p": 2, "-o": 6, "--ol": 2, "--oap": True})
    stock = instance.shelf_stock()
    assert sorted(len(products) for products in stock.values()) == [2] * 12
    assert sorted(len(p.stock) for p in instance.products.values()) == [2] * 12
    assert {units for p in instance.products.values() for units in p.stock.values()} == {3}
    assert [len(o.lines) for o in instance.orders.values()] == [2] * 6
    assert {p for o in instance.orders.values() for p in o.lines} == set(instance.products)  # --oap
    check_instance(instance)


def test_domain_m_alignment():
    instance = one({"-x": 11, "-y": 6, "-X": 4, "-Y": 2, "-H": True, "-p": 1, "-s": 16, "-r": 5, "--domain": "m"})
    counts = instance.counts()
    assert (counts["products"], counts["units"], counts["orders"]) == (16, 16, 5)
    assert Counter(len(p.stock) for p in instance.products.values()) == {1: 16}
    assert all(list(o.lines.values()) == [1] for o in instance.orders.values())
    from asprilo.domain import Domain, detect_domain
    assert detect_domain(instance) is Domain.M


def test_logic_programs_are_documented():
    for program in sorted((ROOT / "asprilo" / "generator").glob("*.lp")):
        text = program.read_text()
        assert text.startswith("% "), program.name
        assert "#program" in text, program.name
