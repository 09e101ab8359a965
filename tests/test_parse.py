"""The parser of data (asprilo.parse): tokens as clingo's, statements, clingo's arithmetic,
constants, the term budgets, no recursion, the fast paths agreeing with the parser,
messages without raw control characters, and what the reader around it refuses."""

from __future__ import annotations

import io
import os
import stat
import subprocess
import sys
from pathlib import Path

import clingo
import pytest

from asprilo.errors import InputError
from asprilo.facts import format_value, scan_facts, value_of
from asprilo.limits import Limits, parse_option
from asprilo.parse import (
    NotData,
    Reader,
    check_program_tokens,
    find_constants,
    line_at,
    parse_terms,
    python_value,
    resolve_constants,
    shown,
    text_of,
    to_symbol,
)
from asprilo.reader import read_instance, read_plan
from asprilo.sources import Source, ground_atoms, split_atoms

LIMITS = Limits()
BUDGET = 60.0  # seconds: a hang guard on what takes well under a second (not a measurement)


def in_child(test) -> None:
    """Run a test function of this module in a process of its own, with a hang guard: a
    crash (a segfault, a recursion error) or a hang fails the test, not the test run."""
    folder = str(Path(__file__).parent)
    code = f"import sys; sys.path.insert(0, {folder!r}); import test_parse; test_parse.{test.__name__}()"
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=BUDGET)
    assert result.returncode == 0, result.stderr[-2000:]


def atoms(text: str, limits: Limits = LIMITS) -> list[str]:
    return [text_of(atom) for atom, _offset in parse_terms(text, "t.lp", limits)]


def refusal(text: str, limits: Limits = LIMITS) -> str:
    with pytest.raises(InputError) as error:
        parse_terms(text, "t.lp", limits)
    return str(error.value)


# --- tokens ------------------------------------------------------------------------------------

def test_names_numbers_strings_and_specials_read_as_clingo_reads_them():
    assert atoms("p(a, _b, __c, 'd, e', f'g_H1, default, override, nota).") == [
        "p(a,_b,__c,'d,e',f'g_H1,default,override,nota)"]
    assert atoms("p(0, 7, 0x1F, 0xa, 0o17, 0b101, 2147483647, 0x7FFFFFFF, -2147483648, 0o0, 0x0, 0x" + "0" * 5000
                 + "1).") == ["p(0,7,31,10,15,5,2147483647,2147483647,-2147483648,0,0,1)"]
    assert "'p(0XA).' holds a variable" in refusal("p(0XA).")  # 0 and XA, as clingo reads it
    assert atoms('p("", "a\\"b", "c\\\\d", "e\\nf", "tab\there", "ü—🚚", "%* not a comment *%").') == [
        'p("","a\\"b","c\\\\d","e\\nf","tab\there","ü—🚚","%* not a comment *%")']
    assert atoms("p(#sup, #supremum, #inf, #infimum).") == ["p(#sup,#sup,#inf,#inf)"]


