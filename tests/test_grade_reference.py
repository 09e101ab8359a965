"""``asprilo grade`` against a model solution: the minima from a teacher's encoding, the plans
checked under a rule variant, every wrong answer a graded line.

The exercise is tests/exercises/visit/ (exercise.yml): domain M under visit-anytime, the
teacher's encoding teacher.lp, three instances written by hand whose minima are derived in
their comments by counting steps on the floor:

- 01-corridor: 6x1, robots at (1,1) and (4,1), ordered shelves at (5,1) and (6,1).  Under
  visit-anytime robot 2 visits both by step 2 (and no robot reaches (6,1) sooner): 2.  Under
  plain M robot 1, stuck behind robot 2, ends on (5,1), 4 cells away: 4.
- 02-alone: 3x1, one robot at (1,1), ordered shelves at (2,1) and (3,1).  Under visit-anytime
  the robot walks past both: 2.  Under plain M one robot cannot stand under two shelves at
  the end: no plan.
- 03-corner: 3x3, the robot at (1,1), the shelf at (3,3): 4 under both rules.

The expected lines follow from these numbers and the search's rules (from the lower bound up,
which visit-anytime lacks, so from 0), never from the grader's output.
"""

from __future__ import annotations

import json
import re
import shutil

import pytest
from helpers import ROOT

from asprilo.cli import main
from asprilo.domain import Domain
from asprilo.domain.variants import with_variants
from asprilo.encodings.exercise import read_exercise
from asprilo.encodings.own import own_encoding
from asprilo.encodings.reference import Reference
from asprilo.errors import InputError
from asprilo.reader import read_instance

VISIT = ROOT / "tests" / "exercises" / "visit"
EXERCISE, TEACHER, INSTANCES = VISIT / "exercise.yml", VISIT / "teacher.lp", VISIT / "instances"
CORRECT, BROKEN, SHAPELESS = (VISIT / "students" / name for name in ("correct.lp", "broken.lp", "shapeless.lp"))
PLAIN_M = ROOT / "asprilo" / "encodings" / "m" / "plain.lp"
#: the minima under visit-anytime and under plain M (None: no plan), counted by hand
VISIT_MINIMA = {"01-corridor": 2, "02-alone": 2, "03-corner": 4}
PLAIN_MINIMA = {"01-corridor": 4, "02-alone": None, "03-corner": 4}
NAMES = list(VISIT_MINIMA)


def _grade(capsys, *arguments):
    code = main(["grade", *map(str, arguments)])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def _lines(out: str) -> list[str]:
    """The instance lines of a text report (after the header's two lines, before the summary)."""
    return out.splitlines()[2:-1]


def test_a_correct_hand_in_is_valid_and_minimal_on_every_instance(capsys):
    code, out, err = _grade(capsys, CORRECT, "--exercise", EXERCISE)
    assert code == 0
    header, rules, *lines, summary = out.splitlines()
    assert header == (f"grading your encoding ({CORRECT}: incremental (step(t)/check(t), query(t))) on the exercise "
                      f"visit ({EXERCISE}): 3 instances, time limit 30 s each")
    assert rules == (f"  rules: M+visit-anytime; minima: the reference encoding {TEACHER} (single-shot with a horizon "
                     "constant), searched from the lower bound up")
    for line, name in zip(lines, NAMES, strict=True):
        assert f" {name} " in line and line.endswith(f"  valid    minimal (makespan {VISIT_MINIMA[name]})")
    assert summary.startswith("3/3 valid, 3/3 minimal; ")
    assert err.splitlines()[0] == "grading [1/3] 01-corridor (the reference's minimum first)"


def test_the_plain_m_encoding_ignores_the_variant_and_is_graded_so(capsys):
    """plain.lp demands every shelf visited at the end: on the corridor its first plan is
    plain M's minimum 4 (horizons 0-3 refuted, 2 and 3 although visit-anytime has plans
    there); alone it has no plan up to where its search stops (0 + 3 cells + 1 robot + 2 per
    order line = 8); on the corner both rules agree."""
    code, out, _err = _grade(capsys, PLAIN_M, "--exercise", EXERCISE)
    assert code == 1
    corridor, alone, corner = _lines(out)
    assert corridor.endswith("  valid    the shortest plan this encoding allows (4); the problem's minimum is 2 "
                             "(horizons 2-3 refuted, yet plans exist from makespan 2 on: a constraint is too strong)")
    assert "  no plan  " in alone and alone.endswith(
        "; horizons 0-8 refuted, yet plans exist from makespan 2 on: a constraint is too strong")
    assert corner.endswith("  valid    minimal (makespan 4)")
    assert out.splitlines()[-1].startswith("2/3 valid, 1/3 minimal, 1 without a plan; ")


