"""Generator layouts: the paper's structured warehouses, -H in general, random floors, -R, templates.
"""

from __future__ import annotations

import re
from collections import Counter

import pytest
from helpers import EXAMPLES
from helpers.generated import FIGURE_1, PAPER, cells_of, check_instance, one, reachable

from asprilo.errors import InputError
from asprilo.generator import GeneratorConfig, populate
from asprilo.model import Instance
from asprilo.reader import read_instance

# --- the paper's benchmark layouts --------------------------------------------------------

@pytest.mark.parametrize("size,robots", [(size, r) for size, (_, rs) in PAPER.items() for r in rs])
def test_paper_calls_reproduce_the_paper_layouts(size, robots):
    options, _ = PAPER[size]
    instance = one({**options, "-H": True, "--prs": 1, "-r": robots, "-o": robots})
    paper, = (EXAMPLES / "paper-m" / size).glob(f"*_r{robots}_*.lp")
    original = read_instance(paper)
    assert instance.nodes == original.nodes
    assert instance.highways == original.highways  # same cells, same ids
    for kind in ("stations", "robots", "shelves"):
        assert cells_of(getattr(instance, kind)) == cells_of(getattr(original, kind)), kind
    assert instance.file_name(1) == paper.name
    check_instance(instance, reach=True)
    # the M alignment that --prs 1 with -P = -u = -s implies: one unit of one product per
    # shelf, as many single-unit single-line orders as robots, on distinct products
    assert sorted(len(p.stock) for p in instance.products.values()) == [1] * len(instance.shelves)
    assert {u for p in instance.products.values() for u in p.stock.values()} == {1}
    assert sorted(len(s) for s in instance.shelf_stock().values()) == [1] * len(instance.shelves)
    lines = [line for order in instance.orders.values() for line in order.lines.items()]
    assert len(instance.orders) == robots and len(lines) == robots
    assert {units for _, units in lines} == {1} and len({p for p, _ in lines}) == robots


def test_figure_1_call_matches_the_paper_instance_layout():
    instance = one(FIGURE_1)
    original = read_instance(EXAMPLES / "asprilo/dom-a/medium/x19_y9_n171_r6_s45_ps3_pr180_u540_o12_N1.lp")
    assert instance.nodes == original.nodes and instance.highways == original.highways
    for kind in ("stations", "robots"):
        assert cells_of(getattr(instance, kind)) == cells_of(getattr(original, kind))
    zones = set(instance.nodes.values()) - set(instance.highways.values()) \
        - cells_of(instance.stations) - cells_of(instance.robots)
    assert len(zones) == 60 and cells_of(instance.shelves) <= zones
    assert instance.file_name(1) == "x19_y9_n171_r6_s45_ps3_pr180_u540_o12_N001.lp"
    check_instance(instance)
    assert all(1 <= len(p.stock) <= 4 for p in instance.products.values())           # --spr 1..4
    assert all(1 <= u <= 10 for p in instance.products.values() for u in p.stock.values())  # --pus 1..10
    assert all(len(products) <= 20 for products in instance.shelf_stock().values())   # --prsmax 20
    assert all(len(order.lines) == 1 for order in instance.orders.values())            # --ol 1


# --- the structured layout in general -------------------------------------------------------

def test_structured_layout_zones_stations_and_robots():
    instance = one({"-x": 20, "-y": 14, "-X": 3, "-Y": 3, "-B": 2, "-H": True, "-p": 4, "-r": 7, "--sc": 100})
    width, height = 20, 14
    highways = set(instance.highways.values())
    zone_cells = cells_of(instance.shelves)  # --sc 100: every zone cell holds a shelf
    # zones: columns 3-5, 7-9, 11-13, 15-17 (border 2 left, right needs 2); rows 4-6, 8-10
    # (station row, border rows 2-3; then border rows and the robot row at the bottom)
    columns = [range(3, 6), range(7, 10), range(11, 14), range(15, 18)]
    rows = [range(4, 7), range(8, 11)]
    assert zone_cells == {(x, y) for cs in columns for x in cs for rs in rows for y in rs}
    for x, y in zone_cells:  # every zone is surrounded by highways
        for step in ((x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)):
            assert step in zone_cells or step in highways
    # picking stations spread evenly over the top row: every round(20/5) = 4th cell
    assert sorted(cells_of(instance.stations)) == [(4, 1), (8, 1), (12, 1), (16, 1)]
    # robots fill the bottom row from the left; every other node is a highway
    assert cells_of(instance.robots) == {(x, height) for x in range(1, 8)}
    assert highways == set(instance.cells) - zone_cells - cells_of(instance.stations) - cells_of(instance.robots)
    assert len(instance.nodes) == width * height
    check_instance(instance)  # (zones three rows deep and full: the middle row is not reachable)


