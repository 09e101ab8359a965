"""A makespan bound for A, B and C when shelves serve several order lines (see trip_bound.lp).

:mod:`asprilo.delivery_bound` schedules lines when each shelf serves one line at most; here a
shelf may serve several lines at several stations, a robot may bring several shelves, and
the relaxation decides the delivery actions themselves.  Its facts are floor distances, all
no longer than real paths, so every horizon it refutes is one that no valid plan has.
"""

from __future__ import annotations

import math
from pathlib import Path

from .delivery_bound import Deliveries, robot_release
from .domain import Domain

#: the conflicts per horizon (a deterministic budget: "unknown" refutes nothing), the
#: horizons tried, and the largest program tried: candidate delivery actions per step,
#: squared, times the longest gap (a measure of the pairs the robot constraints ground)
TRIP_CONFLICTS = 20_000
TRIP_STEPS = 64
TRIP_WORK = 2_000_000
#: clingo's integers are 32 bits: A's unit sums are left out beyond this
LARGEST_SUM = 2**31 - 1
_PROGRAM = Path(__file__).resolve().parent / "trip_bound.lp"


def trip_bound(facts: Deliveries, start: float) -> float:
    """The first horizon from ``start`` on that the relaxation does not refute (``start``
    itself when the program would be too big to try)."""
    stations = sorted({line.station for line in facts.lines})
    shelves = sorted({s for line in facts.lines for s in line.holders})
    gaps = _gaps(facts, stations, shelves)
    longest = max((g for g in gaps.values() if math.isfinite(g)), default=1)
    actions = len(facts.robots) * sum(len(line.holders) for line in facts.lines)
    if actions * actions * longest > TRIP_WORK:
        return start
    text = _trip_facts(facts, stations, shelves, gaps)
    horizon = int(start)
    for _ in range(TRIP_STEPS):
        if not _refuted(text, horizon):
            return float(horizon)
        horizon += 1
    return float(horizon)


def _refuted(text: str, horizon: int) -> bool:
    import clingo

    control = clingo.Control(["--warn=none", f"-c horizon={horizon}", f"--solve-limit={TRIP_CONFLICTS}"])
    control.load(str(_PROGRAM))
    control.add("base", [], text)
    control.ground([("base", [])])
    return bool(control.solve().unsatisfiable)


def _gaps(facts: Deliveries, stations: list, shelves: list[int]) -> dict:
    """Steps a robot needs between two actions, keyed by the fact that states them:
    ``("gap_any", P, Q)`` between deliveries at P and Q from different shelves (through the
    best storage cell); ``("gap_fresh", P, S, Q)`` when the second shelf S is still where it
    started (deliver, walk to a storage cell, put down, walk to S, lift, carry, deliver);
    ``("fetch", P, S)`` from a delivery at P to lifting S where it started."""
    storage = sorted(facts.instance.storage_cells)
    gaps: dict = {}
    if not storage:
        return gaps
    to_storage = facts.floor.distances(stations, storage)
    to_shelves = facts.floor.distances(storage, [facts.shelves[s] for s in shelves])
    for i, p in enumerate(stations):
        for j, q in enumerate(stations):
            gaps["gap_any", p, q] = float((to_storage[i] + to_storage[j]).min()) + 3
        via = (to_storage[i][:, None] + to_shelves).min(axis=0)
        for k, shelf in enumerate(shelves):
            gaps["fetch", p, shelf] = float(via[k]) + 2
            for q in stations:
                gaps["gap_fresh", p, shelf, q] = float(via[k]) + facts.carry(shelf, q) + 3
    return gaps


