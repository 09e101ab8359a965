"""Shared test fixtures: where the example data lives, and small instance texts."""

from __future__ import annotations

from pathlib import Path

import pytest

try:  # the tools are mapped into the package by the install; a plain checkout has only the core
    import asprilo.generator  # noqa: F401
except ImportError:  # pragma: no cover - a setup problem, not a test
    pytest.exit("asprilo's tools are not importable: install the checkout for development first "
                "(pip install -e \".[test]\"); a non-editable install is shadowed by the checkout's "
                "asprilo/ folder when tests run from the repository root", returncode=4)

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
SMALL_A = EXAMPLES / "asprilo/dom-a/small/x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp"
OUTCOME = EXAMPLES / "asprilo/dom-a/small/outcome.txt"
WRONG_OUTCOME = EXAMPLES / "asprilo/dom-a/small/wrong_outcome.txt"


@pytest.fixture
def write(tmp_path):
    """write(name, text) -> path of a new file in a temporary directory."""

    def make(name: str, text: str) -> Path:
        path = tmp_path / name
        path.write_text(text)
        return path

    return make
