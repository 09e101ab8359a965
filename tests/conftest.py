"""Shared test fixtures (shared helpers that are not fixtures live in ``helpers/``)."""

from __future__ import annotations

import gc
import sys
import threading
from pathlib import Path

import pytest
from helpers.online import WAIT, tiny

from asprilo.online.planner import OnlinePlanner, Schedule, encodings_planner
from asprilo.online.serve import listen, serve, simulator_session, solver_session


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The Qt tests (marker ``gui``) first, in a fresh process, the rest after them in their
    usual order.  Three times in eight CI runs of the whole suite a viewer test crashed
    (SIGSEGV) inside Qt while it made a menu or listed actions, never in a run here; the
    likely cause, wrappers of menus Qt made and deleted, is gone (panels/commands.submenu),
    and the viewer tests meet a clean process all the same."""
    items.sort(key=lambda item: item.get_closest_marker("gui") is None)


@pytest.fixture(autouse=True)
def registries_as_found():
    """A variant loaded or a domain registered in a test is known to this process only for that
    test: the registries of domains and object kinds are put back as they were."""
    from asprilo import objects
    from asprilo.domain import descriptor

    kinds, domains = dict(objects.KINDS), dict(descriptor._REGISTRY)
    yield
    objects.KINDS.clear()
    objects.KINDS.update(kinds)
    descriptor._REGISTRY.clear()
    descriptor._REGISTRY.update(domains)


@pytest.fixture(autouse=True)
def qt_objects_deleted_between_tests():
    """After each test, the widgets it closed are deleted and its Python garbage collected, here:
    not later, in the middle of another test (a window deleted while the next test walks its
    own widgets has crashed a run)."""
    yield
    widgets = sys.modules.get("PyQt5.QtWidgets")
    if widgets is None or widgets.QApplication.instance() is None:
        return
    from PyQt5.QtCore import QCoreApplication, QEvent

    QCoreApplication.sendPostedEvents(None, QEvent.DeferredDelete)
    gc.collect()
    QCoreApplication.sendPostedEvents(None, QEvent.DeferredDelete)


@pytest.fixture
def write(tmp_path):
    """write(name, text) -> path of a new file in a temporary directory."""

    def make(name: str, text: str) -> Path:
        path = tmp_path / name
        path.write_text(text)
        return path

    return make


@pytest.fixture
def servers():
    """A solver and a simulator (order 2 arrives at step 3) on ephemeral loopback ports."""
    stop = threading.Event()
    solver, simulator = listen("127.0.0.1", 0), listen("127.0.0.1", 0)
    online = OnlinePlanner(encodings_planner(time_limit=WAIT))
    schedule = Schedule(tiny(), {2: 3})
    threads = [threading.Thread(target=serve, args=(solver, lambda c: solver_session(c, online)),
                                kwargs={"stop": stop}, daemon=True),
               threading.Thread(target=serve, args=(simulator, lambda c: simulator_session(c, schedule, print)),
                                kwargs={"stop": stop}, daemon=True)]
    for thread in threads:
        thread.start()
    yield solver.getsockname()[1], simulator.getsockname()[1], online
    stop.set()
    for thread in threads:
        thread.join(WAIT)
    solver.close()
    simulator.close()
