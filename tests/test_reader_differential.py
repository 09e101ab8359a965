"""One reader (issue 46, item 1): the fast paths of the fact reader (the regular expression
of plain init/occurs facts in asprilo.facts, the plain-token reading in asprilo.parse),
the strict token path (both fast paths off) and clingo's own parser read every text
alike.

The texts are made here, seeded: facts of the instance and plan shapes and others, with
leaves of every kind (numbers, names, strings holding ``%`` and ``.``, ``#sup``, functions,
tuples, negated terms), ``#const`` and ``#program base.``; then perturbed at token level
(a token dropped, doubled, swapped, replaced or inserted from a pool of troublemakers:
``%``, ``%*``, ``not``, ``..``, ``;``, ``:-``, a variable, ``0x1F``, ``007``, ``2147483648``,
...), spliced with comments and line breaks at any character (in a name or a string
too), or changed character by character; 4,000 texts.  For each text:

- fast and token path give the same facts (kind, Python values, offset) or the same
  refusal, word for word;
- what clingo refuses, the reader refuses; what clingo reads, the reader reads as the same
  atoms (every leaf keeps its symbol through the Python values: asprilo.facts.term_of),
  or refuses it for a reason the README gives where clingo is silent: arithmetic that is
  undefined or leaves 32 bits, a number beyond 32 bits, anything but facts (rules,
  directives, intervals, pools, variables, ``p :- .``), a constant defined twice, a limit.

clingo sees each text with its lone CR line ends made LF: the reader ends a ``%`` comment
at CR too, on purpose (asprilo.parse: old Mac files read right), where clingo runs on to
the next LF.
"""

from __future__ import annotations

import random
import re

import clingo
import clingo.ast
import pytest

from asprilo.errors import InputError
from asprilo.facts import fact_atom, scan_facts
from asprilo.limits import Limits
from asprilo.parse import Reader, find_constants, resolve_constants, text_of, to_symbol

LIMITS = Limits()
NAMES = ["robot", "node", "at", "high", "a", "_x", "z'", "move", "nota", "object", "value"]
LEAVES = ["0", "1", "-1", "7", "42", "-999", "999999999", "1000000000", "-2147483648", "0x1F", "0b101",
          '"s"', '""', '"a % b."', '"q\\"x"', '"%* x"', "#sup", "#inf", "#supremum", "-a", "c0", "f(1)",
          "g(a,\"t\")", "(a,1)", "(1,2)", "(1,(2,3))", "()", "(5,)", "-(1,2)", "1+2", "h()"]
#: what token-level perturbations insert or put in place of a token
POOL = ["%", "%*", "*%", ".", ",", "(", ")", "-", "not", "#sup", '"', "X", "_", "0x1F", "007", "2147483648",
        "..", ";", ":-", "\n", "% c\n", "%* c *%", "#program base.", "#const", "a", "1", "'", '"s"', "|", "+",
        "#show", "#include", "~", "**", "/", "0", "-0", "#", "\t", "f(", "%*%", "%**%", "#!", "#inf", '"\\n"',
        "%*%*", "0o7", "-2147483648", "2147483647", "0b", "1a", "#p", "#program", "base", "#const c0 = 1.", "c0",
        "- -", "-(", "|1|", "1/0", "(,)", "==", "=", "@f", "&", ":", "{", "}", "[", "#script", "not ", "f ("]
SPLICES = ["%\n", "% x\n", "%x(1,1)))\n", "%*x*%", "%* % *%\n*%", "\n", "\r\n", "\r", " ", "% .\n", "%", "#!x\n",
           "%*", "*%", '"', "\\", "\t", "(", ")", ",", ".", "-", "%**%", "%*%**%*%\n"]
#: single characters a character-level change inserts
CHARACTERS = "().,%*\n\r -\"#_aX1:;"
_TOKENS = re.compile(r'"(?:[^"\\\n]|\\.)*"|%\*|\*%|#[a-z]+|[A-Za-z_\'][A-Za-z0-9_\']*|0x[0-9A-F]+|\d+|\.\.|:-|\s+|.')


def leaf(rng: random.Random) -> str:
    return rng.choice(LEAVES + NAMES) if rng.random() < 0.5 else rng.choice(NAMES[:4] + ["1", "2", "(1,1)"])