def test_structured_robots_beyond_the_bottom_row_fill_the_rows_above():
    instance = one({"-x": 8, "-y": 10, "-X": 2, "-Y": 2, "-H": True, "-r": 11})
    assert cells_of(instance.robots) == {(x, 10) for x in range(1, 9)} | {(1, 9), (2, 9), (3, 9)}


#: robots with no room below the zones: the options the error names, and the room each gives,
#: derived by hand from structured.lp (zone rows start at row 3, every -Y + 1 rows, and end
#: above the bottom border row; the robots stand below that border row)
ROOM_ADVICE = [
    # 11 robots fit in row 6; with -y 7 the zone row stays 3-4, the border row 5: rows 6-7, 22
    ("-x 11 -y 6 -X 4 -r 12", "-H: -r 12 robots do not fit below the storage zones (room for 11); "
                              "-y 7 gives room for 22"),
    # 4 rows of 11 needed, but below zones 2 rows high lie at most 3 (-y 8: zones 3-4, border 5,
    # robots 6-8; -y 9 makes room for zones 6-7): 3 rows of 14 = 42; zones 3 rows high (3-5,
    # border 6) leave rows 7-10 with -y 10: 4 rows of 11 = 44
    ("-x 11 -y 6 -X 4 -r 40", "-H: -r 40 robots do not fit below the storage zones (room for 11); below zones "
                              "of -Y 2 lie at most 3 rows of 11 robots, whatever -y; -x 14 -y 8 gives room for "
                              "42, -Y 3 -y 10 for 44"),
    # the call: 200 x 200 leaves 3 rows of 200 at best; 1000 / 3 rounded up is 334; zones
    # 4 high on -y 202: 39 zone rows end at row 196, border 197, robots in rows 198-202
    ("-x 200 -y 200 -X 5 -Y 2 -r 1000", "-H: -r 1000 robots do not fit below the storage zones (room for 600); "
                                        "below zones of -Y 2 lie at most 3 rows of 200 robots, whatever -y; "
                                        "-x 334 gives room for 1002, -Y 4 -y 202 for 1000"),
]


@pytest.mark.parametrize("call,message", ROOM_ADVICE)
def test_robots_without_room_are_told_options_that_give_it(call, message):
    options = {**_options(call), "-H": True}
    with pytest.raises(InputError) as refused:
        one(options)
    assert str(refused.value) == message


@pytest.mark.parametrize("call,message", ROOM_ADVICE[:2])
def test_the_options_advised_give_the_robots_room(call, message):
    """Generated with each option the error names: every robot stands below the zones (full
    of shelves), beyond the border row."""
    advice = re.findall(r"((?:-[xyY] \d+ ?)+) (?:gives room )?for \d+", message.split("; ", 1)[1])
    assert advice
    for changed in advice:
        options = {**_options(call), **_options(changed), "-H": True, "--sc": 100}
        instance = one(options)
        robots = cells_of(instance.robots)
        assert len(robots) == options["-r"]
        assert min(y for _, y in robots) > max(y for _, y in cells_of(instance.shelves)) + 1
        check_instance(instance)


def _options(call: str) -> dict[str, int]:
    words = call.split()
    return {flag: int(value) for flag, value in zip(words[::2], words[1::2], strict=True)}


def test_stations_that_do_not_fit_a_rounded_step_are_packed_closer():
    instance = one({"-x": 89, "-y": 8, "-X": 10, "-Y": 2, "-H": True, "-p": 23})
    assert sorted(cells_of(instance.stations)) == [(3 * k, 1) for k in range(1, 24)]


# --- random layouts -----------------------------------------------------------------------

