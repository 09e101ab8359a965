"""The evaluator: terms read token by token with an explicit stack of open brackets,
operators by their precedence, constants put in place, and the arithmetic evaluated as
clingo does (refusing what clingo wraps around or leaves out)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..errors import InputError
from ..limits import Limits
from .refusals import Refuser
from .terms import INT_MAX, INT_MIN, Fn, Str, Term, _Big, shown, text_of
from .tokens import _SUPREMUM

#: binary operators: precedence, function (unary operators bind tighter than all: 7)
_XOR, _OR, _AND, _ADD, _MUL, _POW, _UNARY = 1, 2, 3, 4, 5, 6, 7
_PRECEDENCE = {"^": _XOR, "?": _OR, "&": _AND, "+": _ADD, "-": _ADD, "*": _MUL, "/": _MUL, "\\": _MUL,
               "**": _POW}
_RANGE = "clingo's numbers are 32-bit: -2147483648..2147483647"


@dataclass(frozen=True)
class Constant:
    """A ``#const`` as resolved: its value, its length written out, its depth."""

    value: Term
    length: int
    depth: int


class Evaluator(Refuser):
    """A lexer that reads terms and evaluates their arithmetic, with the constants given."""

    def __init__(self, text: str, name: str, limits: Limits, constants: dict[str, Constant] | None = None):
        super().__init__(text, name, limits)
        self.constants = constants or {}

    # terms ----------------------------------------------------------------------------------------

    def _arguments(self, pos: int, opening: int) -> tuple[tuple, int, int]:
        """The arguments of an atom whose ``(`` is before ``pos``: ``(arguments, end, extra)``."""
        value, end, extra, _depth = self._expression(pos, opening)
        return value.args, end, extra

    def _expression(self, pos: int, opening: int | None) -> tuple[Any, int, int, int]:
        """Read terms from ``pos`` with an explicit stack of open brackets (:class:`_Terms`);
        ``opening`` is the offset of an atom's ``(`` (its arguments are read, up to its
        ``)``) or ``None`` (one term, up to the ``.`` after it, which is not consumed).
        Returns ``(term, end, extra, depth)``: ``extra`` is what constants add to the length
        written out, ``depth`` the deepest nesting (for an atom, its own bracket counted)."""
        return _Terms(self, pos, opening).read()

    def _checked(self, value: Any, offset: int) -> Any:
        if type(value) is _Big:
            self._out_of_range(value.text, offset)
        return value

    # arithmetic ----------------------------------------------------------------------------------

    def _apply(self, operator: tuple[int, str, int], vals: list) -> None:
        precedence, symbol, offset = operator
        if precedence == _UNARY:
            vals.append(self._unary(symbol, vals.pop(), offset))
            return
        right = vals.pop()
        left = vals.pop()
        if type(left) is not int or type(right) is not int:
            self._checked(left, offset)
            self._checked(right, offset)
            raise self._undefined(f"{self._operand(left)}{symbol}{self._operand(right)}",
                                  "arithmetic needs numbers", offset)
        result = _ARITHMETIC[symbol](self, left, right, offset)
        if not INT_MIN <= result <= INT_MAX:
            raise self._overflow(f"{left}{symbol}{right}", offset)
        vals.append(result)

    def _divide(self, left: int, right: int, offset: int, symbol: str = "/") -> int:
        if right == 0:
            raise self._undefined(f"{left}{symbol}{right}", "division by zero", offset)
        quotient = abs(left) // abs(right)  # truncated towards zero, as in C
        return -quotient if (left < 0) != (right < 0) else quotient

    def _remainder(self, left: int, right: int, offset: int) -> int:
        return left - right * self._divide(left, right, offset, "\\")

    def _power(self, base: int, exponent: int, offset: int) -> int:
        if exponent < 0:
            if base == 0:
                raise self._undefined(f"{base}**{exponent}", "zero to a negative power", offset)
            return 0  # as clingo: the integer part, 0 even for 1**-1
        if base in (0, 1):
            return base if exponent else 1
        if base == -1:
            return -1 if exponent % 2 else 1
        if exponent >= 32:
            raise self._overflow(f"{base}**{exponent}", offset)
        return base**exponent

    def _unary(self, symbol: str, value: Any, offset: int) -> Any:
        kind = type(value)
        if kind is int:
            if symbol == "~":
                return ~value
            if value == INT_MIN:
                raise self._overflow(f"-({value})", offset)
            return -value
        if type(value) is _Big and symbol == "-":
            return INT_MIN
        self._checked(value, offset)
        if kind is Fn and symbol == "-":
            return Fn(value.name, value.args, not value.negative)
        raise self._undefined(f"{symbol}{self._operand(value)}", "arithmetic needs numbers", offset)

    def _absolute(self, value: Any, offset: int) -> int:
        if type(value) is not int:
            self._checked(value, offset)
            raise self._undefined(f"|{self._operand(value)}|", "arithmetic needs numbers", offset)
        if value == INT_MIN:
            raise self._overflow(f"|{value}|", offset)
        return abs(value)

    def _operand(self, value: Any) -> str:
        text = text_of(value)
        return text if type(value) is int else shown(text, 30)

    def _undefined(self, what: str, why: str, offset: int) -> InputError:
        return self.error(f"{what} is undefined ({why}; clingo would leave the fact out)", offset)

    def _overflow(self, what: str, offset: int) -> InputError:
        return self.error(f"{what} is out of range ({_RANGE}; clingo would wrap it around)", offset)