def test_the_json_shape(capsys):
    code, out, _err = _grade(capsys, PLAIN_M, "--exercise", EXERCISE, "--json", "--first", "2")
    assert code == 1
    report = json.loads(out)
    seconds = [entry.pop("seconds") for entry in report["instances"]] + [report["summary"].pop("seconds")]
    seconds += [entry["reference"].pop("seconds") for entry in report["instances"]]
    assert all(isinstance(value, float) and value >= 0 for value in seconds)
    corridor, alone = report["instances"]
    assert report == {
        "version": 1, "domain": "m+visit-anytime", "variants": ["visit-anytime"], "ladder": None,
        "exercise": {"name": "visit", "file": str(EXERCISE),
                     "summary": "every ordered product's shelf has a robot under it at some step, in any order"},
        "encoding": {"name": "plain", "own": True, "files": [str(PLAIN_M)], "style": "single-shot with a horizon "
                     "constant", "assumed": [], "constants": {}, "horizon": None, "options": []},
        "reference": {"name": "teacher", "own": True, "files": [str(TEACHER)],
                      "style": "single-shot with a horizon constant"},
        "time_limit": 30.0,
        "instances": [corridor, alone],
        "summary": {"instances": 2, "valid": 1, "minimal": 0, "invalid": 0, "no_plan": 1, "time_outs": 0,
                    "minima_unknown": 0},
    }
    assert corridor == {
        "step": 1, "name": "01-corridor", "file": "01-corridor.lp", "size": "6x1", "robots": 2, "minimum": 2,
        "result": "valid", "valid": True, "minimal": False, "encoding_minimal": True, "makespan": 4, "violation": None,
        "violations": 0, "reason": None, "refuted": [0, 1, 2, 3], "warnings": [],
        "reference": {"proven": True, "makespan": 2, "at_least": 2, "reason": None}}
    assert alone["result"] == "no-plan" and alone["minimum"] == 2 and alone["refuted"] == list(range(9))
    assert alone["reference"] == {"proven": True, "makespan": 2, "at_least": 2, "reason": None}


def test_a_syntax_error_is_a_graded_line_per_instance(capsys):
    """broken.lp lacks the period of line 5: clingo stumbles on line 6, column 1."""
    code, out, _err = _grade(capsys, BROKEN, "--exercise", EXERCISE)
    assert code == 1
    for line in _lines(out):
        assert re.search(r"  no plan  clingo refused the encoding: \S*broken\.lp:6: column 1: syntax error", line)
    assert out.splitlines()[-1].startswith("0/3 valid, 0/3 minimal, 3 without a plan; ")
    code, out, _err = _grade(capsys, BROKEN, "--exercise", EXERCISE, "--json")
    report = json.loads(out)
    assert code == 1 and report["encoding"]["style"] == "refused by clingo"
    assert [(entry["result"], entry["minimum"], entry["reference"]) for entry in report["instances"]] == [
        ("no-plan", None, None)] * 3  # no search was run: the minima were not computed


def test_unsafe_variables_are_a_graded_line_too(tmp_path, capsys):
    unsafe = tmp_path / "unsafe.lp"
    unsafe.write_text("#const horizon = 0.\np(X) :- q.\n#show occurs/3.\n")
    code, out, _err = _grade(capsys, unsafe, "--exercise", EXERCISE, "--first", "1")
    assert code == 1
    assert re.search(rf"  no plan  clingo refused the encoding: {re.escape(str(unsafe))}:2: .*unsafe", _lines(out)[0])


SHAPE = ("its model's occurs/3 atoms are no plan: expected occurs(object(robot,R),action(Name,Args),T), got "
         "occurs(robot(1),move(right),1)")