@pytest.mark.parametrize("text, message", [
    ("p(2147483648).", "t.lp:1: the number 2147483648 is out of range (at most 2147483647)"),
    ("p(0x80000000).", "t.lp:1: the number 0x80000000 is out of range (at most 2147483647)"),
    ("p(0xFFFFFFFF).", "t.lp:1: the number 0xFFFFFFFF is out of range (at most 2147483647)"),
    ("p(0x100000001).", "t.lp:1: the number 0x100000001 is out of range (at most 2147483647)"),
    ("p(0o20000000000).", "t.lp:1: the number 0o20000000000 is out of range (at most 2147483647)"),
    ("p(0b" + "1" * 32 + ").", "t.lp:1: the number 0b11111111...11111 (34 digits) is out of range (at most "
                               "2147483647)"),
    ("p(" + "9" * 5000 + ").", "t.lp:1: the number 9999999999...99999 (5,000 digits) is out of range (at most "
                               "2147483647)"),
    ("p(007).", "t.lp:1: syntax error, unexpected <NUMBER>, expecting , or )"),
    ("p(0x).", "t.lp:1: syntax error, unexpected <IDENTIFIER>, expecting , or )"),
    ("p(X).", "t.lp:1: 'p(X).' holds a variable; data holds only facts, #const and '#program base.' "
              "(rules need --allow-rules)"),
    ("p(_).", "t.lp:1: 'p(_).' holds a variable; data holds only facts, #const and '#program base.' "
              "(rules need --allow-rules)"),
    ("p(not).", "t.lp:1: syntax error, unexpected not"),
    ("not.", "t.lp:1: syntax error, unexpected not"),
    ("p(').", "t.lp:1: lexer error, unexpected '"),
    ('p("\\t").', "t.lp:1: lexer error, the escape '\\t' in a string (strings know \\\", \\\\ and \\n)"),
    ('p("a\nb").', "t.lp:1: lexer error, a string that does not end on its line"),
    ('p("a\rb").', "t.lp:1: lexer error, a string that does not end on its line"),
    ('p("abc', "t.lp:1: lexer error, a string that does not end on its line"),
    ("p(\x0c).", "t.lp:1: character (U+000C) outside a string or comment"),
    ("p(\u00a0).", "t.lp:1: character (U+00A0) outside a string or comment"),
    ("p(ä).", "t.lp:1: character 'ä' (U+00E4) outside a string or comment"),
    ("p(1). %* never closed", "t.lp:1: the comment '%*' is never closed ('*%')"),
    ("p(1). %* %* *% one more needed", "t.lp:1: the comment '%*' is never closed ('*%')"),
    ("p(1). %* a % hides *%\n", "t.lp:1: the comment '%*' is never closed ('*%')"),
    ("#foo.", "t.lp:1: lexer error, unexpected #foo"),
    ("# const n=1.", "t.lp:1: lexer error, unexpected #"),
    ("#sup.", "t.lp:1: syntax error, unexpected #sup"),
])
def test_what_clingo_lexer_refuses_or_wraps_is_refused(text, message):
    assert refusal(text) == message


def test_comments_of_both_kinds_and_every_line_end():
    text = "%* a %* nested *% still a comment *% p(1).\n% line\np(2). %* a % line comment hides *% \n *% p(3)."
    assert atoms(text) == ["p(1)", "p(2)", "p(3)"]
    assert atoms("#!/usr/bin/env clingo\np(1). #! another\np(2).") == ["p(1)", "p(2)"]
    for end in ("\n", "\r\n", "\r"):
        text = f"% header{end}p(1).{end}%* block{end}*% p(2). % tail{end}p(3).{end}"
        assert atoms(text) == ["p(1)", "p(2)", "p(3)"], repr(end)
        assert refusal(f"p(1).{end}p(2).{end}p(3{end}") == "t.lp:4: syntax error, unexpected EOF"
        assert refusal(f"% one{end}% two{end}p(X).") == ("t.lp:3: 'p(X).' holds a variable; data holds only facts, "
                                                        "#const and '#program base.' (rules need --allow-rules)")


def test_lines_end_with_lf_crlf_or_cr():
    text = "a\nb\r\nc\rd"
    assert [line_at(text, text.index(c)) for c in "abcd"] == [1, 2, 3, 4]
    assert line_at("a\r\n", 2) == 2 and line_at("a\r\n", 3) == 2


# --- statements -----------------------------------------------------------------------------------

def test_facts_constants_and_the_base_part():
    text = "#program base. #program base(). p. p(). -q. - q(1). r(f(), (), (1,), (1,2,), (3), -(a), -(1,2), --a)."
    assert atoms(text) == ["p", "p", "-q", "-q(1)", "r(f,(),(1,),(1,2),3,-a,-(1,2),a)"]


