"""A small world for the online link's tests."""

from __future__ import annotations

import contextlib
import subprocess
import sys
import threading
from collections.abc import Callable, Iterator
from dataclasses import dataclass

from asprilo.model import Instance
from asprilo.reader import read_instance
from asprilo.sources import Source

#: 4x3: a highway row in the middle, picking station 1 top right; robot 1 starts carrying
#: shelf 1 (1 unit of product 1), shelf 2 holds 3 units of product 2
TINY = """
init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))). init(object(node,3),value(at,(3,1))).
init(object(node,4),value(at,(4,1))). init(object(node,5),value(at,(1,2))). init(object(node,6),value(at,(2,2))).
init(object(node,7),value(at,(3,2))). init(object(node,8),value(at,(4,2))). init(object(node,9),value(at,(1,3))).
init(object(node,10),value(at,(2,3))). init(object(node,11),value(at,(3,3))). init(object(node,12),value(at,(4,3))).
init(object(highway,5),value(at,(1,2))). init(object(highway,6),value(at,(2,2))).
init(object(highway,7),value(at,(3,2))). init(object(highway,8),value(at,(4,2))).
init(object(pickingStation,1),value(at,(4,1))).
init(object(robot,1),value(at,(1,1))). init(object(robot,1),value(carries,1)).
init(object(robot,2),value(at,(2,3))).
init(object(shelf,1),value(at,(1,1))). init(object(shelf,2),value(at,(3,3))).
init(object(product,1),value(on,(1,1))). init(object(product,2),value(on,(2,3))).
init(object(order,1),value(line,(1,1))). init(object(order,1),value(pickingStation,1)).
init(object(order,2),value(line,(2,2))). init(object(order,2),value(pickingStation,1)).
"""
ORDER_2 = "init(object(order,2),value(line,(2,2))). init(object(order,2),value(pickingStation,1))."
WAIT = 30.0  # seconds any network wait may take at most


def tiny() -> Instance:
    return read_instance(Source("tiny.lp", TINY))


@dataclass
class Served:
    """A server started by :func:`served`: the line it printed first, its port, its process,
    and (after the ``with`` block) what it wrote on standard error."""

    process: subprocess.Popen
    first_line: str = ""
    port: int = 0
    errors: str = ""


@contextlib.contextmanager
def served(*args: str) -> Iterator[Served]:
    """``asprilo serve ARGS --port 0 --once`` in a process of its own, until the block ends."""
    process = subprocess.Popen([sys.executable, "-m", "asprilo.cli", "serve", *args, "--port", "0", "--once"],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    server = Served(process)
    try:
        server.first_line = process.stdout.readline()
        server.port = int(server.first_line.rsplit(":", 1)[1])
        yield server
    finally:
        process.kill()
        _out, server.errors = process.communicate()


#: seconds a server thread may take to end before a test counts as hung
THREAD_GUARD = 60.0


@contextlib.contextmanager
def serving(session: Callable, **options) -> Iterator[int]:
    """A server of ``session`` in a thread of this process on an ephemeral loopback port
    (``options``: :func:`asprilo.online.serve.serve`'s keywords); its port.  The server is
    stopped after the block and must end."""
    from asprilo.online.serve import listen, serve

    stop = threading.Event()
    listener = listen("127.0.0.1", 0)
    thread = threading.Thread(target=serve, args=(listener, session), kwargs={"stop": stop, **options}, daemon=True)
    thread.start()
    try:
        yield listener.getsockname()[1]
    finally:
        stop.set()
        thread.join(THREAD_GUARD)
        listener.close()
    assert not thread.is_alive()
