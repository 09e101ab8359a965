"""The checker rule behind a violation: for ``err(Module,Check,Params)``, the rule of the
domain's checker whose head is ``err(Module,Check,_)``, with its file, line and text.

    from asprilo.checker.rules import rule_of, rules_of
    rule_of(Domain.A, "move", "offFloor")
    # Rule(path=.../checker/move.lp, line=7, text='err(move,offFloor,(R,T)) :- position(R,C,T), ...')

The concern files the domain's descriptor names (:func:`asprilo.checker.programs.concerns`)
are parsed with clingo's AST, once per domain; a rule's text is cut from its file exactly
as written (a rule over several lines keeps its line breaks: :func:`one_line` joins them).
Most checks are derived by exactly one rule; where several rules derive one check (in A,
``deliver/orderAmount`` has one for an order without the product and one for too many
units), :func:`rules_of` lists them all in file order and :func:`rule_of` gives the first.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path
from typing import NamedTuple

import clingo.ast

from asprilo.domain import Domain

from .programs import HERE, concerns


class Rule(NamedTuple):
    """A rule of a checker file: where it starts and its text as written."""

    path: Path
    line: int
    text: str

    @property
    def where(self) -> str:
        """``checker/move.lp:7`` (a file beside the checker's own by its name there, any
        other by its full path)."""
        return f"{display_path(self.path)}:{self.line}"

    def __str__(self) -> str:
        return f"{self.where}: {one_line(self.text)}"


def display_path(path: Path) -> str:
    """``checker/move.lp`` for the checker's own files, the full path for any other."""
    try:
        return f"checker/{path.resolve().relative_to(HERE).as_posix()}"
    except ValueError:
        return str(path)


def one_line(text: str) -> str:
    """A rule's text on one line: every run of blanks and line breaks as one blank (the
    checker's files align their rules with extra blanks)."""
    return " ".join(text.split())


def rules_of(domain: Domain, module: str, check: str) -> list[Rule]:
    """Every rule of ``domain``'s checker whose head is ``err(module,check,_)``, in the
    order of the concern files and of the rules in them (empty: no such check)."""
    return list(_rules(domain).get((module, check), ()))


def rule_of(domain: Domain, module: str, check: str) -> Rule | None:
    """The first rule of ``domain``'s checker whose head is ``err(module,check,_)``."""
    found = _rules(domain).get((module, check))
    return found[0] if found else None


def checks(domain: Domain) -> list[tuple[str, str]]:
    """Every ``(module, check)`` that ``domain``'s checker derives, in file order."""
    return list(_rules(domain))


@cache
def _rules(domain: Domain) -> dict[tuple[str, str], tuple[Rule, ...]]:
    found: dict[tuple[str, str], list[Rule]] = {}
    for path in concerns(domain):
        for key, rule in _err_rules(path):
            found.setdefault(key, []).append(rule)
    return {key: tuple(rules) for key, rules in found.items()}


def _err_rules(path: Path) -> list[tuple[tuple[str, str], Rule]]:
    """The rules of one file whose head is ``err(Module,Check,_)`` with constant module and check."""
    lines = path.read_text(encoding="utf-8").split("\n")
    statements: list[clingo.ast.AST] = []
    clingo.ast.parse_files([str(path)], statements.append)
    found = []
    for statement in statements:
        if statement.ast_type != clingo.ast.ASTType.Rule:
            continue
        key = _err_head(statement.head)
        if key is not None:
            begin, end = statement.location.begin, statement.location.end
            found.append((key, Rule(path, begin.line, _cut(lines, begin.line, begin.column, end.line, end.column))))
    return found


def _err_head(head: clingo.ast.AST) -> tuple[str, str] | None:
    """``(module, check)`` of a head ``err(module,check,_)``, else ``None``."""
    if head.ast_type != clingo.ast.ASTType.Literal or head.atom.ast_type != clingo.ast.ASTType.SymbolicAtom:
        return None
    term = head.atom.symbol
    if term.ast_type != clingo.ast.ASTType.Function or term.name != "err" or len(term.arguments) != 3:
        return None
    names = [_constant(argument) for argument in term.arguments[:2]]
    if names[0] is None or names[1] is None:
        return None
    return names[0], names[1]


def _constant(term: clingo.ast.AST) -> str | None:
    """The name of a constant term (``move``), else ``None``."""
    if term.ast_type == clingo.ast.ASTType.SymbolicTerm:
        symbol = term.symbol
        if symbol.type == clingo.SymbolType.Function and not symbol.arguments and symbol.name:
            return str(symbol.name)
    elif term.ast_type == clingo.ast.ASTType.Function and not term.arguments and term.name and not term.external:
        return str(term.name)
    return None


def _cut(lines: list[str], first: int, first_column: int, last: int, last_column: int) -> str:
    """The text from (line, column) to (line, column), clingo's positions (1-based, the end
    one past the last character)."""
    if first == last:
        return lines[first - 1][first_column - 1:last_column - 1]
    return "\n".join([lines[first - 1][first_column - 1:], *lines[first:last - 1],
                      lines[last - 1][:last_column - 1]])


def rule_line(domain: Domain, module: str, check: str) -> str | None:
    """The rule behind ``err(module,check,_)`` as one line of text: ``checker/move.lp:7:
    err(move,offFloor,(R,T)) :- ...``; where several rules derive the check, the first,
    saying how many there are (``checker/deliver_a.lp:6 (first of 2 rules): ...``)."""
    rules = rules_of(domain, module, check)
    if not rules:
        return None
    first = rules[0]
    many = f" (first of {len(rules)} rules)" if len(rules) > 1 else ""
    return f"{first.where}{many}: {one_line(first.text)}"