@pytest.mark.parametrize("text, what", [
    ("p :- q.", "'p :- q.' is a rule"),
    (":- p.", "':- p.' is a rule"),
    ("p(1) :- .", "'p(1) :- .' is a rule"),
    ("{ p }.", "'{ p }.' is a rule"),
    ("p ; q.", "'p ; q.' is a rule"),
    ("p | q.", "'p | q.' is a rule"),
    ("p(X) : q(X).", "'p(X) : q(X).' is a rule"),
    ("#show p/1.", "'#show p/1.' is a directive"),
    ("#external e.", "'#external e.' is a directive"),
    ("#minimize { 1 : p }.", "'#minimize { 1 : p }.' is a directive"),
    ("p(1..3).", "'p(1..3).' holds an interval (..), which stands for many facts"),
    ("p(1;2).", "'p(1;2).' holds a pool (;), which stands for several facts"),
    ("#program step(t).", "'#program step(t).' starts a program part other than base"),
    ("#program base(k).", "'#program base(k).' has parameters"),
    ("p(X) :-\n   q(X),\n   r(X).", "'p(X) :- q(X), r(X).' is a rule"),
    ("p(" + "a," * 100 + "X).", f"'{('p(' + 'a,' * 100)[:57]}...' holds a variable"),
])
def test_more_than_data_is_refused_naming_what_it_is(text, what):
    with pytest.raises(NotData) as error:
        parse_terms("p(0).\n" + text, "t.lp", LIMITS)
    assert str(error.value) == f"t.lp:2: {what}; data holds only facts, #const and '#program base.' " \
                               "(rules need --allow-rules)"


@pytest.mark.parametrize("text", ['#include "other.lp".', '#script (python)\nimport os\n#end.',
                                  'p("\\q"). #include "other.lp".', "p(''). #include \"other.lp\".",
                                  '#const x = "\\q". #include "other.lp".'])
def test_include_and_script_are_never_followed_not_even_after_a_lexer_error(text, tmp_path):
    with pytest.raises(InputError) as error:
        parse_terms(text, "t.lp", LIMITS)
    assert not isinstance(error.value, NotData)  # not even --allow-rules hands it over
    assert "#include" in str(error.value) or "#script" in str(error.value) or "lexer error" in str(error.value)
    with pytest.raises(InputError):
        check_program_tokens(text + "\np :- q.", "t.lp", Limits(allow_rules=True))


def test_rules_are_handed_over_only_as_checked_text_with_lf_line_ends():
    text = "% rules\rp(1). q(X) :- p(X).\r\n#const n = 2.\r"
    assert check_program_tokens(text, "t.lp", LIMITS) == "% rules\np(1). q(X) :- p(X).\n#const n = 2.\n"
    instance = "init(object(node,1),value(at,(1,1))).\r% a comment\rinit(object(node,X+1),value(at,(X+1,1))) :- " \
               "init(object(node,X),value(at,(X,1))), X < 3.\r"
    read = read_instance(Source("rules.lp", instance), Limits(allow_rules=True))
    assert read.nodes == {1: (1, 1), 2: (2, 1), 3: (3, 1)}


# --- arithmetic -----------------------------------------------------------------------------------

def test_arithmetic_is_evaluated_as_clingo_evaluates_it():
    # every expected value below is what clingo 5.8 grounds (tests/test_parse_differential.py compares more)
    cases = {"-2**2": 4, "2**3**2": 512, "2**-2**2": 16, "1?2^3": 0, "6&3?8": 10, "2^3&1": 3, "|-3|": 3,
             "|1|+1": 2, "~5": -6, "~-1": 0, "- ~1": 2, "~ - 1": 0, "-7/2": -3, "7/-2": -3, "-7/-2": 3,
             "-7\\2": -1, "7\\-2": 1, "-7\\-2": -1, "10\\3*2": 2, "2*3\\4": 2, "1+2*3-4/2": 5, "1-2-3": -4,
             "2**-1": 0, "1**-1": 0, "(-1)**-1": 0, "0**0": 1, "(-3)**3": -27, "-3**3": -27, "(-2)**31": -2147483648,
             "1**100000000": 1, "(-1)**100000001": -1, "- - -1": -1, "-2147483647-1": -2147483648,
             "-(2147483648)": -2147483648, "- 2147483648": -2147483648, "0x10+0b1": 17}
    text = "".join(f"p({expression}).\n" for expression in cases)
    assert atoms(text) == [f"p({value})" for value in cases.values()]
    control = clingo.Control(["--warn=none"])
    control.add("base", [], text)
    control.ground([("base", [])])
    assert {str(atom.symbol) for atom in control.symbolic_atoms} == {f"p({value})" for value in cases.values()}


