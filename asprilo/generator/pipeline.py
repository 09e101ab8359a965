"""The multi-shot driver: one clingo ``Control`` per instance, grounded and solved stage by stage.

Stages: floor, picking stations, robots, shelves, products on shelves (which shelves, then
how many units), orders (which lines, then how many units).  A stage grounds its
``#program`` part, solves, and the driver adds the stage's choices as facts before the next
part is grounded, so later stages only consider admissible choices.  With a split threshold a
stage works in rounds (place K objects, fix them, place K more, ...).  In one-shot mode every
part is grounded first (``oneshot.lp`` hands each stage's choices on) and solved once.

The solver makes every choice.  The programs rank the candidates by seeded pseudo-random
keys (``random.lp``); the driver only passes the seed, the chances of the coin flips, bounds
worked out from what is placed so far (``demand.py``: what the orders need) and, for large
warehouses, a random sample of candidate pairs.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable, Iterable
from copy import deepcopy
from dataclasses import dataclass, field
from pathlib import Path

import clingo

from asprilo.model import Cell, Instance
from asprilo.solver import Solver
from asprilo.writer import format_instance

from .demand import cover_first, line_bounds, line_tiers, served, shelf_supply_need, shelf_tiers, unit_supply_need
from .plan import GenerationPlan
from .sampling import rng, sample_options

HERE = Path(__file__).resolve().parent
_NUMBER = re.compile(r"-?\d+")
PROGRAMS = ("random.lp", "floor.lp", "structured.lp", "open_layout.lp", "template.lp", "stations.lp",
            "robots.lp", "shelves.lp", "reachable.lp", "products.lp", "supply.lp", "orders.lp", "oneshot.lp")
STAGES = ("floor", "stations", "robots", "shelves", "stock", "units", "lines", "quantities")

#: Candidate (product, shelf) or (order, product) pairs of a round above which the driver
#: offers the solver a random sample of them instead of all.
SAMPLE_BUDGET = 10_000
#: The coins of random.lp: a chance p is the threshold p * COIN.
COIN = 32749
#: How likely an order line asks for one more unit.
MORE_UNITS = 0.2


class GenerationFailed(Exception):
    """No instance: the request is unsatisfiable, or the time limit (or, in a child process
    under limits, the memory budget) ran out first; ``reason`` says so in other words."""

    def __init__(self, stage: str, timed_out: bool, reason: str | None = None):
        self.stage = stage
        self.timed_out = timed_out
        self.reason = reason
        reason = reason or ("the time limit ran out" if timed_out else "the request is unsatisfiable")
        super().__init__(f"{reason} (stage {stage})")

    def __reduce__(self):  # pickled whole: failures come back from the child process (api.generate_limited)
        return GenerationFailed, (self.stage, self.timed_out, self.reason)


@dataclass
class World:
    """What the stages decided: cells of new objects, stock and order lines."""

    nodes: set[Cell] = field(default_factory=set)
    highways: set[Cell] = field(default_factory=set)
    stations: list[Cell] = field(default_factory=list)
    robots: list[Cell] = field(default_factory=list)
    shelves: list[Cell] = field(default_factory=list)
    stock: dict[tuple[int, Cell], int | None] = field(default_factory=dict)
    lines: dict[tuple[int, int], int | None] = field(default_factory=dict)
    order_stations: dict[int, Cell] = field(default_factory=dict)

    def record(self, choice: str) -> None:
        """Take in one choice ``new_X(Round,Args...)``, given as text (much quicker than symbols)."""
        kind = choice[4:choice.index("(")]
        numbers = [int(n) for n in _NUMBER.findall(choice)][1:]  # all arguments are numbers or cells
        if kind == "node":
            self.nodes.add((numbers[0], numbers[1]))
        elif kind in ("station", "robot"):
            getattr(self, kind + "s").append((numbers[0], numbers[1]))
        elif kind == "shelf":
            self.shelves.append((numbers[0], numbers[1]))
        elif kind == "stock":
            self.stock.setdefault((numbers[0], (numbers[1], numbers[2])), None)
        elif kind == "units":
            self.stock[(numbers[0], (numbers[1], numbers[2]))] = numbers[3]
        elif kind == "line":
            self.lines.setdefault((numbers[0], numbers[1]), None)
        elif kind == "quantity":
            self.lines[(numbers[0], numbers[1])] = numbers[2]
        elif kind == "order_station":
            self.order_stations[numbers[0]] = (numbers[1], numbers[2])


@dataclass
class StageReport:
    """What a stage took: rounds, seconds and the solver's conflicts (its search)."""

    stage: str
    rounds: int = 0
    seconds: float = 0.0
    conflicts: int = 0


