"""The window's online link (offscreen): solver and simulator servers on 127.0.0.1 ephemeral
ports, orders arriving while the robots are under way, and links that fail."""

from __future__ import annotations

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import socket  # noqa: E402

import pytest  # noqa: E402
from helpers.online import ORDER_2, TINY, WAIT  # noqa: E402
from helpers.viewer import shown_window  # noqa: E402
from PyQt5.QtCore import Qt  # noqa: E402

from asprilo.online.serve import listen  # noqa: E402
from asprilo.visualizer.jobs import network  # noqa: E402

pytestmark = pytest.mark.gui


@pytest.fixture
def window(qtbot, tmp_path_factory):
    window = shown_window(qtbot, tmp_path_factory)
    window.player.set_speed(64)
    return window


def test_orders_arrive_and_robots_are_replanned_live(window, qtbot, servers):
    solver_port, simulator_port, online = servers
    session = window.live.connect_to("127.0.0.1", solver_port, simulator_port)
    assert not window.editor.palette.isEnabled()  # the world belongs to the session
    seen_orders: dict[int, list[int]] = {}
    verdicts: dict[int, str] = {}

    def shown(step: int) -> None:
        seen_orders.setdefault(step, sorted(window.scenario.instance.orders))
        verdicts.setdefault(step, window.status_line.verdict.text())

    window.player.step_changed.connect(shown)
    qtbot.waitUntil(lambda: window.live.session is None, timeout=int(WAIT * 1000))
    assert window.live.last_reason.startswith("the solver has nothing more to do after step")
    assert online.facts[-1] == ORDER_2  # the simulator's order reached the solver ...
    # ... and the window once state 3 was shown (robots can act on it from step 4 on)
    assert seen_orders[3] == [1] and seen_orders[4] == [1, 2]
    plan = window.scenario.plan
    assert plan.actions == session.actions and window.track.horizon == plan.horizon
    deliveries = [a for a in plan.actions if a.name == "deliver" and a.args[0] == 2]
    assert deliveries and min(a.step for a in deliveries) >= 4
    assert not window.track.violations  # valid, and every order complete (the goal is checked now)
    assert window.track.state(plan.horizon).open_lines == {}
    assert window.player.time == plan.horizon
    assert window.editor.palette.isEnabled()
    assert "Online session ended" in window.statusBar().currentMessage()
    assert "no rule broken so far" in verdicts[2] and "valid plan" in window.status_line.verdict.text()


def test_solver_alone_plans_for_the_instance_shown(window, qtbot, servers, write):
    solver_port, _simulator_port, _online = servers
    window.open_files([str(write("tiny.lp", TINY))])
    assert window.live.connect_to("127.0.0.1", solver_port) is not None
    qtbot.waitUntil(lambda: window.live.session is None, timeout=int(WAIT * 1000))
    assert window.live.last_reason.startswith("the solver has nothing more to do after step")
    assert window.track.horizon >= 4 and not window.track.violations
    assert {a.args[0] for a in window.scenario.plan.actions if a.name == "deliver"} == {1, 2}


def test_links_that_fail_end_the_session_with_a_message(window, qtbot, monkeypatch):
    closed = socket.socket()
    closed.bind(("127.0.0.1", 0))
    port = closed.getsockname()[1]
    closed.close()  # nobody listens there
    window.editor.new_instance(2, 2)
    window.live.connect_to("127.0.0.1", port)
    qtbot.waitUntil(lambda: window.live.session is None, timeout=int(WAIT * 1000))
    assert window.live.last_reason == f"the solver at 127.0.0.1:{port}: Connection refused"
    silent = listen("127.0.0.1", 0)  # accepts connections, never answers
    silent_port = silent.getsockname()[1]
    monkeypatch.setattr(network, "SOLVER_SECONDS", 0.5)
    try:
        window.live.connect_to("127.0.0.1", silent_port)
        qtbot.waitUntil(lambda: window.live.session is None, timeout=int(WAIT * 1000))
    finally:
        silent.close()
    assert window.live.last_reason == f"the solver at 127.0.0.1:{silent_port} did not answer within 0.5 s"
    assert window.editor.palette.isEnabled()


