"""The reference encodings of every domain, as their descriptors name them, with their files
found: which program solves which domain, in which style."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from asprilo.domain import Domain, ReferenceEncoding, domains
from asprilo.errors import InputError

HERE = Path(__file__).resolve().parent


@dataclass(frozen=True)
class Encoding:
    """One encoding: a reference encoding of one domain, or a user's own (``own``, for any
    domain: :func:`asprilo.encodings.own.own_encoding`).

    ``program`` is the main file (it includes the rest), ``extra`` the files loaded after it;
    ``theory`` the clingo extension it needs (``"clingcon"``, ``"dl"`` or ``None``); an
    ``incremental`` encoding has ``#program step(t)`` / ``check(t)`` parts and a ``query(t)``
    external instead of a ``horizon`` constant, a ``fixed`` one neither (it is solved once).
    ``names`` is the program that turns a model of an encoding with anonymous robots into a
    plan (``None``: the model shows ``occurs/3`` itself).  ``options`` and ``constants``
    (``-c``) go to clingo; ``renamed`` parts (old, new) and ``additions`` (program text) run an
    older style as its author meant, and ``assumed`` says so in words.  A reference
    encoding is given the facts it can use but need not compute (distances, hints); a
    user's own gets the instance only.
    """

    name: str
    domain: Domain | None
    program: Path
    theory: str | None
    incremental: bool
    summary: str
    names: Path | None = None
    options: tuple[str, ...] = ()
    extra: tuple[Path, ...] = ()
    constants: tuple[tuple[str, str], ...] = ()
    renamed: tuple[tuple[str, str], ...] = ()
    additions: str = ""
    dropped: tuple[str, ...] = ()  # system includes left out (``#include <csp>.``: clingcon 5 needs none)
    own: bool = False
    fixed: bool = False
    assumed: tuple[str, ...] = ()

    @property
    def files(self) -> tuple[Path, ...]:
        """Every file of the encoding, in loading order."""
        return (self.program, *self.extra)


def _path(name: str) -> Path:
    return Path(name) if Path(name).is_absolute() else HERE / name


def _encoding(domain: Domain, reference: ReferenceEncoding) -> Encoding:
    return Encoding(reference.name, domain, _path(reference.program), reference.theory, reference.incremental,
                    reference.summary, None if reference.names is None else _path(reference.names), reference.options)


def reference_encodings(domain: Domain | None = None) -> list[Encoding]:
    """The reference encodings (of one domain), domain by domain in registry order."""
    return [_encoding(d, reference) for d in domains() if domain is None or d is domain for reference in d.encodings]


def encoding_names(domain: Domain | None = None) -> list[str]:
    """The encoding names (of one domain), in registry order."""
    return list(dict.fromkeys(encoding.name for encoding in reference_encodings(domain)))


def find_encoding(domain: Domain, name: str = "plain") -> Encoding:
    """The encoding called ``name`` for ``domain``; an unknown pair is bad input."""
    for reference in domain.encodings:
        if reference.name == name:
            return _encoding(domain, reference)
    known = ", ".join(encoding_names(domain))
    raise InputError(f"no encoding '{name}' for domain {domain.label} (choose one of {known})")


def default_encoding(domain: Domain) -> Encoding:
    """The encoding a search runs when none is named: ``plain`` where the domain has it, else
    its first (a varied domain's: the variant's model solution); bad input where it has none,
    naming the variant and what to do."""
    if not domain.encodings:
        raise InputError(f"no encoding solves {domain.label}: {no_encoding_words(domain)}; give your own encoding to "
                         "solve under its rules: --encoding FILE")
    names = [reference.name for reference in domain.encodings]
    return find_encoding(domain, "plain" if "plain" in names else names[0])


def no_encoding_words(domain: Domain) -> str:
    """Why ``domain`` has no encoding, in words (it is a variant without a model solution)."""
    if domain.variants:
        base = domain.label.split("+")[0]
        return f"variant '{domain.variants[-1]}' names no model solution for {base} (its file's 'encodings:')"
    return f"domain {domain.label} names no encoding"
