"""The parser of data (asprilo.parse) against clingo: random fact files read by both give
the same atoms.

The files (hypothesis) hold facts of random terms -- numbers in every notation clingo
reads (decimal, negative, ``0x``, ``0o``, ``0b``, -2147483648), strings with the escapes
``\\"``, ``\\\\``, ``\\n`` and any other characters (tabs, umlauts, emoji, ``%``, ``.``,
``*%``), names with ``_`` and ``'``, ``#sup``/``#inf``, functions (``f()`` too), tuples
(``()``, ``(t,)``, trailing commas), brackets around a term, ``-`` on names, functions and
tuples, arithmetic (``+ - * / \\ ** & ? ^ ~ |t|``, unary minus) -- with comments of both
kinds (nested block comments too, and a ``%`` inside one) and blanks between any two
tokens, LF, CRLF or CR line ends, ``#program base.``, and ``#const`` definitions used in
the facts (also before they are defined, and by each other).  Plain init/occurs facts go
through the regular-expression fast path, the others through the parser.

The product never hands data to clingo; this test does, to compare: the text with its
line ends made LF (clingo ends lines and ``%`` comments at LF only; the parser also at CR,
on purpose).  Where the parser refuses a fact for its arithmetic -- undefined (division by
zero, a term that is no number) or beyond 32 bits -- clingo must have dropped it
(undefined; beyond 32 bits clingo wraps the number around and keeps the fact, unless it
holds undefined arithmetic too); the other facts must agree.  Each
file is also read with the fast paths off: the same atoms.  400 files by default, 4,000
more with ``pytest -m slow``.
"""

from __future__ import annotations

import clingo
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from asprilo.errors import InputError
from asprilo.facts import fact_atom, scan_facts
from asprilo.limits import Limits
from asprilo.parse import Reader, find_constants, resolve_constants, to_symbol
from asprilo.sources import Source, ground_atoms

LIMITS = Limits()
NAMES = ["a", "b", "robot", "node", "at", "_x", "__y", "z'", "a1_B", "default", "override", "nota", "f", "object"]
CONSTANTS = ["c0", "c1", "c2", "c3"]

# --- pieces of text ----------------------------------------------------------------------------

blank = st.sampled_from([" ", "", "  ", "\t", "\n"])
comment = st.one_of(
    st.sampled_from(["%* c *%", "%**%", "%* a %* nested *% b *%", "%* x % not closed here *% \n still *%",
                     "%*\n*%", "% line\n", "%\n", "%* a\n%* b\n*%*%"]),
    st.text(st.sampled_from("abc .:-(#\"ü"), max_size=8).map(lambda t: f"%*{t}*%"),
    st.text(st.sampled_from("abc .:-(#\"*ü%"), max_size=8).map(lambda t: f"% {t}\n"),
)
gap = st.lists(st.one_of(blank, comment), max_size=2).map("".join)

string_char = st.one_of(st.sampled_from(['\\"', "\\\\", "\\n", "a", " ", "\t", "ü", "—", "🚚", "%", ".", "*%",
                                         "%*", "#", "'", ":-", "("]),
                        st.characters(blacklist_categories=("Cs",), blacklist_characters='"\\\r\n\x00'))
string = st.lists(string_char, max_size=6).map(lambda parts: '"' + "".join(parts) + '"')


def number_text(value: int, style: str) -> str:
    if style == "hex":
        return hex(value)
    if style == "HEX":
        return "0x" + format(value, "X")
    if style == "oct":
        return "0o" + format(value, "o")
    if style == "bin":
        return bin(value)
    return str(value)


number = st.one_of(
    st.builds(number_text, st.integers(0, 2**31 - 1), st.sampled_from(["dec", "dec", "hex", "HEX", "oct", "bin"])),
    st.integers(0, 40).map(str),
    st.builds(lambda n: f"-{n}", st.integers(0, 2**31 - 1)),
    st.just("-2147483648"),
)
small = st.integers(-30, 30).map(lambda n: f"({n})" if n < 0 else str(n))
name = st.sampled_from(NAMES)
constant = st.sampled_from(CONSTANTS)


