"""Constants: the ``#const`` statements of a text found (a quick pass over its strings and
comments), each read up to its period, and all resolved in the order they use each other
(refusing a cycle and a second definition)."""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass

from ..errors import InputError
from .evaluate import Constant, Evaluator
from .tokens import line_at

#: where the quick pass for #const looks: strings, comments and directives
_CONST_SCAN = re.compile(r'["%#]')


@dataclass(frozen=True)
class ConstantDefinition:
    """A ``#const name = term.`` as found: where its value stands."""

    name: str
    reader: ConstantReader
    start: int  # the statement
    value_start: int
    value_end: int  # the final period


class ConstantReader(Evaluator):
    """An evaluator that reads ``#const`` statements."""

    def constant_at(self, start: int) -> tuple[str, int, int, int]:
        """The ``#const`` at ``start``: ``(name, value start, its period, end)``."""
        kind, name, at, pos = self.token(self.token(start)[3])
        if kind != "i" or name == "not":
            raise self._unexpected(kind, name, at)
        kind, text, at, pos = self.token(pos)
        if kind != "p" or text not in ("=", "=="):  # clingo reads both alike
            raise self._unexpected(kind, text, at, ", expecting =")
        value_start = pos
        depth = 0
        while True:  # to the period that ends the value (checked when the value is read)
            kind, text, at, pos = self.token(pos)
            if kind == "e" or (kind == "p" and text == "." and depth == 0):
                break
            if kind == "h" and text in ("#include", "#script"):
                raise self._directive(text, at)
            if kind == "p" and text == "(":
                depth += 1
            elif kind == "p" and text == ")":
                depth -= 1
            if pos - start > self.limits.fact_chars:
                raise self._too_long(start, pos - start)
        if kind == "e":
            raise self._unexpected(kind, text, at)
        return name, value_start, at, pos

    def references(self, start: int, end: int) -> Iterator[str]:
        """The names used as constants (identifiers without arguments) in ``[start, end)``."""
        pos = start
        previous: str | None = None
        while pos < end:
            kind, text, _at, pos = self.token(pos)
            if previous is not None and not (kind == "p" and text == "("):
                yield previous
            previous = text if kind == "i" else None
        if previous is not None:
            yield previous

    def constant_value(self, definition: ConstantDefinition) -> Constant:
        """The value of a ``#const`` (the constants it uses already resolved)."""
        self._start = definition.start
        value, pos, extra, depth = self._expression(definition.value_start, None)
        kind, text, at, _end = self.token(pos)
        if at != definition.value_end:
            raise self._unexpected(kind, text, at)
        length = definition.value_end - definition.value_start + extra
        if length > self.limits.fact_chars:
            message = self.limits.exceeded("fact_chars", f"the constant {definition.name} written out "
                                                         f"({length:,} characters)").message
            raise self.error(message, definition.start)
        return Constant(value, length, depth)


def find_constants(reader: ConstantReader) -> list[ConstantDefinition]:
    """The ``#const`` statements of a text, found by a quick pass over its strings,
    comments and directives (the text between them holds no ``"``, ``%`` or ``#``)."""
    text = reader.text
    if "#const" not in text:
        return []
    found: list[ConstantDefinition] = []
    pos = 0
    while (hit := _CONST_SCAN.search(text, pos)) is not None:
        start = hit.start()
        char = hit.group()
        if char == '"':
            try:
                pos = reader._string(start)[1]
            except InputError:
                return found  # the reading proper says what is wrong
        elif char == "%" or text.startswith("#!", start):
            try:
                pos = reader._comment_end(start)
            except InputError:
                return found
        elif text.startswith("#const", start) and not re.match(r"[A-Za-z0-9_]", text[start + 6:start + 7]):
            name, value_start, value_end, pos = reader.constant_at(start)
            found.append(ConstantDefinition(name, reader, start, value_start, value_end))
        else:
            pos = start + 1
    return found


def resolve_constants(definitions: list[ConstantDefinition]) -> dict[str, Constant]:
    """The constants' values, each read once the constants it uses are (refusing a cycle
    and a second definition)."""
    by_name: dict[str, ConstantDefinition] = {}
    for definition in definitions:
        first = by_name.get(definition.name)
        if first is not None:
            where = f"{first.reader.name}:{line_at(first.reader.text, first.start)}"
            raise definition.reader.error(f"the constant {definition.name} is defined twice (also at {where})",
                                          definition.start)
        by_name[definition.name] = definition
    uses = {name: [used for used in definition.reader.references(definition.value_start, definition.value_end)
                   if used in by_name] for name, definition in by_name.items()}
    resolved: dict[str, Constant] = {}
    for root in by_name:
        if root in resolved:
            continue
        path, pending = [root], [iter(uses[root])]
        while path:
            used = next(pending[-1], None)
            if used is None:
                name = path.pop()
                pending.pop()
                definition = by_name[name]
                definition.reader.constants = resolved
                resolved[name] = definition.reader.constant_value(definition)
            elif used in path:
                cycle = " -> ".join([*path[path.index(used):], used])
                definition = by_name[used]
                raise definition.reader.error(f"the constants {cycle} are defined by each other", definition.start)
            elif used not in resolved:
                path.append(used)
                pending.append(iter(uses[used]))
    return resolved
