"""The exit statuses of every command (README: "Exit status"), one table for all:

- ``0``: done (a plan found, a plan valid, files written);
- ``1``: done, and the answer is no: no plan within the limits, a plan that breaks the rules,
  an encoding graded below full marks;
- ``2`` (:data:`REFUSED`): nothing done: bad input, a usage error, an output that cannot be
  written, a limit that cannot be honoured (a ``--memory-limit`` above ``ulimit -v``);
- ``130`` (:data:`INTERRUPTED`): stopped by Ctrl-C, SIGTERM or SIGHUP, whatever was kept
  (``solve``'s best plan so far, ``gen``'s instances, ``bench``'s finished runs); a server too.
"""

from __future__ import annotations

#: nothing was done: bad input, a usage error, an output that cannot be written
REFUSED = 2
#: stopped from outside (Ctrl-C, SIGTERM, SIGHUP): 128 plus SIGINT's number, as shells say it
INTERRUPTED = 130
