"""docs/EXERCISE.md run as a teacher would: every command of its ```sh blocks, in order, in a
copy of the clone (so that ``cp -r docs/exercise course`` and ``cd course`` work as written),
with the answers the page promises, derived by hand.

The corridor (docs/exercise/corridor.lp) is 8x1 with the robot seven moves from the shelf:
seven moves in a row break the rule at the fourth, at step 4; resting after every third move
takes 3 + 1 + 3 + 1 + 1 = 9 steps, and 7 or 8 steps leave no room for the two rests.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from helpers import ROOT

PAGE = ROOT / "docs" / "EXERCISE.md"
#: a hang guard per command (the whole page runs in a few seconds)
GUARD = 300


def commands() -> list[str]:
    """The command lines of the page's ```sh blocks, in order."""
    blocks = re.findall(r"```sh\n(.*?)```", PAGE.read_text(), re.DOTALL)
    return [line for block in blocks for line in block.splitlines() if line.strip()]


def test_the_page_runs_as_written(tmp_path):
    shutil.copytree(ROOT / "docs" / "exercise", tmp_path / "docs" / "exercise")
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}",
           "QT_QPA_PLATFORM": "offscreen"}
    folder, runs = tmp_path, {}
    for line in commands():
        if line.startswith("cd "):
            folder = folder / line.split()[1]
            continue
        done = subprocess.run(["bash", "-c", line], cwd=folder, env=env, capture_output=True, text=True,
                              timeout=GUARD)
        runs[line] = done
    rushed, rested = (runs[f"check corridor.lp {name}.lp --variant tired.yml"] for name in ("rushed", "rested"))
    assert rushed.returncode == 1
    assert rushed.stdout.splitlines()[0] == "step 4: robot 1 moves a fourth step in a row without resting"
    assert rested.returncode == 0
    assert rested.stdout.splitlines()[0] == "valid plan (domain M+tired (detected), horizon 9)"
    solved = runs["asprilo solve corridor.lp --variant tired.yml -o plan.lp"]
    assert solved.returncode == 0 and "plan: horizon 9 (proven minimal)" in solved.stderr
    course = tmp_path / "course"
    assert (course / "plan.lp").read_text().count("occurs(") == 7
    assert runs["viz corridor.lp plan.lp --variant tired.yml --export plan.gif"].returncode == 0
    assert (course / "plan.gif").stat().st_size > 0
    assert len(list((course / "instances").glob("*.lp"))) == 4
    listed = runs["asprilo grade --list --exercise exercise.yml"]
    assert listed.returncode == 0 and re.search(r"corridor\s+8x1, 1 robot\s+minimum 9", listed.stdout)
    ann = runs["asprilo grade students/ann.lp --exercise exercise.yml"]
    assert ann.returncode == 0 and ann.stdout.splitlines()[-1].startswith("4/4 valid, 4/4 minimal")
    assert runs["asprilo grade students/bob.lp --exercise exercise.yml --json > bob.json"].returncode == 1
    grades = json.loads((course / "bob.json").read_text())
    corridor = next(entry for entry in grades["instances"] if entry["name"] == "corridor")
    assert (corridor["result"], corridor["minimum"], corridor["makespan"]) == ("invalid", 9, 7)
    assert corridor["violation"]["message"] == "step 4: robot 1 moves a fourth step in a row without resting"
