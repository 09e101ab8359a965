"""Who does what: goal cells to robots (M, Md) and shelves to order lines and robots (A, B, C).

Both are logic programs (``assign_goals.lp``, ``assign_shelves.lp``) grounded once per
instance.  :meth:`Assigner.solve` optimises within a time budget (a cut-off answer is still
a valid assignment) and takes the choices of robots that are to stay as they are as
assumptions, so the large-neighbourhood search re-assigns only the robots it freed,
without grounding again.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path

import clingo
import numpy as np

from asprilo.bounds import INFINITE, goal_cells
from asprilo.domain import Domain
from asprilo.model import Cell, Instance
from asprilo.solver import Solver, Status

from .grid import Grid

HERE = Path(__file__).resolve().parent
#: robots offered for each shelf or goal at first (the nearest ones); doubled while that is too few
NEAREST = 12
#: the robots' work is summed in the shelf assignment only where (steps counted) x (robot-shelf
#: pairs offered) stays below this: the sums ground per step
WORK_SIZE = 200_000
#: shelves x robots from which the solver starts from a greedy assignment (on 200x200 with
#: 1,000 robots, its first answers within the first assignment's seconds gave up to 7
#: shelves to one robot while 700 robots stayed idle; with 600 robots and 761 shelves, up to
#: 8; on 100x100 with 200 robots and 130 shelves used, after 0.3 s as on a loaded machine,
#: up to 6: a first plan 2.5 times the bound)
HINT_SIZE = 20_000


@dataclass
class Choice:
    """An assignment as the program's atoms: ``aim(R,G)`` or ``give(S,O,P,N)`` / ``carry(R,S)``."""

    atoms: set[clingo.Symbol] = field(default_factory=set)
    optimal: bool = False

    def of(self, name: str) -> list[tuple[int, ...]]:
        return sorted(tuple(a.number for a in atom.arguments) for atom in self.atoms if atom.name == name)


class Assigner:
    """One grounded assignment program and the facts it was grounded from."""

    def __init__(self, program: str, facts: list[str], constants: dict[str, str] | None = None,
                 options: Iterable[str] = ()):
        self.solver = Solver(options=["--opt-strategy=bb,hier", "--warn=none", *options], constants=constants)
        self.solver.load(HERE / program)
        self.solver.add("\n".join(facts))
        self.solver.ground()
        self.atoms = {atom.symbol for atom in self.solver.control.symbolic_atoms}
        self.unsatisfiable = False  # the last solve call proved that no assignment exists

    def solve(self, keep: Iterable[clingo.Symbol] = (), drop: Iterable[clingo.Symbol] = (),
              budget: float = 1.0, stopped: Callable[[], bool] = lambda: True) -> Choice | None:
        """The best assignment found within ``budget`` seconds (or, when none is found by
        then, the first one found before ``stopped()``), with the atoms of ``keep`` true and
        those of ``drop`` false."""
        keep = list(keep)
        if any(atom not in self.atoms for atom in keep):
            return None  # a kept choice the program does not offer
        assumptions = [(a, True) for a in keep] + [(a, False) for a in drop if a in self.atoms]
        result = self.solver.solve(time_limit=budget, assumptions=assumptions, stop_waiting=stopped)
        self.unsatisfiable = result.status is Status.UNSAT
        if not result.satisfiable:
            return None
        return Choice(set(result.symbols), optimal=result.exhausted)


# --- domains M and Md ----------------------------------------------------------------------

@dataclass
class GoalProblem:
    """Goal cells, the grounded program, and how far each robot is from each goal."""

    goals: list[Cell]
    robots: list[int]
    distance: np.ndarray  # robots x goals
    assigner: Assigner


def goal_problem(instance: Instance, grid: Grid, longest: float) -> GoalProblem:
    """Ground the goal assignment: each robot may take the goals at most ``longest`` steps
    away (the bottleneck bound, so the best assignment is kept), and its nearest ones."""
    goals = goal_cells(instance)
    robots = sorted(instance.robots)
    distance = grid.table([instance.robots[r].at for r in robots], goals)
    labelled = instance.assigned_cells()
    facts = [f"goal({g})." for g in range(len(goals))]
    for i, robot in enumerate(robots):
        if robot in labelled:
            g = goals.index(labelled[robot])
            facts += [f"labelled({robot},{g}).", f"option({robot},{g},{int(distance[i, g])})."]
            continue
        nearest = set(np.argsort(distance[i], kind="stable")[:NEAREST].tolist())
        for g in range(len(goals)):
            if distance[i, g] < INFINITE and (distance[i, g] <= longest or g in nearest):
                facts.append(f"option({robot},{g},{int(distance[i, g])}).")
    return GoalProblem(goals, robots, distance, Assigner("assign_goals.lp", facts))


def aims(choice: Choice, problem: GoalProblem) -> dict[int, Cell]:
    """Robot -> goal cell of an assignment."""
    return {robot: problem.goals[goal] for robot, goal in choice.of("aim")}


