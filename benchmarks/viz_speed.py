"""How fast the viewer loads and animates a big warehouse (issue targets: load <= 2 s,
>= 30 frames per second for 200x200 cells, 1,000 robots, 5,000 shelves).

Builds the instance with ``asprilo.model`` and a random collision-free plan of moves (a
fifth of the robots carry a shelf), writes both to a temporary folder, then measures,
offscreen:

- read: the two files through asprilo.reader (the core's reader, shared by all tools);
- load: from the Instance and Plan in memory: simulate all states, build scene and
  panels, show the first frame;
- frame: one animation frame (items moved, panels updated when the step changes, the
  view repainted) at "fit to window" and zoomed in.

Usage: python benchmarks/viz_speed.py [--size 200] [--robots 1000] [--shelves 5000]
       [--horizon 60] [--repeat 3] [--seed 1]
"""

from __future__ import annotations

import argparse
import os
import random
import statistics
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from PyQt5.QtCore import QEvent, QObject  # noqa: E402

from asprilo.model import DIRECTIONS, Action, Instance, Order, PickingStation, Plan, Product, Robot, Shelf  # noqa: E402
from asprilo.writer import write_instance, write_plan  # noqa: E402


def build_instance(size: int, robots: int, shelves: int, rng: random.Random) -> Instance:
    """A structured floor: 3-cell high storage rows between highways, a few pillars, stations on top."""
    instance = _floor(size)
    for ident, x in enumerate(range(6, size, 20), start=1):
        instance.stations[ident] = PickingStation(ident, (x, 1))
    storage = sorted(instance.storage_cells)
    rng.shuffle(storage)
    for ident, cell in enumerate(storage[:shelves], start=1):
        instance.shelves[ident] = Shelf(ident, cell)
    free = sorted(set(instance.highways.values()) - {s.at for s in instance.stations.values()})
    rng.shuffle(free)
    for ident, cell in enumerate(free[:robots], start=1):
        instance.robots[ident] = Robot(ident, cell)
    for ident in range(1, 201):
        instance.products[ident] = Product(ident, {rng.randint(1, shelves): rng.randint(1, 9)})
    for ident in range(1, 51):
        product = rng.randint(1, 200)
        instance.orders[ident] = Order(ident, {product: 1}, rng.randint(1, len(instance.stations)))
    # a fifth of the robots start under a shelf and carry it
    movers = list(instance.robots.values())[: robots // 5]
    spare = storage[shelves:]
    for robot, cell in zip(movers, spare, strict=False):  # as many as there are spare cells
        ident = len(instance.shelves) + 1
        robot.at = cell
        instance.shelves[ident] = Shelf(ident, cell)
        robot.carries = ident
    return instance


def _floor(size: int) -> Instance:
    """``size`` x ``size`` nodes but a few pillars; highways on the top rows, every 4th row
    and two columns of every twelve."""
    instance = Instance()
    for y in range(1, size + 1):
        for x in range(1, size + 1):
            if (x % 17, y % 13) == (8, 6):
                continue  # a pillar
            ident = len(instance.nodes) + 1
            instance.nodes[ident] = (x, y)
            if y <= 2 or y % 4 == 0 or x % 12 in (0, 1):
                instance.highways[ident] = (x, y)
    return instance


def random_plan(instance: Instance, horizon: int, rng: random.Random) -> Plan:
    """Random moves, no two robots on one cell, no swaps; carriers avoid resting shelves."""
    nodes = instance.cells
    resting = {s.at for s in instance.shelves.values()} - {instance.shelves[r.carries].at
                                                            for r in instance.robots.values() if r.carries}
    where = {r.id: r.at for r in instance.robots.values()}
    carriers = {r.id for r in instance.robots.values() if r.carries}
    actions = []
    for step in range(1, horizon + 1):
        taken = set(where.values())
        for robot in rng.sample(sorted(where), len(where)):
            if rng.random() < 0.15:
                continue  # wait
            x, y = where[robot]
            dx, dy = rng.choice(DIRECTIONS)
            target = (x + dx, y + dy)
            if target not in nodes or target in taken or (robot in carriers and target in resting):
                continue
            taken.discard(where[robot])
            taken.add(target)
            where[robot] = target
            actions.append(Action(step, robot, "move", (dx, dy)))
    return Plan(actions)


def measure_load(scenario):
    """Seconds from an Instance and Plan in memory to the window showing step 0."""
    from PyQt5.QtCore import QSettings
    from PyQt5.QtWidgets import QApplication

    from asprilo.visualizer.window import MainWindow

    settings = QSettings(str(Path(tempfile.mkdtemp()) / "viz.ini"), QSettings.IniFormat)
    window = MainWindow(settings)
    window.resize(1600, 1000)
    window.show()
    QApplication.instance().processEvents()
    start = time.perf_counter()
    window.show_scenario(scenario)
    window.view.viewport().repaint()
    return time.perf_counter() - start, window


def load_parts(scenario) -> dict[str, float]:
    """The viewer's load split into its parts."""
    from asprilo.simulate import simulate
    from asprilo.visualizer.scene.animator import Animator
    from asprilo.visualizer.scene.warehouse import WarehouseScene
    from asprilo.visualizer.state.track import Track

    parts, start = {}, time.perf_counter()
    simulate(scenario.instance, scenario.plan)
    parts["simulator"], start = time.perf_counter() - start, time.perf_counter()
    track = Track(scenario.instance, scenario.plan)
    parts["simulator + state arrays"], start = time.perf_counter() - start, time.perf_counter()
    scene = WarehouseScene(scenario.instance)
    Animator(scene, track).show(0)
    parts["scene + first frame"] = time.perf_counter() - start
    return parts


class PaintCounter(QObject):
    """Counts the paint events of a widget (to check that a frame paints the view once)."""

    def __init__(self):
        super().__init__()
        self.paints = 0

    def eventFilter(self, _watched, event) -> bool:
        if event.type() == QEvent.Paint:
            self.paints += 1
        return False


def measure_frames(window, frames_per_step: int, steps: int) -> tuple[list[float], float]:
    """Seconds per frame while the player walks through ``steps`` steps (items moved, panels,
    slider and labels updated, everything repainted by the event loop, as when playing), and
    the view's paints per frame."""
    from PyQt5.QtWidgets import QApplication
    app, player, viewport = QApplication.instance(), window.player, window.view.viewport()
    counter = PaintCounter()
    viewport.installEventFilter(counter)
    times = []
    for k in range(steps * frames_per_step):
        start = time.perf_counter()
        player.seek(k / frames_per_step)
        app.processEvents()
        times.append(time.perf_counter() - start)
    viewport.removeEventFilter(counter)
    return times, counter.paints / len(times)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=200)
    parser.add_argument("--robots", type=int, default=1000)
    parser.add_argument("--shelves", type=int, default=5000)
    parser.add_argument("--horizon", type=int, default=60)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()

    from PyQt5.QtWidgets import QApplication
    app = QApplication(sys.argv[:1])  # noqa: F841

    rng = random.Random(args.seed)
    instance = build_instance(args.size, args.robots, args.shelves, rng)
    plan = random_plan(instance, args.horizon, rng)
    folder = Path(tempfile.mkdtemp(prefix="viz_speed_"))
    instance_path, plan_path = folder / "instance.lp", folder / "plan.lp"
    write_instance(instance_path, instance)
    write_plan(plan_path, plan)
    c = instance.counts()
    print(f"instance: {c['x']}x{c['y']}, {c['nodes']} nodes, {c['robots']} robots, {c['shelves']} shelves; "
          f"plan: {len(plan)} actions, horizon {plan.horizon}", flush=True)

    from asprilo.visualizer.state.loading import load_scenario
    reads = []
    for _ in range(args.repeat):
        start = time.perf_counter()
        scenario = load_scenario([str(instance_path)], [str(plan_path)])
        reads.append(time.perf_counter() - start)
    print(f"read both files (asprilo.reader), median of {args.repeat}: {statistics.median(reads):.2f} s "
          f"(all: {', '.join(f'{s:.2f}' for s in reads)})")
    loads, windows = [], []
    for _ in range(args.repeat):
        seconds, window = measure_load(scenario)
        loads.append(seconds)
        windows.append(window)
    print(f"viewer load (Instance + Plan -> window showing step 0), median of {args.repeat}: "
          f"{statistics.median(loads):.2f} s (all: {', '.join(f'{s:.2f}' for s in loads)})")
    parts = load_parts(scenario)
    print("  parts: " + ", ".join(f"{name} {seconds:.2f} s" for name, seconds in parts.items()))

    window = windows[-1]
    for label, zoom in (("fit to window", None), ("zoomed in, 40 px per cell", 40.0)):
        window.view.fit()
        if zoom:
            window.view.zoom_by(zoom / window.view.pixels_per_cell)
        measure_frames(window, 10, 2)  # warm up
        frames, paints = measure_frames(window, 10, min(20, plan.horizon))
        ms = sorted(1000 * f for f in frames)
        median, p95 = statistics.median(ms), ms[int(0.95 * (len(ms) - 1))]
        print(f"frame ({label}, {window.view.pixels_per_cell:.1f} px/cell, view "
              f"{window.view.viewport().width()}x{window.view.viewport().height()}): median {median:.1f} ms "
              f"= {1000 / median:.0f} fps, 95th percentile {p95:.1f} ms, slowest {ms[-1]:.1f} ms "
              f"({len(ms)} frames, 10 per step, {paints:.1f} view paints per frame)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
