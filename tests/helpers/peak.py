"""Run asprilo as a user would, in this process, and say this process's peak memory last, on
standard error: ``peak N`` (megabytes, the peak of this program alone, Linux's VmHWM: the
child processes it starts are not counted, nor the process that started it, whose peak
``ru_maxrss`` carries across exec: a test run late in a big pytest process read 600 MB).

    python tests/helpers/peak.py cli ARGUMENT...            # asprilo ARGUMENT...
    python tests/helpers/peak.py viewer INSTANCE ENCODING   # Run > Solve with encoding file

The viewer runs offscreen: the instance opened, the encoding solved by the window's job
runner (``solve_files``), then one line on standard output: the error the window reported,
or ``plan N`` (the actions of the plan it shows)."""

from __future__ import annotations

import os
import sys
import tempfile
import time

#: a hang guard (seconds), not a timing
PATIENCE = 600


def _viewer(instance: str, encoding: str) -> int:
    os.environ["QT_QPA_PLATFORM"] = "offscreen"
    from PyQt5.QtCore import QSettings
    from PyQt5.QtWidgets import QApplication

    application = QApplication([])
    from asprilo.visualizer.window import MainWindow

    with tempfile.TemporaryDirectory() as folder:
        window = MainWindow(QSettings(os.path.join(folder, "viz.ini"), QSettings.IniFormat))
        window.show()
        window.open_files([instance])
        window.jobs.solve_files([encoding], time_limit=60)
        guard = time.monotonic() + PATIENCE
        while window.jobs.job is not None and time.monotonic() < guard:
            application.processEvents()
            time.sleep(0.01)
        print(window.state.last_error or f"plan {len(window.scenario.plan)}", flush=True)
    return 0  # (the window is not closed: it would ask whether to keep the plan shown)


def main() -> int:
    kind, *arguments = sys.argv[1:]
    if kind == "viewer":
        code = _viewer(*arguments)
    else:
        from asprilo.cli import main as asprilo

        code = asprilo(arguments)
    sys.stdout.flush()
    from asprilo.isolation import peak_memory_mb

    print(f"peak {int(peak_memory_mb())}", file=sys.stderr, flush=True)
    return code


if __name__ == "__main__":
    sys.exit(main())