def test_occurs_atoms_that_are_no_plan_are_graded(capsys):
    code, out, _err = _grade(capsys, SHAPELESS, "--exercise", EXERCISE)
    assert code == 1
    assert all(line.endswith(f"  no plan  {SHAPE}") for line in _lines(out))
    # on a ladder too (it was bad input, exit status 2, on the first instance)
    code, out, _err = _grade(capsys, SHAPELESS, "--domain", "m", "--first", "1")
    assert code == 1 and out.splitlines()[1].endswith(f"  no plan  {SHAPE}")


def test_under_sides_a_plan_crossing_the_middle_is_invalid_in_the_variants_words(capsys):
    """tests/variants/corridor.lp: 4x1, the robot at (2,1), the shelf at (4,1).  The middle is
    (4 + 1) // 2 = 2, so the robot belongs left and can never reach the shelf: the variant's
    model solution finds no plan (the minimum is unknown), while plain.lp's plan moves right
    at steps 1 and 2 and leaves the left half at step 1."""
    corridor = ROOT / "tests" / "variants" / "corridor.lp"
    code, out, _err = _grade(capsys, PLAIN_M, "--variant", "sides", "--domain", "m", "--instances", corridor)
    assert code == 1
    assert out.splitlines()[1].startswith("  rules: M+sides; minima: the reference encoding sides (model solution")
    assert _lines(out)[0].endswith("  INVALID  makespan 2: step 1: robot 1 leaves the left half of the floor, where it "
                                   "started")
    assert out.splitlines()[-1].startswith("0/1 valid, 0/1 minimal, 1 invalid, minimum unknown on 1; ")
    code, out, _err = _grade(capsys, PLAIN_M, "--variant", "sides", "--domain", "m", "--instances", corridor,
                             "--json")
    entry = json.loads(out)["instances"][0]
    assert entry["minimum"] is None and entry["minimal"] is False and entry["violation"]["check"] == "crossed"
    assert entry["reference"]["proven"] is False and entry["reference"]["makespan"] is None
    assert entry["reference"]["reason"].startswith("the reference found no plan")


def test_a_minimum_the_reference_did_not_prove_is_unknown(tmp_path, capsys):
    """A teacher's encoding without a horizon constant is solved once: its plan is not proven
    minimal, so no minimum is claimed (the hand-in's makespans are the hand-derived minima)."""
    fixed = tmp_path / "fixed.lp"
    fixed.write_text(TEACHER.read_text().replace("#const horizon = 0.", "#const h = 5.")
                     .replace("time(1..horizon).", "time(1..h)."))
    code, out, _err = _grade(capsys, CORRECT, "--variant", "visit-anytime", "--reference", fixed,
                             "--instances", INSTANCES)
    assert code == 0
    assert out.splitlines()[1].startswith("  rules: M+visit-anytime; ")  # the variant's one domain
    for line, name in zip(_lines(out), NAMES, strict=True):
        assert re.search(rf"  valid    the shortest plan this encoding allows \({VISIT_MINIMA[name]}\); the problem's "
                         r"minimum is unknown \(the reference found makespan \d+ but did not prove it minimal\)$", line)
    assert out.splitlines()[-1].startswith("3/3 valid, 0/3 minimal, minimum unknown on 3; ")


def test_without_a_variant_the_reference_grades_under_the_plain_rules(capsys):
    code, out, _err = _grade(capsys, PLAIN_M, "--reference", "plain", "--instances", INSTANCES / "01-corridor.lp",
                             INSTANCES / "03-corner.lp")
    assert code == 0
    assert out.splitlines()[1].startswith("  rules: M; minima: the reference encoding plain ")
    assert [line.split("  ")[-1] for line in _lines(out)] == [
        f"minimal (makespan {PLAIN_MINIMA[name]})" for name in ("01-corridor", "03-corner")]


def test_the_reference_under_plain_rules_finds_no_plan_where_none_exists(tmp_path):
    domain = Domain.M
    reference = Reference(own_encoding([PLAIN_M]), domain, time_limit=30)
    file = INSTANCES / "02-alone.lp"
    found = reference.minimum(file, read_instance(file))
    assert (found.minimum, found.makespan, found.at_least) == (None, None, None)  # two goals, one robot
    assert found.reason.startswith("no plan exists")