@pytest.mark.parametrize("expression, message", [
    ("7/0", "7/0 is undefined (division by zero; clingo would leave the fact out)"),
    ("7\\0", "7\\0 is undefined (division by zero; clingo would leave the fact out)"),
    ("0**-1", "0**-1 is undefined (zero to a negative power; clingo would leave the fact out)"),
    ("a+1", "a+1 is undefined (arithmetic needs numbers; clingo would leave the fact out)"),
    ('-"s"', '-"s" is undefined (arithmetic needs numbers; clingo would leave the fact out)'),
    ("~a", "~a is undefined (arithmetic needs numbers; clingo would leave the fact out)"),
    ("|f(x)|", "|f(x)| is undefined (arithmetic needs numbers; clingo would leave the fact out)"),
    ("#sup+1", "#sup+1 is undefined (arithmetic needs numbers; clingo would leave the fact out)"),
    ("2147483647+1", "2147483647+1 is out of range (clingo's numbers are 32-bit: -2147483648..2147483647; "
                     "clingo would wrap it around)"),
    ("2**31", "2**31 is out of range (clingo's numbers are 32-bit: -2147483648..2147483647; clingo would wrap it "
              "around)"),
    ("-2147483648/-1", "-2147483648/-1 is out of range (clingo's numbers are 32-bit: -2147483648..2147483647; "
                       "clingo would wrap it around)"),
    ("- -2147483648", "-(-2147483648) is out of range (clingo's numbers are 32-bit: -2147483648..2147483647; "
                      "clingo would wrap it around)"),
    ("|-2147483648|", "|-2147483648| is out of range (clingo's numbers are 32-bit: -2147483648..2147483647; "
                      "clingo would wrap it around)"),
    ("3**100000000000", None),
    ("2147483648+0", "the number 2147483648 is out of range (at most 2147483647)"),
    ("(2147483648)", "the number 2147483648 is out of range (at most 2147483647)"),
])
def test_undefined_arithmetic_and_overflow_are_refused_with_their_line(expression, message):
    if message is None:  # a number too long to read at all
        assert "out of range" in refusal(f"p(1).\np({expression}).")
        return
    assert refusal(f"p(1).\np({expression}).") == f"t.lp:2: {message}"


def test_long_operator_chains_and_deep_brackets_neither_crash_nor_hang():
    in_child(long_chains_and_deep_brackets)


def long_chains_and_deep_brackets():
    assert atoms("p(" + "- " * 20_000 + "1).") == ["p(1)"]
    assert atoms("p(" + "-" * 20_001 + "1).") == ["p(-1)"]
    assert atoms("p(" + "~" * 20_000 + "7).") == ["p(7)"]
    assert atoms("p(" + "1+" * 20_000 + "1).") == ["p(20001)"]
    assert atoms("p(" + "1*" * 20_000 + "3).") == ["p(3)"]
    assert atoms("p(" + "1**" * 20_000 + "3).") == ["p(1)"]
    assert "2**65536 is out of range" in refusal("p(" + "2**" * 20_000 + "2).")
    assert atoms("#const c = " + "- " * 20_000 + "5. p(c).") == ["p(5)"]
    deep = Limits(depth=500)
    assert atoms("p(" + "(" * 498 + "1" + ")" * 498 + ").", deep) == ["p(1)"]
    assert atoms("p(" + "f(" * 498 + "1" + ")" * 498 + ").", deep)[0].count("(") == 499
    assert atoms("p(" + "|" * 498 + "-1" + "|" * 498 + ").", deep) == ["p(1)"]
    assert atoms("p(" + "(" * 499 + "1" + ")" * 499 + ").", deep) == ["p(1)"]  # depth 500
    assert "beyond the limit depth=500" in refusal("p(" + "(" * 500 + "1" + ")" * 500 + ").", deep)
    assert "beyond the limit depth=100" in refusal("p(" + "(" * 100_000)


