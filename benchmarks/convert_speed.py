"""Converting MovingAI data at scale: warehouse-10-20-10-2-1 (5,699 free cells), 1,000 agents.

Prints the time to convert the map + a 1,000-agent scenario into an asprilo instance, to
compute its MAPF bounds (labelled: per agent; anonymous: assignment), and, when the
checker is installed, to check an (empty) plan against it.
Run: python benchmarks/convert_speed.py
"""

from __future__ import annotations

import random
import tempfile
import time
from pathlib import Path

import numpy as np

from asprilo.bounds import Floor, mapf_bounds
from asprilo.cli import main
from asprilo.movingai import Task, format_scenario, parse_map
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
    tasks = [Task(s, g, 0, 0.0, MAP.name, grid.width, grid.height) for s, g in zip(starts, goals)]
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

        def labelled():
            floor = Floor(instance.cells)
            starts = [r.at for _i, r in sorted(instance.robots.items())]
            goals = [d.at for _i, d in sorted(instance.destinations.items())]
            table = floor.distances(starts, goals)
            pairs = np.diag(table)
            return pairs.max(), pairs.sum()

        print("  labelled bounds (max, sum):", timed("labelled bounds", labelled))
        print("  anonymous bounds (makespan, sum of costs):",
              timed("anonymous assignment bounds", lambda: mapf_bounds(instance)))
        timed("convert the instance back to .scen", lambda: main(["convert", str(target), str(folder / "b.scen")]))


if __name__ == "__main__":
    main_()
