"""The online link: the text protocol, a planner that re-plans when orders arrive, a
simulator that releases them, and the TCP servers (``asprilo serve``)."""