def test_deep_tuples_become_python_values_without_recursion():
    deep = Limits(depth=500)
    tuple_text = "1"
    for _ in range(498):
        tuple_text = f"({tuple_text},1)"
    [(atom, _offset)] = parse_terms(f"p({tuple_text}).", "t.lp", deep)
    value = python_value(atom.args[0])
    assert format_value(value) == tuple_text
    symbol = to_symbol(atom)
    assert value_of(symbol.arguments[0]) == value and str(symbol) == f"p({tuple_text})"
    text = ("init(object(node,1),value(at,(1,1))). init(object(robot,1),value(at,(1,1))).\n"
            f"init(object(robot,1),value(energy,{tuple_text})).\n")
    with pytest.warns(UserWarning, match="attribute 'energy' of robot"):
        instance = read_instance(Source("deep.lp", text), deep)
    assert instance.other_facts == [f"init(object(robot,1),value(energy,{tuple_text}))."]


# --- constants ------------------------------------------------------------------------------------

def test_constants_are_used_before_their_definition_by_each_other_and_across_files():
    assert atoms("p(n, -n, n*n, f(n), n(1)). #const n = m+1. #const m = 2. #const t = (n, \"s\").q(t, -t).") == [
        "p(3,-3,9,f(3),n(1))", "q((3,\"s\"),-(3,\"s\"))"]
    assert atoms("#const a = b. p(a, -a, --a).") == ["p(b,-b,b)"]
    assert atoms("#const p = 3. p. p(p).") == ["p", "p(3)"]  # atoms are not constants
    files = [Source("one.lp", "init(object(node,1),value(at,(w,1))). init(object(robot,1),value(at,(1,1)))."),
             Source("two.lp", "#const w = 1.")]
    assert read_instance(files).nodes == {1: (1, 1)}
    clash = Source("kinds.lp", "#const robot = shelf. init(object(robot,7),value(at,(1,1))). "
                               "init(object(node,1),value(at,(1,1))).")
    instance = read_instance(clash)
    assert list(instance.shelves) == [7] and not instance.robots


@pytest.mark.parametrize("text, message", [
    ("#const a = b. #const b = a. p(a).", "t.lp:1: the constants a -> b -> a are defined by each other"),
    ("#const a = a+1. p(a).", "t.lp:1: the constants a -> a are defined by each other"),
    ("#const a = 1.\n#const a = 1.", "t.lp:2: the constant a is defined twice (also at t.lp:1)"),
    ("#const a = 1/0. p.", "t.lp:1: 1/0 is undefined (division by zero; clingo would leave the fact out)"),
    ("#const a = 1;2.", "t.lp:1: '#const a = 1;2.' holds a pool (;), which stands for several facts; data holds only "
                        "facts, #const and '#program base.' (rules need --allow-rules)"),
    ("#const a = X.", "t.lp:1: '#const a = X.' holds a variable; data holds only facts, #const and '#program base.' "
                      "(rules need --allow-rules)"),
    ("#const a = .", "t.lp:1: syntax error, unexpected ."),
    ("#const = 1.", "t.lp:1: syntax error, unexpected ="),
])
def test_bad_constants_are_refused(text, message):
    assert refusal(text) == message


def test_a_constant_bomb_is_refused_by_its_length_written_out():
    in_child(constant_bombs)


def constant_bombs():
    names = [f"c{i}" for i in range(12)]
    text = "".join(f"#const {name} = ({','.join([names[i + 1]] * 8)}).\n" for i, name in enumerate(names[:-1]))
    text += '#const c11 = "xxxxxxxx".\np(c0).\n'
    assert "beyond the limit fact-chars=1,000,000" in refusal(text)
    assert "beyond the limit fact-chars=" in refusal("#const s = \"" + "x" * 90_000 + "\".\np(" + "s," * 20 + "s).")
    chain = "".join(f"#const d{i} = f(d{i + 1}).\n" for i in range(150)) + "#const d150 = 1.\np(d0).\n"
    assert "beyond the limit depth=100" in refusal(chain)


