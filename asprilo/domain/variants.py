"""Rule variants: a teacher's change of a domain's rules, written as data (YAML + ASP).

A variant file names the domains it changes and what it changes, in the checker's own
modular style (docs/VARIANTS.md has every key)::

    variant: diagonal
    summary: robots also move diagonally; no two robots cross each other's diagonal paths
    domains: [m, md]
    moves: [[1, 0], [-1, 0], [0, 1], [0, -1], [1, 1], [1, -1], [-1, 1], [-1, -1]]
    rules: [diagonal.lp]
    messages:
      diagonal/crossing:
        params: {R1: robot, R2: robot, T: step}
        text: robots {R1} and {R2} cross each other's diagonal paths at step {T}

:func:`with_variants` turns a domain and the variants named on a command line
(``--variant NAME|FILE``, built-in names are the files of ``asprilo/variants/``) into the
domain they describe: a descriptor like any other (``M+diagonal``), which every tool asks
instead of the variant.  Its checker is the base's concerns with the variant's added and
replaced, its moves and resources are data the Python rules take as parameters, and its
words are the templates of the file.  The variant's ASP is code its user named, like an own
encoding; instances and plans stay data.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from pathlib import Path

from ..errors import InputError
from ..model import DIRECTIONS
from ..objects import CELL, Attribute, ObjectKind, register_attribute, register_kind
from .descriptor import Domain, ReferenceEncoding, register
from .variant_file import VariantFile, read_variant

#: the folder of the built-in variants (``--variant diagonal`` is ``BUILTIN/diagonal.yml``)
BUILTIN = Path(__file__).resolve().parent.parent / "variants"
#: the checker concern that holds the four standard moves (replaced by a variant's ``moves``)
DIRECTIONS_CONCERN = "directions"

__all__ = ["BUILTIN", "VariantFile", "apply_variant", "base_of", "builtin_variants", "is_standard", "load_variant",
           "with_variants"]


def builtin_variants() -> list[str]:
    """The names of the built-in variants."""
    return sorted(path.stem for path in BUILTIN.glob("*.yml"))


def load_variant(name: str) -> VariantFile:
    """The variant ``name`` (a built-in one's name, or the path of a variant file), its
    attributes made known to the reader (so load it before reading instances that have them)."""
    path = Path(name)
    if path.suffix == "" and len(path.parts) == 1:
        builtin = BUILTIN / f"{name}.yml"
        if not builtin.is_file():
            raise InputError(f"unknown variant '{name}' (built in: {', '.join(builtin_variants())}; "
                             "or the path of a variant file, NAME.yml)")
        path = builtin
    variant = read_variant(path)
    for kind in variant.kinds:
        register_kind(ObjectKind(kind, kind, f"{kind}s", {"at": CELL}))
    for kind, attribute, shape in variant.attributes:
        register_attribute(kind, attribute, Attribute.named(shape))
    return variant


def with_variants(domain: Domain, variants: Sequence[str | VariantFile]) -> Domain:
    """``domain`` changed by ``variants`` in turn (each loaded, or a name or a file); the
    domain made is registered, so that ``--domain`` and child processes know it."""
    for variant in variants:
        domain = apply_variant(domain, variant if isinstance(variant, VariantFile) else load_variant(variant))
    return domain


def base_of(domain: Domain) -> str:
    """The name of the built-in domain a (varied) domain starts from: ``m`` for ``m+diagonal``."""
    return domain.value.split("+")[0]


def apply_variant(domain: Domain, variant: VariantFile) -> Domain:
    """The domain ``variant`` makes of ``domain`` (registered); :class:`InputError` when the
    variant does not fit it."""
    base = base_of(domain)
    if variant.domains and base not in variant.domains:
        shown = ", ".join(name.upper() if len(name) == 1 else name.capitalize() for name in variant.domains)
        raise InputError(f"variant '{variant.name}' changes domain{'s' * (len(variant.domains) > 1)} {shown}, "
                         f"not {domain.label}", str(variant.path))
    if variant.name in domain.variants:
        raise InputError(f"variant '{variant.name}' is given twice", str(variant.path))
    checker = _checker(domain, variant)
    facts = domain.checker_facts
    directions = domain.directions
    if variant.moves:
        directions = variant.moves
        facts += "".join(f"direction(({dx},{dy})).\n" for dx, dy in variant.moves)
    encodings = tuple(ReferenceEncoding(variant.name, str(program), summary=f"model solution of variant "
                                        f"'{variant.name}'") for program in variant.encodings_for(base))
    varied = dataclasses.replace(
        domain, value=f"{domain.value}+{variant.name}", label=f"{domain.label}+{variant.name}",
        summary=variant.summary, checker=checker, encodings=encodings,
        bound=domain.bound if variant.restricts else None,
        messages={**domain.messages, **dict(variant.messages)},
        directions=directions, checker_facts=facts,
        constants=(*[(name, value) for name, value in domain.constants if name not in dict(variant.constants)],
                   *variant.constants),
        resources=(*domain.resources, *([variant.resource] if variant.resource else [])),
        variants=(*domain.variants, variant.name),
        attributes=(*domain.attributes, *variant.generated))
    return register(varied)


def _checker(domain: Domain, variant: VariantFile) -> tuple[str, ...]:
    """The base's checker concerns, with those the variant replaces swapped (or dropped) and
    its own rules added before the goal (the last concern), the moves' concern dropped when
    the variant gives moves of its own (they come as facts)."""
    concerns = list(domain.checker)
    names = [Path(concern).stem for concern in concerns]
    replaced = [*variant.replace, *([(DIRECTIONS_CONCERN, None)] if variant.moves else [])]
    for name, program in replaced:
        if name not in names:
            raise InputError(f"variant '{variant.name}' replaces the checker concern '{name}', which domain "
                             f"{domain.label} does not have (its concerns: {', '.join(names)})", str(variant.path))
        index = names.index(name)
        if program is None:
            del concerns[index], names[index]
        else:
            concerns[index], names[index] = str(program), program.stem
    at = names.index("goal") if "goal" in names else len(concerns)
    concerns[at:at] = [str(program) for program in variant.rules]
    return tuple(concerns)


def is_standard(domain: Domain) -> bool:
    """Whether ``domain`` moves as SPEC.md says (the four directions) and its checker reads no
    facts of a variant: what the Python methods (max-flow, the anytime planner) can honour."""
    return domain.directions == DIRECTIONS and not domain.checker_facts and not domain.variants
