"""The generator's options: the one table that the command line, YAML batch files, the
configuration classes, the defaults and the checks are all made from.

Every option keeps the flag of the original asprilo generator (SPEC.md §6), so the paper's
calls run unchanged.  An option is a field of :class:`~asprilo.generator.config.GeneratorConfig`
(what to generate) or, marked ``run``, of :class:`~asprilo.generator.config.RunOptions` (how
many, where to, which seed).  Flags of the original that this generator does not take are
listed in :data:`REFUSED`, each with what to use instead.
"""

from __future__ import annotations

import math
import shlex
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.yamlfile import shown

from .releases import PROCESSES

#: The seed used when none is given (that of the original tool).
DEFAULT_SEED = 123456789

#: A check of a given value: None when it is fine, else what is wrong ("must be at least 1, got 0").
Check = Callable[[Any], "str | None"]


def at_least(least: int) -> Check:
    return lambda value: None if value >= least else f"must be at least {least}, got {value}"


def at_most(most: int, why: str = "") -> Check:
    return lambda value: None if value <= most else f"must be at most {most}{why}, got {value}"


def positive(value: float) -> str | None:
    if not value > 0:
        return f"must be positive, got {value}"
    return None if math.isfinite(value) else f"must be a finite number, got {value}"


def one_of(choices: tuple[str, ...]) -> Check:
    return lambda value: None if value in choices else f"must be one of {', '.join(choices)}, got {shown(value)}"


def percentage(value: float) -> str | None:
    return None if 0 <= value <= 100 else f"is a percentage (0..100), got {value}"


def name_part(value: str) -> str | None:
    """Text that goes into a file name and keeps the file in its folder."""
    if "/" in value or "\\" in value or value in (".", ".."):
        return f"must be part of a file name (no '/'), got {shown(value)}"
    return None


#: The most clingo threads: clasp's portfolio gives the 15th thread a configuration without
#: the lookback that the generator's domain heuristic needs.
MOST_THREADS = 14


@dataclass(frozen=True)
class Option:
    flags: tuple[str, ...]
    name: str  # field of GeneratorConfig / RunOptions; the shorthands set name_min and name_max
    kind: str  # int | float | str | flag | paths | domain
    help: str  # "{default}" stands for the default
    group: str
    metavar: str | None = None
    default: Any = None  # the value used when the option is not given (None: none, or decided later)
    checks: tuple[Check, ...] = ()
    run: bool = False  # a run option (RunOptions), not part of what an instance looks like

    @property
    def flag(self) -> str:
        """The flag used in messages and command lines (the short one where there is one)."""
        return self.flags[0]

    @property
    def help_text(self) -> str:
        return self.help.format(default=self.default)

    def check(self, value: Any) -> None:
        """Raise an :class:`InputError` naming the flag when ``value`` is out of range."""
        for check in self.checks:
            problem = check(value)
            if problem:
                raise InputError(f"{self.flag} {problem}")


FLOOR, OBJECTS, PRODUCTS, ORDERS, VARIANTS, SOLVING, OUTPUT = (
    "floor and layout", "objects", "products on shelves", "orders", "rule variants (docs/VARIANTS.md)", "solving",
    "output and batches")

COUNT = (at_least(0),)
SIZE = (at_least(1),)


def _o(flags: str, name: str, kind: str, help: str, group: str, metavar: str | None = None, **more: Any) -> Option:
    return Option(tuple(flags.split()), name, kind, help, group, metavar, **more)


