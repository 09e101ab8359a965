"""Convert between asprilo and the MAPF world: MovingAI maps and scenarios, LaCAM results, domains M and Md.

LaCAM/PIBT result files convert into plans; M and Md instances into each other.

Examples:
  asprilo convert random-32-32-20.map floor.lp
  asprilo convert random-32-32-20-random-1.scen agents.lp --agents 50 --goals md
  asprilo convert random-32-32-20-random-1.scen agents.lp --agents 50 --labelled
  asprilo convert instance.lp floor.map
  asprilo convert instance.lp agents.scen
  asprilo convert m-instance.lp md-instance.lp --to md
  asprilo convert result.txt plan.lp --instance agents.lp
  asprilo convert plan.lp result.txt --instance agents.lp

Formats follow the file endings (.map, .scen, .txt = LaCAM result, .lp = asprilo) unless
--from/--to say otherwise.
"""

from __future__ import annotations

import argparse
import math
from collections import Counter
from pathlib import Path
from typing import Any

from asprilo.errors import InputError
from asprilo.facts import format_action
from asprilo.instance_builder import INSTANCE_NAMES, build_instance
from asprilo.limits import current
from asprilo.model import DIRECTIONS, Action, Destination, Instance, Order, PickingStation, Plan, Product, Robot, Shelf
from asprilo.parse import Fn, Str
from asprilo.reader import read_instance, read_plan
from asprilo.sources import Source, as_sources, load_facts
from asprilo.writer import check_output, format_instance, format_plan, header_lines, write_output

from .movingai import (
    PASSABLE,
    LacamResult,
    Map,
    Task,
    format_map,
    format_result,
    format_scenario,
    from_cell,
    is_cell_char,
    octile_lengths,
    parse_map,
    parse_result,
    parse_scenario,
    require_map_size,
    to_cell,
)

GOALS = ("md", "m")

# --- maps --------------------------------------------------------------------------------


def map_to_instance(grid: Map) -> Instance:
    """Every passable cell becomes a node; node ids number the full rectangle row by row."""
    instance = Instance()
    for x, y in grid.free_cells():
        instance.nodes[y * grid.width + x + 1] = to_cell(x, y)
    return instance


def terrain_facts(grid: Map, name: str) -> list[str]:
    """Facts that keep what asprilo's floor cannot say (map name, type, size, the characters
    of blocked cells and of passable cells other than ``.``: ``G``, ``S``), so that ``.map ->
    asprilo -> .map`` gives the same bytes.  asprilo's tools ignore them."""
    blocked = Counter(char for row in grid.rows for char in row if char not in PASSABLE)
    usual = blocked.most_common(1)[0][0] if blocked else "@"
    facts = [f"movingai(map,{_quote(name)}).", f"movingai(type,{_quote(grid.kind)}).",
             f"movingai(size,({grid.width},{grid.height})).", f"movingai(blocked,{_quote(usual)})."]
    for y, row in enumerate(grid.rows):
        for x, char in enumerate(row):
            if char not in (".", usual):
                kind = "passable" if char in PASSABLE else "blocked"
                facts.append(f"movingai({kind},({x + 1},{y + 1}),{_quote(char)}).")
    return facts


