"""Read a YAML file (gen batch files, bench suites) so that every problem names its file and line.

Mappings come back as :class:`YamlMapping` (a dict that remembers the line of each key) and
lists as :class:`YamlList` (a list that remembers the line of each item).  A duplicate key, a
key that is not a name, text that is not UTF-8 (a byte-order mark is fine), a binary file or a
YAML syntax error is an :class:`~asprilo.errors.InputError` ``FILE:LINE: what is wrong``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from .errors import InputError


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
    pass


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


def read_yaml_text(path: str | Path) -> str:
    """The text of a YAML file: UTF-8 (with or without a byte-order mark), no NUL bytes."""
    path = Path(path)
    if not path.is_file():
        raise InputError("no such file" if not path.exists() else "is not a file", str(path))
    try:
        data = path.read_bytes()
    except OSError as error:
        raise InputError(f"cannot read: {error.strerror}", str(path)) from None
    if b"\0" in data:
        raise InputError("a binary file, not YAML text", str(path), data[:data.index(b"\0")].count(b"\n") + 1)
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        line = data[:error.start].count(b"\n") + 1
        raise InputError(f"not UTF-8 text (byte 0x{data[error.start]:02x})", str(path), line) from None


def load_yaml(path: str | Path) -> Any:
    """The document of a YAML file (None for an empty one), mappings and lists with their lines."""
    text = read_yaml_text(path)
    loader = _Loader(text)
    loader.name = str(path)
    try:
        return loader.get_single_data()
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        problem = getattr(error, "problem", None) or str(error)
        raise InputError(f"not valid YAML: {problem}", str(path), mark.line + 1 if mark else None) from None
    finally:
        loader.dispose()


def line_of(node: Any, default: int | None = None) -> int | None:
    """The line where a mapping or list starts (``default`` for a plain value)."""
    return getattr(node, "line", default)
