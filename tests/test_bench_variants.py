"""Bench suites under rule variants (``variant:`` on a run) and with two-stage encodings of
their own (``stage:`` on an encoding): run end to end, labelled in the report, refused in
words where they cannot run.

Expected values by hand (tests/variants/*.lp, tests/encodings/*.lp say what they hold):
corner.lp takes 4 moves in M and 2 under diagonal; corridor.lp 2 under energy (energy 2, two
moves); m-tiny.lp 4 (the stage's one target is where the single robot must go anyway), and
m-pass.lp 1 in M, while its stage's answer needs 4.
"""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest
from helpers import ROOT

from asprilo.bench.results import load_results
from asprilo.bench.suite import load_suite
from asprilo.cli import main

VARIANTS = ROOT / "tests" / "variants"
OWN = ROOT / "tests" / "encodings"


def _suite(folder: Path, body: str) -> Path:
    path = folder / "suite.yml"
    path.write_text("name: rules\ntime_limit: 60\nmemory_limit: 2048\nmakespan_time_limit: 60\n" + body)
    return path


RUNS = (f"instances:\n  corner: {{files: [\"{VARIANTS / 'corner.lp'}\"]}}\n"
        f"  corridor: {{files: [\"{VARIANTS / 'corridor.lp'}\"]}}\n"
        "runs:\n"
        "  - {domain: m, sets: [corner]}\n"
        "  - {domain: m, variant: diagonal, sets: [corner]}\n"
        "  - {domain: m, variant: [energy], sets: [corridor]}\n")


def test_runs_under_variants_solve_and_check_with_their_rules_and_are_labelled(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["bench", str(_suite(tmp_path, RUNS)), "-o", str(out), "--plots", "none"]) == 0
    records = sorted((Path(r["instance"]).name, r["label"], r["encoding"], r["status"], r["horizon"],
                      r.get("variants")) for r in load_results(out))
    assert records == [("corner.lp", "M", "plain", "solved", 4, None),
                       ("corner.lp", "M+diagonal", "diagonal", "solved", 2, ["diagonal"]),
                       ("corridor.lp", "M+energy", "energy", "solved", 2, ["energy"])]
    report = capsys.readouterr().out
    assert "M+diagonal" in report and "M+energy" in report


def test_a_variant_is_loaded_with_the_suite_and_names_the_domain(tmp_path):
    suite = load_suite(_suite(tmp_path, RUNS))
    assert [(spec.label, spec.encoding, spec.variants, spec.base and spec.base.label) for spec in suite.runs] == [
        ("M", "plain", (), None), ("M+diagonal", "diagonal", ("diagonal",), "M"),
        ("M+energy", "energy", ("energy",), "M")]
    assert suite.runs[1].domain_job() == {"domain": "m+diagonal", "base": "m", "variants": ["diagonal"]}


def test_a_variant_file_is_found_beside_the_suite(tmp_path):
    (tmp_path / "rules").mkdir()
    for name in ("sides.yml", "sides.lp", "sides-plan.lp"):
        (tmp_path / "rules" / name).write_text((ROOT / "asprilo" / "variants" / name).read_text())
    suite = load_suite(_suite(tmp_path, RUNS.replace("variant: [energy]", "variant: rules/sides.yml")))
    assert suite.runs[2].variants == (str((tmp_path / "rules" / "sides.yml").resolve()),)
    assert suite.runs[2].label == "M+sides"


@pytest.mark.parametrize("run, said", [
    ("  - {domain: a, variant: diagonal}\n", "8: runs[0].variant: variant 'diagonal' changes domains M, Md, not A"),
    ("  - {domain: a, variant: energy}\n",
     "8: runs[0].variant: no encoding solves A+energy: variant 'energy' names no model solution for A"),
    ("  - {domain: m, variant: diagonal, method: anytime}\n",
     "8: runs[0].variant: the anytime planner knows only SPEC.md's rules, not a variant's"),
    ("  - {domain: m, variant: nowhere}\n", "8: runs[0].variant: unknown variant 'nowhere'"),
    ("  - {domain: m, variant: diagonal, encoding: plain}\n",
     "8: runs[0].encoding: no encoding 'plain' for domain M+diagonal (reference encodings: diagonal"),
])
def test_a_run_that_cannot_run_under_its_variant_is_refused_with_its_line(tmp_path, capsys, run, said):
    body = f"instances:\n  corner: {{files: [\"{VARIANTS / 'corner.lp'}\"]}}\nruns:\n{run}"
    assert main(["bench", str(_suite(tmp_path, body)), "-o", str(tmp_path / "out")]) == 2
    assert capsys.readouterr().err.startswith(f"error: {tmp_path / 'suite.yml'}:{said}")


