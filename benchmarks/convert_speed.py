"""Converting MovingAI data at scale: warehouse-10-20-10-2-1 (5,699 free cells), 1,000 agents.

Prints the time to convert the map + a 1,000-agent scenario into an asprilo instance
(anonymous and labelled), to compute its MAPF bounds (labelled: per agent; anonymous:
assignment), to convert a 100-step plan (a random walk of every robot) to a LaCAM
result.txt and back, and to check that plan with `check` (it is invalid: the walks collide
and end anywhere; the checker still goes through every step of every robot).
Run: python benchmarks/convert_speed.py
"""

from __future__ import annotations

import contextlib
import io
import json
import random
import tempfile
import time
from pathlib import Path

from asprilo.bounds import mapf_bounds
from asprilo.cli import main
from asprilo.interop.movingai import Task, format_scenario, parse_map
from asprilo.reader import read_instance
from asprilo.sources import Source

ROOT = Path(__file__).resolve().parent.parent
MAP = ROOT / "examples/movingai/warehouse-10-20-10-2-1.map"
AGENTS = 1000


def scenario(folder: Path) -> Path:
    grid = parse_map(Source.from_path(MAP))
    free = grid.free_cells()
    rng = random.Random(1)
    starts, goals = rng.sample(free, AGENTS), rng.sample(free, AGENTS)
    tasks = [Task(s, g, 0, 0.0, MAP.name, grid.width, grid.height) for s, g in zip(starts, goals, strict=True)]
    path = folder / "warehouse-random.scen"
    path.write_text(format_scenario(tasks))
    (folder / MAP.name).write_bytes(MAP.read_bytes())
    return path


def timed(label: str, action) -> object:
    started = time.perf_counter()
    result = action()
    print(f"{label}: {time.perf_counter() - started:.2f} s")
    return result


def main_() -> None:
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        scen = scenario(folder)
        target = folder / "agents.lp"
        timed(f"convert map + scenario ({AGENTS} agents) -> asprilo",
              lambda: main(["convert", str(scen), str(target), "--agents", str(AGENTS)]))
        instance = timed("read the converted instance", lambda: read_instance(target))

        print("  anonymous bounds (makespan, sum of costs):",
              timed("anonymous assignment bounds", lambda: mapf_bounds(instance)))
        timed("convert the instance back to .scen", lambda: main(["convert", str(target), str(folder / "b.scen")]))
        bound = folder / "labelled.lp"
        timed(f"convert map + scenario ({AGENTS} agents) -> labelled asprilo",
              lambda: main(["convert", str(scen), str(bound), "--agents", str(AGENTS), "--labelled"]))
        labelled = timed("read the labelled instance", lambda: read_instance(bound))
        print("  labelled bounds (makespan, sum of costs):",
              timed("labelled bounds", lambda: mapf_bounds(labelled)))
        plan = folder / "walk.lp"
        plan.write_text(random_walk(instance, 100))
        result = folder / "result.txt"
        timed("convert the 100-step plan -> result.txt", lambda: main(
            ["convert", str(plan), str(result), "--instance", str(target)]))
        timed("convert result.txt -> plan", lambda: main(
            ["convert", str(result), str(folder / "back.lp"), "--instance", str(target)]))
        for name, path in (("anonymous", target), ("labelled", bound)):
            started = time.perf_counter()
            with contextlib.redirect_stdout(io.StringIO()) as report:
                code = main(["check", str(path), str(plan), "--json"])
            errors = json.loads(report.getvalue())["errors"]
            print(f"check the 100-step plan ({name}): {time.perf_counter() - started:.2f} s "
                  f"(exit {code}, {len(errors)} violations)")


def random_walk(instance, steps: int) -> str:
    """Every robot steps to a random free neighbour at every step."""
    rng = random.Random(2)
    cells = instance.cells
    lines = []
    for robot, state in sorted(instance.robots.items()):
        x, y = state.at
        for step in range(1, steps + 1):
            moves = [(dx, dy) for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1)) if (x + dx, y + dy) in cells]
            dx, dy = rng.choice(moves)
            x, y = x + dx, y + dy
            lines.append(f"occurs(object(robot,{robot}),action(move,({dx},{dy})),{step}).")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    main_()