OPTIONS: tuple[Option, ...] = (
    _o("-x --grid-x", "width", "int", "grid size in x-direction", FLOOR, "X", checks=SIZE),
    _o("-y --grid-y", "height", "int", "grid size in y-direction", FLOOR, "Y", checks=SIZE),
    _o("-n --nodes", "nodes", "int", "number of nodes: a partial grid with gaps (random layout)", FLOOR, "N",
       checks=SIZE),
    _o("--gs --gap-size", "gap_size", "int", "largest gap of missing nodes, in cells (with -n; default {default})",
       FLOOR, "CELLS", default=2, checks=SIZE),
    _o("-H --highway-layout", "structured", "flag",
       "structured layout: storage zones surrounded by highways, picking stations spread over "
       "the top row, robots filling the bottom row from the left", FLOOR),
    _o("-X --cluster-x", "zone_x", "int", "with -H: storage zone width (default {default})", FLOOR, "X",
       default=2, checks=SIZE),
    _o("-Y --cluster-y", "zone_y", "int", "with -H: storage zone height (default {default})", FLOOR, "Y",
       default=2, checks=SIZE),
    _o("-B --beltway-width", "border", "int", "with -H: width of the border highway (default {default})", FLOOR,
       "B", default=1, checks=SIZE),
    _o("-T --template", "templates", "paths",
       "populate hand-made layout(s): nodes, highways and objects of these instance files are kept "
       "(- = stdin)", FLOOR, "FILE"),
    _o("-p --picking-stations", "stations", "int", "number of picking stations", OBJECTS, "P", checks=COUNT),
    _o("-r --robots", "robots", "int", "number of robots", OBJECTS, "R", checks=COUNT),
    _o("-s --shelves", "shelves", "int", "number of shelves", OBJECTS, "S", checks=COUNT),
    _o("--sc --shelf-coverage", "shelf_coverage", "float",
       "shelves as a percentage of the shelf sites (storage nodes without robots; with -H the zones)",
       OBJECTS, "PERCENT", checks=(percentage,)),
    _o("-R --reachable-shelves", "reachable", "flag",
       "every shelf can be carried to every picking station without moving another shelf", OBJECTS),
    _o("-P --products", "products", "int", "number of products", PRODUCTS, "P", checks=COUNT),
    _o("-u --product-units-total", "units", "int", "total number of product units on the shelves",
       PRODUCTS, "U", checks=COUNT),
    _o("--pusmin --min-product-units-per-product-shelf", "pus_min", "int",
       "least units of a product on one of its shelves (default {default})", PRODUCTS, "N", default=1,
       checks=SIZE),
    _o("--pusmax --max-product-units-per-product-shelf", "pus_max", "int",
       "most units of a product on one of its shelves (default {default}; < 1: no limit)", PRODUCTS, "N",
       default=10),
    _o("--pus --product-units-per-product-shelf", "pus", "int", "--pusmin N --pusmax N", PRODUCTS, "N"),
    _o("--prsmin --min-products-per-shelf", "prs_min", "int", "least products on a shelf (default {default})",
       PRODUCTS, "N", default=0, checks=COUNT),
    _o("--prsmax --max-products-per-shelf", "prs_max", "int",
       "most products on a shelf (default {default}; < 1: no limit)", PRODUCTS, "N", default=20),
    _o("--prs --products-per-shelf", "prs", "int", "--prsmin N --prsmax N", PRODUCTS, "N"),
    _o("--sprmin --min-shelves-per-product", "spr_min", "int",
       "least shelves holding a product (default {default})", PRODUCTS, "N", default=1, checks=COUNT),
    _o("--sprmax --max-shelves-per-product", "spr_max", "int",
       "most shelves holding a product (default {default}; < 1: no limit)", PRODUCTS, "N", default=4),
    _o("--spr --shelves-per-product", "spr", "int", "--sprmin N --sprmax N", PRODUCTS, "N"),
    _o("-o --orders", "orders", "int", "number of orders", ORDERS, "O", checks=COUNT),
    _o("--olmin --min-order-lines", "ol_min", "int", "least lines of an order (default {default})", ORDERS, "N",
       default=1, checks=SIZE),
    _o("--olmax --max-order-lines", "ol_max", "int", "most lines of an order (default {default})", ORDERS, "N",
       default=1),
    _o("--ol --order-lines", "ol", "int", "--olmin N --olmax N", ORDERS, "N"),
    _o("--oap --order-all-products", "order_all", "flag", "every product is ordered at least once", ORDERS),
    _o("--release", "release", "str", "online scenarios: release the orders over time, steady (evenly spaced), "
       "poisson (a Poisson process) or bursts (of --burst orders); each order gets value(release,Step)",
       ORDERS, "PROCESS", checks=(one_of(PROCESSES),)),
    _o("--release-over", "release_over", "int", "with --release: the steps the orders are released over "
       "(default: twice the orders)", ORDERS, "STEPS", checks=SIZE),
    _o("--burst", "burst", "int", "with --release bursts: orders per burst (default {default})", ORDERS, "N",
       default=5, checks=SIZE),
    _o("--domain", "domain", "domain",
       "m: the M alignment (as many products as shelves, one unit of one product per shelf, as many "
       "orders as robots, one line of one unit each); a, b, c: no alignment (default a)", ORDERS, "D"),
    _o("--variant", "variants", "paths",
       "rule variants the instances are for (diagonal, energy, ...; or variant files): the attributes they "
       "declare are drawn for every object, as their generate: says; repeatable", VARIANTS, "NAME|FILE"),
    _o("--energy", "energy", "str", "every robot's energy, drawn uniformly from MIN..MAX (the attribute the "
       "variant energy reads; default with --variant energy: the variant's range)", VARIANTS, "MIN-MAX"),
    _o("-t --threads", "threads", "int", "clingo threads (default {default}; more may vary the result)",
       SOLVING, "T", default=1, checks=(at_least(1), at_most(MOST_THREADS))),
    _o("-w --wait", "time_limit", "float", "time limit per instance in seconds (default {default})",
       SOLVING, "SECONDS", default=300, checks=(positive,)),
    _o("-I --gen-inc", "incremental", "flag",
       "split every stage into rounds (threshold-based splitting, see --split-threshold)", SOLVING),
    _o("--split-threshold", "split_threshold", "int",
       "place K objects per round: K, then 2K, ... (implies -I; default with -I: {default})", SOLVING, "K",
       default=100, checks=SIZE),
    _o("--one-shot", "one_shot", "flag",
       "ground all parts together and solve once (for comparison; slower on large instances)", SOLVING),
    _o("-N --num", "count", "int", "number of instances (default {default})", OUTPUT, "N", default=1,
       checks=COUNT, run=True),
    _o("--seed", "seed", "int", "random seed (default {default})", OUTPUT, "S", default=DEFAULT_SEED, run=True),
    _o("-d --directory", "directory", "str", "output directory (default {default})", OUTPUT, "DIR",
       default="generatedInstances", run=True),
    _o("-C --console", "console", "flag", "print the instances to stdout instead of writing files", OUTPUT,
       run=True),
    _o("-f --name-prefix", "prefix", "str", "prefix of every file name", OUTPUT, "PREFIX", default="",
       checks=(name_part,), run=True),
    _o("--instance-dir", "instance_dir", "flag", "one directory per instance", OUTPUT, run=True),
    _o("--instance-count", "first", "int",
       "number of the first instance (default {default}): instance K is the same whatever -N is", OUTPUT, "K",
       default=1, checks=SIZE, run=True),
    _o("--se --skip-existing", "skip_existing", "flag",
       "keep instance files that exist already (resume an interrupted run or batch)", OUTPUT, run=True),
    _o("--force", "force", "flag",
       "replace instance files of the same name (without it or --skip-existing, gen refuses to write "
       "over them)", OUTPUT, run=True),
)