def base_fact(rng: random.Random) -> str:
    """A fact of the instance or plan shape (most), an assignment, or another fact."""
    kind = rng.random()
    if kind < 0.45:
        return f"init(object({rng.choice(NAMES[:3])},{rng.randint(1, 9)}),value({rng.choice(NAMES[2:5])},{leaf(rng)}))."
    if kind < 0.75:
        args = rng.choice(["(0,1)", "(-1,0)", "()", "(1,2,3)", f"({leaf(rng)},{leaf(rng)})", leaf(rng)])
        name = rng.choice(["move", "pickup", "a"])
        return f"occurs(object(robot,{rng.randint(1, 3)}),action({name},{args}),{rng.randint(0, 9)})."
    if kind < 0.85:
        return f"assign(robot({rng.randint(1, 3)}),{rng.choice(['shelf', 'destination'])}({leaf(rng)}))."
    if kind < 0.92:
        return f"#const c0 = {rng.choice(['1', 'a', '(1,2)', '-b', '2+3'])}."
    return f"{rng.choice(['p', '-q', 'r'])}({leaf(rng)}{', ' + leaf(rng) if rng.random() < 0.5 else ''})."


def base_text(rng: random.Random) -> str:
    return "".join(base_fact(rng) + rng.choice(["\n", " ", "", "\n% note\n"]) for _ in range(rng.randint(1, 4)))


def perturbed(rng: random.Random, text: str) -> str:
    tokens = _TOKENS.findall(text)
    for _ in range(rng.randint(1, 3)):
        at = rng.randrange(len(tokens)) if tokens else 0
        how = rng.randrange(5)
        if how == 0 and tokens:
            del tokens[at]
        elif how == 1 and tokens:
            tokens.insert(at, tokens[at])
        elif how == 2 and len(tokens) > 1:
            at = min(at, len(tokens) - 2)
            tokens[at], tokens[at + 1] = tokens[at + 1], tokens[at]
        elif how == 3 and tokens:
            tokens[at] = rng.choice(POOL)
        else:
            tokens.insert(at, rng.choice(POOL))
    return "".join(tokens)


def spliced(rng: random.Random, text: str) -> str:
    for _ in range(rng.randint(1, 3)):
        at = rng.randint(0, len(text))
        text = text[:at] + rng.choice(SPLICES) + text[at:]
    return text


def changed(rng: random.Random, text: str) -> str:
    """One to three characters dropped or inserted anywhere."""
    for _ in range(rng.randint(1, 3)):
        at = rng.randint(0, len(text))
        if rng.random() < 0.5 and at < len(text):
            text = text[:at] + text[at + 1:]
        else:
            text = text[:at] + rng.choice(CHARACTERS) + text[at:]
    return text


def texts(seed: int, count: int) -> list[str]:
    """``count`` texts: perturbed at token level, spliced, both, or changed by character."""
    rng = random.Random(seed)
    out = []
    for index in range(count):
        text = base_text(rng)
        if index % 4 == 3:
            text = changed(rng, text)
        if index % 4 in (0, 1):
            text = perturbed(rng, text)
        if index % 4 in (1, 2):
            text = spliced(rng, text)
        out.append(text)
    return out


# --- the three readers ---------------------------------------------------------------------------

def read(text: str, fast: bool) -> tuple[str, object]:
    """``("read", facts)`` with each fact's kind, Python values and offset, or ``("refused",
    message)``."""
    try:
        reader = Reader(text, "t.lp", LIMITS, quick=fast)
        constants = resolve_constants(find_constants(reader))
        found = scan_facts(text, "t.lp", LIMITS, constants, fast=fast)
    except InputError as error:
        return "refused", str(error)
    return "read", [(kind, text_of(args) if kind == "atom" else args, offset) for kind, args, offset in found]


def atoms_of(text: str) -> set[str]:
    """The atoms the reader reads, as clingo writes their symbols."""
    reader = Reader(text, "t.lp", LIMITS)
    found = scan_facts(text, "t.lp", LIMITS, resolve_constants(find_constants(reader)))
    return {str(to_symbol(fact_atom(kind, args))) for kind, args, _offset in found}


def clingo_reads(text: str) -> tuple[set[str] | None, bool]:
    """The atoms clingo grounds from the text (lone CR made LF), ``None`` where it refuses;
    and whether clingo's parser sees data in it: facts of terms without variables,
    intervals or pools, ``#const`` and ``#program base.`` only."""
    text = re.sub(r"\r(?!\n)", "\n", text)
    control = clingo.Control(["--warn=none"], logger=lambda _code, _message: None)
    try:
        control.add("base", [], text)
        control.ground([("base", [])])
    except RuntimeError:
        return None, False
    statements: list[clingo.ast.AST] = []
    clingo.ast.parse_string(text, statements.append, logger=lambda _code, _message: None)
    return {str(atom.symbol) for atom in control.symbolic_atoms}, all(map(_is_data, statements))