# --- domains A, B and C --------------------------------------------------------------------

@dataclass
class ShelfProblem:
    """The lines to serve, the shelves that can serve them, and the grounded program."""

    lines: dict[tuple[int, int], int]        # (order, product) -> units
    assigner: Assigner
    haul: dict[tuple[int, int], int] = field(default_factory=dict)  # (shelf, station) -> steps


def shelf_problem(instance: Instance, grid: Grid, domain: Domain, homes: dict[int, Cell],
                  nearest: int = NEAREST) -> ShelfProblem:
    """Ground the shelf assignment with each shelf offered to its ``nearest`` robots."""
    stock = instance.shelf_stock()
    lines = {(o.id, p): (1 if q is None or not domain.counts_units else q)
             for o in instance.orders.values() for p, q in o.lines.items()}
    wanted = {p for _, p in lines}
    shelves = sorted(s for s in homes if wanted & set(stock.get(s, {})))
    facts = [f"line({o},{p},{q})." for (o, p), q in lines.items()]
    facts += [f"order({o.id},{o.station})." for o in instance.orders.values()]
    facts += [f"holds({s},{p},{1 if u is None or not domain.counts_units else u})."
              for s in shelves for p, u in stock[s].items() if p in wanted]
    haul = _hauls(instance, grid, homes, shelves)
    facts += [f"haul({s},{ps},{d})." for (s, ps), d in haul.items()]
    robots = max(1, sum(1 for r in instance.robots.values() if r.carries is None))
    cap = max(1, math.ceil(len(lines) / robots))
    hinted = len(shelves) * len(instance.robots) >= HINT_SIZE
    orders = {o.id: o.station for o in instance.orders.values() if o.station is not None}
    # the shelves of the greedy start are matched to robots first, so each gets one of its own
    # (matched among all shelves, on 200x200 with 600 robots 33 of its 490 had none: a robot
    # with two shelves, an errand of twice the bound)
    used = [s for s, *_ in _greedy_gives(lines, {s: stock[s] for s in shelves}, haul, orders, domain.counts_units)
            ] if hinted else []
    options, matched = _carriers(instance, grid, homes, shelves, nearest, cap, used)
    facts += [f"option({r},{s},{d})." for r, s, d in options]
    # the robots' work is summed where some robot must bring several shelves: more lines than
    # robots, or a line that needs more units than any one shelf holds
    several = cap > 1 or any(q > max((stock[s].get(p) or 0 for s in shelves), default=0)
                             for (_, p), q in lines.items() if domain.counts_units)
    facts += _workloads(instance, options, haul, cap) if several else []
    facts.append(f"cap({cap}).")
    if hinted:
        facts += _greedy(lines, {s: stock[s] for s in shelves}, haul, orders, options, cap, domain.counts_units,
                         matched)
    assigner = Assigner("assign_shelves.lp", facts, {"delivery": domain.delivery.value},
                        ["--heuristic=Domain"] if hinted else [])
    return ShelfProblem(lines, assigner, haul)


def _greedy(lines: dict[tuple[int, int], int], stock: dict[int, dict[int, int | None]],
            haul: dict[tuple[int, int], int], orders: dict[int, int], options: list[tuple[int, int, int]],
            cap: int, counts_units: bool, matched: dict[int, int] | None = None) -> list[str]:
    """A greedy assignment as ``hint_give/4`` and ``hint_carry/2`` facts: every line served by
    the shelves holding its product nearest to its station (in A as many as its units need,
    none giving more than it has left), each shelf used carried by the robot ``matched`` to it
    (shelf -> robot), else by the nearest robot offered that has fewer than ``cap`` shelves yet
    (or the least busy one)."""
    gives = _greedy_gives(lines, stock, haul, orders, counts_units)
    carriers: dict[int, list[tuple[int, int]]] = {}
    for robot, shelf, steps in options:
        carriers.setdefault(shelf, []).append((steps, robot))
    hints = [f"hint_give({shelf},{order},{product},{units})." for shelf, order, product, units in gives]
    load: dict[int, int] = {}
    for shelf in dict.fromkeys(shelf for shelf, *_ in gives):
        offered = [robot for _, robot in sorted(carriers.get(shelf, ()))]
        if offered:
            room = [robot for robot in offered if load.get(robot, 0) < cap]
            robot = room[0] if room else min(offered, key=load.__getitem__)
            if matched is not None and shelf in matched:
                robot = matched[shelf]
            load[robot] = load.get(robot, 0) + 1
            hints.append(f"hint_carry({robot},{shelf}).")
    return hints