#: flag (short and long) -> option
BY_FLAG: dict[str, Option] = {flag: option for option in OPTIONS for flag in option.flags}
#: option name -> option
BY_NAME: dict[str, Option] = {option.name: option for option in OPTIONS}
#: --pus N stands for --pusmin N --pusmax N, and so on
SHORTHANDS = ("pus", "prs", "spr", "ol")


def convert(option: Option, value: Any) -> Any:
    """Check and convert a value given for ``option`` (in a YAML file or through the API)."""
    converted = _CONVERTERS[option.kind](value)
    if converted is None:
        raise InputError(f"{option.flag} needs {_EXPECTED[option.kind]}, got {shown(value)}")
    option.check(converted)
    return converted


def _flag(value: Any) -> bool | None:
    return value if isinstance(value, bool) else None


def _int(value: Any) -> int | None:
    return value if isinstance(value, int) and not isinstance(value, bool) else None


def _number(value: Any) -> float | None:
    return value if isinstance(value, (int, float)) and not isinstance(value, bool) else None


def _text(value: Any) -> str | None:
    return value if isinstance(value, str) else None


def _paths(value: Any) -> tuple[str, ...] | None:
    values = [value] if isinstance(value, str) else value
    if not isinstance(values, (list, tuple)) or not all(isinstance(v, str) for v in values):
        return None
    return tuple(values)


