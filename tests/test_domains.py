"""Domains are data: every descriptor is complete, and no tool tests a domain's name."""

from __future__ import annotations

import ast
import dataclasses
import re

import pytest
from helpers import ROOT

from asprilo.domain import Bound, Delivery, Domain, Goal, Job, domains
from asprilo.generator import GeneratorConfig
from asprilo.objects import KINDS

BUILTIN = ["a", "b", "c", "m", "md"]
#: the actions the simulator and the checker know
ACTIONS = {"move", "pickup", "putdown", "deliver"}
#: the folders of the tools (the descriptors themselves live in asprilo/domain/)
TOOLS = ["asprilo", "checker", "generator", "encodings", "visualizer", "online", "interop", "cli", "benchmarks"]


def test_the_builtin_domains_are_registered_in_order():
    assert [domain.value for domain in domains()] == BUILTIN
    assert [domain.label for domain in domains()] == ["A", "B", "C", "M", "Md"]
    assert list(domains()) == [Domain.A, Domain.B, Domain.C, Domain.M, Domain.MD]


@pytest.mark.parametrize("name", BUILTIN)
def test_a_descriptor_is_complete(name):
    domain = Domain.parse(name)
    assert domain.summary and domain.label
    assert domain.actions and domain.actions <= ACTIONS and "move" in domain.actions
    assert ("deliver" in domain.actions) == (domain.delivery is not None) == (domain.goal is Goal.LINES)
    assert isinstance(domain.goal, Goal) and isinstance(domain.bound, Bound) and isinstance(domain.work, Job)
    assert domain.delivery is None or isinstance(domain.delivery, Delivery)
    assert domain.reads and domain.reads <= set(KINDS)
    assert domain.checker[-1] == "goal" and len(set(domain.checker)) == len(domain.checker)
    for concern in domain.checker:
        assert (ROOT / "asprilo" / "checker" / f"{concern}.lp").is_file(), concern
    assert domain.encodings and domain.encodings[0].name == "plain"
    for encoding in domain.encodings:
        assert (ROOT / "asprilo" / "encodings" / encoding.program).is_file(), encoding.program
        assert encoding.names is None or (ROOT / "asprilo" / "encodings" / encoding.names).is_file()
        assert encoding.theory in (None, "clingcon", "dl")
    if domain.generation is None:
        assert domain.made_by
    else:
        options = {field.name for field in dataclasses.fields(GeneratorConfig)}
        assert set(domain.generation.exercise) <= options


@pytest.mark.parametrize("name", BUILTIN)
def test_the_plain_clingo_checker_file_includes_exactly_the_descriptors_concerns(name):
    text = (ROOT / "asprilo" / "checker" / "domains" / f"{name}.lp").read_text()
    included = re.findall(r'#include "\.\./(\w+)\.lp"\.', text)
    assert tuple(included) == Domain.parse(name).checker


def test_a_descriptor_survives_pickling_as_the_registered_one():
    import pickle
    for domain in domains():
        assert pickle.loads(pickle.dumps(domain)) is domain


def _branches(path, root=ROOT):
    """Places in a module that name a built-in domain: ``Domain.A`` ... or a comparison of
    something called domain with a domain's name."""
    tree = ast.parse(path.read_text(), str(path))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "Domain" \
                and node.attr in {"A", "B", "C", "M", "MD"}:
            found.append(f"{path.relative_to(root)}:{node.lineno}: Domain.{node.attr}")
        if isinstance(node, ast.Compare):
            sides = [node.left, *node.comparators]
            names = [s.value for s in sides if isinstance(s, ast.Constant) and s.value in BUILTIN]
            if names and any("domain" in ast.unparse(s).lower() for s in sides):
                found.append(f"{path.relative_to(root)}:{node.lineno}: {ast.unparse(node)}")
    return sorted(found, key=lambda place: int(place.split(":")[1]))


def test_no_tool_branches_on_a_domains_name():
    modules = [path for folder in TOOLS for path in (ROOT / folder).rglob("*.py")
               if "domain" not in path.relative_to(ROOT).parts[:2]]
    assert len(modules) > 100
    assert [place for path in modules for place in _branches(path)] == []


def test_the_branch_finder_finds_branches(tmp_path):
    sample = tmp_path / "sample.py"
    sample.write_text("if domain is Domain.A:\n    pass\nif spec.domain.value == 'md':\n    pass\n")
    assert _branches(sample, tmp_path) == ["sample.py:1: Domain.A", "sample.py:3: spec.domain.value == 'md'"]