_ARITHMETIC = {
    "+": lambda _reader, a, b, _at: a + b,
    "-": lambda _reader, a, b, _at: a - b,
    "*": lambda _reader, a, b, _at: a * b,
    "/": Evaluator._divide,
    "\\": Evaluator._remainder,
    "**": Evaluator._power,
    "&": lambda _reader, a, b, _at: a & b,
    "?": lambda _reader, a, b, _at: a | b,
    "^": lambda _reader, a, b, _at: a ^ b,
}


class _Frame:
    """An open bracket: ``kind`` ``a`` (an atom's arguments), ``f`` (a function's), ``(``,
    ``|`` (absolute value) or ``t`` (the top of a #const value, no bracket); the arguments
    read, and the operators and values of the argument being read."""

    __slots__ = ("kind", "name", "opening", "args", "ops", "vals", "comma")

    def __init__(self, kind: str, name: str, opening: int):
        self.kind = kind
        self.name = name
        self.opening = opening
        self.args: list = []
        self.ops: list[tuple[int, str, int]] = []
        self.vals: list = []
        self.comma = False  # a comma was read: (t,) is a tuple


class _Terms:
    """Terms read token by token with an explicit stack of open brackets (no recursion):
    operands and operators alternate, operators waiting on a stack until one of lower
    precedence, a comma or a closing bracket comes (see :meth:`Evaluator._expression`)."""

    def __init__(self, reader: Evaluator, pos: int, opening: int | None):
        self.reader = reader
        self.pos = pos
        top = _Frame("a", "", opening) if opening is not None else _Frame("t", "", pos)
        self.frames = [top]
        self.frame = top
        self.base = 0 if opening is not None else 1  # a #const value's top is no bracket
        self.deepest = 1 if opening is not None else 0
        self.extra = 0
        self.statement = reader._start
        self.most_end = reader._start + reader.limits.fact_chars
        self.result: tuple[Any, int, int, int] | None = None

    def read(self) -> tuple[Any, int, int, int]:
        token, expect = self.reader.token, True
        operand, operator = self._operand, self._operator
        while self.result is None:
            kind, text, start, self.pos = token(self.pos)
            if self.pos > self.most_end:
                raise self.reader._too_long(self.statement, self.pos - self.statement)
            expect = operand(kind, text, start) if expect else operator(kind, text, start)
        return self.result

    # an operand is expected --------------------------------------------------------------------

    def _operand(self, kind: str, text: str, start: int) -> bool:
        """Read a token where an operand belongs; whether an operand is still expected."""
        if kind == "n":
            self.frame.vals.append(self.reader._number(text, start))
        elif kind == "i":
            return self._name(text, start)
        elif kind == "s":
            self.frame.vals.append(Str(text))
        elif kind == "h" and text in _SUPREMUM:
            self.frame.vals.append(_SUPREMUM[text])
        elif kind == "p":
            return self._prefix(text, start)
        else:
            raise self.reader._beyond_term(start, kind, text)
        return False

    def _name(self, text: str, start: int) -> bool:
        """An identifier: a function if a ``(`` follows, else a constant (or its value)."""
        reader = self.reader
        if text == "not":
            raise reader._beyond_term(start, "i", text)
        kind2, text2, start2, end2 = reader.token(self.pos)
        if kind2 == "p" and text2 == "(":
            self.pos = end2
            self._open(_Frame("f", text, start2))
            return True
        constant = reader.constants.get(text)
        if constant is None:
            self.frame.vals.append(Fn(text))
            return False
        depth = len(self.frames) - self.base + constant.depth
        if depth > reader.limits.depth:
            raise reader._too_deep(start)
        self.deepest = max(self.deepest, depth)
        self.extra += constant.length - len(text)
        if self.pos - self.statement + self.extra > reader.limits.fact_chars:
            raise reader._too_long(self.statement, self.pos - self.statement + self.extra)
        self.frame.vals.append(constant.value)
        return False

    def _prefix(self, text: str, start: int) -> bool:
        """Punctuation where an operand belongs: a unary operator, an opening bracket, or
        the ``)`` of ``f()``, ``()`` and a tuple's trailing comma (``(a,)``)."""
        frame = self.frame
        if text == "-" or text == "~":
            frame.ops.append((_UNARY, text, start))
        elif text == "(" or text == "|":
            self._open(_Frame(text, "", start))
        elif text == ")" and not frame.ops and (frame.kind == "(" or (frame.kind in "af" and not frame.args)):
            self._close(self._tuple(frame))
            return False
        elif text == "," and frame.kind == "(" and not (frame.args or frame.ops or frame.comma):
            kind, text, start, self.pos = self.reader.token(self.pos)  # (,) is (), as in clingo
            if kind != "p" or text != ")":
                raise self.reader._beyond_term(start, kind, text, ", expecting )")
            self._close(self._tuple(frame))
            return False
        else:
            raise self.reader._beyond_term(start, "p", text)
        return True

    def _open(self, frame: _Frame) -> None:
        self.frames.append(frame)
        self.frame = frame
        depth = len(self.frames) - self.base
        if depth > self.reader.limits.depth:
            raise self.reader._too_deep(frame.opening)
        self.deepest = max(self.deepest, depth)

    # an operator (or the end of a term) is expected ------------------------------------------------

    def _operator(self, kind: str, text: str, start: int) -> bool:
        """Read a token after an operand; whether an operand is expected next."""
        frame = self.frame
        precedence = _PRECEDENCE.get(text) if kind == "p" else None
        if precedence is not None:
            ops, vals = frame.ops, frame.vals
            while ops and (ops[-1][0] > precedence or (ops[-1][0] == precedence and precedence != _POW)):
                self.reader._apply(ops.pop(), vals)
            ops.append((precedence, text, start))
            return True
        if kind == "p" and text == "," and frame.kind in "af(":
            frame.args.append(self.reader._checked(self._value(frame), start))
            frame.comma = True
            return True
        if kind == "p" and ((text == ")" and frame.kind in "af(") or (text == "|" and frame.kind == "|")):
            self._close(self._closed(frame, start))
            return False
        if kind == "p" and text == "." and frame.kind == "t":
            self.result = (self.reader._checked(self._value(frame), start), start, self.extra, self.deepest)
            return False
        expecting = "" if kind == "e" else ", expecting , or )" if frame.kind in "af(" else \
            ", expecting |" if frame.kind == "|" else ""
        raise self.reader._beyond_term(start, kind, text, expecting)

    def _value(self, frame: _Frame) -> Any:
        """The argument being read, its operators applied."""
        ops, vals = frame.ops, frame.vals
        while ops:
            self.reader._apply(ops.pop(), vals)
        return vals.pop()

    def _closed(self, frame: _Frame, offset: int) -> Any:
        """The term a closing bracket ends."""
        value = self._value(frame)
        if frame.kind == "|":
            return self.reader._absolute(value, frame.opening)
        if frame.kind == "(" and not frame.args and not frame.comma:
            return value  # (t) is t
        frame.args.append(self.reader._checked(value, offset))
        return self._tuple(frame)

    @staticmethod
    def _tuple(frame: _Frame) -> Fn:
        return Fn(frame.name if frame.kind != "(" else "", tuple(frame.args))

    def _close(self, value: Any) -> None:
        self.frames.pop()
        if not self.frames:
            self.result = (value, self.pos, self.extra, self.deepest)
            return
        self.frame = self.frames[-1]
        self.frame.vals.append(value)