def _greedy_gives(lines: dict[tuple[int, int], int], stock: dict[int, dict[int, int | None]],
                  haul: dict[tuple[int, int], int], orders: dict[int, int],
                  counts_units: bool) -> list[tuple[int, int, int, int]]:
    """(shelf, order, product, units) for every line, from the shelves nearest its station."""
    left = {(s, p): (u or 1) if counts_units else 1 for s, held in stock.items() for p, u in held.items()}
    holders: dict[int, list[int]] = {}
    for shelf, held in stock.items():
        for product in held:
            holders.setdefault(product, []).append(shelf)
    gives = []
    for (order, product), units in sorted(lines.items()):
        station = orders.get(order)
        if station is None:
            continue  # no station to deliver at: no plan serves the line
        for shelf in sorted(holders.get(product, ()), key=lambda s: haul.get((s, station), INFINITE)):
            if units <= 0:
                break
            given = min(units, left[(shelf, product)]) if counts_units else 1
            if given > 0:
                left[(shelf, product)] -= given
                units -= given
                gives.append((shelf, order, product, given))
    return gives


def _workloads(instance: Instance, options: list[tuple[int, int, int]], haul: dict[tuple[int, int], int],
               cap: int) -> list[str]:
    """``most(K)``: no robot's work (its shelves' rounds one after the other) is counted beyond
    K steps -- the longest round times the cap, plus one: an assignment above that is bad
    anyway; ``spread(W)``: the steps between the two stations farthest apart.  None on big
    instances (robots x steps beyond :data:`WORK_SIZE`), where the sums would ground too much."""
    if not options or not haul:
        return []
    longest = max(haul.values())
    reach = {r: 0 for r, _, _ in options}
    for r, _, d in options:
        reach[r] = max(reach[r], d)
    most = (max(reach.values()) + 2 * longest + 2 + len(instance.orders)) * (cap + 1)
    if most * len(options) > WORK_SIZE:
        return []
    stations = [station.at for station in instance.stations.values()]
    spread = max((abs(a[0] - b[0]) + abs(a[1] - b[1]) for a in stations for b in stations), default=0)
    return [f"most({most}).", f"spread({spread})."]


def _hauls(instance: Instance, grid: Grid, homes: dict[int, Cell], shelves: list[int]) -> dict[tuple[int, int], int]:
    """(shelf, station) -> steps to carry the shelf there around the other resting shelves."""
    carried = {robot.carries for robot in instance.robots.values()}
    resting = grid.mask(cell for shelf, cell in homes.items() if shelf not in carried)
    haul = {}
    for station in sorted(instance.stations.values(), key=lambda s: s.id):
        distance = grid.distances([station.at], grid.floor & ~resting)
        for shelf in shelves:
            x, y = homes[shelf]
            steps = min(distance[x + dx, y + dy] for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1)))
            if steps < INFINITE:
                haul[(shelf, station.id)] = int(steps) + 1
    return haul


def _carriers(instance: Instance, grid: Grid, homes: dict[int, Cell], shelves: list[int], nearest: int,
              cap: int, first: list[int] | None = None) -> tuple[list[tuple[int, int, int]], dict[int, int]]:
    """``option(R,S,D)`` as (R, S, D): the robots nearest to each shelf, and the robot a
    matching of robots (each up to ``cap`` times) to shelves gives it, so that the cap can be
    kept even where many shelves have the same nearest robots (the shelves of ``first``
    matched first); a robot that starts with a shelf carries that one or none, and nobody
    else carries it.  Also the matching, shelf -> robot."""
    carried = {r.carries: r.id for r in instance.robots.values() if r.carries is not None}
    free = sorted(r.id for r in instance.robots.values() if r.carries is None)
    facts = [(carried[s], s, 0) for s in shelves if s in carried]
    loose = [s for s in shelves if s not in carried]
    distance = grid.table([instance.robots[r].at for r in free], [homes[s] for s in loose])
    offered = {(int(row), column) for column in range(len(loose))
               for row in np.argsort(distance[:, column], kind="stable")[:nearest]}
    matched: dict[int, int] = {}
    if free and loose:
        column_of = {shelf: column for column, shelf in enumerate(loose)}
        pairs = _matching(distance, cap, [column_of[s] for s in first or () if s in column_of])
        offered |= pairs
        matched = {loose[column]: free[row] for row, column in pairs}
    facts += [(free[row], loose[column], int(distance[row, column]))
              for row, column in sorted(offered) if distance[row, column] < INFINITE]
    return facts, matched


def _matching(distance: np.ndarray, cap: int, first: list[int] | None = None) -> set[tuple[int, int]]:
    """(row, column) pairs of robots (rows, each at most ``cap`` times) and shelves (columns):
    shelf after shelf, those of ``first`` before the others, the one whose nearest robot is
    nearest first, to its nearest robot with room left (greedy: scipy's optimal assignment
    takes longer to import than the whole first plan of an exercise-size instance)."""
    load = np.zeros(distance.shape[0], dtype=np.int64)
    pairs = set()
    ahead = np.zeros(distance.shape[1], dtype=bool)
    ahead[first or []] = True
    for column in np.lexsort((distance.min(axis=0), ~ahead)):
        for row in np.argsort(distance[:, column], kind="stable"):
            if distance[row, column] >= INFINITE:
                break
            if load[row] < cap:
                load[row] += 1
                pairs.add((int(row), int(column)))
                break
    return pairs