STAGED = (f"encodings:\n  staged: {{files: [\"{OWN / 'stage-plan.lp'}\"], stage: [\"{OWN / 'stage-assign.lp'}\"]}}\n"
          f"instances:\n  tiny: {{files: [\"{OWN / 'm-tiny.lp'}\", \"{OWN / 'm-pass.lp'}\"]}}\n"
          "runs:\n  - {domain: m, encoding: staged}\n")


def test_an_encoding_with_a_first_stage_runs_it_at_the_minimal_makespan(tmp_path):
    out = tmp_path / "out"
    assert main(["bench", str(_suite(tmp_path, STAGED)), "-o", str(out), "--plots", "none"]) == 0
    records = {Path(r["instance"]).name: (r["status"], r["horizon"], r.get("error")) for r in load_results(out)}
    assert records == {"m-tiny.lp": ("solved", 4, None),
                       "m-pass.lp": ("error", 1, "no plan at horizon 1 along the first stage's answer (not "
                                                 "refuted for the problem)")}


def test_a_stage_that_is_no_file_is_refused_at_its_line(tmp_path, capsys):
    body = STAGED.replace(str(OWN / "stage-assign.lp"), str(tmp_path / "missing.lp"))
    assert main(["bench", str(_suite(tmp_path, body)), "-o", str(tmp_path / "out")]) == 2
    assert capsys.readouterr().err == (f"error: {tmp_path / 'suite.yml'}:6: encodings.staged.stage[0]: "
                                       f"{tmp_path / 'missing.lp'}: no such file\n")


def test_the_btool_export_carries_variants_by_name_and_the_stage_s_files(tmp_path):
    """The cluster's run of m-tiny.lp with the staged encoding: the stage's copy is found from
    the description, relative to it (m-tiny.lp: 4, by hand)."""
    enc = tmp_path / "enc"
    enc.mkdir()
    for name in ("stage-plan.lp", "stage-assign.lp", "m-moves.lp"):
        shutil.copy(OWN / name, enc / name)
    body = ("encodings:\n  staged: {files: [enc/stage-plan.lp], stage: [enc/stage-assign.lp]}\n"
            f"instances:\n  corner: {{files: [\"{VARIANTS / 'corner.lp'}\", \"{OWN / 'm-tiny.lp'}\"]}}\n"
            "runs:\n  - {domain: m, variant: diagonal}\n  - {domain: m, encoding: staged}\n")
    cluster = tmp_path / "cluster"
    assert main(["bench", "export-btool", str(_suite(tmp_path, body)), str(cluster)]) == 0
    runscript = (cluster / "runscripts/rules.xml").read_text()
    assert 'cmdline="--domain m --variant diagonal --encoding diagonal"' in runscript
    assert json.loads((cluster / "encodings/staged.json").read_text())["stage"] == ["staged/stage-assign.lp"]
    shutil.rmtree(enc)  # the exported runs use the copies
    program = next((cluster / "programs").glob("asprilo-*"))
    done = subprocess.run([str(program), "--domain", "m", "--encoding", "staged", "--own-encoding",
                           "encodings/staged.json", "--time-limit", "60", str(cluster / "benchmarks/corner/m-tiny.lp")],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout.splitlines()[-1])["status"] == "solved"
    done = subprocess.run([str(program), "--domain", "m", "--variant", "diagonal", "--encoding", "diagonal",
                           "--time-limit", "60", str(cluster / "benchmarks/corner/corner.lp")],
                          capture_output=True, text=True, timeout=300)
    record = json.loads(done.stdout.splitlines()[-1])
    assert (done.returncode, record["label"], record["status"], record["horizon"]) == (0, "M+diagonal", "solved", 2)


def test_export_btool_refuses_a_variant_file(tmp_path, capsys):
    body = RUNS.replace("variant: [energy]", f"variant: \"{ROOT / 'asprilo/variants/sides.yml'}\"")
    assert main(["bench", "export-btool", str(_suite(tmp_path, body)), str(tmp_path / "cluster")]) == 2
    assert "export-btool carries the built-in variants only, by name" in capsys.readouterr().err