# --- budgets --------------------------------------------------------------------------------------

def test_string_and_fact_budgets_have_limit_names():
    assert parse_option("string-chars=5") == ("string_chars", 5)
    assert parse_option("fact-chars=1_000") == ("fact_chars", 1000)
    small = Limits(string_chars=5, fact_chars=40)
    assert atoms('p("12345").', small) == ['p("12345")']
    assert refusal('p("123456").', small) == ("t.lp:1: a string of more than 5 characters, beyond the limit "
                                             "string-chars=5 (raise it with --limit string-chars=N)")
    assert atoms('p("\\n\\n\\n").', Limits(string_chars=6)) == ['p("\\n\\n\\n")']  # counted as written
    assert "string-chars=5" in refusal('p("\\n\\n\\n").', small)
    assert refusal("p(" + "1," * 30 + "1).", small) == ("t.lp:1: a statement of more than 40 characters, beyond the "
                                                        "limit fact-chars=40 (raise it with --limit fact-chars=N)")
    assert "fact-chars=40" in refusal("p(" + " " * 100 + "1).", small)
    facts = scan_facts("init(object(node,1),value(at,(1,1)))." + " " * 50, "t.lp", small)
    assert facts == [("init", ("node", 1, "at", (1, 1)), 0)]
    assert "fact-chars=40" in refusal("init(object(node,1),value(at,(1," + " " * 40 + "1))).", small)


# --- the fast paths agree with the parser ----------------------------------------------------------

FAST_CASES = [
    "init(object(node,1),value(at,(1,1))).",
    "init( object( node , 1 ) ,\r\n value( at , ( 1 , 1 ) ) ) .",
    "init(object(node,-0),value(at,-5)).",
    "occurs(object(robot,1),action(move,(5)),1).",
    "occurs(object(robot,1),action(move,(5,)),1).",
    "occurs(object(robot,1),action(move,(1,2,)),1).",
    "occurs(object(robot,1),action(pickup,()),2).",
    "init(object(x'_1,1),value(_y,(1,1))).",
    "init(object(node,999999999),value(at,(1,1))).",
    'init(object(node,1),value(at,"(1,1)")).',
    "init(object(node,1),value(at,(1,1))).%c\rinit(object(node,2),value(at,(2,1))).",
    "init(object(node,1),%* c *%value(at,(1,1))).",
    "p(a,b,f(c,(1,2)),-3). q. -r(x).",
    "p(f(g(h(1)))). p((1,(2,(3,4)))).",
]
FAST_REFUSED = [
    "init(object(not,1),value(at,(1,1))).",
    "init(object(Robot,1),value(at,(1,1))).",
    "init(object(node,007),value(at,(1,1))).",
    "init(object(node,1),value(at,(1,1))).\x0cinit(object(node,2),value(at,(2,1))).",
    "init(object(node,1),value(at,(1,1))).. init(object(node,2),value(at,(2,1))).",
    "init(object(node,1),value(at,(1,1))),q.",
    "p(a),q(b).",
    "p(1)(2).",
]


def _read(text: str, fast: bool) -> list:
    reader = Reader(text, "t.lp", LIMITS, quick=fast)
    constants = resolve_constants(find_constants(reader))
    return [(kind, text_of(args) if kind == "atom" else args, offset)
            for kind, args, offset in scan_facts(text, "t.lp", LIMITS, constants, fast=fast)]


@pytest.mark.parametrize("text", FAST_CASES)
def test_the_fast_paths_read_what_the_parser_reads(text):
    assert _read(text, True) == _read(text, False)


@pytest.mark.parametrize("text", FAST_REFUSED)
def test_the_fast_paths_refuse_what_the_parser_refuses(text):
    for fast in (True, False):
        with pytest.raises(InputError):
            _read(text, fast)