def _quote(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def instance_to_map(instance: Instance, terrain: dict | None = None) -> Map:
    """The floor as a map: nodes are ``.``, other cells blocked (``@`` unless ``terrain`` says)."""
    terrain = terrain or {}
    width, height = terrain.get("size", instance.size)
    usual = terrain.get("blocked", "@")
    exceptions = terrain.get("cells", {})
    cells = instance.cells
    if any(not (1 <= x <= width and 1 <= y <= height) for x, y in cells):
        raise InputError(f"the floor does not fit the map size {width}x{height}")
    require_map_size(width, height, current())
    passable = terrain.get("passable", {})
    rows = ["".join(_node_char(passable.get((x, y)) or exceptions.get((x, y))) if (x, y) in cells
                    else _blocked_char(exceptions.get((x, y)), usual)
                    for x in range(1, width + 1)) for y in range(1, height + 1)]
    return Map(rows, terrain.get("type", "octile"))


def _node_char(kept: str | None) -> str:
    """The character of a node's cell: ``G`` or ``S`` where the terrain facts keep one (as
    ``passable``, or as ``blocked`` in files written before issue 46), else ``.``."""
    return kept if kept is not None and kept in PASSABLE else "."


def _blocked_char(kept: str | None, usual: str) -> str:
    """The character of a cell without a node: the one kept for it if it is a blocked one."""
    return kept if kept is not None and kept not in PASSABLE else usual


def _terrain(atoms: list[Fn]) -> dict:
    """What the ``movingai`` atoms of an instance keep; atoms of other shapes are ignored."""
    terrain: dict = {"cells": {}, "passable": {}}
    for atom in atoms:
        args = atom.args
        if atom.negative or not args or type(args[0]) is not Fn:
            continue
        what, last = args[0].name, args[-1]
        if len(args) == 2 and what == "size" and _pair(last):
            terrain["size"] = _pair(last)
        elif type(last) is not Str:
            continue
        elif len(args) == 2 and what in _SETTINGS and _SETTINGS[what](last.value):
            terrain[what] = last.value
        elif len(args) == 3 and what == "blocked" and _pair(args[1]) and is_cell_char(last.value):
            terrain["cells"][_pair(args[1])] = last.value
        elif len(args) == 3 and what == "passable" and _pair(args[1]) and last.value in PASSABLE:
            terrain["passable"][_pair(args[1])] = last.value
    return terrain


def _pair(term: Any) -> tuple[int, int] | None:
    """``(X, Y)`` of a pair of numbers, else ``None``."""
    if type(term) is not Fn or term.name or term.negative or len(term.args) != 2 or \
            any(type(value) is not int for value in term.args):
        return None
    return term.args[0], term.args[1]


def _word(text: str) -> bool:
    return bool(text) and all(map(is_cell_char, text))


def _blocked(char: str) -> bool:
    return is_cell_char(char) and char not in PASSABLE


#: the map's settings kept in movingai/2 facts, each with what it may be (a map header's
#: word, a blocked cell's character)
_SETTINGS = {"map": _word, "type": _word, "blocked": _blocked}


# --- scenarios ---------------------------------------------------------------------------


def scenario_to_instance(grid: Map, tasks: list[Task], agents: int, goals: str = "md",
                         labelled: bool = False) -> Instance:
    """Robots at the first ``agents`` starts; goals as Md destinations (``md``) or as M
    shelves, products and orders (``m``), numbered like the scenario rows.  ``labelled``
    assigns robot k to goal k, as the scenario does (otherwise any robot may take any goal)."""
    if agents < 1 or agents > len(tasks):
        raise InputError(f"--agents must be between 1 and {len(tasks)} (the scenario's rows), got {agents}")
    tasks = tasks[:agents]
    for role in ("start", "goal"):
        seen: dict = {}
        for number, task in enumerate(tasks, 1):
            cell = getattr(task, role)
            if not grid.passable(*cell):
                raise InputError(f"agent {number}'s {role} {cell} is not a passable cell of the map")
            if cell in seen:
                raise InputError(f"agents {seen[cell]} and {number} share the {role} {cell}")
            seen[cell] = number
    instance = map_to_instance(grid)
    for number, task in enumerate(tasks, 1):
        instance.robots[number] = Robot(number, to_cell(*task.start))
        if labelled:
            instance.assignment[number] = ("destination" if goals == "md" else "shelf", number)
        if goals == "md":
            instance.destinations[number] = Destination(number, to_cell(*task.goal))
        else:
            instance.shelves[number] = Shelf(number, to_cell(*task.goal))
            instance.products[number] = Product(number, {number: 1})
            instance.orders[number] = Order(number, {number: 1}, 1)
    if goals == "m":
        goal_cells = {shelf.at for shelf in instance.shelves.values()}
        free = next(cell for _id, cell in sorted(instance.nodes.items()) if cell not in goal_cells)
        instance.stations[1] = PickingStation(1, free)
    return instance


def goals_of(instance: Instance) -> list:
    """The goal cell of each robot, in robot order: destinations (Md) or the cells of the
    shelves ordered by the orders (M), the k-th goal belonging to the k-th robot; or each
    robot's labelled goal when the instance assigns one to every robot."""
    if instance.assignment and set(instance.assignment) == set(instance.robots):
        cells = instance.assigned_cells()
        return [cells[robot] for robot in sorted(instance.robots)]
    if instance.destinations:
        goals = [d.at for _id, d in sorted(instance.destinations.items())]
    else:
        goals = [_order_goal(instance, order) for _id, order in sorted(instance.orders.items())]
    if len(goals) != len(instance.robots):
        raise InputError(f"{len(instance.robots)} robots but {len(goals)} goals: a scenario pairs each "
                         "robot with one goal")
    return goals


def _order_goal(instance: Instance, order: Order):
    if len(order.lines) != 1:
        raise InputError(f"order {order.id} has {len(order.lines)} lines; domain M orders have one")
    product = next(iter(order.lines))
    shelves = list(instance.products[product].stock) if product in instance.products else []
    if len(shelves) != 1 or shelves[0] not in instance.shelves:
        raise InputError(f"product {product} of order {order.id} must lie on exactly one shelf (domain M)")
    return instance.shelves[shelves[0]].at


def instance_to_scenario(instance: Instance, map_name: str) -> list[Task]:
    """One scenario row per robot, with its goal, octile optimum and bucket."""
    grid = instance_to_map(instance)
    pairs = [(from_cell(robot.at), from_cell(goal))
             for (_id, robot), goal in zip(sorted(instance.robots.items()), goals_of(instance), strict=True)]
    lengths = octile_lengths(grid, pairs)
    tasks = []
    for (start, goal), length in zip(pairs, lengths, strict=True):
        if math.isinf(length):
            raise InputError(f"no path from {to_cell(*start)} to {to_cell(*goal)}")
        tasks.append(Task(start, goal, int(length // 4), length, map_name, grid.width, grid.height))
    return tasks


# --- M <-> Md ----------------------------------------------------------------------------


def m_to_md(instance: Instance) -> Instance:
    """Each order becomes the destination with its id at the cell of its ordered shelf.

    Nothing is lost: shelves, products and stations stay, and each order keeps its picking
    station (an order without lines asks for nothing), so :func:`md_to_m` rebuilds it.
    """
    result = _copy(instance)
    for ident, order in sorted(instance.orders.items()):
        product = next(iter(order.lines), None)
        cell = _order_goal(instance, order)
        shelf = next(s for s in instance.shelves.values() if s.at == cell)
        if order.lines[product] not in (None, 1) or product != min(_products_on(instance, shelf.id)):
            raise InputError(f"order {ident} is not a domain M order (one unit of the first product "
                             f"on a shelf); it cannot become a destination without loss")
        result.destinations[ident] = Destination(ident, cell)
        result.orders[ident] = Order(ident, {}, order.station)
    result.assignment = _relabel(instance, result, "destination")
    return result


def md_to_m(instance: Instance) -> Instance:
    """Each destination becomes the order with its id, asking for one unit of the first product
    on the shelf at the destination; missing shelves, products and a station are added."""
    result = _copy(instance)
    result.destinations = {}
    next_shelf = max(instance.shelves, default=0) + 1
    next_product = max(instance.products, default=0) + 1
    if not result.stations:
        goals = {d.at for d in instance.destinations.values()}
        shelf_cells = {s.at for s in instance.shelves.values()}
        free = next((cell for _id, cell in sorted(instance.nodes.items())
                     if cell not in goals and cell not in shelf_cells), None)
        if free is None:
            raise InputError("domain M needs a picking station, and no node is free for one")
        result.stations[1] = PickingStation(1, free)
    first_station = min(result.stations)
    for ident, destination in sorted(instance.destinations.items()):
        shelf = next((s for s in result.shelves.values() if s.at == destination.at), None)
        if shelf is None:
            shelf = result.shelves[next_shelf] = Shelf(next_shelf, destination.at)
            next_shelf += 1
        products = _products_on(result, shelf.id)
        if not products:
            result.products[next_product] = Product(next_product, {shelf.id: 1})
            products, next_product = [next_product], next_product + 1
        kept = instance.orders.get(ident)
        station = kept.station if kept is not None and kept.station is not None else first_station
        result.orders[ident] = Order(ident, {min(products): 1}, station)
    result.assignment = _relabel(instance, result, "shelf")
    return result


def _relabel(source: Instance, target: Instance, kind: str) -> dict[int, tuple[str, int]]:
    """The labelled goals of ``source`` as goals of ``kind`` in ``target``, found by their cells."""
    table = target.destinations if kind == "destination" else target.shelves
    at = {item.at: item.id for item in table.values()}
    return {robot: (kind, at[cell]) for robot, cell in source.assigned_cells().items()}


def _products_on(instance: Instance, shelf: int) -> list[int]:
    return sorted(p.id for p in instance.products.values() if shelf in p.stock)


def _copy(instance: Instance) -> Instance:
    return Instance(
        nodes=dict(instance.nodes), highways=dict(instance.highways),
        robots={i: Robot(r.id, r.at, r.carries) for i, r in instance.robots.items()},
        shelves={i: Shelf(s.id, s.at) for i, s in instance.shelves.items()},
        stations={i: PickingStation(s.id, s.at) for i, s in instance.stations.items()},
        products={i: Product(p.id, dict(p.stock)) for i, p in instance.products.items()},
        orders={i: Order(o.id, dict(o.lines), o.station) for i, o in instance.orders.items()},
        destinations={i: Destination(d.id, d.at) for i, d in instance.destinations.items()},
        assignment=dict(instance.assignment), other_facts=list(instance.other_facts),
        attributes={key: dict(values) for key, values in instance.attributes.items()},
        placed={kind: dict(cells) for kind, cells in instance.placed.items()})


# --- plans -------------------------------------------------------------------------------


def result_to_plan(result: LacamResult, instance: Instance | None = None) -> Plan:
    """Agent k's path (0-based) becomes robot k+1's moves; waiting is no action."""
    configurations = result.configurations
    if instance is not None:
        starts = [from_cell(r.at) for _i, r in sorted(instance.robots.items())]
        if configurations[0] != starts:
            raise InputError("the result's first configuration is not the instance's robot positions")
    actions = []
    for step in range(1, len(configurations)):
        for agent, (before, after) in enumerate(zip(configurations[step - 1], configurations[step], strict=True)):
            dx, dy = after[0] - before[0], after[1] - before[1]
            if (dx, dy) == (0, 0):
                continue
            if abs(dx) + abs(dy) != 1:
                raise InputError(f"agent {agent} jumps from {before} to {after} at step {step}")
            actions.append(Action(step, agent + 1, "move", (dx, dy)))
    return Plan(actions)


def plan_to_result(instance: Instance, plan: Plan) -> LacamResult:
    """Robot positions at every step (moves only) as a LaCAM/PIBT result."""
    robots = sorted(instance.robots)
    position = {r: from_cell(instance.robots[r].at) for r in robots}
    configurations = [[position[r] for r in robots]]
    by_step = plan.by_step()
    last_move = dict.fromkeys(robots, 0)
    for step in range(1, plan.horizon + 1):
        for action in by_step.get(step, []):
            if action.name != "move" or action.robot not in position or action.kind != "robot" \
                    or action.args not in DIRECTIONS:
                raise InputError(f"only moves of the instance's robots convert, got {format_action(action)}")
            x, y = position[action.robot]
            position[action.robot] = (x + action.args[0], y + action.args[1])
            last_move[action.robot] = step
        configurations.append([position[r] for r in robots])
    goals = [from_cell(goal) for goal in goals_of(instance)] if (
        instance.destinations or instance.orders) else []
    fields = {"agents": str(len(robots)), "solver": "asprilo", "solved": "1",
              "soc": str(sum(last_move.values())), "makespan": str(plan.horizon),
              "starts": "".join(f"({x},{y})," for x, y in configurations[0]),
              "goals": "".join(f"({x},{y})," for x, y in goals), "solution": ""}
    return LacamResult(fields, configurations)


# --- the command -------------------------------------------------------------------------

FORMATS = {".map": "map", ".scen": "scen", ".txt": "result", ".lp": "asprilo"}
#: how convert writes to standard output, for the refusal of a device as OUT
STANDARD_OUTPUT = "- as OUT"


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("source", metavar="IN", help="file to convert (- = stdin for asprilo files)")
    parser.add_argument("target", metavar="OUT", help="file to write (a regular file, not an input; - = stdout)")
    parser.add_argument("--from", dest="source_format", choices=["map", "scen", "result", "asprilo", "plan"],
                        help="format of IN (default: from its ending)")
    parser.add_argument("--to", dest="target_format", choices=["map", "scen", "result", "m", "md", "plan"],
                        help="format of OUT (default: from its ending)")
    parser.add_argument("--agents", type=int, help="number of scenario rows to use (default: all)")
    parser.add_argument("--goals", choices=GOALS, default="md",
                        help="scenario goals as Md destinations (md, default) or M shelves and orders (m)")
    parser.add_argument("--labelled", action="store_true",
                        help="keep the scenario's pairing: robot k must reach goal k (assign/2 facts)")
    parser.add_argument("--map", help="map of a scenario (default: the map named in it, next to it)")
    parser.add_argument("--instance", help="asprilo instance a plan or result belongs to")


def _format(path: str, given: str | None, what: str) -> str:
    if given:
        return given
    found = FORMATS.get(Path(path).suffix)
    if found is None:
        flag = "--from" if what == "IN" else "--to"
        raise InputError(f"cannot tell the format from the ending {Path(path).suffix!r}; say it with {flag}", path)
    return found


def _instance_and_terrain(path: str) -> tuple[Instance, dict]:
    """The instance, read as every command reads it, and what its ``movingai`` facts keep."""
    limits = current()
    sources = as_sources(path, limits)
    facts = load_facts(sources, limits, INSTANCE_NAMES | {"movingai"})
    terrain = _terrain([args for kind, args, _origin in facts if kind == "atom" and args.name == "movingai"])
    return build_instance(sources, facts, [], limits), terrain


def convert(args: argparse.Namespace) -> str:
    """The text of the converted file."""
    source_format = _format(args.source, args.source_format, "IN")
    target_format = _format(args.target, args.target_format, "OUT")
    if source_format == "asprilo" and target_format == "result":
        source_format = "plan"
    if source_format == "result" and target_format == "asprilo":
        target_format = "plan"
    if source_format in ("map", "scen"):
        if target_format not in ("asprilo", "m", "md"):
            raise InputError(f"a {source_format} converts to an asprilo instance (.lp), not {target_format}")
        return _from_movingai(args, source_format)
    try:
        if source_format == "asprilo":
            return _from_instance(args, target_format)
        return _plan_or_result(args, source_format, target_format)
    except InputError as error:
        raise error.at(args.source) from None


def _from_instance(args: argparse.Namespace, target_format: str) -> str:
    instance, terrain = _instance_and_terrain(args.source)
    if target_format == "map":
        return format_map(instance_to_map(instance, terrain))
    if target_format == "scen":
        map_name = Path(args.map).name if args.map else terrain.get(
            "map", Path(args.target).with_suffix(".map").name)
        return format_scenario(instance_to_scenario(instance, map_name))
    if target_format == "md":
        return format_instance(m_to_md(instance))
    if target_format == "m":
        return format_instance(md_to_m(instance))
    raise InputError("say --to m or --to md to convert an asprilo instance into another instance")


def _plan_or_result(args: argparse.Namespace, source_format: str, target_format: str) -> str:
    instance = read_instance(args.instance) if args.instance else None
    if source_format == "result":
        return format_plan(result_to_plan(parse_result(Source.from_path(args.source)), instance))
    if source_format == "plan" and target_format == "result":
        if instance is None:
            raise InputError("converting a plan into a result needs --instance (robot starts and goals)")
        return format_result(plan_to_result(instance, read_plan(args.source)))
    raise InputError(f"no conversion from {source_format} to {target_format}")


def _from_movingai(args: argparse.Namespace, source_format: str) -> str:
    if source_format == "map":
        map_path = Path(args.source)
        grid = parse_map(Source.from_path(map_path))
        if args.agents is not None:
            raise InputError("--agents needs a scenario: convert the .scen file (its map is found next to it)")
        instance = map_to_instance(grid)
    else:
        tasks = parse_scenario(Source.from_path(args.source))
        map_path = Path(args.map) if args.map else _map_beside(args.source, tasks[0].map_name)
        check_output(args.target, [map_path], STANDARD_OUTPUT)  # the map found beside is an input too
        grid = parse_map(Source.from_path(map_path))
        instance = scenario_to_instance(grid, tasks, len(tasks) if args.agents is None else args.agents,
                                        args.goals, args.labelled)
    header = header_lines(instance, command=f"asprilo convert {args.source} {args.target}")
    return format_instance(instance, header) + "\n% MovingAI map data (kept for exact .map round trips)\n" + \
        "\n".join(terrain_facts(grid, map_path.name)) + "\n"


def _map_beside(scenario: str, name: str) -> Path:
    """The map a scenario names: a file in the scenario's folder."""
    if Path(name).name != name or name in ("", ".", ".."):
        raise InputError(f"the scenario names the map {name!r}, not a file beside it; give the map with --map",
                         scenario)
    return Path(scenario).parent / name


def run(args: argparse.Namespace) -> int:
    inputs = [args.source, args.instance, args.map]
    check_output(args.target, inputs, STANDARD_OUTPUT)
    text = convert(args)
    write_output(args.target, text, inputs)
    return 0