@st.composite
def term(draw, depth: int = 0):
    """A term's text, with gaps between its tokens."""
    g = lambda: draw(gap)  # noqa: E731
    leaves = st.one_of(number, string, name, constant, st.sampled_from(["#sup", "#inf", "#supremum", "#infimum"]))
    if depth >= 3:
        return draw(leaves)
    sub = term(depth + 1)
    kind = draw(st.sampled_from(["leaf", "leaf", "function", "tuple", "group", "negated", "arithmetic"]))
    if kind == "leaf":
        return draw(leaves)
    if kind == "function":
        args = draw(st.lists(sub, max_size=3))
        return f"{draw(name)}{g()}({g()}{(g() + ',' + g()).join(args)}{g()})"
    if kind == "tuple":
        args = draw(st.lists(sub, max_size=3))
        trailing = "," if len(args) == 1 or (args and draw(st.booleans())) else ""
        return f"({g()}{(',' + g()).join(args)}{trailing}{g()})"
    if kind == "group":
        return f"({g()}{draw(sub)}{g()})"
    if kind == "negated":
        return f"-{g()}{draw(st.one_of(name, sub))}"
    return draw(arithmetic_term(depth))


@st.composite
def constant_value(draw, index: int):
    """The value of constant ``c<index>``: it may use those with a higher number (no cycle);
    no arithmetic that could fail, numbers small (clingo crashes on -2147483648/-1)."""
    uses = st.sampled_from(CONSTANTS[index + 1:]) if index + 1 < len(CONSTANTS) else small
    simple = st.one_of(small, string, name, uses, st.builds(lambda a, b: f"{a}+{b}", small, small),
                       name.map(lambda n: f"-{n}"))
    return draw(st.one_of(simple, st.lists(simple, min_size=2, max_size=3).map(lambda a: f"({','.join(a)})"),
                          st.lists(simple, max_size=2).map(lambda a: f"g({','.join(a)})")))


@st.composite
def arithmetic_term(draw, depth: int = 0):
    """Arithmetic on small numbers and constants, sometimes on a term that is no number."""
    g = lambda: draw(gap)  # noqa: E731
    operand = st.one_of(small, small, constant, arithmetic_term(depth + 1) if depth < 2 else small,
                        st.sampled_from(["a", '"s"', "(1,2)", "0"]))
    kind = draw(st.sampled_from(["binary", "binary", "unary", "abs", "power"]))
    if kind == "binary":
        operator = draw(st.sampled_from(["+", "-", "*", "/", "\\", "&", "?", "^"]))
        return f"({g()}{draw(operand)}{g()}{operator}{g()}{draw(operand)}{g()})"
    if kind == "unary":
        return f"{draw(st.sampled_from(['-', '~', '- -', '~ ~', '-~']))}{g()}{draw(operand)}"
    if kind == "abs":
        return f"|{g()}{draw(operand)}{g()}|"
    exponent = draw(st.integers(-2, 5))
    return f"({g()}{draw(small)}{g()}**{g()}{exponent if exponent >= 0 else f'({exponent})'}{g()})"


plain_value = st.one_of(st.integers(-999, 999).map(str),
                        st.tuples(st.integers(-999, 999), st.integers(-999, 999)).map(lambda p: f"({p[0]},{p[1]})"))


@st.composite
def plain_fact(draw):
    """An init/2 or occurs/3 fact of the plain shape (the fast path), blanks anywhere."""
    b = lambda: draw(st.sampled_from(["", " ", "\n", "\t"]))  # noqa: E731
    if draw(st.booleans()):
        return (f"init({b()}object({b()}{draw(name)}{b()},{b()}{draw(st.integers(-99, 99))}{b()}){b()},{b()}"
                f"value({b()}{draw(name)}{b()},{b()}{draw(plain_value)}{b()}){b()}){b()}.")
    args = draw(st.sampled_from(["()", "(1,0)", "(-1,0)", "(0,1)", "(1,2,3)", "(5)", "(5,)"]))
    return (f"occurs({b()}object({b()}{draw(name)},{draw(st.integers(1, 9))}){b()},{b()}action({b()}{draw(name)}"
            f"{b()},{b()}{args}{b()}){b()},{b()}{draw(st.integers(0, 99))}{b()}).")


