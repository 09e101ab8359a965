"""The grader's probes (asprilo/encodings/probes.py): illegal plans a correct encoding must
refuse, whatever clingo's configuration and seed.

Every probe's plan was derived by hand (the comments of the files in the ladders' probes/
folders); here the checker must report exactly the violations of that derivation
(:data:`BREAKS`), every reference encoding must refuse the plan while a legal plan exists
at the probe's horizon, and an encoding without the rule must accept it: a student's
encoding minus one rule (tests/students/) or a copy of a reference encoding with the rule's
line deleted.
"""

from __future__ import annotations

import json
import shutil
from dataclasses import replace
from pathlib import Path

import pytest
from helpers import ROOT

from asprilo.cli import main
from asprilo.domain import Domain
from asprilo.encodings.ladder import bundled_ladder, read_ladder
from asprilo.encodings.own import own_encoding
from asprilo.encodings.probes import Probe, forced_answer, violations
from asprilo.encodings.registry import find_encoding, reference_encodings
from asprilo.errors import InputError
from asprilo.reader import read_instance

STUDENTS = ROOT / "tests" / "students"
ENCODINGS = ROOT / "asprilo" / "encodings"

#: by hand, from the plans (robots numbered as in the instance files, steps from 1)
_M = {"swap": ["err(collision,swap,(1,2,1))"], "vertex": ["err(collision,sameNode,(1,2,1))"],
      "off-floor": ["err(move,offFloor,(1,1))"]}
_ABC = {"swap": ["err(collision,swap,(2,3,1))"], "vertex": ["err(collision,sameNode,(2,3,1))"],
        "off-floor": ["err(move,offFloor,(2,1))"], "through": ["err(move,ontoShelf,(2,2))"],
        "pickup": ["err(pickup,noShelf,(2,1))"],
        # the void delivery hands nothing over, so the order is still open at the plan's horizon 1
        "deliver": ["err(deliver,notCarrying,(1,1))", "err(goal,unfilledOrder,(1,1,1,1))"]}
BREAKS = {"m": _M, "md": _M, "a": _ABC, "b": _ABC, "c": _ABC}
#: by hand: a legal plan needs this many steps at least (M: 0, the goals are covered at the
#: start, but robot 2 of the vertex probe needs one step; A/B/C: lift, carry, deliver)
HORIZONS = {"m": {"swap": 1, "vertex": 2, "off-floor": 2}, "a": dict.fromkeys(_ABC, 3) | {"deliver": 4}}
HORIZONS |= {"md": HORIZONS["m"], "b": HORIZONS["a"], "c": HORIZONS["a"]}

#: five ways to run clingo: the verdicts must not change
CONFIGURATIONS = [["--configuration=frumpy"], ["--configuration=crafty", "--seed=7"], ["--rand-freq=1", "--seed=3"],
                  ["--configuration=jumpy", "--seed=11"], ["--configuration=trendy", "--rand-freq=0.5", "--seed=5"]]


def _probes(domain: str) -> list[Probe]:
    return list(bundled_ladder(Domain.parse(domain)).probes)


def _answer(encoding, probe: Probe, domain: str, forced: bool = True) -> str:
    atoms = [str(atom) for atom in probe.atoms()] if forced else []
    return forced_answer(read_instance(probe.instance), Domain.parse(domain), encoding, atoms, probe.horizon)


@pytest.mark.parametrize("domain", sorted(BREAKS))
def test_the_checker_finds_exactly_the_violations_derived_by_hand(domain):
    probes = _probes(domain)
    assert [probe.name for probe in probes] == list(BREAKS[domain])
    for probe in probes:
        assert sorted(violations(probe, Domain.parse(domain))) == sorted(BREAKS[domain][probe.name]), probe.name
        assert sorted(probe.breaks) == sorted(BREAKS[domain][probe.name])
        assert probe.horizon == HORIZONS[domain][probe.name]


@pytest.mark.parametrize("domain", sorted(BREAKS))
def test_every_reference_encoding_refuses_every_probe_where_a_legal_plan_exists(domain):
    for encoding in reference_encodings(Domain.parse(domain)):
        for probe in _probes(domain):
            assert _answer(encoding, probe, domain, forced=False) == "sat", (encoding.name, probe.name)
            assert _answer(encoding, probe, domain) == "unsat", (encoding.name, probe.name)


