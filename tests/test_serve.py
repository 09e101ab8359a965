"""The online link without a window: messages, the re-planning solver, the order simulator,
and both servers on 127.0.0.1 ephemeral ports driven by a plain socket client."""

from __future__ import annotations

import subprocess
import sys

import pytest
from helpers import SMALL_A
from helpers.clocks import patient_solves
from helpers.online import ORDER_2, TINY, WAIT, served, tiny

from asprilo import encodings
from asprilo.checker import check
from asprilo.encodings import SolveStatus
from asprilo.errors import InputError
from asprilo.model import Action, Plan
from asprilo.online.planner import OnlinePlanner, Schedule, anytime_planner, parse_arrivals, world_at
from asprilo.online.protocol import DONE, END, RESET, Channel, Message, done, parse, read_actions, read_world, reset
from asprilo.reader import read_instance
from asprilo.simulate import simulate

# --- messages -----------------------------------------------------------------------------------------

def test_messages_are_lines_of_facts_with_a_control_word_last():
    assert reset().text() == "%$RESET.\n"
    assert done(3).text() == "%$done(3).\n"
    assert Message("a. b.", DONE, 7).text() == "a. b. %$done(7).\n"
    assert Message("", END).text() == "%$end.\n"
    assert Message("").text() == "\n"
    assert parse("init(a,b). %$done(12).\r\n") == Message("init(a,b).", DONE, 12)
    assert parse("%$RESET.") == Message("", RESET)
    assert parse("occurs(x,y,1).\n") == Message("occurs(x,y,1).")
    for bad, words in (("%$done.", "malformed control word '%$done.'"),
                       ("%$RESET(2).", "malformed control word '%$RESET(2).'"),
                       ("a. %$stop.", "unknown control word in 'a. %$stop.'")):
        with pytest.raises(InputError) as error:
            parse(bad)
        assert error.value.message == words


def test_facts_of_several_messages_make_one_world():
    world = read_world([Schedule(tiny(), {2: 3}).world(), ORDER_2])
    assert world == tiny()
    assert read_actions("") == []
    assert read_actions("occurs(object(robot,1),action(move,(1,0)),4).") == [Action(4, 1, "move", (1, 0))]


# --- the simulator's schedule ---------------------------------------------------------------------------

def test_schedule_releases_orders_at_their_steps():
    schedule = Schedule(tiny(), parse_arrivals(["3:2"]))
    assert schedule.arrivals == {1: 0, 2: 3} and schedule.last == 3
    assert "order,2" not in schedule.world() and "order,1" in schedule.world()
    assert [schedule.arriving(t) for t in range(5)] == ["", "", "", ORDER_2, ""]
    assert Schedule.every(tiny(), 4).arrivals == {1: 0, 2: 4}
    with pytest.raises(InputError, match="the instance has no order 9"):
        Schedule(tiny(), {9: 1})
    with pytest.raises(InputError, match="expected STEP:ORDER"):
        parse_arrivals(["x:1"])


# --- the re-planning solver, with a planner that records what it is asked --------------------------------

def test_world_at_a_step_is_an_instance_of_its_own():
    instance = tiny()
    plan = Plan([Action(1, 1, "move", (1, 0)), Action(1, 2, "move", (1, 0)), Action(2, 2, "pickup"),
                 Action(2, 1, "move", (1, 0)), Action(3, 1, "move", (1, 0)), Action(4, 1, "deliver", (1, 1, 1))])
    now = world_at(instance, simulate(instance, plan).state(4))
    assert {r.id: (r.at, r.carries) for r in now.robots.values()} == {1: ((4, 1), 1), 2: ((3, 3), 2)}
    assert {s.id: s.at for s in now.shelves.values()} == {1: (4, 1), 2: (3, 3)}
    assert {p.id: p.stock for p in now.products.values()} == {2: {2: 3}}  # product 1 is used up
    assert {o.id: (o.lines, o.station) for o in now.orders.values()} == {2: ({2: 2}, 1)}


def test_online_planner_replans_from_the_state_reached_when_facts_arrive():
    asked: list[tuple[int, dict]] = []

    def planner(instance, domain, cancel):
        asked.append((len(asked), {r: robot.at for r, robot in instance.robots.items()},
                      sorted(instance.orders)))
        return Plan([Action(1, 1, "move", (1, 0)), Action(2, 1, "move", (1, 0))])

    online = OnlinePlanner(planner)
    online.learn(Schedule(tiny(), {2: 3}).world())
    assert online.next_actions(0) == [Action(1, 1, "move", (1, 0))]
    assert online.next_actions(1) == [Action(2, 1, "move", (1, 0))]
    assert online.next_actions(2) == []
    online.learn(ORDER_2)
    assert online.next_actions(3) == [Action(4, 1, "move", (1, 0))]
    assert online.next_actions(3) == [Action(4, 1, "move", (1, 0))]  # asked again: the same answer
    assert asked == [(0, {1: (1, 1), 2: (2, 3)}, [1]), (1, {1: (3, 1), 2: (2, 3)}, [1, 2])]
    online.reset()
    assert online.next_actions(0) == [] and len(asked) == 2  # nothing known: nothing planned


# --- the anytime method as the online planner -------------------------------------------------------

def run_online(online: OnlinePlanner, schedule: Schedule, steps: int = 200) -> Plan:
    """Ask for every step as the visualizer would, orders arriving as scheduled, until the
    last order is known and nothing is left to do; the plan sent."""
    online.learn(schedule.world())
    actions = []
    for step in range(steps):
        online.learn(schedule.arriving(step))
        answer = online.next_actions(step)
        if step >= schedule.last and not answer:
            break
        actions += answer
    return Plan(actions)


