"""YAML batch files (``gen -j FILE``): many runs from one preset tree.

    global_settings: { '-N': 30, '-H': true }       # options of every run
    run_configs:                                     # the tree of runs
      1x2x4:                                         # a key is a directory level
        args: { '-x': 11, '-y': 6, ... }             # a preset for everything below
        r02: { args: { '-r': 2, '-o': 2 } }          # a leaf: one run, in 1x2x4/r02/
        r05:
          args:                                      # a list at a leaf: one run each
            - { '-r': 5, '-o': 5 }
            - { '-r': 5, '-o': 10, '-f': 'more-orders-' }
        conf: { args: {...}, ... }                   # a sub-configuration without a directory level

Nested nodes inherit their parents' args; only leaves run.  Keys are option flags (or field
names); values are checked as on the command line.  Errors name the file and line.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from asprilo.errors import InputError
from asprilo.yamlfile import YamlMapping, line_of, load_yaml, printable, shown

from .config import parse_values

_NAME = re.compile(r"^[\w.+=@-]+$")


@dataclass(frozen=True)
class Run:
    """One run of a batch: its directory below the output directory and its option values."""

    path: tuple[str, ...]
    index: int  # position among the runs of one leaf (several when args is a list)
    values: dict[str, Any]
    line: int

    @property
    def directory(self) -> str:
        return "/".join(self.path)


def load_batch(path: str | Path) -> list[Run]:
    """Read a batch file into its runs (leaves), each with its merged option values."""
    return list(_Batch(Path(path)).runs(load_yaml(path)))


class _Batch:
    def __init__(self, path: Path):
        self.path = path
        self.name = str(path)

    def fail(self, message: str, line: int | None) -> InputError:
        return InputError(printable(message), self.name, line)  # keys and values may hold any character

    def runs(self, document: Any) -> Iterator[Run]:
        if not isinstance(document, YamlMapping):
            raise self.fail("a batch file is a mapping with global_settings and run_configs", 1)
        for key in document:
            if key not in ("global_settings", "run_configs"):
                raise self.fail(f"unknown key {shown(key)} (expected global_settings, run_configs)",
                                document.key_lines[key])
        if "run_configs" not in document:
            raise self.fail("no run_configs", document.line)
        settings = document.get("global_settings") or {}
        line = document.line_of("global_settings")
        preset = self.options(settings, line)
        tree = document["run_configs"]
        if not isinstance(tree, YamlMapping):
            raise self.fail("run_configs must be a mapping", document.key_lines["run_configs"])
        yield from self.walk(tree, (), preset)

    def options(self, args: Any, line: int) -> dict[str, Any]:
        if not isinstance(args, dict):
            raise self.fail(f"args must be a mapping of options, got {shown(args)}", line)
        try:
            values = parse_values(args)
        except InputError as error:
            line = args.line_of(_first_bad_key(args, error)) if isinstance(args, YamlMapping) else line
            raise error.at(self.name, line) from None
        if "templates" in values:  # template files are relative to the batch file
            values["templates"] = tuple(t if t == "-" else str(self.path.parent / t) for t in values["templates"])
        return values

    def walk(self, node: Any, path: tuple[str, ...], inherited: dict[str, Any]) -> Iterator[Run]:
        line = line_of(node)
        if not isinstance(node, YamlMapping):
            raise self.fail(f"{'/'.join(path) or 'run_configs'}: expected a mapping "
                            f"(args, conf or sub-directories), got {shown(node)}", line)
        children = {key: value for key, value in node.items() if key not in ("args", "conf")}
        confs = node.get("conf")
        confs = [] if confs is None else confs if isinstance(confs, list) else [confs]
        args = node.get("args", {})
        args_line = node.line_of("args")
        leaf = not children and not confs
        if isinstance(args, list):
            if not leaf:
                raise self.fail("a list of args (one run each) belongs to a leaf, not to a node "
                                "with sub-configurations", args_line)
            for index, item in enumerate(args):
                values = {**inherited, **self.options(item, line_of(item, args_line))}
                yield Run(path, index, values, line_of(item, args_line))
            return
        values = {**inherited, **self.options(args or {}, args_line)}
        if leaf:
            yield Run(path, 0, values, line)
            return
        for conf in confs:
            yield from self.walk(conf, path, values)
        for key, child in children.items():
            name = self.directory_name(node, key, path)
            yield from self.walk(child, path + (name,), values)

    def directory_name(self, node: YamlMapping, key: Any, path: tuple[str, ...]) -> str:
        """A key of the tree as the name of a sub-directory (checked)."""
        name = str(key)
        if name.startswith("-"):
            raise self.fail(f"{shown(name)}: an option where a sub-directory is expected; options go under "
                            f"'args:' (see asprilo/generator/README.md)", node.key_lines[key])
        if not _NAME.match(name) or name in (".", ".."):
            raise self.fail(f"{shown(name)} cannot name a directory", node.key_lines[key])
        if node[key] is None:
            raise self.fail(f"{'/'.join(path + (name,))} is empty", node.key_lines[key])
        return name


def _first_bad_key(args: dict, error: InputError) -> Any:
    """The key of ``args`` that an error message is about (its flag is quoted in the message)."""
    for key in args:
        if str(key) in error.message:
            return key
    return None