#: a student's encoding without one rule, and the one probe it must fail (all others refused)
FORGETFUL = [("m", "m-no-swap.lp", "swap"), ("m", "m-no-vertex.lp", "vertex"),
             ("m", "m-moves-off-floor.lp", "off-floor"), ("md", "m-no-swap.lp", "swap"),
             ("a", "a-no-swap.lp", "swap"), ("a", "a-through-shelves.lp", "through"),
             ("a", "a-lift-nothing.lp", "pickup"), ("a", "a-empty-hands.lp", "deliver")]


@pytest.mark.parametrize(("domain", "student", "forgotten"), FORGETFUL)
def test_an_encoding_without_the_rule_accepts_its_probe_only(domain, student, forgotten):
    encoding = own_encoding([STUDENTS / student])
    answers = {probe.name: _answer(encoding, probe, domain) for probe in _probes(domain)}
    assert answers == {name: "sat" if name == forgotten else "unsat" for name in BREAKS[domain]}


@pytest.mark.parametrize(("domain", "student"), [("m", "m-cells.lp"), ("m", "m-moves.lp"), ("a", "a-correct.lp")])
def test_a_correct_student_encoding_refuses_every_probe(domain, student):
    encoding = own_encoding([STUDENTS / student])
    assert {_answer(encoding, probe, domain) for probe in _probes(domain)} == {"unsat"}


#: a reference encoding's file, a rule's line deleted from it, and the probe that must pass then
WITHOUT = [("m", "m/incremental/plain.lp", ":- moveto(B,C,t), moveto(C,B,t), B < C.", "swap", "plain-inc"),
           ("a", "abc/robots.lp", ":- go(B,C,T), go(C,B,T), B < C.", "swap", "plain"),
           ("b", "abc/shelves.lp", ":- loaded(C,T), resting(C,T).", "through", "plain"),
           ("c", "abc/shelves.lp", ":- lift(C,T), not resting(C,T-1).", "pickup", "plain")]


@pytest.mark.parametrize(("domain", "file", "rule", "forgotten", "name"), WITHOUT)
def test_a_reference_encoding_without_the_rule_accepts_its_probe(tmp_path, domain, file, rule, forgotten, name):
    copy = tmp_path / "encodings"
    shutil.copytree(ENCODINGS, copy, ignore=shutil.ignore_patterns("ladders", "*.py", "__pycache__"))
    text = (copy / file).read_text()
    assert text.count(rule) == 1
    (copy / file).write_text(text.replace(rule, ""))
    encoding = find_encoding(Domain.parse(domain), name)
    program = copy / encoding.program.relative_to(ENCODINGS)
    names = None if encoding.names is None else copy / encoding.names.relative_to(ENCODINGS)
    encoding = replace(encoding, program=program, names=names)
    probe = next(probe for probe in _probes(domain) if probe.name == forgotten)
    assert _answer(encoding, probe, domain) == "sat"


def _small_ladder(tmp_path: Path, domain: str) -> Path:
    """The bundled ladder's first instance and all its probes (so a grade is quick)."""
    ladder = bundled_ladder(Domain.parse(domain))
    rung = ladder.rungs[0]
    lines = [f"domain: {domain}", "instances:", f"  - file: {rung.file}", f"    minimum: {rung.minimum}",
             "    established: the bundled ladder", "probes:"]
    for probe in ladder.probes:
        lines += [f"  - name: {probe.name}", f"    rule: {probe.rule}", f"    case: {probe.case}",
                  f"    instance: {probe.instance}", f"    plan: {probe.plan}", f"    horizon: {probe.horizon}"]
    path = tmp_path / f"{domain}.yml"
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize(("domain", "student", "forgotten"),
                         [("m", "m-no-swap.lp", "swap"), ("m", "m-no-vertex.lp", "vertex"),
                          ("a", "a-through-shelves.lp", "through"), ("m", "m-cells.lp", None),
                          ("a", "a-correct.lp", None)])
def test_grade_names_the_forgotten_rule_under_five_configurations(tmp_path, capsys, domain, student, forgotten):
    ladder = _small_ladder(tmp_path, domain)
    probes = _probes(domain)
    for options in CONFIGURATIONS:
        code = main(["grade", str(STUDENTS / student), "--ladder", str(ladder), "-q", *options])
        out = capsys.readouterr().out.splitlines()
        lines = out[2:-1]  # after the header and the instance, before the summary
        expected = []
        for probe in probes:
            if probe.name == forgotten:
                expected.append(f"forgot: {probe.rule} ({probe.name} probe: {probe.case})")
            else:
                expected.append(f"kept: {probe.rule} ({probe.name} probe refused)")
        assert lines == expected, options
        count = len(probes)
        if forgotten is None:
            assert code == 0 and out[-1].endswith(f"; probes: {count}/{count} refused"), options
        else:
            assert code == 1 and out[-1].endswith(f"; probes: {count - 1}/{count} refused, forgot 1 rule "
                                                  f"({forgotten})"), options