def test_the_fast_path_leaves_a_fact_that_names_a_constant_to_the_parser():
    text = "#const at = on. #const node = shelf. init(object(node,1),value(at,(1,1))). " \
           "occurs(object(robot,1),action(at,(1,0)),1)."
    assert _read(text, True) == _read(text, False) == [
        ("init", ("shelf", 1, "on", (1, 1)), text.index("init")), ("occurs", ("robot", 1, "on", (1, 0), 1),
                                                                   text.index("occurs"))]


def test_cr_line_ends_are_read_right():
    text = ("% a corridor\rinit(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))).\r"
            "% robots\rinit(object(robot,1),value(at,(1,1))).\r")
    instance = read_instance(Source("cr.lp", text))
    assert len(instance.nodes) == 2 and list(instance.robots) == [1]
    with pytest.raises(InputError) as error:
        read_instance(Source("cr.lp", text + "% line 5\rinit(object(robot,2),value(at,(1,1)).\r"))
    assert str(error.value) == "cr.lp:6: syntax error, unexpected ., expecting , or )"
    plan = read_plan(Source("plan.lp", "% moves\roccurs(object(robot,1),action(move,(1,0)),1).\r"))
    assert len(plan.actions) == 1


# --- the reader around the parser -------------------------------------------------------------------

def test_known_atoms_of_another_arity_are_warned_with_their_arity():
    text = ("init(object(node,1),value(at,(1,1))). init(object(robot,1),value(at,(1,1))).\n"
            "init(a,b,c). init(object(robot,1)). assign(robot(1)). -init(x,y). init.\n")
    with pytest.warns(UserWarning) as caught:
        instance = read_instance(Source("arity.lp", text))
    assert [str(w.message) for w in caught] == [
        "arity.lp:2: ignored (and kept when written): init/3 (init has 2 arguments), "
        "init/1 (init has 2 arguments), assign/1 (assign has 2 arguments), init/0 (init has 2 arguments)"]
    assert instance.other_facts == ["init(a,b,c).", "init(object(robot,1)).", "assign(robot(1)).", "init."]
    with pytest.warns(UserWarning) as caught:
        plan = read_plan(Source("plan.lp", "occurs(object(robot,1),action(move,(1,0)),1).\n"
                                           "occurs(object(robot,1),action(move,(1,0))).\n"))
    assert [str(w.message) for w in caught] == [
        "plan.lp:2: occurs/2 is ignored: occurs has 3 arguments, occurs(object(robot,R),action(Name,Args),T) "
        "(a parenthesis in the wrong place?)"]
    assert len(plan.actions) == 1
    symbols = [clingo.Function("init", [clingo.Number(1)]), clingo.parse_term("init(object(node,1),value(at,(1,1)))")]
    from asprilo.reader import instance_from_atoms
    with pytest.warns(UserWarning, match=r"init/1 \(init has 2 arguments\)"):
        assert instance_from_atoms(symbols).nodes == {1: (1, 1)}


def test_wrong_shapes_of_known_arities_are_refused_with_their_line():
    with pytest.raises(InputError) as error:
        read_instance(Source("shape.lp", "init(object(node,1),value(at,(1,1))).\ninit(robot(2),at(%*c*%2,1)).\n"))
    assert str(error.value) == "shape.lp:2: expected init(object(Type,Id),value(Attribute,Value)), got " \
                               "init(robot(2),at(2,1))"
    with pytest.raises(InputError) as error:
        read_plan(Source("plan.lp", "\noccurs(object(robot,1),action(move,(1,0)),soon)."))
    assert str(error.value) == "plan.lp:2: the time step of occurs(object(robot,1),action(move,(1,0)),soon) " \
                               "must be an integer"


