"""The import-linter contracts cover what they should: the core's contract names every module of
the core folder, the visualizer's Qt-free contract names the folder ``asprilo/visualizer/state/``, its
layers name every room; and the checkout's root hides no module."""

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
    tools = {module for module in contract["forbidden_modules"] if module.startswith("asprilo.")}
    assert core - tools == listed


VIZ = ROOT / "asprilo" / "visualizer"


def _config() -> dict:
    return tomllib.loads((ROOT / "pyproject.toml").read_text())


def _contract(name_start: str) -> dict:
    contracts = _config()["tool"]["importlinter"]["contracts"]
    return next(c for c in contracts if c["name"].startswith(name_start))


def _rooms() -> set[str]:
    """The visualizer's subpackages: every folder under ``asprilo/visualizer/`` with an ``__init__.py``."""
    return {".".join(init.parent.relative_to(VIZ).parts) for init in VIZ.rglob("__init__.py") if init.parent != VIZ}


def test_every_module_of_the_visualizer_state_folder_is_under_the_qt_free_contract():
    contract = _contract("the visualizer's state")
    assert contract["source_modules"] == ["asprilo.visualizer.state"]  # the folder, so new modules are covered
    assert contract["forbidden_modules"] == ["PyQt5"] and contract["allow_indirect_imports"] is False
    modules = [".".join(("asprilo.visualizer", *path.relative_to(VIZ).with_suffix("").parts))
               for path in (VIZ / "state").rglob("*.py")]
    assert len(modules) > 10
    assert all(m.startswith("asprilo.visualizer.state.") for m in modules)


def test_the_visualizer_layers_name_every_room_and_top_module():
    contract = _contract("the visualizer's rooms are layered")
    assert contract["containers"] == ["asprilo.visualizer"] and contract["exhaustive"] is True
    named = {part.strip() for layer in contract["layers"] for part in layer.split("|")}
    top = {path.stem for path in VIZ.glob("*.py") if path.stem != "__init__"}
    assert named == {room for room in _rooms() if "." not in room} | top


def test_the_checkout_root_shadows_no_module():
    """The file tree is the import tree: a fresh interpreter started in the checkout's root (which
    Python puts first on ``sys.path``) finds the whole package ``asprilo`` there, every tool in it,
    and no folder or module that hides one of the standard library's."""
    import sys

    importable = {path.stem for path in ROOT.glob("*.py")}
    importable |= {path.name for path in ROOT.iterdir() if path.is_dir() and (path / "__init__.py").is_file()}
    assert importable == {"asprilo"}
    assert not {path.name for path in ROOT.iterdir() if path.is_dir()} & set(sys.stdlib_module_names)
    assert all((ROOT / "asprilo" / tool / "__init__.py").is_file() for tool in ("cli", "bench", "encodings"))