def gaps(instance: Instance, width: int, height: int) -> list[int]:
    """The sizes of the groups of connected missing cells."""
    missing = {(x, y) for x in range(1, width + 1) for y in range(1, height + 1)} - instance.cells
    sizes = []
    while missing:
        group = reachable(missing, next(iter(missing)))
        sizes.append(len(group))
        missing -= group
    return sizes


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_random_floor_keeps_the_node_count_small_gaps_and_connectivity(seed):
    instance = one({"-x": 12, "-y": 10, "-n": 96, "--gs": 3, "-p": 3, "-r": 4, "-s": 25, "-P": 10,
                    "-u": 40, "-o": 5}, seed)
    assert len(instance.nodes) == 96 and not instance.highways
    sizes = gaps(instance, 12, 10)
    assert sum(sizes) == 24 and max(sizes) <= 3
    cells = instance.cells
    assert reachable(cells, next(iter(cells))) == cells
    check_instance(instance)


def test_random_layout_spreads_objects_over_the_floor():
    instance = one({"-x": 30, "-y": 30, "-s": 200, "-r": 40, "-p": 20})
    for objects in (instance.shelves, instance.robots, instance.stations):
        at = cells_of(objects)
        quarters = Counter((x > 15, y > 15) for x, y in at)
        assert len(quarters) == 4 and max(quarters.values()) <= 0.4 * len(at), quarters
        assert abs(sum(x for x, _ in at) / len(at) - 15.5) < 3


def test_reachable_shelves():
    options = {"-x": 9, "-y": 7, "-p": 2, "-r": 2, "-s": 30, "-R": True}
    for seed in (1, 2):
        check_instance(one(options, seed), reach=True)
    # without -R the same request leaves some shelf enclosed by others
    assert any(not _all_reachable(one({**options, "-R": False}, seed)) for seed in range(1, 6))


def _all_reachable(instance: Instance) -> bool:
    shelves = cells_of(instance.shelves)
    return all(cells_of(instance.stations) <= reachable(instance.cells, s, shelves - {s}) for s in shelves)


# --- templates ----------------------------------------------------------------------------

def template() -> Instance:
    """8 x 6 with a 2 x 2 pillar, a highway column, a station, a robot and a shelf."""
    pillar = {(4, 3), (5, 3), (4, 4), (5, 4)}
    layout = Instance()
    cells = [(x, y) for y in range(1, 7) for x in range(1, 9) if (x, y) not in pillar]
    layout.nodes = {i: cell for i, cell in enumerate(cells, 1)}
    layout.highways = {i: (1, y) for i, y in enumerate(range(1, 7), 1)}
    from asprilo.model import PickingStation, Robot, Shelf
    layout.stations = {7: PickingStation(7, (8, 1))}
    layout.robots = {3: Robot(3, (1, 6))}
    layout.shelves = {2: Shelf(2, (2, 2))}
    return layout


def test_template_is_populated_around_its_fixed_objects():
    layout = template()
    generated = populate(layout, GeneratorConfig(stations=2, robots=3, shelves=12, products=5, units=20,
                                                 orders=3), seed=4)
    instance = generated.instance
    assert instance.nodes == layout.nodes and instance.highways == layout.highways
    assert instance.stations[7].at == (8, 1) and instance.robots[3].at == (1, 6)
    assert instance.shelves[2].at == (2, 2)
    assert sorted(instance.stations) == [7, 8] and sorted(instance.robots) == [3, 4, 5]
    assert sorted(instance.shelves) == list(range(2, 14))
    assert instance.counts()["products"] == 5 and instance.units == 20 and len(instance.orders) == 3
    assert not cells_of(instance.shelves) & set(layout.highways.values())
    check_instance(instance)
    assert layout.robots.keys() == {3}  # the caller's layout is left as it was


def test_template_objects_count_towards_the_totals(write):
    layout = template()
    instance = populate(layout, robots=1, shelves=1).instance
    assert instance.robots.keys() == {3} and instance.shelves.keys() == {2}


def test_a_quantity_free_template_gets_quantity_free_additions():
    from asprilo.model import Product
    layout = template()
    layout.products = {1: Product(1, {2: None})}
    instance = populate(layout, shelves=4, products=3, units=None, stations=1, orders=2).instance
    assert instance.products[1].stock == {2: None}
    assert all(u is None for p in instance.products.values() for u in p.stock.values())
    assert all(u is None for o in instance.orders.values() for u in o.lines.values())
    check_instance(instance)
