"""A makespan bound for A, B and C when shelves serve several order lines (see trip.lp).

:mod:`asprilo.bounds.delivery` schedules lines when each shelf serves one line at most; here a
shelf may serve several lines at several stations, a robot may bring several shelves, and
the relaxation decides the delivery actions themselves.  Its facts are floor distances, all
no longer than real paths, so every horizon it refutes is one that no valid plan has.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

from ..model import DIRECTIONS
from .delivery import Deliveries, carry_arrivals, robot_release, storage_to_shelves
from .floor import INFINITE
from .passages import INSTANCE_STATES, PASSAGE_STATES, passages

if TYPE_CHECKING:
    import numpy as np

#: the conflicts per horizon (a deterministic budget: "unknown" refutes nothing), the
#: horizons tried, and the largest program tried: candidate delivery actions per step,
#: squared, times the longest gap (a measure of the pairs the robot constraints ground)
TRIP_CONFLICTS = 20_000
TRIP_STEPS = 64
TRIP_WORK = 2_000_000
#: clingo's integers are 32 bits: A's unit sums are left out beyond this
LARGEST_SUM = 2**31 - 1
_PROGRAM = Path(__file__).resolve().parent / "trip.lp"


def trip_bound(facts: Deliveries, start: float, conflicts: int = TRIP_CONFLICTS) -> float:
    """The first horizon from ``start`` on that the relaxation does not refute within
    ``conflicts`` conflicts each (``start`` itself when the program would be too big to try;
    a larger budget may refute more: what a benchmark spends for its best bound)."""
    actions = len(facts.robots) * sum(len(line.holders) for line in facts.lines)
    if actions * actions > TRIP_WORK:  # too big whatever the gaps (each is a step at least)
        return start
    stations = sorted({line.station for line in facts.lines})
    shelves = sorted({s for line in facts.lines for s in line.holders})
    gaps = _gaps(facts, stations, shelves)
    longest = max((g for g in gaps.values() if math.isfinite(g)), default=1)
    if actions * actions * longest > TRIP_WORK:
        return start
    text = _trip_facts(facts, stations, shelves, gaps)
    horizon = int(start)
    for _ in range(TRIP_STEPS):
        if not _refuted(text, horizon, conflicts):
            return float(horizon)
        horizon += 1
    return float(horizon)


def _refuted(text: str, horizon: int, conflicts: int) -> bool:
    from ..solver import Solver, Status

    solver = Solver(options=["--warn=none"], constants={"horizon": horizon})
    solver.load(_PROGRAM)
    solver.add(text)
    solver.ground()
    return solver.solve(conflicts=conflicts).status is Status.UNSAT


def _gaps(facts: Deliveries, stations: list, shelves: list[int]) -> dict:
    """Steps a robot needs between two actions, keyed by the fact that states them:
    ``("gap_any", P, Q)`` between deliveries at P and Q from different shelves (put the first
    down on a storage cell, walk to the second, lift it, bring it, deliver);
    ``("gap_hand", P, Q)`` between deliveries of one shelf by two robots (the first puts it
    down, moves off the cell as the second moves on, who lifts it, brings it, delivers);
    ``("gap_fresh", P, S, Q)`` when the second shelf S is still where it started;
    ``("fetch", P, S)`` from a delivery at P to lifting S where it started; ``("aside", S, Q)``
    from lifting S where it started to delivering another shelf at Q (put S down elsewhere,
    walk to the other shelf, lift it, bring it, deliver); ``("detour", S, Q)`` the moves of S
    from where it started to Q through another storage cell.

    A shelf is never put down where another one rests: not on the cell of the shelf the robot
    fetches next (while it still stands there), and the robot that leaves a shelf on a cell
    lifts the next one elsewhere, or walks away and back."""
    storage = sorted(facts.instance.storage_cells)
    gaps: dict = {}
    if not storage:
        return gaps
    to_storage = facts.floor.distances(stations, storage)
    to_shelves = storage_to_shelves(facts, storage, shelves)
    resting = set(storage) | set(facts.shelves.values())
    onward = {q: _onward(facts, storage, resting, q) for q in stations}
    for i, p in enumerate(stations):
        for j, q in enumerate(stations):
            gaps["gap_any", p, q] = float((to_storage[i] + onward[q]).min()) + 3
            gaps["gap_hand", p, q] = float((to_storage[i] + to_storage[j]).min()) + 4
        via = (to_storage[i][:, None] + to_shelves).min(axis=0)
        for k, shelf in enumerate(shelves):
            gaps["fetch", p, shelf] = float(via[k]) + 2
            for q in stations:
                gaps["gap_fresh", p, shelf, q] = float(via[k]) + facts.carry(shelf, q) + 3
    for j, q in enumerate(stations):
        for k, shelf in enumerate(shelves):
            gaps["aside", shelf, q] = float((to_shelves[:, k] + onward[q]).min()) + 3
            gaps["detour", shelf, q] = float((to_shelves[:, k] + to_storage[j]).min())
    return gaps


def _onward(facts: Deliveries, storage: list, resting: set, station) -> np.ndarray:
    """For each storage cell C: the fewest moves from C, where a robot has just put a shelf
    down, to ``station`` with another shelf: walk to a cell where that shelf rests (leaving C
    and coming back when it is C itself), then carry it there.  A multi-source search whose
    sources are the cells a shelf may rest on, each starting at its distance to the station."""
    import numpy as np
    cells = facts.floor.cells
    near = facts.floor.distances([station], cells)[0]
    sources = {cell: float(near[k]) for k, cell in enumerate(cells) if cell in resting and math.isfinite(near[k])}
    best = carry_arrivals(facts.instance.cells, sources, {})
    return np.array([1 + min((best.get((x + dx, y + dy), INFINITE) for dx, dy in DIRECTIONS), default=INFINITE)
                     for x, y in storage])


def _trip_facts(facts: Deliveries, stations: list, shelves: list[int], gaps: dict) -> str:
    index = {cell: k for k, cell in enumerate(stations)}
    out = _line_facts(facts, index)
    carrier = {r.carries: r.id for r in facts.instance.robots.values() if r.carries is not None}
    for position, robot in enumerate(facts.robots):
        out.extend(_robot_facts(facts, robot, position, shelves, stations, carrier))
    for shelf in shelves:
        for q, station in enumerate(stations):
            # put down on the way and lifted again: a put-down and a lift more than the detour
            carry, detour = facts.carry(shelf, station), gaps.get(("detour", shelf, station), INFINITE)
            handled = max(facts.arrival(shelf, station) + 1, facts.lifted[shelf] + detour + 3)
            if math.isfinite(handled):
                out.append(f"handled({shelf},{q},{int(handled)}). carry({shelf},{q},{int(carry)}).")
    out.extend(f"carried({shelf})." for shelf in shelves if shelf in facts.carried)
    out.extend(_shelf_gaps(facts, shelves))
    out.extend(blocker_facts(facts, shelves, stations))
    for (name, *key), steps in gaps.items():
        if math.isfinite(steps):
            out.append(f"{name}({','.join(str(index.get(part, part)) for part in key)},{int(steps)}).")
    distances = facts.floor.distances(stations, stations)
    out.extend(f"apart({i},{j},{int(distances[i][j])})." for i in range(len(stations)) for j in range(len(stations)))
    delivery = facts.domain.delivery
    assert delivery is not None  # the bounds of the domains with deliveries
    out.append(f"#const delivery = {delivery.value}.")
    return "\n".join(out)


def _shelf_gaps(facts: Deliveries, shelves: list[int]) -> list[str]:
    """``between(S,S2,G)``: a robot that lifts S where it started lifts S2 where S2 started G
    steps later at the earliest: it carries S to a storage cell where neither shelf stands,
    puts it down, walks to S2 and lifts it."""
    storage = sorted(facts.instance.storage_cells)
    to_shelves = storage_to_shelves(facts, storage, shelves)
    out: list[str] = []
    for i, s in enumerate(shelves):
        through = (to_shelves[:, i:i + 1] + to_shelves).min(axis=0, initial=INFINITE) + 2
        out.extend(f"between({s},{s2},{int(through[j])})." for j, s2 in enumerate(shelves)
                   if i != j and math.isfinite(through[j]))
    return out


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
    if facts.domain.counts_units and sum(demand) + sum(units for *_, units in stock) <= LARGEST_SUM:
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
        reach = _reach_step(facts, robot, position, shelf)
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


def blocker_facts(facts: Deliveries, shelves: list[int], stations: list) -> list[str]:
    """The shelves resting in the way of a carry (trip.lp's lift/3), as facts:
    ``clear(S,P,C)``: the fewest moves of S from where it started to station P through no
    cell where another shelf starts; ``passage(S,P,O,K)``: a way O of K < C moves, whose cells
    the shelves B of ``passes(S,P,O,B,D)`` start on, D moves from P (every way shorter than C
    has one passage's moves and shelves at least); and the robot time a lift of each such B
    costs (:func:`_lift_gaps`)."""
    resting = {s: cell for s, cell in facts.shelves.items() if s not in facts.carried}
    own = [s for s in shelves if s in resting]
    if not own or not stations:
        return []
    out: list[str] = []
    needed: set[int] = set()
    left = INSTANCE_STATES
    for q, station in enumerate(stations):
        ways, left = _ways(facts, resting, own, q, station, needed, left)
        out.extend(ways)
    return out + _lift_gaps(facts, shelves, stations, sorted(needed))


def _ways(facts: Deliveries, resting: dict, own: list[int], q: int, station, needed: set[int],
          left: int) -> tuple[list[str], int]:
    """``clear`` and the passages (:mod:`asprilo.bounds.passages`) of the shelves ``own`` at
    ``station`` (number ``q``), listed while the ``left`` states last; adds the shelves in the
    passages' way to ``needed``.  The facts and the states left."""
    others = sorted(resting)
    cells = sorted(facts.instance.cells)
    near = dict(zip(cells, facts.floor.distances([station], cells)[0], strict=True))
    around = carry_arrivals(facts.instance.cells - set(resting.values()), {station: 0}, {})
    out = []
    for shelf in own:
        x, y = resting[shelf]
        clear = 0 if resting[shelf] == station else 1 + min(
            (around.get((x + dx, y + dy), INFINITE) for dx, dy in DIRECTIONS), default=INFINITE)
        clear = min(clear, 10**6)
        out.append(f"clear({shelf},{q},{int(clear)}).")
        in_way = {cell: other for other, cell in resting.items() if other != shelf}
        found, states = passages(facts.instance.cells, in_way, resting[shelf], station, near, clear,
                                 min(PASSAGE_STATES, left))
        left -= states
        if found is None:  # too many to list: each shelf in the way alone
            to_other = facts.floor.distances([resting[shelf]], [resting[b] for b in others])[0]
            over = [to_other[j] + near[resting[other]] for j, other in enumerate(others)]
            found = [(int(moves), frozenset([other])) for moves, other in zip(over, others, strict=True)
                     if other != shelf and moves < clear]
        for number, (moves, shelves) in enumerate(found):
            out.append(f"passage({shelf},{q},{number},{moves}).")
            out.extend(f"passes({shelf},{q},{number},{b},{int(near[resting[b]])})." for b in sorted(shelves))
            needed.update(shelves)
    return out, left


def _lift_gaps(facts: Deliveries, shelves: list[int], stations: list, lifted: list[int]) -> list[str]:
    """For each shelf B of ``lifted``, lifted where it started and moved off (it may be put
    back there later): ``set_down(B,Q,A)`` and ``lift_gap(B,S,G)`` as :func:`_gaps`' aside/3
    and ``between/3`` but with B's own cell allowed for the put-down; for a B that no line
    needs, also ``reach_shelf``, ``fetch`` and ``between(S,B,G)`` as for the lines' shelves."""
    storage = sorted(facts.instance.storage_cells)
    if not lifted or not storage:
        return []
    extra = [b for b in lifted if b not in shelves]
    out = _reach(facts, extra)
    everyone = shelves + extra
    standing = storage_to_shelves(facts, storage, everyone)  # nothing put down where they stand
    moved = facts.floor.distances([facts.shelves[b] for b in lifted], storage).T
    to_storage = facts.floor.distances(stations, storage)
    resting = set(storage) | set(facts.shelves.values())
    for q, station in enumerate(stations):
        onward = _onward(facts, storage, resting, station)
        for k, shelf in enumerate(lifted):
            aside = float((moved[:, k] + onward).min()) + 3
            if math.isfinite(aside):
                out.append(f"set_down({shelf},{q},{int(aside)}).")
            fetch = float((to_storage[q] + standing[:, everyone.index(shelf)]).min()) + 2
            if shelf in extra and math.isfinite(fetch):
                out.append(f"fetch({q},{shelf},{int(fetch)}).")
    return out + _orders_of_lifts(shelves, lifted, extra, standing, moved)


def _reach(facts: Deliveries, extra: list[int]) -> list[str]:
    """``reach_shelf`` of the shelves ``extra`` (as :func:`_robot_facts` for the lines' shelves)."""
    out = []
    for position, robot in enumerate(facts.robots):
        for shelf in extra:
            reach = _reach_step(facts, robot, position, shelf)
            if math.isfinite(reach):
                out.append(f"reach_shelf({robot},{shelf},{int(reach)}).")
    return out


def _reach_step(facts: Deliveries, robot: int, position: int, shelf: int) -> float:
    """The earliest step ``robot`` (number ``position``) lifts ``shelf`` where it started: it
    walks there (after putting down a shelf it carries from the start) and lifts it."""
    return float(facts.walk[shelf][position]) + 1 + (facts.instance.robots[robot].carries is not None)


def _orders_of_lifts(shelves: list[int], lifted: list[int], extra: list[int], standing: np.ndarray,
                     moved: np.ndarray) -> list[str]:
    """``lift_gap(B,S,G)`` for each lifted B, and ``between(S,B,G)`` for each B of ``extra``:
    carry the first shelf to a storage cell, put it down, walk to the second, lift it."""
    everyone = shelves + extra
    out = []
    for k, shelf in enumerate(lifted):
        column = standing[:, everyone.index(shelf)]
        for j, other in enumerate(everyone):
            if other == shelf:
                continue
            after = float((moved[:, k] + standing[:, j]).min()) + 2
            if math.isfinite(after):
                out.append(f"lift_gap({shelf},{other},{int(after)}).")
            before = float((standing[:, j] + column).min()) + 2
            if shelf in extra and other in shelves and math.isfinite(before):
                out.append(f"between({other},{shelf},{int(before)}).")
    return out