def test_the_issue_s_student_is_caught_on_the_whole_m_ladder_in_json(capsys):
    code = main(["grade", str(STUDENTS / "m-no-swap.lp"), "--domain", "m", "--json", "-q", "--rand-freq=1",
                 "--seed=3"])
    report = json.loads(capsys.readouterr().out)
    assert code == 1
    seconds = [entry.pop("seconds") for entry in report["probes"]]
    assert all(isinstance(value, float) and value >= 0 for value in seconds)
    probes = bundled_ladder(Domain.M).probes
    assert report["probes"] == [
        {"name": probe.name, "rule": probe.rule, "case": probe.case, "instance": str(probe.instance),
         "plan": str(probe.plan), "horizon": probe.horizon, "result": "accepted" if probe.name == "swap" else "refused",
         "forgot": probe.name == "swap", "reason": None} for probe in probes]
    assert report["summary"]["probes"] == {"probes": 3, "refused": 2, "forgotten": 1, "undecided": 0}


def test_a_part_of_the_ladder_runs_no_probes(capsys):
    code = main(["grade", str(STUDENTS / "m-no-swap.lp"), "--domain", "m", "--first", "1", "--json", "-q"])
    report = json.loads(capsys.readouterr().out)
    assert code == 0 and "probes" not in report and "probes" not in report["summary"]


def test_a_probe_whose_plan_is_legal_is_a_mistake_of_the_ladder(tmp_path, capsys):
    ladder = _small_ladder(tmp_path, "m")
    legal = tmp_path / "legal.lp"
    # on the swap probe's corridor, robot 2 steps right onto the station cell (3,1) and back: legal
    legal.write_text("occurs(object(robot,2),action(move,(1,0)),1).\noccurs(object(robot,2),action(move,(-1,0)),2).\n")
    text = ladder.read_text().replace(str(bundled_ladder(Domain.M).probes[0].plan), str(legal))
    text = text.replace("    horizon: 1\n", "    horizon: 2\n", 1)
    ladder.write_text(text)
    code = main(["grade", str(STUDENTS / "m-cells.lp"), "--ladder", str(ladder), "-q"])
    out, err = capsys.readouterr()
    assert (code, out) == (2, "")  # refused before the first instance is graded
    assert err.strip() == (f"error: {legal}: the swap probe's plan breaks no rule of M: a probe's plan must be "
                           "illegal")


@pytest.mark.parametrize(("entry", "message"), [
    ("  - name: x\n    rule: r\n    case: c\n    instance: nowhere.lp\n    plan: nowhere.lp\n",
     "no such instance file: {folder}/nowhere.lp"),
    ("  - name: x\n    rule: r\n    case: c\n    plan: p.lp\n", "the probe has no 'instance'"),
    ("  - name: x\n    rule: r\n    case: c\n    instance: i.lp\n    plan: p.lp\n    colour: red\n",
     "unknown key 'colour' (a probe has name, rule, case, instance, plan, horizon, breaks)"),
    ("  - name: x\n    rule: r\n    case: c\n    instance: i.lp\n    plan: p.lp\n    horizon: 0\n",
     "the horizon is a whole number, at least the plan's makespan 1; got 0"),
])
def test_bad_probes_are_refused_with_their_line(tmp_path, entry, message):
    (tmp_path / "i.lp").write_text((ENCODINGS / "ladders" / "m" / "probes" / "swap.lp").read_text())
    (tmp_path / "p.lp").write_text("occurs(object(robot,1),action(move,(1,0)),1).\n")
    rung = bundled_ladder(Domain.M).rungs[0]
    path = tmp_path / "ladder.yml"
    path.write_text(f"domain: m\ninstances:\n  - file: {rung.file}\n    minimum: 3\n    established: x\n"
                    f"probes:\n{entry}")
    with pytest.raises(InputError) as raised:
        read_ladder(path)
    assert raised.value.message == message.format(folder=tmp_path)
    assert raised.value.file == str(path) and raised.value.line is not None and raised.value.line >= 7
