"""The one parser of data: the fact language SPEC.md §2-3 allows, read without clingo.

Instances, plans, solver answers and online messages are text from strangers.  They are
read here, token by token, into terms; clingo never sees their text (DESIGN.md: "Encodings
are code, data is data").  What is read:

- **Tokens** as clingo 5.8's lexer makes them: identifiers ``[_']*[a-z][A-Za-z0-9_']*``
  (``not`` is a keyword), variables ``[_']*[A-Z][A-Za-z0-9_']*`` and ``_`` (refused:
  data is ground), numbers (decimal ``0`` or ``[1-9][0-9]*``, ``0x…``, ``0o…``, ``0b…``),
  strings (``"…"`` with the escapes ``\\"``, ``\\\\`` and ``\\n`` only, on one line),
  ``#sup``/``#supremum``, ``#inf``/``#infimum``, the directives ``#const`` and
  ``#program``, punctuation and operators; comments ``%`` to the end of the line, ``#!``
  likewise, ``%* … *%`` (nested, and a ``%`` inside one comments out the rest of its
  line, as in clingo); blanks are space, tab and line ends: LF, CRLF and CR (clingo ends
  a line at LF only: a ``%`` comment in a file with CR line ends would run to the end of
  the file there, here it ends at the CR).
- **Statements**: facts ``[-]name[(term, …)].``, ``#const name = term.`` (``==`` too) and
  ``#program base.``.  Anything else (rules, ``#show``, intervals, pools, variables, other
  program parts) is refused with a message that says what it is; ``#include`` and
  ``#script`` are never followed.
- **Terms**: numbers, strings, ``#sup``/``#inf``, constants, functions ``f(t, …)`` (``f()``
  is ``f``), tuples ``()`` (also ``(,)``), ``(t,)``, ``(t, u)`` (a trailing comma allowed), ``(t)`` is
  ``t``, and arithmetic evaluated as clingo does: unary ``-`` (on a function or tuple it
  flips the sign: ``-a``, ``-(1,2)``), ``~``, ``|t|``, and binary ``^`` < ``?`` < ``&`` <
  ``+ -`` < ``* / \\`` < ``**`` (right-associative), unary operators binding tightest
  (``-2**2`` is 4).  ``/`` and ``\\`` truncate towards zero, ``x**-n`` is 0.
- **Refused where clingo is silent**: a number beyond 32 bits (clingo wraps ``0xFFFFFFFF``
  to -1 and ``2147483648`` to -2147483648; ``-2147483648`` itself is read), arithmetic
  whose result leaves 32 bits (clingo wraps it), and undefined arithmetic (division by
  zero, ``0**-1``, arithmetic on a term that is not a number: clingo leaves the fact out
  with an info message).  Each is an :class:`InputError` located at its line.
- **Constants**: ``#const`` values are found first (a quick pass over strings and comments
  only, in texts that contain ``#const`` at all), then resolved in the order they use each
  other (a cycle or a second definition is refused), then put in place while the facts
  are read, with the arithmetic around them evaluated.  As in clingo, a constant applies
  to every text read together and may be used before its definition.

Budgets (:mod:`asprilo.limits`): ``depth`` (brackets nested in a statement, constants
written out), ``string-chars`` (characters of one string as written) and ``fact-chars``
(characters of one statement, constants written out); nothing here recurses (explicit
stacks), so 20,000 operators in a row or 500 nested brackets cost time in proportion
only.

Terms are Python values: ``int`` for numbers, :class:`Fn` for functions, constants and
tuples (name ``""``), :class:`Str` for strings, :data:`SUP` and :data:`INF`;
:func:`text_of` writes one as clingo does, :func:`to_symbol` makes a ``clingo.Symbol`` and
:func:`python_value` the value :func:`asprilo.facts.value_of` makes of that symbol.

The modules, each on the ones before it: :mod:`.terms` (the values), :mod:`.tokens` (the
lexer), :mod:`.refusals` (what is not data, and the limits), :mod:`.evaluate` (terms and
their arithmetic), :mod:`.constants` (``#const``) and :mod:`.statements` (the reader).
"""

from .constants import ConstantDefinition, ConstantReader, find_constants, resolve_constants
from .evaluate import Constant, Evaluator
from .refusals import DATA_ONLY, NotData, Refuser, check_program_tokens
from .statements import Reader, parse_terms
from .terms import (
    INF,
    INT_MAX,
    INT_MIN,
    SUP,
    Fn,
    Special,
    Str,
    Term,
    from_symbol,
    python_value,
    quoted,
    shown,
    text_of,
    to_symbol,
)
from .tokens import Lexer, line_at

__all__ = ["DATA_ONLY", "INF", "INT_MAX", "INT_MIN", "SUP", "Constant", "ConstantDefinition", "ConstantReader",
           "Evaluator", "Fn", "Lexer", "NotData", "Reader", "Refuser", "Special", "Str", "Term",
           "check_program_tokens", "find_constants", "from_symbol", "line_at", "parse_terms", "python_value",
           "quoted", "resolve_constants", "shown", "text_of", "to_symbol"]
