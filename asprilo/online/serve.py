"""Serve the online link: a solver that re-plans as orders arrive, or a simulator releasing orders over time.

The solver plans step by step and re-plans when orders arrive; the simulator releases an
instance's orders over time.  The visualizer connects to
both (Online > Connect…) and plays what they say; see asprilo/visualizer/README.md for the protocol.

Examples:
  asprilo serve solver --port 5000
  asprilo serve solver --method anytime --time-limit 5             (each answer after about 5 s: the best plan by then)
  asprilo serve simulator instance.lp --port 5001 --every 4        (one order every 4 steps)
  asprilo serve simulator instance.lp --at 3:2 --at 8:3,4          (order 2 at step 3, 3 and 4 at step 8)
  asprilo serve solver --port 0                                     (any free port; the port is printed)

Both listen on 127.0.0.1 (loopback) by default and run until interrupted (Ctrl+C), or for
one session with --once.  Each client is served on its own (up to --clients at once) and
with a session of its own; a client silent for --idle-timeout seconds is let go.  Each line
must arrive whole within the line-seconds limit from its first byte (a client's first line:
from connecting), and each answer be taken within it (--limit line-seconds=S, default 60), so
slow clients hold a place no longer.  A session lasts at most --session-seconds (default an
hour) and sends at most --lines-per-minute lines, so a client trickling short lines holds a
place no longer either; unfinished lines and the facts kept for sessions take at most
--memory-mb (default 512) for all clients together.  A line that is refused (not UTF-8, too long, too slow,
not facts, a step outside the plan) is answered with an error (``%$error.``) and the
connection closes; the server goes on.  Messages are data: parsed as facts, never handed to
clingo as text, so no client makes the server open a file.
"""

from __future__ import annotations

import argparse
import contextlib
import select
import socket
import sys
import threading
from collections.abc import Callable

from asprilo.arguments import domain_argument, limit_argument, port_argument, seconds_argument
from asprilo.errors import InputError
from asprilo.limits import current, using

from .budgets import LINES_PER_MINUTE, MEMORY_MB, SESSION_SECONDS, MemoryPool, SessionBudget
from .planner import OnlinePlanner, Planner, Schedule, anytime_planner, encodings_planner, parse_arrivals
from .protocol import DONE, END, RESET, Channel, Message, action_facts, check_facts, error

DEFAULT_PORTS = {"solver": 5000, "simulator": 5001}
CLIENTS = 16  # clients served at once
IDLE_SECONDS = 3600.0  # a client silent this long is let go
GOODBYE_SECONDS = 1.0  # the last line to a client (an error) is given up after this long


def configure(parser: argparse.ArgumentParser) -> None:
    roles = parser.add_subparsers(dest="role", metavar="ROLE", required=True)
    solver = roles.add_parser("solver", help="plan with the reference encodings or the anytime planner, "
                                             "re-plan when the world changes")
    solver.add_argument("--domain", type=domain_argument, help="a|b|c|m|md (default: detected)")
    solver.add_argument("--method", choices=("asp", "anytime"), default="asp",
                        help="asp: minimal makespan with --encoding (default); anytime: a plan fast, then "
                             "better ones, the best by the time limit")
    solver.add_argument("--encoding", default="plain", help="reference encoding (default plain)")
    solver.add_argument("--time-limit", type=seconds_argument, default=60.0, metavar="S",
                        help="seconds per (re-)planning (default 60); anytime: each re-planning answers "
                             "after about S with its best plan")
    simulator = roles.add_parser("simulator", help="release the orders of an instance over time")
    simulator.add_argument("instance", metavar="INSTANCE", help="the warehouse and all its orders")
    simulator.add_argument("--at", action="append", default=[], metavar="STEP:ORDER[,ORDER...]",
                           help="these orders arrive at STEP (repeatable); the others are known at step 0")
    simulator.add_argument("--every", type=int, metavar="K",
                           help="orders arrive one by one in id order: the first at step 0, then one every K steps")
    for name, role in (("solver", solver), ("simulator", simulator)):
        role.add_argument("--host", default="127.0.0.1", help="address to listen on (default 127.0.0.1)")
        role.add_argument("--port", type=port_argument, default=DEFAULT_PORTS[name],
                          help="port (default %(default)s; 0: any free port, printed on start)")
        role.add_argument("--once", action="store_true", help="serve one session, then exit")
        role.add_argument("--clients", type=int, default=CLIENTS, metavar="N",
                          help=f"clients served at once (default {CLIENTS}); more are turned away")
        role.add_argument("--idle-timeout", type=float, default=IDLE_SECONDS, metavar="S",
                          help=f"let a client go after S seconds of silence (default {IDLE_SECONDS:g})")
        role.add_argument("--session-seconds", type=float, default=SESSION_SECONDS, metavar="S",
                          help=f"let a client go S seconds after it connected (default {SESSION_SECONDS:g})")
        role.add_argument("--lines-per-minute", type=int, default=LINES_PER_MINUTE, metavar="N",
                          help="let a client go that sends more than N lines within a minute "
                               f"(default {LINES_PER_MINUTE})")
        role.add_argument("--memory-mb", type=float, default=MEMORY_MB, metavar="M",
                          help=f"megabytes of unfinished lines and kept facts for all clients together; a line "
                               f"beyond them is refused (default {MEMORY_MB})")
        role.add_argument("--limit", action="append", default=[], dest="role_limits", type=limit_argument,
                          metavar="NAME=N", help="a limit on data, as --limit before the role (repeatable); "
                                                 "line-seconds=S: each line must arrive whole within S seconds "
                                                 "of its first byte, a client's first line within S of "
                                                 "connecting, each answer be taken within S (default 60)")


