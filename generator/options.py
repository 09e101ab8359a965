"""The generator's options: one table shared by the command line, YAML batch files and headers.

Every option keeps the flag of the original asprilo generator (SPEC.md §6), so the paper's
calls run unchanged.  An option sets one field of :class:`GeneratorConfig` (what to
generate) or of :class:`RunOptions` (how many, where to, which seed).
"""

from __future__ import annotations

import shlex
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from asprilo.domain import Domain
from asprilo.errors import InputError

#: The seed used when none is given (that of the original tool).
DEFAULT_SEED = 123456789


@dataclass(frozen=True)
class Option:
    flags: tuple[str, ...]
    name: str  # field of GeneratorConfig / RunOptions; shorthands set name_min and name_max
    kind: str  # int | float | str | flag | paths | domain
    help: str
    group: str
    metavar: str | None = None

    @property
    def flag(self) -> str:
        """The flag used in messages and command lines (the short one where there is one)."""
        return self.flags[0]


def _o(flags: str, name: str, kind: str, help: str, group: str, metavar: str | None = None) -> Option:
    return Option(tuple(flags.split()), name, kind, help, group, metavar)


FLOOR, OBJECTS, PRODUCTS, ORDERS, SOLVING, OUTPUT = (
    "floor and layout", "objects", "products on shelves", "orders", "solving", "output and batches")

OPTIONS: tuple[Option, ...] = (
    _o("-x --grid-x", "width", "int", "grid size in x-direction", FLOOR, "X"),
    _o("-y --grid-y", "height", "int", "grid size in y-direction", FLOOR, "Y"),
    _o("-n --nodes", "nodes", "int", "number of nodes: a partial grid with gaps (random layout)", FLOOR, "N"),
    _o("--gs --gap-size", "gap_size", "int", "largest gap of missing nodes, in cells (with -n; default 2)",
       FLOOR, "CELLS"),
    _o("-H --highway-layout", "structured", "flag",
       "structured layout: storage zones surrounded by highways, picking stations spread over "
       "the top row, robots filling the bottom row from the left", FLOOR),
    _o("-X --cluster-x", "zone_x", "int", "with -H: storage zone width (default 2)", FLOOR, "X"),
    _o("-Y --cluster-y", "zone_y", "int", "with -H: storage zone height (default 2)", FLOOR, "Y"),
    _o("-B --beltway-width", "border", "int", "with -H: width of the border highway (default 1)", FLOOR, "B"),
    _o("-T --template", "templates", "paths",
       "populate hand-made layout(s): nodes, highways and objects of these instance files are kept "
       "(- = stdin)", FLOOR, "FILE"),
    _o("-p --picking-stations", "stations", "int", "number of picking stations", OBJECTS, "P"),
    _o("-r --robots", "robots", "int", "number of robots", OBJECTS, "R"),
    _o("-s --shelves", "shelves", "int", "number of shelves", OBJECTS, "S"),
    _o("--sc --shelf-coverage", "shelf_coverage", "float",
       "shelves as a percentage of the shelf sites (storage nodes without robots; with -H the zones)",
       OBJECTS, "PERCENT"),
    _o("-R --reachable-shelves", "reachable", "flag",
       "every shelf can be carried to every picking station without moving another shelf", OBJECTS),
    _o("-P --products", "products", "int", "number of products", PRODUCTS, "P"),
    _o("-u --product-units-total", "units", "int", "total number of product units on the shelves",
       PRODUCTS, "U"),
    _o("--pusmin --min-product-units-per-product-shelf", "pus_min", "int",
       "least units of a product on one of its shelves (default 1)", PRODUCTS, "N"),
    _o("--pusmax --max-product-units-per-product-shelf", "pus_max", "int",
       "most units of a product on one of its shelves (default 10; < 1: no limit)", PRODUCTS, "N"),
    _o("--pus --product-units-per-product-shelf", "pus", "int", "--pusmin N --pusmax N", PRODUCTS, "N"),
    _o("--prsmin --min-products-per-shelf", "prs_min", "int", "least products on a shelf (default 0)",
       PRODUCTS, "N"),
    _o("--prsmax --max-products-per-shelf", "prs_max", "int",
       "most products on a shelf (default 20; < 1: no limit)", PRODUCTS, "N"),
    _o("--prs --products-per-shelf", "prs", "int", "--prsmin N --prsmax N", PRODUCTS, "N"),
    _o("--sprmin --min-shelves-per-product", "spr_min", "int",
       "least shelves holding a product (default 1)", PRODUCTS, "N"),
    _o("--sprmax --max-shelves-per-product", "spr_max", "int",
       "most shelves holding a product (default 4; < 1: no limit)", PRODUCTS, "N"),
    _o("--spr --shelves-per-product", "spr", "int", "--sprmin N --sprmax N", PRODUCTS, "N"),
    _o("-o --orders", "orders", "int", "number of orders", ORDERS, "O"),
    _o("--olmin --min-order-lines", "ol_min", "int", "least lines of an order (default 1)", ORDERS, "N"),
    _o("--olmax --max-order-lines", "ol_max", "int", "most lines of an order (default 1)", ORDERS, "N"),
    _o("--ol --order-lines", "ol", "int", "--olmin N --olmax N", ORDERS, "N"),
    _o("--oap --order-all-products", "order_all", "flag", "every product is ordered at least once", ORDERS),
    _o("--domain", "domain", "domain",
       "m: the M alignment (as many products as shelves, one unit of one product per shelf, as many "
       "orders as robots, one line of one unit each); a, b, c: no alignment (default a)", ORDERS, "D"),
    _o("-t --threads", "threads", "int", "clingo threads (default 1; more may vary the result)",
       SOLVING, "T"),
    _o("-w --wait", "time_limit", "float", "time limit per instance in seconds (default 300)",
       SOLVING, "SECONDS"),
    _o("-I --gen-inc", "incremental", "flag",
       "split every stage into rounds (threshold-based splitting, see --split-threshold)", SOLVING),
    _o("--split-threshold", "split_threshold", "int",
       "place K objects per round: K, then 2K, ... (implies -I; default with -I: 100)", SOLVING, "K"),
    _o("--one-shot", "one_shot", "flag",
       "ground all parts together and solve once (for comparison; slower on large instances)", SOLVING),
    _o("-N --num", "count", "int", "number of instances (default 1)", OUTPUT, "N"),
    _o("--seed", "seed", "int", f"random seed (default {DEFAULT_SEED})", OUTPUT, "S"),
    _o("-d --directory", "directory", "str", "output directory (default generatedInstances)", OUTPUT, "DIR"),
    _o("-C --console", "console", "flag", "print the instances to stdout instead of writing files", OUTPUT),
    _o("-f --name-prefix", "prefix", "str", "prefix of every file name", OUTPUT, "PREFIX"),
    _o("--instance-dir", "instance_dir", "flag", "one directory per instance", OUTPUT),
    _o("--se --skip-existing", "skip_existing", "flag",
       "keep instance files that exist already (resume an interrupted run or batch)", OUTPUT),
)