def _domain(value: Any) -> Domain:
    domain = value if isinstance(value, Domain) else Domain.parse(str(value))
    if domain.generation is None:
        raise InputError(f"--domain {domain.value} is not generated; {domain.made_by}")
    return domain


_CONVERTERS: dict[str, Callable[[Any], Any]] = {
    "flag": _flag, "int": _int, "float": _number, "str": _text, "paths": _paths, "domain": _domain}
_EXPECTED = {"flag": "true or false", "int": "an integer", "float": "a number", "str": "a text",
             "paths": "a file name or a list of file names"}


def option_for(key: str) -> Option:
    """The option named by a flag (``-x``, ``--grid-x``) or a field name (``width``)."""
    option = BY_FLAG.get(key) or BY_NAME.get(key)
    if option is None:
        refuse_original(key)
        raise InputError(f"unknown option {shown(key)}")
    return option


def format_command(values: Mapping[str, Any], program: str = "gen") -> str:
    """A canonical command line for option values (name -> value), in table order."""
    words = [program]
    for option in OPTIONS:
        if option.name in values:
            words += _words(option, values[option.name])
    return shlex.join(words)


def _words(option: Option, value: Any) -> list[str]:
    if option.kind == "flag":
        return [option.flag] if value else []
    if option.kind == "paths":
        return [option.flag, *value]
    if option.kind == "domain":
        return [option.flag, value.value]
    if option.kind == "float" and float(value).is_integer():
        return [option.flag, str(int(value))]
    return [option.flag, str(value)]


def split_values(values: Mapping[str, Any]) -> tuple[dict[str, Any], dict[str, Any]]:
    """Option values -> (GeneratorConfig fields, RunOptions fields)."""
    config = {name: value for name, value in values.items() if not BY_NAME[name].run}
    run = {name: value for name, value in values.items() if BY_NAME[name].run}
    return config, run


# --- flags of the original generator that this one does not take --------------------------

#: flags -> what to do instead (one line each)
REFUSED: dict[tuple[str, ...], str] = {
    ("--rand-freq", "--sign-def"): "not needed: every choice is random, drawn from --seed "
                                   "(give another --seed for other instances)",
    ("--sopts", "--solve-opts"): "clingo options are not passed through (use -t for threads, -w for the "
                                 "time limit)",
    ("--im", "--inc-im"): "intermediate instances of -I are not written (generate them with smaller "
                          "counts, or -V for each stage's rounds)",
    ("--gstats",): "no grounding statistics (use -V for each stage's rounds and seconds)",
    ("-D", "--debug"): "there is no debug output (use -V for each stage's rounds and seconds)",
    ("--instance-dir-suffix",): "use --instance-dir (one directory per instance) or -f PREFIX",
    ("--ph-pickstas",): "not needed: -H keeps the top row for picking stations whatever -p is (give -p)",
    ("--ph-robots",): "not needed: -H keeps the bottom row for robots whatever -r is (give -r)",
    ("--prj-warehouse",): "generate the warehouse without orders (leave out -o), then add orders with "
                          "-T FILE -o N",
    ("--prj-orders",): "add orders to an existing warehouse with -T FILE -o N",
    ("--split",): "make the warehouses without orders (-N W, no -o), then the orders of each with "
                  "-T FILE -o O -N K",
    ("-c", "--cat"): "there is no category filter: run a batch file that holds only those sub-directories",
    ("--su", "--skip-existing-sub"): "use --skip-existing: it keeps every instance file that exists, so an "
                                     "interrupted batch resumes",
    ("--tr", "--template-relative"): "templates in a batch file are relative to the batch file",
    ("--preo", "--pre-only", "--pret", "--pre-too"): "batch files have no pre/var presets: every leaf of "
                                                     "run_configs runs (see asprilo/generator/README.md)",
}

#: refused flag -> its message
REFUSED_BY_FLAG: dict[str, str] = {flag: f"{flag}: {advice}" for flags, advice in REFUSED.items()
                                   for flag in flags}


def refuse_original(flag: str) -> None:
    """Raise the one-line advice for a flag of the original generator that is not taken here."""
    if flag in REFUSED_BY_FLAG:
        raise InputError(REFUSED_BY_FLAG[flag])


#: flags of the original that are taken and change nothing, because what they ask for always holds
ALWAYS_ON: dict[str, str] = {"--random": "every choice is random, drawn from --seed"}