def test_viz_online_options_are_checked(write):
    import subprocess
    import sys
    for args, message in ((["--simulator", "5001"], "error: --simulator goes with --solver"),
                          (["--solver", "5000"], "error: --solver needs an INSTANCE to plan for"),
                          ([str(write("tiny.lp", TINY)), "--solver", "5000", "--export", "x.png"],
                           "error: --solver and --export do not go together")):
        result = subprocess.run([sys.executable, "-m", "asprilo.cli", "viz", *args], capture_output=True, text=True,
                                timeout=WAIT)
        assert result.returncode == 2 and result.stderr.startswith(message), result.stderr


def test_an_order_written_during_the_session_reaches_the_solver_and_is_delivered(window, qtbot, servers, write):
    solver_port, _simulator_port, online = servers
    window.open_files([str(write("one-order.lp", TINY.replace(ORDER_2, "")))])
    assert sorted(window.scenario.instance.orders) == [1]
    sent_after: list[int] = []

    def write_order_2(_change) -> None:  # as soon as the actions of step 1 are in
        if sent_after or window.track.horizon < 1:
            return
        orders = window.editor.orders
        assert orders.buttons["send"].isVisible() and orders.isEnabled()
        assert orders.model.rows == []  # the world's orders are not drafts
        assert orders.add_order()
        model = orders.model
        assert model.setData(model.index(0, 1), 2) and model.setData(model.index(0, 2), 2)  # product 2, 2 units
        assert window.editor.send_drafts()
        sent_after.append(window.live.session.frontier)

    window.state.track_changed.connect(write_order_2)
    assert window.live.connect_to("127.0.0.1", solver_port) is not None
    assert not window.editor.palette.isEnabled()  # the layout belongs to the session, orders do not
    qtbot.waitUntil(lambda: window.live.session is None, timeout=int(WAIT * 1000))
    assert window.live.last_reason.startswith("the solver has nothing more to do after step")
    assert sent_after == [1] and online.facts[-1] == ORDER_2  # the solver got exactly order 2's facts
    assert sorted(window.scenario.instance.orders) == [1, 2]
    deliveries = [a for a in window.scenario.plan.actions if a.name == "deliver" and a.args[0] == 2]
    assert deliveries and min(a.step for a in deliveries) >= 2  # known after step 1: acted on from step 2
    assert not window.track.violations and window.track.state(window.track.horizon).open_lines == {}
    assert not window.editor.orders.buttons["send"].isVisible() and window.editor.palette.isEnabled()


def test_the_end_of_a_session_stays_shown_until_dismissed(window, qtbot, servers, write):
    solver_port, _simulator_port, _online = servers
    window.open_files([str(write("tiny.lp", TINY))])
    assert not window.banner.isVisible()
    window.live.connect_to("127.0.0.1", solver_port)
    qtbot.waitUntil(lambda: window.live.session is None, timeout=int(WAIT * 1000))
    assert window.banner.isVisible()
    assert window.banner.text.text() == f"<b>Online session ended:</b> {window.live.last_reason}"
    qtbot.mouseClick(window.banner.dismiss, Qt.LeftButton)
    assert not window.banner.isVisible()


def test_drafts_are_refused_while_they_cannot_be_sent_and_can_be_discarded(window, qtbot, servers, write):
    solver_port, _simulator_port, _online = servers
    window.open_files([str(write("tiny.lp", TINY))])
    window.player.set_speed(0.25)  # slowly: the session runs while the drafts are written
    window.live.connect_to("127.0.0.1", solver_port)
    qtbot.waitUntil(lambda: window.editor.drafts is not None and window.track.horizon >= 1, timeout=int(WAIT * 1000))
    orders = window.editor.orders
    assert not window.editor.send_drafts()
    assert window.editor.last_message == "no orders to send: add one first"
    orders.add_order()
    model = orders.model
    model.setData(model.index(0, 1), 7)  # a product no shelf holds
    assert not window.editor.send_drafts()
    assert window.editor.last_message == "order 3 asks for product 7, which no shelf holds"
    window.editor.discard_drafts()
    assert model.rows == [] and sorted(window.scenario.instance.orders) == [1, 2]
    window.live.disconnect()
    assert window.live.last_reason == "disconnected" and window.editor.drafts is None
