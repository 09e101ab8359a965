"""Shared test helpers: where the example data lives; tiny worlds (:mod:`.worlds`), the
generator's guarantees (:mod:`.generated`) and the online link's small world (:mod:`.online`)."""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent
EXAMPLES = ROOT / "examples"
SMALL_A = EXAMPLES / "asprilo/dom-a/small/x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp"
OUTCOME = EXAMPLES / "asprilo/dom-a/small/outcome.txt"
WRONG_OUTCOME = EXAMPLES / "asprilo/dom-a/small/wrong_outcome.txt"
