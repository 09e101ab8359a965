"""Terms, the values data is read into: ``int`` for numbers, :class:`Fn` for functions,
constants and tuples, :class:`Str` for strings, :data:`SUP` and :data:`INF`; how clingo writes
one (:func:`text_of`), the ``clingo.Symbol`` of one and back, its Python value, and text fit
for a one-line message (:func:`shown`)."""

from __future__ import annotations

from typing import Any

import clingo

INT_MIN, INT_MAX = -(2**31), 2**31 - 1


class Fn:
    """A function term ``name(args)``: a constant has no arguments, a tuple the name ``""``;
    ``negative`` for ``-name(args)``."""

    __slots__ = ("name", "args", "negative")

    def __init__(self, name: str, args: tuple = (), negative: bool = False):
        self.name = name
        self.args = args
        self.negative = negative

    def __repr__(self) -> str:
        return f"Fn({shown(text_of(self), 80)})"


class Str:
    """A string term (its value, escapes resolved)."""

    __slots__ = ("value",)

    def __init__(self, value: str):
        self.value = value

    def __repr__(self) -> str:
        return f"Str({shown(text_of(self), 80)})"


class Special:
    """``#sup`` or ``#inf``."""

    __slots__ = ("text",)

    def __init__(self, text: str):
        self.text = text

    def __repr__(self) -> str:
        return self.text


SUP, INF = Special("#sup"), Special("#inf")
Term = int | Fn | Str | Special


class _Big(Special):
    """The literal 2147483648 (``text`` as written), read only as the operand of a unary
    minus (-2147483648)."""

    __slots__ = ()


def quoted(value: str) -> str:
    """A string's value written as clingo writes it."""
    return '"' + value.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'


def text_of(term: Term) -> str:
    """The term written as clingo writes it (``str`` of its symbol)."""
    if type(term) is int:
        return str(term)
    out: list[str] = []
    stack: list[Any] = [term]
    while stack:
        item = stack.pop()
        kind = type(item)
        if kind is str:  # a piece of text pushed below
            out.append(item)
        elif kind is int:
            out.append(str(item))
        elif kind is Fn:
            sign = "-" if item.negative else ""
            if not item.args:
                out.append(sign + (item.name or "()"))
                continue
            stack.append(",)" if not item.name and len(item.args) == 1 else ")")
            for index in range(len(item.args) - 1, -1, -1):
                stack.append(item.args[index])
                if index:
                    stack.append(",")
            out.append(sign + item.name + "(")
        elif kind is Str:
            out.append(quoted(item.value))
        else:
            out.append(item.text)
    return "".join(out)


def to_symbol(term: Term) -> clingo.Symbol:
    """The term as a ``clingo.Symbol`` (built bottom-up, without recursion)."""
    if type(term) is not Fn:
        return _leaf_symbol(term)
    # post-order: (term, its arguments' symbols so far)
    stack: list[tuple[Fn, list[clingo.Symbol]]] = [(term, [])]
    while True:
        node, done = stack[-1]
        if len(done) < len(node.args):
            child = node.args[len(done)]
            if type(child) is Fn and child.args:
                stack.append((child, []))
            else:
                done.append(_leaf_symbol(child))
            continue
        stack.pop()
        symbol = clingo.Function(node.name, done, not node.negative)
        if not stack:
            return symbol
        stack[-1][1].append(symbol)


def _leaf_symbol(term: Term) -> clingo.Symbol:
    kind = type(term)
    if kind is int:
        return clingo.Number(term)  # type: ignore[arg-type]
    if kind is Str:
        return clingo.String(term.value)  # type: ignore[union-attr]
    if kind is Fn:
        return clingo.Function(term.name, [], not term.negative)  # type: ignore[union-attr]
    return clingo.Supremum if term is SUP else clingo.Infimum


def python_value(term: Term) -> Any:
    """The term as :func:`asprilo.facts.value_of` makes its symbol: numbers -> int, tuples ->
    tuple, constants -> their name, anything else -> its text."""
    kind = type(term)
    if kind is int:
        return term
    if kind is not Fn or term.negative or (term.name and term.args):  # type: ignore[union-attr]
        return text_of(term)
    if term.name:  # type: ignore[union-attr]
        return term.name  # type: ignore[union-attr]
    args = term.args  # type: ignore[union-attr]
    if all(type(arg) is int for arg in args):
        return args
    # nested tuples, without recursion: (tuple term, values of its arguments so far)
    stack: list[tuple[Fn, list[Any]]] = [(term, [])]  # type: ignore[list-item]
    while True:
        node, done = stack[-1]
        if len(done) < len(node.args):
            child = node.args[len(done)]
            if type(child) is Fn and not child.name and child.args and not child.negative:
                stack.append((child, []))
            else:
                done.append(python_value(child))
            continue
        stack.pop()
        value = tuple(done)
        if not stack:
            return value
        stack[-1][1].append(value)


def from_symbol(symbol: clingo.Symbol) -> Term:
    """A ``clingo.Symbol`` as a term (the inverse of :func:`to_symbol`)."""
    kind = symbol.type
    if kind == clingo.SymbolType.Number:
        return symbol.number
    if kind == clingo.SymbolType.String:
        return Str(symbol.string)
    if kind == clingo.SymbolType.Supremum:
        return SUP
    if kind == clingo.SymbolType.Infimum:
        return INF
    stack: list[tuple[clingo.Symbol, list[Term]]] = [(symbol, [])]
    while True:
        node, done = stack[-1]
        arguments = node.arguments
        if len(done) < len(arguments):
            child = arguments[len(done)]
            if child.type == clingo.SymbolType.Function and child.arguments:
                stack.append((child, []))
            else:
                done.append(from_symbol(child))
            continue
        stack.pop()
        term = Fn(node.name, tuple(done), node.negative)
        if not stack:
            return term
        stack[-1][1].append(term)


def shown(text: str, most: int = 60) -> str:
    """Text fit for a one-line message: at most ``most`` characters (``...`` where cut) and
    no control character raw (``\\x1b``, ``\\n``, ``\\u202e`` instead)."""
    if len(text) > most:
        text = text[:max(most - 3, 1)] + "..."
    if not text.isprintable():
        text = "".join(char if char.isprintable() else char.encode("unicode_escape").decode("ascii")
                       for char in text)
    return text