def _chance(probability: float) -> int:
    """A probability as the threshold of the programs' coins (0..32748)."""
    return max(0, min(COIN, round(probability * COIN)))


def _geometric(mean: float) -> int:
    """The coin for "one more" that makes the number of extra items geometric with ``mean``."""
    mean = max(0.0, mean)
    return _chance(mean / (1 + mean))


class Generator:
    """Generates one instance of a plan from one seed."""

    def __init__(self, plan: GenerationPlan, seed: int, on_stage: Callable[[str], None] | None = None):
        self.plan = plan
        self.seed = seed
        self.on_stage = on_stage  # told each stage as it starts (the child process tells its parent)
        self._stage = ""
        self.solver = Solver(options=["--heuristic=Domain", f"--parallel-mode={plan.threads}"],
                             constants={**plan.constants(), "seed": seed % COIN, "seed2": seed // COIN % COIN})
        for program in PROGRAMS:
            self.solver.load(HERE / program)
        self.deadline = time.monotonic() + plan.time_limit
        self.world = World()
        self.reports = {stage: StageReport(stage) for stage in STAGES}
        self._rounds = {stage: 0 for stage in STAGES}
        self._parts = 0
        self._keyed: set[str] = set()
        self._samples = rng(seed, "samples")

    # --- the stages ----------------------------------------------------------------------

    def run(self) -> World:
        """Run every stage; the clingo control is released afterwards (it holds the ground program)."""
        try:
            self._run()
        finally:
            # Control and Solver refer to each other (the logger): drop the control now
            # rather than at the next garbage collection, so memory stays flat over -N runs.
            self.solver.control = None
        return self.world

    def _run(self) -> None:
        plan = self.plan
        self._layout()
        self._place("stations", plan.stations)
        self._place("robots", plan.robots)
        self._place("shelves", plan.shelves)
        if plan.products:
            self._stock()
            self._units()
        if plan.orders:
            self._lines()
            self._quantities()
        if plan.one_shot:
            self._solve_once()

    def _layout(self) -> None:
        plan = self.plan
        self._enter("floor")
        if plan.layout == "structured":
            self.solver.ground([("structured", []), ("keys", [])])
        elif plan.layout == "template":
            self.solver.add(template_facts(plan.template), "template_input")
            self.solver.ground([("template_input", []), ("template", []), ("keys", []), ("open_layout", [])])
        else:
            self.solver.ground([("grid", []), ("keys", [])])
            if plan.partial_floor:
                round_ = self._round("floor")
                self._step("floor", round_, [("floor", [round_, plan.nodes])], "pass_floor")
            else:
                self.solver.ground([("full_floor", [])])
            self.solver.ground([("open_layout", [])])
        if plan.layout != "template":
            if not plan.partial_floor:
                self.world.nodes = {(x, y) for x in range(1, plan.width + 1) for y in range(1, plan.height + 1)}
            self.world.highways = self._cells("highway")
        if plan.reachable:
            self.solver.ground([("edges", [])])

    def _place(self, stage: str, count: int) -> None:
        """Stations, robots or shelves: ``count`` more, K per round with a split threshold."""
        sizes = self._split(count)
        for index, size in enumerate(sizes):
            round_ = self._round(stage)
            parts = [(stage, [round_, size])]
            last = index == len(sizes) - 1
            if stage == "shelves" and last and self.plan.reachable and self.plan.station_total:
                parts.append(("reachable", [round_]))  # -R is checked once, for all shelves
            self._step(stage, round_, parts, f"pass_{stage}")

    def _stock(self) -> None:
        plan = self.plan
        least, target, most = plan.pairs
        self._add_facts("".join(f"product({p}).\n" for p in plan.products))
        self._keys("product", self._all_products())
        shelves = self._all_shelves()
        ids = list(plan.products)
        spread_chance = _geometric(target / len(ids) - plan.spr_min)  # shelves beyond spr_min
        fill = shelf_tiers(plan, most + len(self._all_stock()), len(shelves))
        done = 0
        for chunk in self._chunks(ids):
            later = len(ids) - ids.index(chunk[-1]) - 1
            bounds = (max(0, least - done - later * plan.spr_max), most - done - later * plan.spr_min)
            shelf_min = 0 if later else plan.prs_min

            def attempt(per_product: int | None, chunk=chunk, bounds=bounds,
                        shelf_min=shelf_min, later=later) -> list[str] | None:
                round_ = self._round("stock")
                facts = ""
                if per_product:
                    facts = "".join(f"sample(stock,{round_},{p},({x},{y})).\n"
                                    for p, (x, y) in sample_options(chunk, shelves, per_product, self._samples))
                parts = [("stock", [round_, chunk[0], chunk[-1], int(bool(per_product)), shelf_min, *bounds,
                                    fill, spread_chance])]
                need = shelf_supply_need(plan, self._shelf_counts(), len(chunk), later, self._served_elsewhere())
                if need:
                    parts.append(("shelf_supply", [round_, chunk[0], chunk[-1], len(plan.orders), need]))
                return self._step("stock", round_, parts, "pass_stock", facts)

            chosen = self._sampled_or_all(attempt, len(chunk), plan.shelf_total, plan.spr_max)
            done += len(chosen or ())

    def _units(self) -> None:
        plan = self.plan
        pairs = plan.pairs[1] if plan.one_shot else len(self.world.stock)
        # the requested units spread evenly over the pairs, on average
        mean = (plan.units - pairs * plan.pus_min) / pairs if plan.units is not None and pairs else 1.0
        total = plan.units if plan.units is not None else -1
        round_ = self._round("units")
        parts = [("units", [round_, plan.products[0], plan.products[-1], total, _geometric(mean)])]
        need = unit_supply_need(plan, self._shelf_counts(), self._served_elsewhere())
        if need:
            parts.append(("supply", [round_, plan.products[0], plan.products[-1], len(plan.orders), need]))
        self._step("units", round_, parts, "pass_units")

    def _shelf_counts(self) -> dict[int, int]:
        """How many shelves each new product of the earlier stock rounds lies on."""
        counts: dict[int, int] = {}
        for product, _shelf in self.world.stock:
            counts[product] = counts.get(product, 0) + 1
        return counts

    def _served_elsewhere(self) -> int:
        """Lines of the new orders that the template's products can serve."""
        return served((units for product, units in self._room().items() if product not in self.plan.products),
                      len(self.plan.orders))

    def _lines(self) -> None:
        plan = self.plan
        products = self._all_products()
        self._keys("product", products)
        self._keys("order", list(plan.orders))
        lines_chance = _geometric((plan.ol_max - plan.ol_min) / 2)  # lines beyond ol_min
        chunks = self._chunks(list(plan.orders))
        for index, chunk in enumerate(chunks):
            final = int(index == len(chunks) - 1)
            later = sum(len(c) for c in chunks[index + 1:])

            def attempt(per_order: int | None, chunk=chunk, final=final, later=later) -> list[str] | None:
                round_ = self._round("lines")
                room = self._room()
                facts = "".join(f"room({round_},{p},{n}).\n" for p, n in room.items())
                if per_order:
                    facts += "".join(f"sample(line,{round_},{o},{p}).\n"
                                     for o, p in sample_options(chunk, products, per_order, self._samples))
                unordered = len(room) - len(self._ordered()) if plan.order_all else 0
                bounds = line_bounds(plan, room, len(chunk), later, unordered)
                spread = line_tiers(plan, room, len(chunk), bounds[1])
                cover = int(cover_first(plan, room, len(chunk), later, unordered))
                part = ("lines", [round_, chunk[0], chunk[-1], int(bool(per_order)), final, *bounds, spread, cover,
                                  lines_chance])
                return self._step("lines", round_, [part], "pass_lines", facts)

            self._sampled_or_all(attempt, len(chunk), len(products), plan.ol_max)

    def _held(self) -> dict[int, int]:
        """The units of every product on the shelves (in one-shot mode, where they are not
        known yet, the most a product can have)."""
        plan = self.plan
        if plan.one_shot:
            return dict.fromkeys(self._all_products(), plan.spr_max * plan.pus_max)
        held = dict.fromkeys(self._all_products(), 0)
        for (product, _shelf), units in self._all_stock().items():
            held[product] += units
        return held

    def _asked(self) -> list[tuple[int, int]]:
        """Every order line so far: its product and the units it asks for (a new line one at
        least: its quantity comes later)."""
        template = self.plan.template
        asked = [(p, q or 1) for o in template.orders.values() for p, q in o.lines.items()] if template else []
        return asked + [(p, 1) for _order, p in self.world.lines]

    def _ordered(self) -> set[int]:
        return {product for product, _units in self._asked()}

    def _room(self) -> dict[int, int]:
        """The units of every product that no order line asks for yet."""
        room = self._held()
        for product, units in self._asked():
            room[product] = room.get(product, 0) - units
        return room

    def _quantities(self) -> None:
        plan = self.plan
        held = self._held()
        round_ = self._round("quantities")
        part = ("quantities", [round_, plan.orders[0], plan.orders[-1], _chance(MORE_UNITS)])
        self._step("quantities", round_, [part], facts="".join(f"held({p},{n}).\n" for p, n in held.items()))

    # --- multi-shot mechanics ------------------------------------------------------------

    def _step(self, stage: str, round_: int, parts: list, pass_part: str | None = None,
              facts: str = "") -> list[str] | None:
        """Ground a stage's parts for one round, solve, and fix the choices as facts.

        Returns the round's choices (``new_*`` atoms as text); ``None`` in one-shot mode, where
        solving waits until every part is grounded.
        """
        started = time.perf_counter()
        self._enter(stage)
        report = self.reports[stage]
        report.rounds += 1
        self._add_facts(facts, parts)
        active = clingo.Function("active", [clingo.Function(stage), clingo.Number(round_)])
        self.solver.assign_external(active, True)
        if self.plan.one_shot:
            if pass_part:
                self.solver.ground([(pass_part, [])])
            report.seconds += time.perf_counter() - started
            return None
        conflicts = self.solver.stats.conflicts
        result = self.solver.solve(time_limit=self._remaining(stage))
        self.solver.release_external(active)
        report.seconds += time.perf_counter() - started
        report.conflicts += self.solver.stats.conflicts - conflicts
        if not result.satisfiable:
            raise GenerationFailed(stage, result.timed_out)
        # new_X(Round,Args) -> the fact X(Args)
        chosen = [text for text in map(str, result.symbols) if text.startswith("new_")]
        self._add_facts("".join(f"{text[4:text.index('(') + 1]}{text[text.index(',') + 1:]}.\n"
                                for text in chosen))
        for text in chosen:
            self.world.record(text)
        return chosen

    def _sampled_or_all(self, attempt: Callable[[int | None], list | None], rows: int, columns: int,
                        most_per_row: int) -> list | None:
        """Solve a round on a sample of the candidate pairs when there are too many of them.

        A row (product or order) gets a few times the candidates it may take
        (``most_per_row``), within the budget, and enough that every column is offered about
        twice.  ``attempt(per_row)`` solves the round with ``per_row`` sampled candidates per
        row, or with all of them (``None``); a sample that turns out unsatisfiable is retried
        in full.
        """
        per_row = max(2 * -(-columns // rows), most_per_row + 1, min(8 * most_per_row, SAMPLE_BUDGET // rows))
        if not self.plan.one_shot and rows * columns > SAMPLE_BUDGET and per_row < columns:
            try:
                return attempt(per_row)
            except GenerationFailed as failure:
                if failure.timed_out:
                    raise
        return attempt(None)

    def _solve_once(self) -> None:
        self._enter("one-shot")
        started = time.perf_counter()
        result = self.solver.solve(time_limit=self._remaining("one-shot"))
        self.reports["floor"].seconds += time.perf_counter() - started
        if not result.satisfiable:
            raise GenerationFailed("one-shot", result.timed_out)
        for text in map(str, result.symbols):
            if text.startswith("new_"):
                self.world.record(text)

    def _add_facts(self, facts: str, parts: Iterable = ()) -> None:
        """Add facts in a part of their own and ground it together with ``parts``."""
        parts = list(parts)
        if facts:
            self._parts += 1
            name = f"facts_{self._parts}"
            self.solver.add(facts, name)
            parts.insert(0, (name, []))
        if parts:
            self.solver.ground(parts)

    def _keys(self, kind: str, ids: list[int]) -> None:
        """Ground the random keys of products or orders (once)."""
        if kind not in self._keyed:
            self._keyed.add(kind)
            self.solver.ground([("number_keys", [kind, min(ids), max(ids)])])

    def _enter(self, stage: str) -> None:
        """Say that ``stage`` starts (to ``on_stage``), once."""
        if self.on_stage is not None and stage != self._stage:
            self._stage = stage
            self.on_stage(stage)

    def _round(self, stage: str) -> int:
        self._rounds[stage] += 1
        return self._rounds[stage]

    def _remaining(self, stage: str) -> float:
        remaining = self.deadline - time.monotonic()
        if remaining <= 0:
            raise GenerationFailed(stage, timed_out=True)
        return remaining

    def _split(self, count: int) -> list[int]:
        if count <= 0:
            return []
        size = self.plan.split or count
        return [min(size, count - start) for start in range(0, count, size)]

    def _chunks(self, ids: list[int]) -> list[list[int]]:
        size = self.plan.split or len(ids)
        return [ids[start:start + size] for start in range(0, len(ids), size)]

    def _cells(self, name: str) -> set[Cell]:
        """The cells C of the facts ``name(C)`` (read from their text: many, and quicker so)."""
        cells = set()
        for atom in self.solver.control.symbolic_atoms.by_signature(name, 1):
            if atom.is_fact:
                x, y = str(atom.symbol)[len(name) + 2:-2].split(",")
                cells.add((int(x), int(y)))
        return cells

    # --- everything placed so far (template and new) -------------------------------------

    def _all_shelves(self) -> list[Cell]:
        template = self.plan.template
        fixed = [s.at for s in template.shelves.values()] if template else []
        return sorted(fixed + self.world.shelves, key=lambda c: (c[1], c[0]))

    def _all_products(self) -> list[int]:
        template = self.plan.template
        return sorted((set(template.products) if template else set()) | set(self.plan.products))

    def _all_stock(self) -> dict[tuple[int, Cell], int]:
        stock: dict[tuple[int, Cell], int] = {}
        template = self.plan.template
        if template:
            cells = {s.id: s.at for s in template.shelves.values()}
            for product in template.products.values():
                for shelf, units in product.stock.items():
                    stock[(product.id, cells[shelf])] = 1 if units is None else units
        stock.update({key: 1 if units is None else units for key, units in self.world.stock.items()})
        return stock


def template_facts(template: Instance) -> str:
    """The template's ``init/2`` facts, with quantity-free entries written as one unit."""
    normal = deepcopy(template)
    for product in normal.products.values():
        product.stock = {shelf: 1 if units is None else units for shelf, units in product.stock.items()}
    for order in normal.orders.values():
        order.lines = {item: 1 if units is None else units for item, units in order.lines.items()}
    return "\n".join(line for line in format_instance(normal, header=[]).splitlines()
                     if line.startswith("init("))