def test_the_minima_are_computed_once_per_instance_and_kept_in_memory_only(tmp_path, capsys):
    folder = tmp_path / "visit"
    shutil.copytree(VISIT, folder)
    before = sorted(path.relative_to(folder) for path in folder.rglob("*"))
    reference = Reference(own_encoding([folder / "teacher.lp"]), with_variants(Domain.M, ["visit-anytime"]),
                          time_limit=30)
    file = folder / "instances" / "03-corner.lp"
    first = reference.minimum(file, read_instance(file))
    assert first.minimum == VISIT_MINIMA["03-corner"]
    assert reference.minimum(file, read_instance(file)) is first
    code, out, _err = _grade(capsys, folder / "students" / "correct.lp", "--exercise", folder / "exercise.yml",
                             "--first", "1")
    assert code == 0
    assert sorted(path.relative_to(folder) for path in folder.rglob("*")) == before  # nothing written


def test_the_list_shows_the_minima_the_reference_proves(capsys):
    code, out, _err = _grade(capsys, "--list", "--exercise", EXERCISE)
    assert code == 0
    lines = out.splitlines()
    assert lines[0] == f"the exercise visit ({EXERCISE}): 3 instances"
    minima = [line.split()[-1] for line in lines if line.split()[-2:-1] == ["minimum"]]
    assert minima == [str(VISIT_MINIMA[name]) for name in NAMES]
    assert sum("established: proven by the reference's horizon search" in line for line in lines) == 3


def test_the_exercise_file():
    exercise = read_exercise(EXERCISE)
    assert (exercise.name, exercise.domain, exercise.variants, exercise.time_limit) == (
        "visit", Domain.M, ("visit-anytime",), 30.0)
    assert exercise.reference == (str(TEACHER),)
    assert [path.stem for path in exercise.instances] == NAMES


@pytest.mark.parametrize("text, message", [
    ("domain: m\n", ":1: 'instances:' is missing"),
    ("domain: m\ninstances: nowhere\n", ":2: no such instance file or folder: "),
    ("domain: m\ninstances: inst\ntime-limit: -3\n", ":3: 'time-limit:' must be a positive number of seconds"),
    ("domain: m\ninstances: inst\nvariant: diagonal\n", ":3: unknown key 'variant'"),
    ("domain: q\ninstances: inst\n", ":1: "),
    ("exercise: Week 3\ndomain: m\ninstances: inst\n", ":1: the exercise's name 'Week 3' is not a name"),
    ("domain: m\ninstances: [inst, 3]\n", ":2: 'instances:' must be a text or a list of texts"),
    ("- domain: m\n", ":1: an exercise file is a mapping"),
])
def test_bad_exercise_files_are_refused_with_their_line(tmp_path, text, message):
    (tmp_path / "inst").mkdir()
    (tmp_path / "inst" / "a.lp").write_text((INSTANCES / "03-corner.lp").read_text())
    path = tmp_path / "exercise.yml"
    path.write_text(text)
    with pytest.raises(InputError) as refused:
        read_exercise(path)
    assert str(refused.value).startswith(f"{path}{message}")


def test_bad_input_on_the_teachers_side_exits_2(tmp_path, capsys):
    code, _out, err = _grade(capsys, CORRECT, "--variant", "visit-anytime")
    assert code == 2 and err.startswith("error: --variant grades against a model solution: name the instances")
    code, _out, err = _grade(capsys, CORRECT, "--exercise", EXERCISE, "--reference", TEACHER)
    assert code == 2 and err.startswith("error: --reference and --exercise: the exercise file names its own")
    code, _out, err = _grade(capsys, CORRECT, "--exercise", EXERCISE, "--domain", "a")
    assert (code, err) == (2, f"error: {EXERCISE}: the exercise is of domain M, not A\n")
    code, _out, err = _grade(capsys, CORRECT, "--variant", "visit-anytime", "--reference", BROKEN,
                             "--instances", INSTANCES)
    assert code == 2 and re.match(r"error: \S*broken\.lp:6: column 1: syntax error", err)
    code, _out, err = _grade(capsys, tmp_path / "missing.lp", "--exercise", EXERCISE)
    assert (code, err) == (2, f"error: {tmp_path / 'missing.lp'}: no such file\n")