def test_control_characters_are_never_echoed_raw():
    assert shown("\x1b[31mred\x1b[0m") == "\\x1b[31mred\\x1b[0m"
    assert shown("a\nb\r\tc\u202ed\x7f") == "a\\nb\\r\\tc\\u202ed\\x7f"
    assert shown("x" * 100, 20) == "x" * 17 + "..."
    escape = '"\x1b]2;owned\x07\x1b[2J"'
    with pytest.raises(InputError) as error:
        read_instance(Source("esc.lp", f"init(object(robot,{escape}),value(at,(1,1)))."))
    assert str(error.value) == 'esc.lp:1: robot id must be an integer, got "\\x1b]2;owned\\x07\\x1b[2J"'
    with pytest.warns(UserWarning) as caught:
        read_instance(Source("esc.lp", "init(object(node,1),value(at,(1,1))).\n"
                                       f"init(object({escape},1),value(at,(1,1)))."))
    assert str(caught[0].message) == "esc.lp:2: ignored (and kept when written): " \
                                     "object type '\"\\x1b]2;owned\\x07\\x1b[2J\"'"
    long = '"' + "y" * 10_000 + '"'
    with pytest.raises(InputError) as error:
        read_instance(Source("long.lp", f"init(object(robot,{long}),value(at,(1,1)))."))
    assert len(str(error.value)) < 120


def test_clingo_output_lines_split_at_blanks_outside_strings():
    assert split_atoms('p("a\\\\") q("b c\\"d") r((1, 2))') == ['p("a\\\\")', 'q("b c\\"d")', "r((1, 2))"]
    output = 'Answer: 1\r\noccurs(object(robot,1),action(move,(1,0)),1) note("x\\\\")\r\nSATISFIABLE\r\n'
    assert read_plan(Source("out.txt", output)).horizon == 1


def test_ground_atoms_gives_each_atom_once_as_a_clingo_symbol():
    text = "p(1). p(1). init(object(node,1),value(at,(1,1))). #const c = 5. q(c)."
    assert [str(s) for s in ground_atoms([Source("t.lp", text)])] == [
        "p(1)", "init(object(node,1),value(at,(1,1)))", "q(5)"]


# --- inputs that are no regular files ---------------------------------------------------------------

@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="FIFOs need a POSIX system")
def test_a_fifo_or_a_device_is_refused_not_waited_for():
    in_child(fifo_and_device)  # (tests/test_hostile.py runs every command on a FIFO)


def fifo_and_device():
    import tempfile
    fifo = Path(tempfile.mkdtemp()) / "fifo.lp"
    os.mkfifo(fifo)
    with pytest.raises(InputError) as error:
        Source.from_path(fifo)
    assert str(error.value) == f"{fifo}: is a FIFO (named pipe), not a regular file (give data on standard input as -)"
    device = next(path for path in ("/dev/zero", "/dev/urandom", "/dev/null") if stat.S_ISCHR(os.stat(path).st_mode))
    with pytest.raises(InputError) as error:
        Source.from_path(device)  # (read to the file-mb limit before)
    assert str(error.value) == f"{device}: is a character device, not a regular file (give data on standard input as -)"
    with pytest.raises(InputError) as error:
        Source.from_path(fifo.parent)
    assert str(error.value) == f"{fifo.parent}: is a directory, not a file"


def test_standard_input_is_still_read(monkeypatch):
    monkeypatch.setattr(sys, "stdin", io.StringIO("init(object(robot,1),value(at,(1,1)))."))
    assert read_instance("-").robots[1].at == (1, 1)


def test_online_messages_go_through_the_parser():
    """The solver server checks each line, the viewer reads the solver's actions: both parse."""
    from asprilo.model import Action
    from asprilo.online.protocol import check_facts, read_actions

    assert read_actions("occurs(object(robot,1),action(move,(1,0))," + "0+" * 20_000 + "1).") == [
        Action(1, 1, "move", (1, 0))]
    with pytest.raises(InputError) as error:
        check_facts('p("\\q"). #include "/etc/passwd".')
    assert str(error.value).startswith("<online>:1: lexer error, the escape '\\q' in a string")
    with pytest.raises(InputError) as error:
        read_actions("occurs(object(robot,1),action(move,(1,0)),0x80000000).")
    assert str(error.value) == "<solver>:1: the number 0x80000000 is out of range (at most 2147483647)"