def test_the_anytime_planner_replans_when_an_order_arrives():
    plan = run_online(OnlinePlanner(anytime_planner(time_limit=WAIT)), Schedule(tiny(), {2: 3}))
    assert check(tiny(), plan).valid
    # order 1 alone: robot 1 carries shelf 1 along its only shortest way to the station;
    # robot 2 has nothing to do until order 2 arrives at step 3
    assert [a for a in plan.actions if a.step <= 3] == [Action(t, 1, "move", (1, 0)) for t in (1, 2, 3)]
    # then robot 1 delivers (step 4) and robot 2 needs 6 steps: onto shelf 2, pick it up,
    # 3 cells to the station, deliver (step 9)
    deliveries = sorted((a.step, a.robot, a.args) for a in plan.actions if a.name == "deliver")
    assert deliveries == [(4, 1, (1, 1, 1)), (9, 2, (2, 2, 2))] and plan.horizon == 9


def test_anytime_replanning_answers_at_its_time_limit_with_the_best_plan(monkeypatch):
    searches = []  # the outcome of each search the planner ran
    solve = encodings.solve

    def recorded(*args, **options):
        searches.append(solve(*args, **options))
        return searches[-1]

    monkeypatch.setattr(encodings, "solve", recorded)
    # the search at step 0 stops by itself, the one at step 2 runs out of time at its first plan
    clocks = patient_solves(monkeypatch, None, 1)
    instance = read_instance(SMALL_A)
    said: list[str] = []
    online = OnlinePlanner(anytime_planner(time_limit=5.0), log=said.append)
    plan = run_online(online, Schedule(instance, {3: 2}))
    assert check(instance, plan).valid
    assert simulate(instance, plan).state(plan.horizon).open_lines == {}
    # it planned at step 0 and again when order 3 arrived (step 2); every other step was
    # answered from the plan
    assert [line.split(":")[0] for line in said if "planning from" in line] == ["step 0", "step 2"]
    # each search answered with the best plan found: at step 0 (orders 1 and 2 only) one of the
    # lower bound's makespan, proven minimal by it; at step 2 (all three orders) its first plan
    # does not meet the bound, so that search ran to its time limit (the planner's cancel is
    # never set)
    assert [(o.status, o.method) for o in searches] == [(SolveStatus.FOUND, "anytime")] * 2
    assert [o.minimal for o in searches] == [o.horizon == o.lower_bound for o in searches] == [True, False]
    assert len(clocks) == 2 and clocks[1]() >= 5.0  # the second search stopped at its time limit


# --- both servers on loopback, a plain client -----------------------------------------------------------

def test_an_order_injected_at_step_3_is_delivered(servers):
    solver_port, simulator_port, _online = servers
    solver = Channel.connect("127.0.0.1", solver_port, timeout=WAIT)
    simulator = Channel.connect("127.0.0.1", simulator_port, timeout=WAIT)
    simulator.send(reset())
    world = simulator.receive()
    assert world.control is None and "order,2" not in world.facts
    solver.send(reset())
    solver.send(Message(world.facts))
    actions: list[Action] = []
    arrivals: dict[int, str] = {}
    ended = False
    for step in range(40):
        simulator.send(done(step))
        news = simulator.receive()
        ended = ended or news.control == END
        if news.facts:
            arrivals[step] = news.facts
        solver.send(Message(news.facts, DONE, step))
        answer = read_actions(solver.receive().facts)
        assert all(action.step == step + 1 for action in answer)
        if ended and not answer:
            break
        actions += answer
    solver.close()
    simulator.close()
    assert arrivals == {3: ORDER_2}
    plan = Plan(actions)
    timeline = simulate(tiny(), plan)
    assert timeline.valid, [v.message for v in timeline.violations]
    deliveries = [a for a in actions if a.name == "deliver" and a.args[0] == 2]
    assert deliveries and min(a.step for a in deliveries) > 4
    assert sum(a.args[2] for a in deliveries) == 2
    assert timeline.state(plan.horizon).open_lines == {}


def test_serve_solver_plans_with_the_anytime_method():
    with served("solver", "--method", "anytime", "--time-limit", "5") as server:
        channel = Channel.connect("127.0.0.1", server.port, timeout=WAIT)
        channel.send(reset())
        channel.send(Message(Schedule(tiny(), {2: 3}).world(), DONE, 0))
        assert read_actions(channel.receive().facts) == [Action(1, 1, "move", (1, 0))]
        channel.close()
        assert server.process.wait(WAIT) == 0
    assert "solver: step 0: planned 4 actions for steps 1..4" in server.errors


def test_serve_command_prints_its_port_and_rejects_bad_input(tmp_path):
    with served("solver") as server:
        assert server.first_line.startswith("asprilo serve solver: listening on 127.0.0.1:")
        channel = Channel.connect("127.0.0.1", server.port, timeout=WAIT)
        channel.send(reset())
        channel.send(done(0))
        assert channel.receive() == Message("")  # nothing known, nothing to do
        channel.close()
        assert server.process.wait(WAIT) == 0
    instance = tmp_path / "tiny.lp"
    instance.write_text(TINY)
    for args, message in ((["simulator", str(instance), "--at", "3:9"],
                           f"error: {instance}: the instance has no order 9"),
                          (["simulator", str(tmp_path / "none.lp")], f"error: {tmp_path / 'none.lp'}: no such file"),
                          (["simulator", str(instance), "--every", "0"], "error: --every needs K >= 1")):
        result = subprocess.run([sys.executable, "-m", "asprilo.cli", "serve", *args, "--port", "0"],
                                capture_output=True, text=True, timeout=WAIT)
        assert result.returncode == 2 and result.stderr.startswith(message), result.stderr
