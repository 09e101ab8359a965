"""How quickly the editor, the GUI jobs and the online link respond (issue 7), offscreen.

- edit: one edit in the window (the change, the scene updated, the plan's states computed
  again, the panels refreshed), median of several, on the 200x200 warehouse of
  viz_speed.py (1,000 robots, 5,000 shelves) and on the small example instance;
- solve: the longest pause of the window's event loop (a 10 ms timer) while the solver
  runs in the background on the small example for a few seconds, then cancel -> idle;
- online: solver and simulator servers on 127.0.0.1 ephemeral ports, a plain socket
  client in place of the window; a random 7x5 warehouse (2 robots, 3 orders, one order
  arriving every 3 steps): milliseconds per step for the whole round trip (simulator
  and solver), split into steps with and without re-planning.

Usage: python benchmarks/editor_online_speed.py [--repeat 5]
"""

from __future__ import annotations

import argparse
import os
import random
import statistics
import sys
import threading
import time
from itertools import pairwise
from pathlib import Path

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
sys.path.insert(0, str(Path(__file__).resolve().parent))

from PyQt5.QtCore import QEventLoop, QSettings, QTimer  # noqa: E402
from PyQt5.QtWidgets import QApplication  # noqa: E402
from viz_speed import build_instance  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
SMALL = ROOT / "examples/asprilo/dom-a/small/x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp"


def median_ms(values: list[float]) -> str:
    return f"{1000 * statistics.median(values):7.1f} ms"


def edit_latency(app, window, repeat: int) -> dict[str, list[float]]:
    """Seconds per edit of each kind (each edit is undone again, so all run on the same instance)."""
    editor = window.editor
    instance = editor.document.instance
    taken = {s.at for s in instance.shelves.values()} | {r.at for r in instance.robots.values()} \
        | {s.at for s in instance.stations.values()}
    free = sorted(instance.storage_cells - taken)
    robot = min(instance.robots)
    times: dict[str, list[float]] = {"add shelf": [], "move robot": [], "toggle highway": [], "undo": []}
    for i in range(repeat):
        cell = free[(7 * i) % len(free)]
        for kind, edit in (("add shelf", lambda cell=cell: editor.add("shelf", cell)),
                           ("move robot", lambda cell=cell: editor.move("robot", robot, cell)),
                           ("toggle highway", lambda cell=cell: editor.set_floor(cell, "highway")),
                           ("undo", editor.document.history.undo)):
            started = time.perf_counter()
            edit()
            app.processEvents()
            times[kind].append(time.perf_counter() - started)
            if kind != "undo":
                editor.document.history.undo()
                app.processEvents()
        editor.add("shelf", cell)  # for the timed undo of the next round
    editor.document.history.clear()  # nothing unsaved: closing asks nothing
    return times


def solve_responsiveness(app, window, seconds: float) -> tuple[float, float]:
    """(longest event-loop pause, seconds from cancel to idle) while solving the small example."""
    window.open_files([str(SMALL)])
    ticks: list[float] = []
    timer = QTimer()
    timer.timeout.connect(lambda: ticks.append(time.perf_counter()))
    timer.start(10)
    window.jobs.solve()
    started = time.perf_counter()
    while time.perf_counter() - started < seconds:
        app.processEvents(QEventLoop.AllEvents, 5)
    cancelled = time.perf_counter()
    window.jobs.cancel()
    while window.jobs.job is not None:
        app.processEvents(QEventLoop.AllEvents, 5)
    idle = time.perf_counter() - cancelled
    timer.stop()
    return max(b - a for a, b in pairwise(ticks)), idle


def online_steps() -> tuple[list[float], list[float], int]:
    """Seconds per step without and with re-planning, and the plan's length."""
    from asprilo.generator import GeneratorConfig, generate
    from asprilo.online.planner import OnlinePlanner, Schedule, encodings_planner
    from asprilo.online.protocol import DONE, END, Channel, Message, read_actions, reset
    from asprilo.online.serve import listen, serve, simulator_session, solver_session

    config = GeneratorConfig.from_options({"-x": 7, "-y": 5, "-p": 1, "-s": 6, "-P": 3, "-u": 12, "-r": 2, "-o": 3})
    instance = generate(config, 1, seed=7)[0].instance
    schedule = Schedule.every(instance, 3)
    online = OnlinePlanner(encodings_planner(time_limit=60))
    stop = threading.Event()
    solver, simulator = listen("127.0.0.1", 0), listen("127.0.0.1", 0)
    for listener, session in ((solver, lambda c: solver_session(c, online)),
                              (simulator, lambda c: simulator_session(c, schedule, lambda _t: None))):
        threading.Thread(target=serve, args=(listener, session), kwargs={"stop": stop}, daemon=True).start()
    to_solver = Channel.connect("127.0.0.1", solver.getsockname()[1])
    to_simulator = Channel.connect("127.0.0.1", simulator.getsockname()[1])
    to_simulator.send(reset())
    world = to_simulator.receive()
    to_solver.send(reset())
    to_solver.send(Message(world.facts))
    plain, replanned, actions, ended = [], [], 0, world.control == END
    for step in range(200):
        started = time.perf_counter()
        to_simulator.send(Message(control=DONE, step=step))
        news = to_simulator.receive()
        ended = ended or news.control == END
        to_solver.send(Message(news.facts, DONE, step))
        answer = read_actions(to_solver.receive().facts)
        (replanned if news.facts or step == 0 else plain).append(time.perf_counter() - started)
        if ended and not answer:
            break
        actions += len(answer)
    to_solver.close()
    to_simulator.close()
    stop.set()
    return plain, replanned, actions


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    app = QApplication(sys.argv[:1])
    from asprilo.reader import read_instance
    from asprilo.visualizer.state.loading import Scenario
    from asprilo.visualizer.window import MainWindow

    settings = QSettings(str(Path(os.environ.get("TMPDIR", "/tmp")) / "asprilo-bench-viz.ini"), QSettings.IniFormat)
    window = MainWindow(settings)
    window.resize(1360, 860)
    window.show()
    for title, instance in (("200x200, 1,000 robots, 5,000 shelves", build_instance(200, 1000, 5000, random.Random(1))),
                            ("small example (11x6, 3 robots, 12 shelves)", read_instance(SMALL))):
        window.show_scenario(Scenario(instance))
        app.processEvents()
        print(f"edit latency, {title} (median of {args.repeat}):")
        for kind, times in edit_latency(app, window, args.repeat).items():
            print(f"  {kind:<16}{median_ms(times)}   (max {1000 * max(times):.1f} ms)")
    pause, idle = solve_responsiveness(app, window, 4.0)
    print(f"solving in the background: longest event-loop pause {1000 * pause:.0f} ms; "
          f"cancel -> idle {1000 * idle:.0f} ms")
    plain, replanned, actions = online_steps()
    print(f"online link (7x5, 2 robots, 3 orders arriving at steps 0, 3, 6; {actions} actions, "
          f"{len(plain) + len(replanned)} steps):")
    print(f"  step without re-planning  {median_ms(plain)}   (max {1000 * max(plain):.1f} ms, {len(plain)} steps)")
    print(f"  step with re-planning     {median_ms(replanned)}   (max {1000 * max(replanned):.1f} ms, "
          f"{len(replanned)} steps)")
    window.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
