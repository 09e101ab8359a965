"""The import-linter contract of the core names every module of the core folder."""

from __future__ import annotations

import pytest
from helpers import ROOT

tomllib = pytest.importorskip("tomllib")  # Python 3.11 and later


def test_every_core_module_is_under_the_core_contract():
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())
    contract = next(c for c in config["tool"]["importlinter"]["contracts"] if c["name"] == "the core imports no tool")
    listed = set(contract["source_modules"])
    core = {f"asprilo.{path.stem}" for path in (ROOT / "asprilo").glob("*.py") if path.stem != "__init__"}
    core |= {f"asprilo.{path.name}" for path in (ROOT / "asprilo").iterdir() if (path / "__init__.py").is_file()}
    assert core == listed
