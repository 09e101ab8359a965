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

A job names its domain (``"domain"``); a varied one also by its base and its variants
(``"base"``, ``"variants"``: names or variant files), from which this process makes it
again (loading the variants before it reads the instance: their attributes are data).  An
encoding of the suite's own may have a first stage (``own["stage"]``: its files).
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


def _stage(job: dict):
    """The first stage of the suite's own encoding of the run (``None``: none)."""
    if "own" not in job or not job["own"].get("stage"):
        return None
    from .suite import OwnEncoding
    return OwnEncoding.from_job(job["encoding"], job["own"]).stage_encoding()


def job_domain(job: dict):
    """The job's domain: by its name, or made again from its base and variants."""
    from asprilo.domain import Domain

    if not job.get("variants"):
        return Domain.parse(job["domain"])
    from asprilo.domain.variants import load_variant, with_variants
    return with_variants(Domain.parse(job["base"]), [load_variant(name) for name in job["variants"]])


def run(job: dict, report=None) -> dict:
    """Do one job and return its report (a JSON object; ``report``: the child process's
    channel for progress messages, unused)."""
    from asprilo.encodings import solve
    from asprilo.encodings.solving import find_method
    from asprilo.writer import format_plan

    started = time.perf_counter()
    domain = job_domain(job)
    if job["kind"] == "makespan":
        # max-flow where it honours the domain's rules; with a task assignment, the horizon of
        # the runs is the shortest plan along it
        flow = find_method("flow").honours(domain) and not job.get("assign")
        outcome = solve(job["instance"], domain=domain, encoding=job.get("encoding"),
                        assign=job.get("assign", False), time_limit=job["time_limit"],
                        method="flow" if flow else "asp", tighten=False)
    elif job["kind"] == "anytime":
        outcome = solve(job["instance"], domain=domain, method="anytime", time_limit=job["time_limit"])
    else:
        encoding = _encoding(job)
        fixed = not isinstance(encoding, str) and encoding.fixed  # solved as it is: no horizon to give
        outcome = solve(job["instance"], domain=domain, encoding=encoding,
                        horizon=None if fixed else job["horizon"], assign=job.get("assign", False),
                        time_limit=job["time_limit"], assignment=job.get("assignment"), stage=_stage(job))
    seconds = time.perf_counter() - started
    return {
        "status": outcome.status.value,
        "time": seconds,
        "horizon": outcome.horizon,
        # for the problem (never for an invalid plan; an own encoding's: where it meets the lower
        # bound): what a makespan search needs to be "solved"
        "minimal": outcome.minimal_along_assignment if job.get("assign") else outcome.minimal,
        "plan": format_plan(outcome.plan) if outcome.plan is not None else None,
        "stats": outcome.stats,
        "memory_mb": peak_memory_mb(),
        "message": outcome.message,
        "assignment": outcome.assignment.facts if outcome.assignment is not None else None,
        **({"history": outcome.history, "lower_bound": outcome.lower_bound} if job["kind"] == "anytime" else {}),
    }
