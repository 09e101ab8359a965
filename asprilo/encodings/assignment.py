"""Task assignment (the paper's subscript a): the first of two programs.

:func:`assign_tasks` runs ``assign/m.lp`` or ``assign/abc.lp`` with the real floor
distances as ``distance/3`` facts and returns the best assignment it finds within its
budget (optimisation is anytime: a cut-off answer is still a valid assignment).  The budget
is counted in conflicts, so that an instance gets the same assignment on every machine and
in every run (a benchmark's makespan search and its runs follow the same one); a time limit
only guards against slow machines.  The planners read the facts it returns (format in
asprilo/encodings/README.md).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

from asprilo.bounds import Floor, goal_cells
from asprilo.domain import Domain, Job
from asprilo.model import Cell, Instance, Plan
from asprilo.simulate import simulate
from asprilo.solver import Solver, Statistics, Status
from asprilo.writer import format_instance

from .registry import HERE

#: the optimisation's budget in conflicts (about 4 s on the medium paper instances, 2-core
#: development machine): the assignment found within it is proven optimal on the small ones
CONFLICTS = 20_000


@dataclass
class Assignment:
    """The assignment facts, the optimisation costs and whether they are proven optimal.

    ``origin`` says where the facts come from: ``optimised`` (:func:`assign_tasks`),
    ``given`` (by the caller) or ``read off a plan`` (:func:`assignment_of_plan`; ``read off a
    plan that also moves other shelves`` when the plan returned does not follow it exactly).
    """

    facts: list[str]
    status: Status = Status.SAT  # UNSAT: no assignment exists; UNKNOWN: none found in time
    cost: list[int] = field(default_factory=list)
    optimal: bool = False
    seconds: float = 0.0
    stats: Statistics = field(default_factory=Statistics)
    origin: str = "optimised"

    def text(self) -> str:
        return "".join(f"{fact}.\n" for fact in self.facts)


def distance_facts(instance: Instance, domain: Domain, floor: Floor | None = None) -> list[str]:
    """``distance(From,To,D)`` facts for the pairs an assignment program looks at."""
    floor = floor or Floor(instance.cells)
    robots = sorted({robot.at for robot in instance.robots.values()})
    if domain.work is Job.TRIPS:
        stock = instance.shelf_stock()
        ordered = {p for order in instance.orders.values() for p in order.lines}
        shelves = sorted({s.at for s in instance.shelves.values() if ordered & set(stock.get(s.id, {}))})
        pairs = [(robots, shelves), (shelves, sorted({p.at for p in instance.stations.values()}))]
    else:
        pairs = [(robots, goal_cells(instance))]
    import numpy as np  # here, not on import: every solve and check imports this module

    facts = []
    for sources, targets in pairs:
        table = floor.distances(sources, targets)
        for (i, j) in zip(*np.nonzero(np.isfinite(table)), strict=True):
            facts.append(f"distance({_cell(sources[i])},{_cell(targets[j])},{int(table[i, j])})")
    if domain.work is Job.TRIPS:
        facts.extend(_set_down_facts(instance, floor))
    return facts


def _set_down_facts(instance: Instance, floor: Floor) -> list[str]:
    """``set_down(PS,D)``: D moves from station PS to the nearest storage cell no shelf starts on."""
    free = sorted(instance.storage_cells - {shelf.at for shelf in instance.shelves.values()})
    stations = sorted(instance.stations.items())
    if not free or not stations:
        return []
    table = floor.distances([station.at for _, station in stations], free)
    return [f"set_down({number},{int(row.min())})" for (number, _), row in zip(stations, table, strict=True)
            if math.isfinite(row.min())]


def _cell(cell: Cell) -> str:
    return f"({cell[0]},{cell[1]})"


def assign_tasks(instance: Instance, domain: Domain, time_limit: float | None = 10.0,
                 watch: Callable[[Solver], None] | None = None, conflicts: int = CONFLICTS) -> Assignment:
    """The best assignment found within ``conflicts`` conflicts and ``time_limit`` seconds
    (``facts`` empty if none).

    ``watch(solver)`` is called with the solver before it runs, so that a caller can
    interrupt it from another thread.
    """
    started = time.perf_counter()
    trips = domain.work is Job.TRIPS
    program = HERE / "assign" / ("abc.lp" if trips else "m.lp")
    constants = {"delivery": domain.delivery.value} if trips and domain.delivery else {}
    solver = Solver(options=["--opt-strategy=bb,hier"], constants=constants)
    solver.add(format_instance(instance, []))
    solver.add("".join(f"{fact}.\n" for fact in distance_facts(instance, domain)))
    solver.load(program)
    solver.ground()
    if watch is not None:
        watch(solver)
    result = solver.solve(time_limit=time_limit, conflicts=conflicts)
    facts = sorted(str(symbol) for symbol in result.symbols)
    return Assignment(facts, result.status, result.cost, result.optimal,
                      time.perf_counter() - started, solver.stats)


def assignment_of_plan(instance: Instance, domain: Domain, plan: Plan) -> tuple[Assignment, bool]:
    """The assignment of an A/B/C plan's deliveries (which robot brings which shelf to which
    station), and whether the plan follows it exactly (abc/assigned.lp): it does not when it
    also lifts a shelf that serves no delivery or hands a shelf from one robot to another."""
    history = simulate(instance, plan, domain).history
    carries = [history.snapshot(step).carries for step in range(plan.horizon + 1)]
    carried = {(robot, shelf) for now in carries for robot, shelf in now.items()}
    facts, delivering = set(), set()
    for action in plan.actions:
        shelf = carries[action.step - 1].get(action.robot)
        if action.name == "deliver" and shelf is not None:
            robot, order = action.robot, instance.orders[action.args[0]]
            delivering.add((robot, shelf))
            facts.add(f"assign(robot({robot}),shelf({shelf}),pickingStation({order.station}))")
    exact = carried == delivering and len({shelf for _, shelf in carried}) == len(carried)
    return Assignment(sorted(facts), origin="read off a plan"), exact
