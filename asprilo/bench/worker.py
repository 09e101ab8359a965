"""What the child process of a benchmark run does (:mod:`asprilo.bench.limits` starts it
under the limits): read the instance, run the solver and report what it found, its
statistics, the plan, and the process's own peak memory.  Jobs:

- ``{"kind": "makespan", ...}``: the minimal makespan of an instance in a domain: the flow
  solver for M/Md, else the horizon search; with task assignment, the shortest plan along
  the assignment (the horizon the assigned runs are given), and that assignment;
- ``{"kind": "run", ...}``: one benchmark run at a given horizon (along ``assignment`` if given),
  of a reference encoding by name, or of the suite's own (``own``: its files, constants and
  options, from which the encoding is made here);
- ``{"kind": "anytime", ...}``: one run of the anytime planner for the whole time limit.
"""

from __future__ import annotations

import time

from asprilo.isolation import peak_memory_mb


def _encoding(job: dict):
    """The run's encoding: a reference one by name, or the suite's own made again from its
    files, constants and options (``job["own"]``)."""
    if "own" not in job:
        return job["encoding"]
    from .suite import OwnEncoding
    return OwnEncoding.from_job(job["encoding"], job["own"]).encoding()


def run(job: dict, report=None) -> dict:
    """Do one job and return its report (a JSON object; ``report``: the child process's
    channel for progress messages, unused)."""
    from asprilo.encodings import solve
    from asprilo.writer import format_plan

    started = time.perf_counter()
    if job["kind"] == "makespan":
        flow = job["domain"] in ("m", "md") and not job.get("assign")
        # with a task assignment, the horizon of the runs is the shortest plan along it
        outcome = solve(job["instance"], domain=job["domain"], encoding=job.get("encoding", "plain"),
                        assign=job.get("assign", False), time_limit=job["time_limit"],
                        method="flow" if flow else "asp", tighten=False)
    elif job["kind"] == "anytime":
        outcome = solve(job["instance"], domain=job["domain"], method="anytime", time_limit=job["time_limit"])
    else:
        encoding = _encoding(job)
        fixed = not isinstance(encoding, str) and encoding.fixed  # solved as it is: no horizon to give
        outcome = solve(job["instance"], domain=job["domain"], encoding=encoding,
                        horizon=None if fixed else job["horizon"], assign=job.get("assign", False),
                        time_limit=job["time_limit"], assignment=job.get("assignment"))
    seconds = time.perf_counter() - started
    return {
        "status": outcome.status.value,
        "time": seconds,
        "horizon": outcome.horizon,
        "minimal": outcome.minimal_along_assignment if job.get("assign") else outcome.minimal,
        "plan": format_plan(outcome.plan) if outcome.plan is not None else None,
        "stats": outcome.stats,
        "memory_mb": peak_memory_mb(),
        "message": outcome.message,
        "assignment": outcome.assignment.facts if outcome.assignment is not None else None,
        **({"history": outcome.history, "lower_bound": outcome.lower_bound} if job["kind"] == "anytime" else {}),
    }