#: flag (short and long) -> option
BY_FLAG: dict[str, Option] = {flag: option for option in OPTIONS for flag in option.flags}
#: option name -> option
BY_NAME: dict[str, Option] = {option.name: option for option in OPTIONS}
#: the run options (not part of what an instance looks like)
RUN_FIELDS = ("count", "seed", "directory", "console", "prefix", "instance_dir", "skip_existing")
SHORTHANDS = ("pus", "prs", "spr", "ol")


def convert(option: Option, value: Any) -> Any:
    """Check and convert a value given for ``option`` (in a YAML file or through the API)."""
    def bad(expected: str) -> InputError:
        return InputError(f"{option.flag} needs {expected}, got {value!r}")

    kind = option.kind
    if kind == "flag":
        if not isinstance(value, bool):
            raise bad("true or false")
        return value
    if kind == "int":
        if isinstance(value, bool) or not isinstance(value, int):
            raise bad("an integer")
        return value
    if kind == "float":
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise bad("a number")
        return value
    if kind == "str":
        if not isinstance(value, str):
            raise bad("a text")
        return value
    if kind == "paths":
        values = [value] if isinstance(value, str) else value
        if not isinstance(values, (list, tuple)) or not all(isinstance(v, str) for v in values):
            raise bad("a file name or a list of file names")
        return tuple(values)
    if kind == "domain":
        domain = value if isinstance(value, Domain) else Domain.parse(str(value))
        if domain is Domain.MD:
            raise InputError("--domain md is not generated; generate m and convert it")
        return domain
    raise AssertionError(kind)


def option_for(key: str) -> Option:
    """The option named by a flag (``-x``, ``--grid-x``) or a field name (``width``)."""
    option = BY_FLAG.get(key) or BY_NAME.get(key)
    if option is None:
        raise InputError(f"unknown option {key!r}")
    return option


def format_command(values: Mapping[str, Any], program: str = "gen") -> str:
    """A canonical command line for option values (name -> value), in table order."""
    words = [program]
    for option in OPTIONS:
        if option.name not in values:
            continue
        value = values[option.name]
        if option.kind == "flag":
            if value:
                words.append(option.flag)
        elif option.kind == "paths":
            words += [option.flag, *value]
        elif option.kind == "domain":
            words += [option.flag, value.value]
        elif option.kind == "float" and float(value).is_integer():
            words += [option.flag, str(int(value))]
        else:
            words += [option.flag, str(value)]
    return shlex.join(words)


def split_values(values: Mapping[str, Any]) -> tuple[dict[str, Any], dict[str, Any]]:
    """Option values -> (GeneratorConfig fields, RunOptions fields)."""
    config = {name: value for name, value in values.items() if name not in RUN_FIELDS}
    run = {name: value for name, value in values.items() if name in RUN_FIELDS}
    return config, run


def names_of(options: Iterable[str]) -> str:
    return "/".join(BY_NAME[name].flag for name in options)
