"""Read a YAML file (gen batch files, bench suites) so that every problem names its file and line.

Mappings come back as :class:`YamlMapping` (a dict that remembers the line of each key) and
lists as :class:`YamlList` (a list that remembers the line of each item).  A duplicate key, a
key that is not a name, text that is not UTF-8 (a byte-order mark is fine), a binary file or a
YAML syntax error is an :class:`~asprilo.errors.InputError` ``FILE:LINE: what is wrong``.

Every YAML file is read within budgets (:mod:`asprilo.limits`, ``--limit NAME=N``): its size
(``yaml-kb``), its nesting (``yaml-depth``), its aliases (``yaml-aliases``) and its nodes with
every alias counted as what it stands for (``yaml-nodes``), so that a few hundred bytes of
aliases to aliases ("billion laughs") or thousands of brackets are refused in one line before
anything is built.  An alias inside what its anchor names (a value that contains itself) is
refused too.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from .errors import InputError
from .limits import Limits, current


class YamlMapping(dict):
    """A YAML mapping with the line of the mapping (``line``) and of each key (``key_lines``)."""

    line: int = 0
    key_lines: dict

    def line_of(self, key: Any) -> int:
        """The line of ``key``, or of the mapping when the key is not there."""
        return self.key_lines.get(key, self.line)


class YamlList(list):
    """A YAML sequence with its line (``line``) and the line of each item (``item_lines``)."""

    line: int = 0
    item_lines: list


class _Loader(yaml.SafeLoader):
    """PyYAML's safe loader that composes within the budgets of ``limits``."""

    name: str
    limits: Limits = Limits()

    def budget(self, limits: Limits) -> None:
        self.limits = limits
        self.depth = 0
        self.nodes = 0  # nodes composed so far, aliases counted as what they stand for
        self.aliases = 0
        self.open: set[str] = set()  # anchors of the lists and mappings being composed
        self.sizes: dict[int, int] = {}  # id(node) -> its nodes, for the anchored ones

    def compose_node(self, parent: yaml.Node | None, index: Any) -> yaml.Node:
        event = self.peek_event()
        line = event.start_mark.line + 1
        if isinstance(event, yaml.AliasEvent):
            self.aliases += 1
            if self.aliases > self.limits.yaml_aliases:
                raise self.limits.exceeded("yaml_aliases", f"more than {self.limits.yaml_aliases:,} aliases") \
                    .at(self.name, line)
            if event.anchor in self.open:
                raise InputError(f"the alias *{event.anchor} stands for a value that contains it", self.name, line)
            alias = super().compose_node(parent, index)
            assert alias is not None  # an alias event always composes a node
            self._count(self._size(alias), line)
            return alias
        self._count(1, line)
        if isinstance(event, yaml.CollectionStartEvent):
            self.depth += 1
            if self.depth > self.limits.yaml_depth:
                raise self.limits.exceeded("yaml_depth", f"lists and mappings nested more than "
                                                         f"{self.limits.yaml_depth:,} deep").at(self.name, line)
        anchor = event.anchor
        if anchor is not None:
            self.open.add(anchor)
        before = self.nodes
        try:
            node = super().compose_node(parent, index)
        finally:
            if anchor is not None:
                self.open.discard(anchor)
            if isinstance(event, yaml.CollectionStartEvent):
                self.depth -= 1
        assert node is not None  # a node event always composes a node
        if anchor is not None:
            self.sizes[id(node)] = self.nodes - before + 1
        return node

    def _count(self, nodes: int, line: int) -> None:
        self.nodes += nodes
        if self.nodes > self.limits.yaml_nodes:
            raise self.limits.exceeded("yaml_nodes", f"more than {self.limits.yaml_nodes:,} values, lists and "
                                                     f"mappings (aliases counted as what they stand for)") \
                .at(self.name, line)

    def _size(self, node: yaml.Node) -> int:
        """The nodes an alias stands for (its anchor's, counted when the anchor was composed)."""
        return self.sizes.get(id(node), 1)


def _mapping(loader: _Loader, node: yaml.MappingNode) -> YamlMapping:
    loader.flatten_mapping(node)
    mapping = YamlMapping()
    mapping.line = node.start_mark.line + 1
    mapping.key_lines = {}
    for key_node, value_node in node.value:
        key = loader.construct_object(key_node, deep=True)
        line = key_node.start_mark.line + 1
        if not isinstance(key, (str, int)) or isinstance(key, bool):
            raise InputError(f"a key must be a name, got {key!r}", loader.name, line)
        if key in mapping:
            raise InputError(f"duplicate key {key!r}", loader.name, line)
        mapping[key] = loader.construct_object(value_node, deep=True)
        mapping.key_lines[key] = line
    return mapping


def _sequence(loader: _Loader, node: yaml.SequenceNode) -> YamlList:
    items = YamlList(loader.construct_object(child, deep=True) for child in node.value)
    items.line = node.start_mark.line + 1
    items.item_lines = [child.start_mark.line + 1 for child in node.value]
    return items


_Loader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _mapping)
_Loader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_SEQUENCE_TAG, _sequence)


def read_yaml_text(path: str | Path, limits: Limits | None = None) -> str:
    """The text of a YAML file: UTF-8 (with or without a byte-order mark), no NUL bytes, at
    most ``yaml-kb`` kilobytes (PyYAML reads about a megabyte in seconds)."""
    path = Path(path)
    limits = limits or current()
    if not path.is_file():
        raise InputError("no such file" if not path.exists() else "is not a file", str(path))
    most = limits.yaml_kb * 1024
    try:
        with path.open("rb") as stream:
            data = stream.read(most + 1)
    except OSError as error:
        raise InputError(f"cannot read: {error.strerror}", str(path)) from None
    if len(data) > most:
        raise limits.exceeded("yaml_kb", f"a YAML file of more than {limits.yaml_kb:,} kB").at(str(path))
    if b"\0" in data:
        raise InputError("a binary file, not YAML text", str(path), data[:data.index(b"\0")].count(b"\n") + 1)
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        line = data[:error.start].count(b"\n") + 1
        raise InputError(f"not UTF-8 text (byte 0x{data[error.start]:02x})", str(path), line) from None


def load_yaml(path: str | Path, limits: Limits | None = None) -> Any:
    """The document of a YAML file (None for an empty one), mappings and lists with their
    lines, read within the YAML budgets of ``limits`` (default: those in force)."""
    limits = limits or current()
    text = read_yaml_text(path, limits)
    loader = _Loader(text)
    loader.name = str(path)
    loader.budget(limits)
    try:
        return loader.get_single_data()
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        problem = getattr(error, "problem", None) or str(error)
        raise InputError(f"not valid YAML: {problem}", str(path), mark.line + 1 if mark else None) from None
    finally:
        loader.dispose()


def shown(value: Any, most: int = 80) -> str:
    """A value of a YAML file as a message quotes it: its ``repr``, cut to ``most`` characters."""
    text = repr(value)
    return text if len(text) <= most else text[:most - 3] + "..."


def printable(text: str) -> str:
    """``text`` with every character that is not printable escaped (``\\x1b``, ``\\n``,
    ``\\u202e``): messages that quote a YAML file's keys and values never echo control
    characters raw (``"\\e[2J"`` is a valid YAML key)."""
    if text.isprintable():
        return text
    return "".join(char if char.isprintable() else char.encode("unicode_escape").decode("ascii") for char in text)


def line_of(node: Any, default: int | None = None) -> int | None:
    """The line where a mapping or list starts (``default`` for a plain value)."""
    return getattr(node, "line", default)
