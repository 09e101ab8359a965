"""The README's screenshots of the viewer: the whole window at 1366x768, taken on a real X
server (e.g. Xvfb), not offscreen: an M, an Md and an A instance, a plan with violations,
the editor refusing a drag, and an online session (``asprilo serve`` started here).

Usage (plans made with asprilo solve; see the README):
  Xvfb :77 -screen 0 1366x768x24 &
  DISPLAY=:77 python asprilo/visualizer/pictures/screenshots.py M-INSTANCE M-PLAN MD-INSTANCE MD-PLAN OUT-FOLDER
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
from pathlib import Path

from PyQt5.QtCore import QEvent, QPointF, QSettings, Qt
from PyQt5.QtGui import QMouseEvent
from PyQt5.QtTest import QTest
from PyQt5.QtWidgets import QApplication

ROOT = Path(__file__).resolve().parents[2]
OUTCOME = ROOT / "examples/asprilo/dom-a/small/outcome.txt"
WRONG = ROOT / "examples/asprilo/dom-a/small/wrong_outcome.txt"


def shoot(window, path: Path) -> None:
    QTest.qWait(300)  # let the window settle (layout, fonts)
    window.grab().save(str(path))
    print(f"wrote {path} ({window.width()}x{window.height()})")


def main(m: str, m_plan: str, md: str, md_plan: str, out: str) -> int:
    from asprilo.visualizer.window import MainWindow

    app = QApplication(sys.argv[:1])  # noqa: F841 (the windows need it)
    folder = Path(out)
    settings = QSettings(str(Path(tempfile.mkdtemp()) / "viz.ini"), QSettings.IniFormat)
    window = MainWindow(settings)
    window.show()
    QTest.qWaitForWindowExposed(window)

    window.open_files([m], [m_plan])  # M: two robots under their shelves, robot 2's path
    window.go_to(4)
    window.select_robots([2])
    shoot(window, folder / "window-m.png")

    window.open_files([md], [md_plan])  # Md with labelled goals, zoomed in, the legend beside
    window.select_robots([])
    window.go_to(28)  # the robots on their way: each destination framed in its robot's colour
    window.view.zoom_by(40 / window.view.pixels_per_cell)
    window.view.centre_on_cell((24, 25))
    window.docks["legend"].raise_()
    shoot(window, folder / "window-md.png")

    window.open_files([str(OUTCOME)])  # A: shelf 1 at its station, the atoms pane
    window.docks["orders"].raise_()
    window.go_to(7)
    window.select_robots([3])
    window.docks["atoms"].raise_()
    shoot(window, folder / "window-a.png")

    window.open_files([str(WRONG)])  # a violation chosen in its panel
    window.docks["violations"].raise_()
    panel = window.panels["violations"]
    panel.table.clicked.emit(panel.proxy.index(1, 0))
    shoot(window, folder / "window.png")

    editor_picture(window, folder / "editor.png")
    live_picture(window, m, folder / "live.png")
    window.close()
    return 0


def editor_picture(window, path: Path) -> None:
    """Shelf 6 dragged onto a highway: the target cell is red, the status bar says why."""
    window.clear_selection()
    window.open_files([str(ROOT / "examples/asprilo/dom-a/small/x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp")])
    window.docks["order_editor"].raise_()
    window.docks["robots"].raise_()
    viewport = window.view.viewport()
    start = window.view.mapFromScene(window.stage.scene.shelves[6].pos())
    QTest.mousePress(viewport, Qt.LeftButton, pos=start)
    for step in range(1, 9):
        point = QPointF(start.x(), start.y() - step * 0.25 * window.view.pixels_per_cell)
        QApplication.sendEvent(viewport, QMouseEvent(QEvent.MouseMove, point, Qt.NoButton, Qt.LeftButton,
                                                     Qt.NoModifier))
    shoot(window, path)
    QTest.mouseRelease(viewport, Qt.LeftButton, pos=point.toPoint())


def live_picture(window, m_instance: str, path: Path) -> None:
    """A solver and a simulator (an order every 3 steps) on local ports, an order being written."""
    servers = [_serve("solver"), _serve("simulator", m_instance, "--every", "3")]
    try:
        (_, solver), (_, simulator) = servers
        window.open_files([m_instance])
        window.player.set_speed(1)
        window.live.connect_to("127.0.0.1", solver, simulator)
        for _ in range(600):
            QTest.qWait(50)
            if window.track is not None and window.track.horizon >= 3:
                break
        window.docks["order_editor"].raise_()
        window.editor.orders.add_order()
        shoot(window, path)
        window.live.disconnect()
    finally:
        for process, _port in servers:
            process.terminate()
            process.wait()


def _serve(*args: str) -> tuple[subprocess.Popen, int]:
    process = subprocess.Popen([sys.executable, "-m", "asprilo.cli", "serve", *args, "--port", "0", "--once"],
                               stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    line = process.stdout.readline()  # asprilo serve ROLE: listening on HOST:PORT
    return process, int(line.rsplit(":", 1)[1])


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:6]))
