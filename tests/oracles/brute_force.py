"""The minimal makespan of a tiny A/B/C instance by breadth-first search over joint states.

An oracle for the tests: it follows SPEC.md section 4 step by step and shares no code with
the encodings, the checker or the simulator.  A state is where every robot stands, what it
carries, where every resting shelf stands, and what is left to deliver; one step applies
one action (or waiting) per robot at once.  Only for instances of a few cells, robots and
shelves: the number of states grows exponentially.
"""

from __future__ import annotations

from itertools import product

MOVES = ((1, 0), (-1, 0), (0, 1), (0, -1))


class World:
    def __init__(self, instance, domain: str):
        self.domain = domain
        self.cells = set(instance.cells)
        self.storage = set(instance.storage_cells)
        self.robots = sorted(instance.robots)
        self.station_of = {o.id: instance.stations[o.station].at for o in instance.orders.values()}
        self.lines = sorted((o.id, p) for o in instance.orders.values() for p in o.lines)
        demand = {(o.id, p): (u or 1) for o in instance.orders.values() for p, u in o.lines.items()}
        stock = {(s, p.id): (u or 1) for p in instance.products.values() for s, u in p.stock.items()}
        self.holds = {s: {p for (t, p) in stock if t == s} for s in instance.shelves}
        carried = {r.carries for r in instance.robots.values() if r.carries is not None}
        positions = tuple(instance.robots[r].at for r in self.robots)
        loads = tuple(instance.robots[r].carries for r in self.robots)
        resting = frozenset((s, sh.at) for s, sh in instance.shelves.items() if s not in carried)
        if domain == "a":
            need = tuple(demand[line] for line in self.lines)
            left = tuple(sorted(stock.items()))
        else:
            need, left = tuple(1 for _ in self.lines), ()
        self.start = (positions, loads, resting, need, left)

    def done(self, state) -> bool:
        return not any(state[3])

    def options(self, state, i):
        """Every action robot ``i`` may try: ('wait',), ('move', d), ('pickup',), ('putdown',), ('deliver', ...)."""
        positions, loads, resting, _, _ = state
        at, load = positions[i], loads[i]
        yield ("wait",)
        for d in MOVES:
            yield ("move", d)
        if load is None and any(cell == at for _, cell in resting):
            yield ("pickup",)
        if load is not None and at in self.storage:
            yield ("putdown",)
        if load is not None:
            yield from self.deliveries(state, at, load)

    def deliveries(self, state, at, load):
        """The deliveries a robot carrying shelf ``load`` on ``at`` may make."""
        need, left = state[3], state[4]
        open_here = [k for k, (o, p) in enumerate(self.lines) if need[k] and self.station_of[o] == at
                     and p in self.holds[load]]
        if self.domain == "a":
            stock = dict(left)
            for k in open_here:
                p = self.lines[k][1]
                for n in range(1, min(need[k], stock.get((load, p), 0)) + 1):
                    yield ("deliver", k, n)
        elif self.domain == "b":
            for k in open_here:
                yield ("deliver", k, 1)
        elif open_here:
            yield ("deliver", None, 0)  # C: every open line of the station the shelf serves

    def step(self, state, actions):
        """The next state, or None when the joint action breaks a rule."""
        positions, loads, resting, need, left = state
        positions, loads = list(positions), list(loads)
        resting = dict((cell, s) for s, cell in resting)
        need, stock = list(need), dict(left)
        for i, action in enumerate(actions):
            at = positions[i]
            if action[0] == "move":
                nxt = (at[0] + action[1][0], at[1] + action[1][1])
                if nxt not in self.cells:
                    return None
                positions[i] = nxt
            elif action[0] == "pickup":
                loads[i] = resting.pop(at)
            elif action[0] == "putdown":
                resting[at] = loads[i]
                loads[i] = None
            elif action[0] == "deliver":
                self._deliver(i, action, state, need, stock)
        return self._checked(state[0], positions, loads, resting, need, stock)

    def _deliver(self, i, action, state, need, stock):
        _, k, n = action
        load, at = state[1][i], state[0][i]
        if self.domain == "a":
            need[k] -= n
            stock[(load, self.lines[k][1])] -= n
        elif self.domain == "b":
            need[k] = 0
        else:
            for j, (o, p) in enumerate(self.lines):
                if self.station_of[o] == at and p in self.holds[load]:
                    need[j] = 0

    def _checked(self, before, positions, loads, resting, need, stock):
        if len(set(positions)) < len(positions):
            return None  # two robots on one node
        for i in range(len(positions)):
            for j in range(i + 1, len(positions)):
                if positions[i] == before[j] and positions[j] == before[i] and before[i] != before[j]:
                    return None  # swap
        for i, load in enumerate(loads):
            if load is not None and positions[i] in resting:
                return None  # a carrying robot under a resting shelf
        return (tuple(positions), tuple(loads), frozenset((s, c) for c, s in resting.items()),
                tuple(need), tuple(sorted(stock.items())))


def minimal_makespan(instance, domain: str, limit: int = 30, max_states: int = 3_000_000) -> int | None:
    """The fewest steps after which every order line is fulfilled (``None``: not within ``limit``)."""
    world = World(instance, domain)
    layer, seen = {world.start}, {world.start}
    for depth in range(limit + 1):
        if any(world.done(state) for state in layer):
            return depth
        following = set()
        for state in layer:
            choices = [list(world.options(state, i)) for i in range(len(world.robots))]
            for actions in product(*choices):
                nxt = world.step(state, actions)
                if nxt is not None and nxt not in seen:
                    seen.add(nxt)
                    following.add(nxt)
        if not following or len(seen) > max_states:
            return None
        layer = following
    return None