def run(args: argparse.Namespace) -> int:
    """Serve within the limits in force, with those given after the role (``--limit``)."""
    with using(current().with_options(getattr(args, "role_limits", []))):
        return _run(args)


def _run(args: argparse.Namespace) -> int:
    if args.clients < 1 or args.lines_per_minute < 1 or not min(args.idle_timeout, args.session_seconds,
                                                                    args.memory_mb) > 0:
        raise InputError("--clients, --idle-timeout, --session-seconds, --lines-per-minute and --memory-mb "
                         "must be positive")
    budget = SessionBudget(args.session_seconds, args.lines_per_minute)
    if args.role == "solver":
        planner, log = _planner(args), _log("solver")
        session = lambda channel: solver_session(channel, OnlinePlanner(planner, args.domain, log))  # noqa: E731
    else:
        schedule = _schedule(args)
        session = lambda channel: simulator_session(channel, schedule, _log("simulator"))  # noqa: E731
    listener = listen(args.host, args.port)
    host, port = listener.getsockname()[:2]
    print(f"asprilo serve {args.role}: listening on {host}:{port}", flush=True)
    try:
        serve(listener, session, once=args.once, clients=args.clients, idle=args.idle_timeout, budget=budget,
              pool=MemoryPool(args.memory_mb))
    except KeyboardInterrupt:
        print(f"asprilo serve {args.role}: stopped", file=sys.stderr)
        return 130  # asprilo.exits.INTERRUPTED: stopped from outside, as every command
    finally:
        listener.close()
    return 0


def _planner(args: argparse.Namespace) -> Planner:
    if args.method == "anytime":
        return anytime_planner(args.time_limit)
    return encodings_planner(args.encoding, args.time_limit)


def _log(role: str) -> Callable[[str], None]:
    return lambda text: print(f"{role}: {text}", file=sys.stderr, flush=True)


def _schedule(args: argparse.Namespace) -> Schedule:
    from asprilo.reader import read_instance
    instance = read_instance(args.instance)
    if args.every is not None:
        if args.every < 1 or args.at:
            raise InputError("--every needs K >= 1 and goes without --at")
        return Schedule.every(instance, args.every)
    try:
        return Schedule(instance, parse_arrivals(args.at))
    except InputError as error:
        raise InputError(error.message, args.instance) from None


# --- sockets ------------------------------------------------------------------------------------

def listen(host: str, port: int) -> socket.socket:
    """A listening TCP socket (``port`` 0: any free port)."""
    try:
        listener = socket.create_server((host, port), reuse_port=False)
    except OSError as error:
        raise InputError(f"cannot listen on {host}:{port}: {error.strerror or error}") from None
    return listener


def serve(listener: socket.socket, session: Callable[[Channel], None], once: bool = False,
          stop: threading.Event | None = None, clients: int = CLIENTS, idle: float = IDLE_SECONDS,
          budget: SessionBudget | None = None, pool: MemoryPool | None = None) -> None:
    """Serve each connection in a thread of its own, up to ``clients`` at once, until
    ``stop`` is set (or until the first connection ends, with ``once``); each session
    within ``budget``, all drawing memory from ``pool`` (the defaults: :mod:`.budgets`)."""
    budget, pool = budget or SessionBudget(), pool or MemoryPool()
    listener.settimeout(0.2)
    places = threading.BoundedSemaphore(clients)
    while stop is None or not stop.is_set():
        try:
            connection, _address = listener.accept()
        except TimeoutError:
            continue
        if not places.acquire(blocking=False):
            _turn_away(connection, f"the server serves {clients} clients at once; try again later")
            continue
        channel = Channel(connection, timeout=idle, speaks_first=True, session=budget, pool=pool)
        thread = threading.Thread(target=_serve_one, args=(channel, session, places), daemon=True)
        thread.start()
        if once:
            thread.join()
            return


