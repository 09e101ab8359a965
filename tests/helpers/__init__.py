"""Shared test helpers: where the example data lives; tiny worlds (:mod:`.worlds`), the
generator's guarantees (:mod:`.generated`) and the online link's small world (:mod:`.online`)."""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent
EXAMPLES = ROOT / "examples"
SMALL_A = EXAMPLES / "asprilo/dom-a/small/x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp"
OUTCOME = EXAMPLES / "asprilo/dom-a/small/outcome.txt"
WRONG_OUTCOME = EXAMPLES / "asprilo/dom-a/small/wrong_outcome.txt"

#: a corridor P S S R: the robot can never bring shelf 2 past shelf 1 (it can only carry
#: shelf 1 onto the station, where no shelf may be put down), so every horizon is refuted
#: and a search without an end climbs until its time limit (detected as domain A: the line
#: asks for 2 of the 3 units on shelf 2)
CORRIDOR = """
init(object(grid,1),value(xsize,4)). init(object(grid,1),value(ysize,1)).
init(object(pickingStation,1),value(at,(1,1))). init(object(robot,1),value(at,(4,1))).
init(object(shelf,1),value(at,(2,1))). init(object(shelf,2),value(at,(3,1))).
init(object(product,1),value(on,(2,3))).
init(object(order,1),value(line,(1,2))). init(object(order,1),value(pickingStation,1)).
"""
