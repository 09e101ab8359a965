"""Plain-words descriptions of actions and objects at a step: tooltips and panel texts."""

from __future__ import annotations

from html import escape

from asprilo.model import Action, Cell
from asprilo.writer import format_value

from .gauges import Gauge
from .track import Track

_DIRECTIONS = {(1, 0): "right", (-1, 0): "left", (0, 1): "down", (0, -1): "up",
               (1, 1): "down-right", (-1, 1): "down-left", (1, -1): "up-right", (-1, -1): "up-left"}


def cell_text(cell: Cell | tuple[float, float]) -> str:
    return f"({int(cell[0])},{int(cell[1])})"


def units_text(units: int | None) -> str:
    return "–" if units is None else str(units)


def action_text(action: Action | None) -> str:
    """``move right``, ``pick up``, ``deliver 2 × product 4 to order 1``, ``wait`` ..."""
    if action is None:
        return "wait"
    args = action.args
    if action.name == "move" and args in _DIRECTIONS:
        return f"move {_DIRECTIONS[args]}"
    if action.name == "pickup" and args == ():
        return "pick up"
    if action.name == "putdown" and args == ():
        return "put down"
    if action.name == "deliver" and isinstance(args, tuple) and len(args) in (2, 3):
        amount = f"{args[2]} × " if len(args) == 3 else ""
        return f"deliver {amount}product {args[1]} to order {args[0]}"
    return f"{action.name}{format_value(args) if args != () else ''}"


def actions_text(actions: list[Action]) -> str:
    """What a robot does at a step: ``wait``, one action, or several joined by ``+``."""
    return " + ".join(action_text(action) for action in actions) or "wait"


def _lines(title: str, rows: list[str]) -> str:
    return f"<b>{escape(title)}</b>" + "".join(f"<br>{escape(row)}" for row in rows)


def robot_lines(track: Track, robot: int, step: int) -> list[str]:
    state = track.state(step)
    index = track.robot_index[robot]
    cell = state.robots.get(robot, track.robot_xy[step, index])
    shelf = state.carries.get(robot)
    rows = [f"at {cell_text(cell)}" + ("  — not a node!" if track.off_floor[step, index] else ""),
            f"carries shelf {shelf}" if shelf is not None else "carries nothing"]
    if step >= 1:
        rows.append(f"step {step}: {actions_text(track.actions(robot, step))}")
    if step < track.horizon:
        rows.append(f"next (step {step + 1}): {actions_text(track.actions(robot, step + 1))}")
    rows.append(f"idle {int(track.idle[step, index])} of {step} steps")
    rows += [gauge_text(gauge, index, robot, step, long=True) for gauge in track.gauges]
    if robot in track.instance.assignment:
        kind, goal = track.instance.assignment[robot]
        rows.append(f"assigned goal: {kind} {goal} at {cell_text(track.instance.assigned_cells()[robot])}")
    return rows


def gauge_text(gauge: Gauge, index: int, robot: int, step: int, long: bool = False) -> str:
    """A robot's level of a resource after ``step``: ``1``, ``-1 ⚠`` at the step it falls
    below the least level, ``–`` when the instance gives none; ``long``: in a sentence
    (``energy 1 after step 1 (2 at the start)``, ``…; below 0 since step 3``)."""
    level, name = gauge.level(index, step), gauge.resource.attribute.replace("_", " ")
    fell = gauge.ran_out(robot, step) if gauge.below(index, step) else None
    if not long:
        return "–" if level is None else f"{level}" + (" ⚠" if fell == step else "")
    if level is None:
        return f"{name}: none given (init(object(robot,{robot}),value({gauge.resource.attribute},N)))"
    text = f"{name} {level} after step {step} ({gauge.level(index, 0)} at the start)" if step else \
        f"{name} {level} at the start"
    if fell is not None:
        text += f"; below {gauge.resource.least} since step {fell}: out of {name} ⚠"
    return text


def destination_lines(track: Track, destination: int) -> list[str]:
    robots = [robot for robot, goal in sorted(track.instance.assignment.items())
              if goal == ("destination", destination)]
    return [f"assigned to robot {', '.join(map(str, robots))}"] if robots else []


def shelf_lines(track: Track, shelf: int, step: int) -> list[str]:
    state = track.state(step)
    carrier = next((robot for robot, carried in state.carries.items() if carried == shelf), None)
    cell = state.shelves.get(shelf)
    rows = [(f"at {cell_text(cell)}, " if cell is not None else "")
            + (f"carried by robot {carrier}" if carrier is not None else "resting")]
    initial = track.instance.shelf_stock().get(shelf, {})
    if initial:
        rows.append("stock now / initially:")
        rows += [f"  product {product}: {units_text(state.stock.get((shelf, product), units))}"
                 f" / {units_text(units)}" for product, units in sorted(initial.items())]
    else:
        rows.append("no products")
    return rows


def station_lines(track: Track, station: int, step: int) -> list[str]:
    state = track.state(step)
    rows = []
    for order in sorted(track.instance.orders.values(), key=lambda o: o.id):
        if order.station != station:
            continue
        parts = []
        for product, units in sorted(order.lines.items()):
            key = (order.id, product)
            if key not in state.open_lines:
                parts.append(f"product {product} done")
            elif units is None or state.open_lines[key] is None:
                parts.append(f"product {product} open")
            else:
                parts.append(f"product {product} {state.open_lines[key]} of {units} open")
        done = all((order.id, product) not in state.open_lines for product in order.lines)
        rows.append(f"order {order.id}{' ✓ complete' if done else ''}: " + ", ".join(parts))
    return rows or ["no orders"]


def cell_kind(track: Track, cell: Cell) -> str:
    instance = track.instance
    if any(station.at == cell for station in instance.stations.values()):
        return "picking station"
    if cell in set(instance.highways.values()):
        return "highway"
    if cell in instance.cells:
        return "storage node"
    return "not a node"


def tooltip(track: Track, step: int, cell: Cell, objects: list[tuple[str, int]]) -> str:
    """Rich-text tooltip: the objects under the mouse, then the cell and what stands on it."""
    parts = []
    for kind, ident in objects:
        if kind == "robot":
            parts.append(_lines(f"Robot {ident}", robot_lines(track, ident, step)))
        elif kind == "shelf":
            parts.append(_lines(f"Shelf {ident}", shelf_lines(track, ident, step)))
        elif kind == "station":
            parts.append(_lines(f"Picking station {ident}", station_lines(track, ident, step)))
        elif kind == "destination":
            parts.append(_lines(f"Destination {ident}", destination_lines(track, ident)))
    state = track.state(step)
    occupants = [f"robot {r}" for r, at in sorted(state.robots.items()) if tuple(at) == cell]
    occupants += [f"shelf {s}" for s, at in sorted(state.shelves.items()) if tuple(at) == cell]
    parts.append(_lines(f"Cell {cell_text(cell)}: {cell_kind(track, cell)}",
                        [("holds " + ", ".join(occupants)) if occupants else "empty"]))
    return "<hr>".join(parts)