def _trip_facts(facts: Deliveries, stations: list, shelves: list[int], gaps: dict) -> str:
    index = {cell: k for k, cell in enumerate(stations)}
    out = _line_facts(facts, index)
    carrier = {r.carries: r.id for r in facts.instance.robots.values() if r.carries is not None}
    for position, robot in enumerate(facts.robots):
        out.extend(_robot_facts(facts, robot, position, shelves, stations, carrier))
    for shelf in shelves:
        for q, station in enumerate(stations):
            # put down on the way and lifted again: two steps more than a straight carry
            carry = facts.carry(shelf, station)
            handled = max(facts.arrival(shelf, station) + 1, facts.lifted[shelf] + carry + 3)
            if math.isfinite(handled):
                out.append(f"handled({shelf},{q},{int(handled)}). carry({shelf},{q},{int(carry)}).")
    out.extend(f"carried({shelf})." for shelf in shelves if shelf in facts.carried)
    out.extend(_shelf_gaps(facts, shelves))
    for (name, *key), steps in gaps.items():
        if math.isfinite(steps):
            out.append(f"{name}({','.join(str(index.get(part, part)) for part in key)},{int(steps)}).")
    distances = facts.floor.distances(stations, stations)
    out.extend(f"apart({i},{j},{int(distances[i][j])})." for i in range(len(stations)) for j in range(len(stations)))
    on_station = any(cell in stations for cell in facts.shelves.values())
    out.append(f"aside({5 if on_station else 6}). #const domain = {facts.domain.value}.")
    return "\n".join(out)


def _shelf_gaps(facts: Deliveries, shelves: list[int]) -> list[str]:
    """``between(S,S2,G)``: a robot that lifts S where it started lifts S2 where S2 started G
    steps later at the earliest (carry S somewhere else, put it down, walk to S2: at least a
    step each, and never less than the distance between the two)."""
    cells = [facts.shelves[s] for s in shelves]
    distances = facts.floor.distances(cells, cells)
    return [f"between({s},{s2},{int(max(4, distances[i][j] + 2))})."
            for i, s in enumerate(shelves) for j, s2 in enumerate(shelves)
            if i != j and math.isfinite(distances[i][j])]


def _line_facts(facts: Deliveries, index: dict) -> list[str]:
    """The lines, their stations and holders, and in A the units ordered and held (left out
    where clingo's sums over them could overflow: then every line only needs a delivery)."""
    out = []
    for number, line in enumerate(facts.lines):
        out.append(f"line({number}). station_of({number},{index[line.station]}). product_of({number},{line.product}).")
        out.extend(f"holder({number},{s})." for s in line.holders)
    demand = [_units(facts.instance.orders[line.order].lines[line.product]) for line in facts.lines]
    stock = [(shelf, product, _units(units)) for shelf, products in facts.stock.items()
             for product, units in products.items()]
    if facts.domain is Domain.A and sum(demand) + sum(units for *_, units in stock) <= LARGEST_SUM:
        out.extend(f"demand({number},{units})." for number, units in enumerate(demand))
        out.extend(f"stock({shelf},{product},{units})." for shelf, product, units in stock)
    return out


def _units(units: int | None) -> int:
    """A quantity-free fact counts as one unit."""
    return 1 if units is None else units


def _robot_facts(facts: Deliveries, robot: int, position: int, shelves: list[int], stations: list,
                 carrier: dict[int, int]) -> list[str]:
    """When ``robot`` can deliver from each shelf at each station at the earliest, and, if it
    can carry the shelf from where it starts (a shelf carried from the start only by its
    ``carrier``), when that first delivery can be."""
    out = [f"robot({robot})."]
    start = facts.instance.robots[robot]
    lift = 0 if start.carries is not None else 1
    walks = facts.floor.distances([start.at], stations)[0]
    for shelf in shelves:
        # lifting a shelf where it started: walk there (after putting down a carried one), lift
        reach = float(facts.walk[shelf][position]) + 1 + (start.carries is not None)
        if shelf not in facts.carried and math.isfinite(reach):
            out.append(f"reach_shelf({robot},{shelf},{int(reach)}).")
        for q, station in enumerate(stations):
            earliest = max(facts.arrival(shelf, station) + 1, walks[q] + lift + 1)
            if math.isfinite(earliest):
                out.append(f"earliest({robot},{shelf},{q},{int(earliest)}).")
            own = robot_release(facts, robot, position, shelf, station)
            if carrier.get(shelf, robot) == robot and math.isfinite(own):
                out.append(f"own({robot},{shelf},{q},{int(own)}).")
    return out
