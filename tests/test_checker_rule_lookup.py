"""The checker rule behind a violation (``asprilo.checker.rules``): for every check of every
domain's checker, the rule whose head is ``err(Module,Check,_)``, its file, line and text."""

from __future__ import annotations

import dataclasses

import pytest
from test_check_rules import CASES

from asprilo.checker.programs import HERE, concerns, err_atoms
from asprilo.checker.rules import Rule, checks, display_path, one_line, rule_line, rule_of, rules_of
from asprilo.domain import Domain, domains
from asprilo.simulate.messages import MESSAGES

BUILTIN = (Domain.A, Domain.B, Domain.C, Domain.M, Domain.MD)
#: the one check derived by more than one rule: an order without the product, and too many units
SEVERAL = {("deliver", "orderAmount"): [6, 7]}


def test_exact_rules():
    assert rule_of(Domain.A, "move", "offFloor") == Rule(
        HERE / "move.lp", 7, "err(move,offFloor,(R,T)) :- position(R,C,T), not node(C), moves(R,T).")
    assert rule_of(Domain.M, "collision", "swap") == Rule(
        HERE / "collision.lp", 6, "err(collision,swap,(R1,R2,T)) :- position(R1,To,T), position(R2,To,T-1), R1 < R2,\n"
                                  "                                 position(R2,From,T), position(R1,From,T-1), "
                                  "From != To.")
    assert str(rule_of(Domain.M, "collision", "swap")) == (
        "checker/collision.lp:6: err(collision,swap,(R1,R2,T)) :- position(R1,To,T), position(R2,To,T-1), R1 < R2, "
        "position(R2,From,T), position(R1,From,T-1), From != To.")
    assert rule_of(Domain.B, "deliver", "lineClosed").where == "checker/deliver_bc.lp:6"
    assert rule_of(Domain.MD, "goal", "missedAssignedGoal").where == "checker/assigned.lp:11"


def test_several_rules_for_one_check_the_first_and_how_many():
    first, second = rules_of(Domain.A, "deliver", "orderAmount")
    assert (first.where, second.where) == ("checker/deliver_a.lp:6", "checker/deliver_a.lp:7")
    assert second.text == ("err(deliver,orderAmount,(R,T)) :- does(R,deliver,(O,P,N),T), line(O,P,Units),\n"
                           "    #sum{ M,Other,U : gives(Other,_,O,P,M,U), U < T } > Units - N.")
    assert rule_of(Domain.A, "deliver", "orderAmount") == first
    assert rule_line(Domain.A, "deliver", "orderAmount") == (
        "checker/deliver_a.lp:6 (first of 2 rules): err(deliver,orderAmount,(R,T)) :- does(R,deliver,(O,P,_),T), "
        "order(O), not line(O,P,_).")
    assert rule_line(Domain.A, "deliver", "shelfAmount").startswith("checker/deliver_a.lp:10: err(deliver,")


@pytest.mark.parametrize("domain", BUILTIN, ids=lambda d: d.label)
def test_every_check_has_one_rule_in_a_file_of_the_domain(domain):
    found = checks(domain)
    assert found and len(found) == len(set(found))
    files = set(concerns(domain))
    for module, check in found:
        rules = rules_of(domain, module, check)
        assert [rule.line for rule in rules] == SEVERAL.get((module, check), [rules[0].line]), (module, check)
        for rule in rules:
            assert rule.path in files
            assert rule.text.startswith(f"err({module},{check},") and rule.text.endswith(".")
            # the line named is where the rule starts in its file, and the text is the file's
            lines = rule.path.read_text().split("\n")
            assert lines[rule.line - 1].startswith(rule.text.split("\n")[0])
            assert " ".join(rule.text.split()) == one_line(rule.text) and "\n" not in str(rule)


def test_the_checks_with_rules_are_the_checks_the_simulator_words():
    with_rules = {key for domain in BUILTIN for key in checks(domain)}
    raw_only = {("instance", "manyPositions")}  # raw facts only: the reader refuses such input
    assert with_rules == set(MESSAGES) | raw_only
    assert ("deliver", "lineClosed") not in checks(Domain.A) and ("deliver", "orderAmount") not in checks(Domain.B)
    assert ("deliver", "notCarrying") not in checks(Domain.M)


@pytest.mark.parametrize("name", CASES)
def test_every_atom_the_checker_derives_has_its_rule(name):
    domain, instance, plan, _expected = CASES[name]
    atoms, _statistics = err_atoms(instance, plan, domain)
    assert atoms
    for atom in atoms:
        module, check = atom.arguments[0].name, atom.arguments[1].name
        rule = rule_of(domain, module, check)
        assert rule is not None and rule.text.startswith(f"err({module},{check},"), str(atom)


def test_no_rule():
    assert rule_of(Domain.A, "move", "teleport") is None
    assert rules_of(Domain.A, "move", "teleport") == []
    assert rule_line(Domain.M, "deliver", "shelfAmount") is None  # M has no deliveries


def test_a_domain_with_a_checker_file_of_its_own(tmp_path):
    extra = tmp_path / "battery.lp"
    extra.write_text("% a check of its own\n\nerr(battery,empty,(R,T)) :-\n    does(R,move,_,T), T > 10.\n")
    variant = dataclasses.replace(Domain.M, value="mbattery", checker=(*Domain.M.checker, str(extra)))
    assert variant not in domains()  # looked up without registering it
    rule = rule_of(variant, "battery", "empty")
    assert rule == Rule(extra, 3, "err(battery,empty,(R,T)) :-\n    does(R,move,_,T), T > 10.")
    assert rule.where == f"{extra}:3" and display_path(HERE / "move.lp") == "checker/move.lp"
    assert rule_of(variant, "move", "offFloor") == rule_of(Domain.M, "move", "offFloor")
