"""The reference encodings: which program file solves which domains, in which style."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from asprilo.domain import Domain
from asprilo.errors import InputError

HERE = Path(__file__).resolve().parent

@dataclass(frozen=True)
class Encoding:
    """One reference encoding of one domain.

    ``program`` is the main file (it includes the rest); ``theory`` the clingo extension it
    needs (``"clingcon"``, ``"dl"`` or ``None``); an ``incremental`` encoding has
    ``#program step(t)`` / ``check(t)`` parts and a ``query(t)`` external instead of a
    ``horizon`` constant.  ``names`` is the program that turns a model of an encoding
    with anonymous robots into a plan (``None``: the model shows ``occurs/3`` itself).
    """

    name: str
    domain: Domain
    program: Path
    theory: str | None
    incremental: bool
    summary: str
    names: Path | None = None


def _m(name: str, file: str, theory: str | None, summary: str) -> list[Encoding]:
    return [Encoding(name, domain, HERE / "m" / file, theory, file.startswith("incremental"), summary)
            for domain in (Domain.M, Domain.MD)]


def _abc(name: str, folder: str, theory: str | None, summary: str,
         domains: str = "abc") -> list[Encoding]:
    return [Encoding(name, Domain(d), HERE / folder / f"{d}.lp", theory, False, summary,
                     names=HERE / "abc" / "names.lp") for d in domains]


ENCODINGS: tuple[Encoding, ...] = tuple([
    *_m("plain", "plain.lp", None, "positions as cells (paper Listings 1-2)"),
    *_m("split", "split.lp", None, "X and Y positions as separate atoms"),
    *_m("clingcon", "clingcon.lp", "clingcon", "X and Y as clingcon integer variables"),
    *_m("dl", "dl.lp", "dl", "X and Y as clingo-dl difference-logic variables"),
    *_m("plain-inc", "incremental/plain.lp", None, "plain, multi-shot over the horizon"),
    *_m("split-inc", "incremental/split.lp", None, "split, multi-shot over the horizon"),
    *_m("clingcon-inc", "incremental/clingcon.lp", "clingcon", "clingcon, multi-shot over the horizon"),
    *_abc("plain", "abc", None, "anonymous robots, named shelves in distance bands + the domain's deliveries"),
    *_abc("clingcon", "abc/clingcon", "clingcon", "plain, with quantities as clingcon integer variables", "a"),
])


def encoding_names(domain: Domain | None = None) -> list[str]:
    """The encoding names (of one domain), in registry order."""
    names = [e.name for e in ENCODINGS if domain is None or e.domain is domain]
    return list(dict.fromkeys(names))


def find_encoding(domain: Domain, name: str = "plain") -> Encoding:
    """The encoding called ``name`` for ``domain``; an unknown pair is bad input."""
    for encoding in ENCODINGS:
        if encoding.domain is domain and encoding.name == name:
            return encoding
    known = ", ".join(encoding_names(domain))
    raise InputError(f"no encoding '{name}' for domain {domain.label} (choose one of {known})")
