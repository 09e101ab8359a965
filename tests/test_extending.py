"""docs/EXTENDING.md walked through: a new object kind (chargers) and a domain variant that
uses it ("mc": Md, and every robot passes over a charger), with the files in docs/extending/.

Expected values by hand: on the 3x2 floor of corridor.lp, robot 1 goes from (1,1) to its
destination (3,1); the charger (2,2) is two moves away from both, so the shortest plan
that passes it has 4 moves (on a grid every way between two cells of even distance is
even, and 2 moves cannot pass (2,2)); without the charger, 2 moves suffice.
"""

from __future__ import annotations

import dataclasses
import threading

import pytest
from helpers import ROOT

from asprilo.checker import check
from asprilo.cli import main
from asprilo.domain import Domain, ReferenceEncoding, Words, register, unregister
from asprilo.model import Action, Plan
from asprilo.objects import CELL, ObjectKind, register_kind, unregister_kind
from asprilo.reader import read_instance, read_plan
from asprilo.writer import format_instance

EXAMPLE = ROOT / "docs" / "extending"
CORRIDOR = EXAMPLE / "corridor.lp"
STRAIGHT = Plan([Action(1, 1, "move", (1, 0)), Action(2, 1, "move", (1, 0))])


NEVER_CHARGED = Words((("R", "robot"), ("T", "step")), "robot {R} never stands on a charger")


@pytest.fixture
def charger():
    kind = register_kind(ObjectKind("charger", "charger", "chargers", {"at": CELL}))
    yield kind
    unregister_kind("charger")


@pytest.fixture
def mc(charger):
    md = Domain.parse("md")
    domain = register(dataclasses.replace(
        md, value="mc", label="Mc", summary="as Md, and every robot passes over a charger",
        reads=md.reads | {"charger"},
        checker=(*md.checker[:-1], str(EXAMPLE / "charged.lp"), "goal"),
        encodings=(ReferenceEncoding("charge", str(EXAMPLE / "charge.lp"), summary="Md's plain encoding + charging"),),
        generation=None, made_by="write it by hand (see docs/extending/corridor.lp)",
        messages={("charged", "neverCharged"): NEVER_CHARGED}))
    yield domain
    unregister(domain)


def test_a_registered_kind_is_read_checked_and_written_back(charger):
    instance = read_instance(CORRIDOR)
    assert instance.placed == {"charger": {1: (2, 2)}}
    assert instance.other_facts == []
    assert "% chargers\ninit(object(charger,1),value(at,(2,2))).\n" in format_instance(instance)


def test_an_unregistered_kind_is_kept_aside_with_a_warning():
    with pytest.warns(UserWarning, match="object type 'charger'"):
        instance = read_instance(CORRIDOR)
    assert instance.placed == {}
    assert instance.other_facts == ["init(object(charger,1),value(at,(2,2)))."]


def test_a_registered_kind_gets_the_readers_checks(charger, tmp_path):
    twice = tmp_path / "twice.lp"
    twice.write_text(CORRIDOR.read_text() + "init(object(charger,1),value(at,(1,2))).\n")
    with pytest.raises(Exception, match=r"charger 1 is at two places"):
        read_instance(twice)


def test_the_variant_checks_with_its_own_concern_and_words(mc):
    instance = read_instance(CORRIDOR)
    report = check(instance, STRAIGHT, mc)
    assert [error.atom for error in report.errors] == ["err(charged,neverCharged,(1,2))"]
    assert report.errors[0].message == "step 2: robot 1 never stands on a charger"
    assert check(instance, STRAIGHT, Domain.parse("md")).valid  # Md itself does not ask for charging


@pytest.fixture(params=["fork", "spawn"])
def start_method(request):
    """How solve's child process starts: ``fork`` (it inherits the variant) or ``spawn`` (a
    fresh interpreter that never saw it registered: used while another thread runs)."""
    if request.param == "fork":
        yield
        return
    done = threading.Event()
    other = threading.Thread(target=done.wait, daemon=True)
    other.start()
    yield
    done.set()
    other.join()


def test_the_variant_solves_with_its_encoding_from_the_command_line(mc, tmp_path, capsys, start_method):
    plan = tmp_path / "plan.lp"
    assert main(["solve", str(CORRIDOR), "--domain", "mc", "--encoding", "charge", "-o", str(plan)]) == 0
    report = check(read_instance(CORRIDOR), read_plan(plan), mc)
    assert report.valid and report.horizon == 4
    assert main(["check", str(CORRIDOR), str(plan), "--domain", "mc"]) == 0
    assert "valid plan (domain Mc, horizon 4)" in capsys.readouterr().out


def test_the_variant_is_known_to_every_tool_by_its_name(mc, tmp_path, capsys):
    plan = tmp_path / "straight.lp"
    plan.write_text("occurs(object(robot,1),action(move,(1,0)),1).\noccurs(object(robot,1),action(move,(1,0)),2).\n")
    assert main(["check", str(CORRIDOR), str(plan), "--domain", "mc"]) == 1
    assert "step 2: robot 1 never stands on a charger" in capsys.readouterr().out
    assert main(["gen", "-x", "3", "-y", "2", "--domain", "mc"]) == 2
    assert capsys.readouterr().err == "error: --domain mc is not generated; write it by hand " \
                                      "(see docs/extending/corridor.lp)\n"



def test_the_variant_file_works_by_its_path_in_a_fresh_process(tmp_path):
    """The command line knows no domain registered in another process: the variant file
    (docs/extending/charged.yml) is how a shell user gives Mc."""
    import subprocess
    import sys

    plan = tmp_path / "straight.lp"
    plan.write_text("occurs(object(robot,1),action(move,(1,0)),1).\noccurs(object(robot,1),action(move,(1,0)),2).\n")
    done = subprocess.run([sys.executable, "-m", "asprilo.cli", "check", str(CORRIDOR), str(plan), "--variant",
                           str(EXAMPLE / "charged.yml")], capture_output=True, text=True, cwd=tmp_path)
    assert (done.returncode, done.stderr) == (1, "")
    assert done.stdout.splitlines()[:2] == ["step 2: robot 1 never stands on a charger",
                                            "invalid plan: 1 violation (domain Md+charged (detected), horizon 2)"]


def test_the_words_of_a_check_survive_a_child_process():
    import pickle

    words = pickle.loads(pickle.dumps(NEVER_CHARGED))
    assert words(None, 1, 2) == ("robot 1 never stands on a charger", {"robots": [1]})