@st.composite
def fact_file(draw):
    """The file as pieces ``(what, text)``: ``f<i>`` for the fact named so (init/occurs facts
    and other statements are ``-``); the text is their concatenation."""
    g = lambda: draw(gap)  # noqa: E731
    statements: list[tuple[str, str]] = []
    for index in range(draw(st.integers(1, 8))):
        if draw(st.integers(0, 3)) == 0:
            statements.append(("-", draw(plain_fact())))
            continue
        sign = draw(st.sampled_from(["", "", "-", "- "]))
        args = draw(st.lists(term(), max_size=3))
        arguments = f"{g()}({g()}{(g() + ',' + g()).join(args)}{g()})" if args else ""
        statements.append((f"f{index}", f"{sign}f{index}{arguments}{g()}."))
    for index in sorted(draw(st.sets(st.integers(0, len(CONSTANTS) - 1), max_size=len(CONSTANTS)))):
        definition = f"#const{g() or ' '}c{index}{g()}={g()}{draw(constant_value(index))}{g()}."
        statements.insert(draw(st.integers(0, len(statements))), ("-", definition))
    if draw(st.booleans()):
        statements.insert(draw(st.integers(0, len(statements))), ("-", "#program base."))
    line_end = draw(st.sampled_from(["\n", "\r\n", "\r", None]))
    pieces = []
    for what, statement in statements:
        pieces += [(what, statement), ("-", draw(st.sampled_from([" ", "\n", "\n\n", " %c\n", "%*x*%"])))]
    if line_end is None:  # mixed
        return [(what, "".join(c if c != "\n" else draw(st.sampled_from(["\n", "\r\n", "\r"])) for c in text))
                for what, text in pieces]
    return [(what, text.replace("\n", line_end)) for what, text in pieces]


# --- the two readers -----------------------------------------------------------------------------

def clingo_atoms(text: str) -> set[str]:
    """The atoms clingo grounds from ``text`` (its line ends made LF), as text."""
    control = clingo.Control(["--warn=none"], logger=lambda _code, _message: None)
    control.add("base", [], text.replace("\r\n", "\n").replace("\r", "\n"))
    control.ground([("base", [])])
    return {str(atom.symbol) for atom in control.symbolic_atoms if atom.is_fact}


def parser_atoms(text: str) -> set[str]:
    return {str(symbol) for symbol in ground_atoms([Source("random.lp", text)], LIMITS)}


def slow_atoms(text: str) -> set[str]:
    """The atoms with both fast paths off: every fact read token by token."""
    reader = Reader(text, "random.lp", LIMITS, quick=False)
    constants = resolve_constants(find_constants(reader))
    found = scan_facts(text, "random.lp", LIMITS, constants, fast=False)
    return {str(to_symbol(fact_atom(kind, args))) for kind, args, _offset in found}


def arithmetic_refusal(error: InputError) -> str | None:
    """``undefined`` or ``range`` for a refusal of arithmetic clingo does not refuse."""
    if "is undefined (" in error.message:
        return "undefined"
    if " is out of range (" in error.message:
        return "range"
    return None


def _check(pieces: list[tuple[str, str]]) -> None:
    text = "".join(piece for _what, piece in pieces)
    expected = clingo_atoms(text)
    try:
        read = parser_atoms(text)
    except InputError as error:
        assert arithmetic_refusal(error), (error, text)
        _check_refused(pieces, expected)
        return
    assert read == expected, text
    assert slow_atoms(text) == read, text


def _check_refused(pieces: list[tuple[str, str]], expected: set[str]) -> None:
    """The parser refused some fact for its arithmetic: find each such fact (read alone,
    with the file's other statements); clingo dropped the undefined ones and kept the
    others (wrapped around); the remaining facts read alike."""
    facts = {what for what, _text in pieces if what != "-"}
    refused = {}
    for fact in facts:
        alone = "".join(text for what, text in pieces if what in ("-", fact))
        try:
            parser_atoms(alone)
        except InputError as error:
            why = arithmetic_refusal(error)
            assert why, (error, alone)
            refused[fact] = why
    assert refused, pieces
    named = {atom.split("(")[0].lstrip("-") for atom in expected}
    for fact, why in refused.items():  # (a fact beyond 32 bits may hold undefined arithmetic too)
        assert why == "range" or fact not in named, (fact, why, pieces)
    rest = "".join(text for what, text in pieces if what not in refused)
    assert parser_atoms(rest) == {atom for atom in expected if atom.split("(")[0].lstrip("-") not in refused}, rest


def _settings(examples: int, derandomize: bool = True):
    return settings(max_examples=examples, deadline=None, derandomize=derandomize,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much,
                                           HealthCheck.data_too_large])


@_settings(400)
@given(pieces=fact_file())
def test_random_fact_files_read_as_clingo_reads_them(pieces):
    _check(pieces)


@pytest.mark.slow
@_settings(4000, derandomize=False)
@given(pieces=fact_file())
def test_many_more_random_fact_files(pieces):
    _check(pieces)
