"""How fast instances are read: the paper's 46x15 instance and a 10,000-robot warehouse.

Run: python benchmarks/read_speed.py
"""

from __future__ import annotations

import statistics
import tempfile
import time
from pathlib import Path

from asprilo.model import Instance, Order, PickingStation, Product, Robot, Shelf
from asprilo.reader import read_instance
from asprilo.writer import write_instance

ROOT = Path(__file__).resolve().parent.parent
PAPER = ROOT / "examples/paper-m/4x5x8/x46_y15_n690_r46_s320_ps10_pr320_u320_o46_N001.lp"


def big_instance(width: int = 200, height: int = 200, robots: int = 10_000) -> Instance:
    """A full grid with a highway every third row, robots on highways, shelves elsewhere."""
    instance = Instance()
    free_rows = []
    for y in range(1, height + 1):
        for x in range(1, width + 1):
            node = (y - 1) * width + x
            instance.nodes[node] = (x, y)
            if y % 3 == 1:
                instance.highways[node] = (x, y)
        (free_rows if y % 3 != 1 else []).append(y)
    highway_cells = sorted(instance.highways.values(), key=lambda c: (c[1], c[0]))
    storage = sorted(instance.storage_cells, key=lambda c: (c[1], c[0]))
    for i, cell in enumerate(highway_cells[:robots], 1):
        instance.robots[i] = Robot(i, cell)
    for i, cell in enumerate(storage[:robots], 1):
        instance.shelves[i] = Shelf(i, cell)
        instance.products[i] = Product(i, {i: 1})
    for i in range(1, 11):
        instance.stations[i] = PickingStation(i, (i * 10, 1))
    for i in range(1, robots + 1):
        instance.orders[i] = Order(i, {i: 1}, 1 + i % 10)
    return instance


def timed(path: Path, repeat: int = 5) -> float:
    times = []
    for _ in range(repeat):
        started = time.perf_counter()
        read_instance(path)
        times.append(time.perf_counter() - started)
    return statistics.median(times)


def main() -> None:
    print(f"paper 46x15, 46 robots ({PAPER.stat().st_size // 1024} KiB): "
          f"{timed(PAPER):.3f} s (median of 5)")
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "big.lp"
        write_instance(path, big_instance())
        size = path.stat().st_size / 2**20
        print(f"200x200, 10,000 robots, 10,000 shelves/products/orders ({size:.1f} MiB): "
              f"{timed(path, 3):.3f} s (median of 3)")


if __name__ == "__main__":
    main()
