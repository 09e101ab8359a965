"""What each limit of the README's limits table costs at its edge: wall time and peak memory.

Each case builds an input just within one limit (the defaults of ``asprilo.limits.Limits``,
so a changed default is measured at its new edge), runs the command a user would in a
process of its own, and records its wall time and the peak resident memory of it and its
children (``getrusage(RUSAGE_CHILDREN)`` of a fresh measuring process, so one case's peak
never shows in another's).  The rule (issue 46): no accepted input takes more than 60 s or
2 GB in any command.

    python benchmarks/limits_edges.py                 # every case, a table on stdout
    python benchmarks/limits_edges.py facts gen-cells # some cases
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from asprilo.limits import Limits

LIMITS = Limits()
RULE_SECONDS, RULE_MB = 60.0, 2048


def _node_facts(width: int, height: int) -> str:
    return "".join(f"init(object(node,{x + (y - 1) * width}),value(at,({x},{y}))).\n"
                   for y in range(1, height + 1) for x in range(1, width + 1))


def _robot(x: int = 1, y: int = 1) -> str:
    return f"init(object(robot,1),value(at,({x},{y}))).\n"


def facts_edge(folder: Path) -> tuple[list[str], str]:
    """An instance of ``facts - 999`` facts (the issue's 1,999,001): nodes and one robot; a one-move plan."""
    count = LIMITS.facts - 999
    width = 1999
    height, rest = divmod(count - 1, width)
    text = _node_facts(width, height) + "".join(
        f"init(object(node,{width * height + x}),value(at,({x},{height + 1}))).\n" for x in range(1, rest + 1))
    (folder / "instance.lp").write_text(text + _robot())
    (folder / "plan.lp").write_text("occurs(object(robot,1),action(move,(1,0)),1).\n")
    return ["check", "instance.lp", "plan.lp"], f"check: {count:,} facts"


def robot_steps_edge(folder: Path) -> tuple[list[str], str]:
    """One robot moving to and fro for ``robot-steps`` steps, every step valid."""
    steps = LIMITS.robot_steps
    (folder / "instance.lp").write_text(_node_facts(2, 1) + _robot())
    (folder / "plan.lp").write_text("".join(f"occurs(object(robot,1),action(move,({1 if t % 2 else -1},0)),{t}).\n"
                                            for t in range(1, steps + 1)))
    return ["check", "instance.lp", "plan.lp"], f"check: 1 robot x {steps:,} steps"


def two_robot_steps_edge(folder: Path) -> tuple[list[str], str]:
    """Two robots, each moving to and fro on a row of its own for ``robot-steps`` / 2 steps:
    the same robot-steps as one robot, with twice the robots to keep apart at every step."""
    steps = LIMITS.robot_steps // 2
    robots = _robot() + "init(object(robot,2),value(at,(1,2))).\n"
    (folder / "instance.lp").write_text(_node_facts(2, 2) + robots)
    (folder / "plan.lp").write_text("".join(f"occurs(object(robot,{r}),action(move,({1 if t % 2 else -1},0)),{t}).\n"
                                            for t in range(1, steps + 1) for r in (1, 2)))
    return ["check", "instance.lp", "plan.lp"], f"check: 2 robots x {steps:,} steps"


def file_mb_edge(folder: Path) -> tuple[list[str], str]:
    """A file of ``file-mb`` MB less a kilobyte: comments, then a small instance."""
    size = LIMITS.file_mb * 2**20 - 1024
    tail = _node_facts(2, 1) + _robot()
    line = "%" + "x" * 1022 + "\n"
    with open(folder / "instance.lp", "w") as out:
        out.write(line * ((size - len(tail)) // len(line)))
        out.write(tail)
    return ["info", "instance.lp"], f"info: a file of {LIMITS.file_mb:,} MB less 1 kB"


def gen_cells_edge(folder: Path) -> tuple[list[str], str]:
    """gen of a floor of exactly ``gen-cells`` cells with one robot (the issue's case)."""
    width = 1000
    height = LIMITS.gen_cells // width
    return (["gen", "-x", str(width), "-y", str(height), "-r", "1", "-d", str(folder / "out")],
            f"gen -x {width} -y {height} -r 1")


def pixels_edge(folder: Path) -> tuple[list[str], str]:
    """A PNG picture of at most ``pixels`` pixels: a square floor, the largest --cell that fits."""
    from asprilo.visualizer.export import images
    side = 40
    (folder / "instance.lp").write_text(_node_facts(side, side) + _robot())
    cell = max(c for c in range(2, 2000)
               if _pixels(images, side, side, c, caption=False) <= LIMITS.pixels)
    return (["viz", "instance.lp", "--export", str(folder / "picture.png"), "--cell", str(cell)],
            f"viz --export png: {_pixels(images, side, side, cell, caption=False):,} pixels")


def animation_edge(folder: Path) -> tuple[list[str], str]:
    """A GIF of at most ``animation-pixels`` pixels in all: 1,001 frames (a robot moving to and
    fro for 100 steps, 10 frames a step), the largest --cell that fits."""
    from asprilo.visualizer.export import images
    side, horizon, per_step = 10, 100, 10
    frames = images.animation_frames(horizon, per_step)
    (folder / "instance.lp").write_text(_node_facts(side, side) + _robot())
    (folder / "plan.lp").write_text("".join(f"occurs(object(robot,1),action(move,({1 if t % 2 else -1},0)),{t}).\n"
                                            for t in range(1, horizon + 1)))
    cell = max(c for c in range(2, 2000)
               if frames * _pixels(images, side, side, c, caption=True) <= LIMITS.animation_pixels)
    pixels = frames * _pixels(images, side, side, cell, caption=True)
    return (["viz", "instance.lp", "plan.lp", "--export", str(folder / "plan.gif"), "--cell", str(cell),
             "--frames", str(per_step)], f"viz --export gif: {frames:,} frames, {pixels:,} pixels")


def _pixels(images, width: int, height: int, cell: int, caption: bool) -> int:
    w = round((width + 2 * images.PICTURE_MARGIN) * cell)
    h = round((height + 2 * images.PICTURE_MARGIN) * cell) + (images.caption_height(cell) if caption else 0)
    return w * h


CASES: dict[str, tuple[str, Callable[[Path], tuple[list[str], str]]]] = {
    "facts": ("facts", facts_edge),
    "robot-steps": ("robot_steps", robot_steps_edge),
    "robot-steps-2": ("robot_steps", two_robot_steps_edge),
    "file-mb": ("file_mb", file_mb_edge),
    "gen-cells": ("gen_cells", gen_cells_edge),
    "pixels": ("pixels", pixels_edge),
    "animation-pixels": ("animation_pixels", animation_edge),
}


def measure(command: list[str], folder: Path) -> dict:
    """Run ``command`` in a fresh measuring process: wall seconds, peak MB of it and its children, exit status."""
    script = ("import json, resource, subprocess, sys, time\n"
              "start = time.monotonic()\n"
              "done = subprocess.run(sys.argv[1:], capture_output=True, text=True)\n"
              "peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024\n"
              "print(json.dumps({'seconds': time.monotonic() - start, 'mb': peak, 'status': done.returncode,"
              " 'said': (done.stderr.strip().splitlines() or [''])[-1][:160]}))\n")
    asprilo = [sys.executable, "-m", "asprilo.cli"]
    out = subprocess.run([sys.executable, "-c", script, *asprilo, *command], cwd=folder, capture_output=True,
                         text=True, check=True)
    return json.loads(out.stdout)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", nargs="*", choices=[*CASES, []], metavar="CASE",
                        help=f"some of {', '.join(CASES)} (default: all)")
    args = parser.parse_args()
    print(f"{'limit':<17} {'value':>13}  {'case':<48} {'exit':>4} {'seconds':>8} {'peak MB':>8}  rule")
    worst = True
    for name in args.cases or CASES:
        field, build = CASES[name]
        with tempfile.TemporaryDirectory(prefix="edge-") as temp:
            folder = Path(temp)
            command, what = build(folder)
            result = measure(command, folder)
        within = result["seconds"] <= RULE_SECONDS and result["mb"] <= RULE_MB
        worst &= within
        print(f"{name:<17} {getattr(LIMITS, field):>13,}  {what:<48} {result['status']:>4} "
              f"{result['seconds']:>8.1f} {result['mb']:>8.0f}  {'ok' if within else 'BEYOND'}", flush=True)
        if result["status"] != 0:
            print(f"  said: {result['said']}", flush=True)
    print(f"(rule: at most {RULE_SECONDS:g} s and {RULE_MB:,} MB; {resource.getpagesize()} B pages, "
          f"measured {time.strftime('%Y-%m-%d')})")
    return 0 if worst else 1


if __name__ == "__main__":
    sys.exit(main())