def _serve_one(channel: Channel, session: Callable[[Channel], None], place: threading.BoundedSemaphore) -> None:
    """One client: its session; a refused line is answered with the reason, then the
    connection closes (and its place is free for the next client).  Nothing a client
    sends ends the server: a failure of the session ends the client's connection only."""
    log = _log("session")
    try:
        session(channel)
        if channel.cut_off:
            log("closed in the middle of a line (the part was ignored)")
    except InputError as refused:
        log(f"refused: {refused}")
        _goodbye(channel, str(refused))
    except TimeoutError as late:
        log(f"{late}: connection closed")
    except OSError as failure:
        log(f"ended: {failure}")
    except Exception as failure:  # noqa: BLE001 - a bug or no memory: this client only
        log(f"failed: {type(failure).__name__}: {failure}")
        _goodbye(channel, f"the server failed on this line ({type(failure).__name__})")
    finally:
        place.release()
        channel.close()


def _goodbye(channel: Channel, reason: str) -> None:
    """The last line to a client: why it is let go (given up if not taken at once)."""
    with contextlib.suppress(OSError):
        channel.send(error(reason), timeout=GOODBYE_SECONDS)


def _turn_away(connection: socket.socket, reason: str) -> None:
    channel = Channel(connection, timeout=GOODBYE_SECONDS)
    _goodbye(channel, reason)
    channel.close()


def solver_session(channel: Channel, online: OnlinePlanner) -> None:
    """Answer every ``%$done(T).`` with the actions of step T+1 (see :class:`OnlinePlanner`).
    The facts of a session (since ``%$RESET.``) stay within the ``file-mb`` limit together,
    and are held from the server's memory pool while kept."""
    online.reset()
    learned = 0
    while (message := channel.receive()) is not None:
        if message.control == RESET:
            online.reset()
            channel.forget()
            learned = 0
            continue
        check_facts(message.facts)
        learned += len(message.facts)
        limits = current()
        if learned > limits.file_mb * 2**20:
            raise limits.exceeded("file_mb", f"facts of more than {limits.file_mb:,} MB in one session "
                                             "(since its last reset)")
        channel.keep(len(message.facts))
        online.learn(message.facts)
        if message.control == DONE:
            actions = _while_connected(channel, online, lambda: online.next_actions(message.step))
            if actions is None:
                return
            channel.send(Message(action_facts(actions)))


def _while_connected(channel: Channel, online: OnlinePlanner, work: Callable):
    """Run ``work`` in a thread; stop it (``None``) if the visualizer hangs up meanwhile."""
    outcome: dict = {}

    def target() -> None:
        try:
            outcome["result"] = work()
        except BaseException as failure:  # handed to the session's thread
            outcome["error"] = failure

    worker = threading.Thread(target=target, daemon=True)
    worker.start()
    while worker.is_alive():
        worker.join(0.1)
        readable, _, _ = select.select([channel.connection], [], [], 0)
        if readable and not channel.connection.recv(1, socket.MSG_PEEK):
            online.cancel.set()
            worker.join()
            return None
    if "error" in outcome:
        raise outcome["error"]
    return outcome.get("result")


def simulator_session(channel: Channel, schedule: Schedule, log: Callable[[str], None]) -> None:
    """The world on ``%$RESET.``; on ``%$done(T).`` the orders arriving at T; ``%$end.`` when no more will."""
    while (message := channel.receive()) is not None:
        if message.control == RESET:
            channel.send(Message(schedule.world(), END if schedule.last == 0 else None))
            log("new session: sent the world at step 0")
        elif message.control == DONE:
            step = message.step
            if step < 0:
                raise InputError(f"done({step}): steps start at 0")
            facts = schedule.arriving(step)
            if facts:
                arrived = sorted(o for o, t in schedule.arrivals.items() if t == step)
                log(f"step {step}: " + (f"order {arrived[0]} arrives" if len(arrived) == 1 else
                                        f"orders {', '.join(map(str, arrived))} arrive"))
            channel.send(Message(facts, END if step >= schedule.last else None))