def _is_data(statement: clingo.ast.AST) -> bool:
    kind = statement.ast_type
    if kind == clingo.ast.ASTType.Comment:
        return True
    if kind == clingo.ast.ASTType.Program:
        return statement.name == "base" and not statement.parameters
    if kind == clingo.ast.ASTType.Definition:
        return _ground(statement.value)
    head = statement.head if kind == clingo.ast.ASTType.Rule else None
    return (head is not None and not statement.body and head.ast_type == clingo.ast.ASTType.Literal
            and head.sign == clingo.ast.Sign.NoSign and head.atom.ast_type == clingo.ast.ASTType.SymbolicAtom
            and _ground(head.atom.symbol))


def _ground(term: clingo.ast.AST) -> bool:
    """No variable, interval, pool or call of a script function (``@f(1)``) in the term."""
    stack = [term]
    while stack:
        node = stack.pop()
        if node.ast_type in (clingo.ast.ASTType.Variable, clingo.ast.ASTType.Interval, clingo.ast.ASTType.Pool) or \
                (node.ast_type == clingo.ast.ASTType.Function and node.external):
            return False
        for key in node.child_keys:
            child = getattr(node, key)
            stack.extend(child if isinstance(child, (list, clingo.ast.ASTSequence)) else
                         [child] if child is not None else [])
    return True


#: refusals of data clingo reads, each a reason the README gives ('p :- .' is a fact to
#: clingo, a rule to the reader)
_STRICTER = re.compile(r"is undefined \(| is out of range \(|is defined twice|are defined by each other|"
                       r"beyond the limit|' is a rule; ")


def disagreement(text: str) -> str | None:
    """Why the readers disagree on ``text``, or ``None``."""
    fast, token = read(text, True), read(text, False)
    if fast != token:
        return f"fast path {fast} but token path {token}"
    expected, data = clingo_reads(text)
    if fast[0] == "refused":
        if data and not _STRICTER.search(str(fast[1])):
            return f"refused ({fast[1]}) what clingo reads as {sorted(expected or ())}"
        return None
    if not data:
        return f"read {fast[1]} what clingo " + ("refuses" if expected is None else "reads as more than data")
    got = atoms_of(text)
    return None if got == expected else f"read {sorted(got)}, clingo {sorted(expected or ())}"


KNOWN = [  # issue 46's cases
    "init(object(node,1),value(at,(1,1))).\ninit(%object(robot,1),value(at,(1,1)))\n.",
    "init(object(robot,1),value(at,%x(1,1)))\n.",
    "occurs(object(robot,1),action(move,(0,1)),1) % x\n.",
    "p(not(1)).",
    "init(object(robot,1),value(energy,high)).",
    'init(object(robot,1),value(energy,"s")).',
    "init(object(robot,1),value(energy,f(1))).",
    "init(object(robot,1),value(energy,(a,1))).",
    "init(object(robot,a),value(at,(1,1))).",
    "init(object(robot,1),value(energy,#sup)).",
    "occurs(object(robot,1),action(move,(a,#inf)),1).",
    # found by the texts below: (,) is (), '==' is '=', '..' after a plain fact, p :- .
    "p((,)). p(-(,)). p((,1)).", "#const c == 2. p(c).", "init(object(robot,1),value(at,(1,1)))..",
    "p(1) :- .", "p(@f(1)).",
]


@pytest.mark.parametrize("text", KNOWN)
def test_the_issues_cases_read_alike(text):
    assert disagreement(text) is None


def test_a_comment_before_the_period_is_refused_as_clingo_refuses_it():
    text = "init(object(node,1),value(at,(1,1))).\ninit(%object(robot,1),value(at,(1,1)))\n."
    assert read(text, True) == ("refused", "t.lp:3: syntax error, unexpected .")


def test_every_leaf_keeps_its_symbol():
    text = ('init(object(robot,1),value(energy,high)). init(object("r",-a),value(e,(a,1,(b,"x",()),(1,)))). '
            "occurs(object(robot,1),action(move,f(#sup,-(1,2))),1).")
    assert atoms_of(text) == {'init(object(robot,1),value(energy,high))',
                              'init(object("r",-a),value(e,(a,1,(b,"x",()),(1,))))',
                              "occurs(object(robot,1),action(move,f(#sup,-(1,2))),1)"}


@pytest.mark.parametrize("seed", range(8))
def test_perturbed_and_spliced_texts_read_alike(seed):
    failures = [(text, why) for text in texts(seed, 500) if (why := disagreement(text)) is not None]
    assert failures == []
