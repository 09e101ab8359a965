"""The ladders of ``asprilo grade`` (asprilo/encodings/ladders/): their stored minima derived again,
independently of the grader.

- every minimum by the method that established it: max-flow for M/Md (exact), the
  reference encoding's proven minimum for A/B/C;
- the tiny ones (those the manifest says were cross-checked so) by breadth-first search over
  joint states (tests/oracles/: brute_force.py for A/B/C, mapf_brute_force.py for M/Md),
  which shares no code with the encodings, the max-flow solver or the checker;
- every instance file is what its header says: made again by the command it records (gen,
  convert), or equal to the example it was copied from.
"""

from __future__ import annotations

import importlib.resources
import re
import shlex

import pytest
from helpers import EXAMPLES
from oracles import brute_force, mapf_brute_force

from asprilo.cli import main
from asprilo.domain import Domain
from asprilo.encodings import solve
from asprilo.encodings.ladder import MANIFEST, bundled_domains, bundled_ladder
from asprilo.reader import read_instance

DOMAINS = [Domain.A, Domain.B, Domain.C, Domain.M, Domain.MD]
RUNGS = [(domain, rung) for domain in DOMAINS for rung in bundled_ladder(domain).rungs]
TINY = [(domain, rung) for domain, rung in RUNGS if any("breadth-first" in check for check in rung.cross_checked)]
#: how a ladder instance made by gen for B or C says its quantity-free facts were rewritten
UNIT_QUANTITIES = ("every quantity-free value(on,S) and value(line,P) written with quantity 1: "
                   "value(on,(S,1)), value(line,(P,1))")


def _id(item) -> str:
    domain, rung = item
    return f"{domain.value}-{rung.name}"


def test_every_domain_has_a_ladder_from_tiny_to_exercise_size():
    assert bundled_domains() == sorted(domain.value for domain in DOMAINS)
    for domain in DOMAINS:
        ladder = bundled_ladder(domain)
        assert 6 <= len(ladder.rungs) <= 10 and ladder.domain is domain
        instances = [read_instance(rung.file) for rung in ladder.rungs]
        assert len(instances[0].robots) == 1 and len(instances[0].cells) <= 9
        last = instances[-1]
        assert last.size == (11, 6) and 3 <= len(last.robots) <= 5
        assert all(rung.established and rung.cross_checked for rung in ladder.rungs)
        assert [rung.name[:2] for rung in ladder.rungs] == [f"{n:02d}" for n in range(1, len(ladder.rungs) + 1)]


def test_the_ladders_are_package_data():
    ladders = importlib.resources.files("asprilo.encodings") / "ladders"
    for domain in DOMAINS:
        manifest = ladders / domain.value / MANIFEST
        assert manifest.is_file()
        assert all((ladders / domain.value / rung.file.name).is_file() for rung in bundled_ladder(domain).rungs)


@pytest.mark.parametrize("item", RUNGS, ids=_id)
def test_the_stored_minimum_is_the_one_its_method_establishes(item):
    domain, rung = item
    method = "flow" if domain in (Domain.M, Domain.MD) else "asp"
    assert rung.established.startswith("max-flow" if method == "flow" else "the reference encoding plain")
    outcome = solve(read_instance(rung.file), domain, method=method, time_limit=120)
    assert outcome.found and outcome.minimal and outcome.horizon == rung.minimum


@pytest.mark.parametrize("item", TINY, ids=_id)
def test_the_tiny_minima_by_breadth_first_search(item):
    domain, rung = item
    oracle = mapf_brute_force if domain in (Domain.M, Domain.MD) else brute_force
    assert oracle.minimal_makespan(read_instance(rung.file), domain.value) == rung.minimum


def test_the_breadth_first_search_covers_the_small_instances_of_every_ladder():
    for domain in DOMAINS:
        tiny = [rung for d, rung in TINY if d is domain]
        assert len(tiny) >= 5 and tiny == list(bundled_ladder(domain).rungs[:len(tiny)])


def test_some_minima_exceed_the_lower_bound():
    """Instances where robots and shelves get in each other's way: the minimum exceeds the
    lower bound the search starts from, and the search over joint states confirms it."""
    for domain, step in ((Domain.M, 5), (Domain.MD, 5), (Domain.A, 1), (Domain.B, 1), (Domain.C, 1)):
        rung = bundled_ladder(domain).rungs[step]
        outcome = solve(read_instance(rung.file), domain, horizon=rung.minimum)
        assert outcome.lower_bound < rung.minimum and (domain, rung) in TINY


def _origin(rung) -> str:
    """The second header line: where the instance comes from."""
    return rung.file.read_text().splitlines()[1]


def _body(text: str) -> str:
    return "\n".join(text.splitlines()[2:]) + "\n"


@pytest.mark.parametrize("item", RUNGS, ids=_id)
def test_every_instance_is_what_its_header_says(item, tmp_path, capsys):
    _domain, rung = item
    origin = _origin(rung)
    if origin.startswith("% copied from "):
        assert _body(rung.file.read_text()) == (EXAMPLES.parent / origin.removeprefix("% copied from ")).read_text()
        return
    words = shlex.split(origin.removeprefix("% made with: ").split(">")[0].split("(")[0])
    if words[:2] == ["asprilo", "gen"]:
        assert main(words[1:]) == 0
        made = capsys.readouterr().out
        if origin.endswith(f", then {UNIT_QUANTITIES}"):
            made = re.sub(r"value\((on|line),(\d+)\)\)", r"value(\1,(\2,1)))", made)
        assert _body(rung.file.read_text()) == made
        return
    assert words[:2] == ["asprilo", "convert"]
    source, target = rung.file.parent / words[2], tmp_path / words[3]
    assert main([*words[1:2], str(source), str(target), *words[4:]]) == 0
    assert _body(rung.file.read_text()) == target.read_text()


#: the one instance format of every ladder (docs/GRADING.md): stock and order lines as pairs
#: with a quantity in every domain (B and C ignore it; M asks one unit), as the public
#: encodings' input.lp reads them; Md states destinations instead of order lines
PAIR = r"\(\d+,\d+\)"
LADDER_FORMAT = {
    Domain.A: {"on": PAIR, "line": PAIR},
    Domain.B: {"on": PAIR, "line": PAIR},
    Domain.C: {"on": PAIR, "line": PAIR},
    Domain.M: {"on": r"\(\d+,1\)", "line": r"\(\d+,1\)"},
    Domain.MD: {"on": r"\(\d+,1\)", "destination": r"\(\d+,\d+\)"},
}


@pytest.mark.parametrize("item", RUNGS, ids=_id)
def test_every_ladder_instance_uses_only_its_domains_format(item):
    domain, rung = item
    formats = LADDER_FORMAT[domain]
    stated = re.findall(r"^init\(object\((\w+),\d+\),value\((\w+),(.*)\)\)\.$", rung.file.read_text(), re.M)
    quantified = [(kind, attribute, value) for kind, attribute, value in stated
                  if attribute in ("on", "line") or kind == "destination"]
    assert quantified, rung.file
    for kind, attribute, value in quantified:
        key = "destination" if kind == "destination" else attribute
        assert key in formats and re.fullmatch(formats[key], value), (rung.file.name, kind, attribute, value)
