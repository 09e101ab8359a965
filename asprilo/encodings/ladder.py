"""The ladders of ``asprilo grade``: per domain a few instances from tiny to exercise size,
each with its minimal makespan, established independently of the grader.

A ladder is a folder with a manifest ``ladder.yml`` and the instance files it names:

    domain: m
    instances:
      - file: 01-x3_y2_r1.lp
        minimum: 3
        established: max-flow, exact (asprilo solve --domain m --method flow)
        cross-checked: [reference encoding plain, breadth-first search over joint states]

``minimum`` is the instance's minimal makespan; ``established`` says how it was found and
``cross-checked`` by which other methods it was confirmed (words, shown by ``--list``).
The bundled ladders are in ``ladders/<domain>/`` next to this file (docs/GRADING.md); a
course may write its own and pass ``--ladder FILE``.  Graded against a model solution
(``--reference``, :mod:`.reference`), a rung's minimum is what the reference's search proved,
``None`` (unknown) where it proved none, and :class:`ReferenceMinimum` says what it found.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.yamlfile import YamlList, YamlMapping, load_yaml

from .probes import Probe, read_probes

#: the bundled ladders, one folder per domain
LADDERS = Path(__file__).resolve().parent / "ladders"
MANIFEST = "ladder.yml"
_KEYS = {"file", "minimum", "established", "cross-checked"}


@dataclass(frozen=True)
class ReferenceMinimum:
    """What the reference encoding (a teacher's model solution) found on one instance.

    ``minimum``: the makespan its horizon search proved minimal (``None``: unknown, and
    ``reason`` says why in words); ``makespan``: of its plan, which the checker accepted
    (``None``: no such plan); ``at_least``: no plan is shorter (the lower bound raised past
    the horizons it refuted; ``None``: no plan exists at all); ``seconds``: its whole solve.
    """

    minimum: int | None
    makespan: int | None
    at_least: int | None
    seconds: float
    reason: str = ""

    def words(self) -> str:
        """How the minimum was found, or why it is unknown."""
        if self.minimum is not None:
            return f"proven by the reference's horizon search ({self.seconds:.1f} s)"
        below = f"; none shorter than {self.at_least}" if self.at_least else ""
        return f"{self.reason}{below}"

    def as_json(self) -> dict[str, object]:
        """The entry ``reference`` of an instance in ``asprilo grade --json``."""
        return {"proven": self.minimum is not None, "makespan": self.makespan, "at_least": self.at_least,
                "seconds": round(self.seconds, 3), "reason": self.reason or None}


@dataclass(frozen=True)
class Rung:
    """One instance of a ladder and its minimal makespan (``None``: unknown; graded against
    a reference, ``reference`` says what its search found)."""

    file: Path
    minimum: int | None
    established: str
    cross_checked: tuple[str, ...] = ()
    reference: ReferenceMinimum | None = None

    @property
    def name(self) -> str:
        return self.file.stem

    @property
    def plans_from(self) -> int | None:
        """The least makespan known to have a plan (from it on every makespan has one): the
        minimum, else the makespan of the reference's plan; ``None``: none known."""
        if self.minimum is not None:
            return self.minimum
        return None if self.reference is None else self.reference.makespan


@dataclass(frozen=True)
class Ladder:
    """The instances of one domain, from tiny to exercise size (``manifest``: its file)."""

    domain: Domain
    manifest: Path
    rungs: tuple[Rung, ...]
    bundled: bool = False
    title: str = ""  # how the grader names instances that are no ladder (an exercise, a folder)
    probes: tuple[Probe, ...] = ()  # illegal plans an encoding must refuse (:mod:`.probes`)

    @property
    def label(self) -> str:
        """How the grader names it: ``the M ladder``, the manifest's path, or its title."""
        if self.title:
            return self.title
        return f"the {self.domain.label} ladder" if self.bundled else f"the ladder {self.manifest}"


def bundled_ladder(domain: Domain) -> Ladder:
    """The ladder shipped for ``domain``."""
    manifest = LADDERS / domain.value / MANIFEST
    if not manifest.is_file():
        raise InputError(f"no ladder for domain {domain.label} (ladders: {', '.join(bundled_domains())})")
    return replace(read_ladder(manifest), bundled=True)


def bundled_domains() -> list[str]:
    """The domains with a bundled ladder."""
    return sorted(path.parent.name for path in LADDERS.glob(f"*/{MANIFEST}"))


def read_ladder(path: str | Path) -> Ladder:
    """The ladder of the manifest ``path`` (bad input: :class:`InputError` ``FILE:LINE``)."""
    path = Path(path)
    document = load_yaml(path)
    if not isinstance(document, YamlMapping):
        raise InputError("a ladder is a mapping with 'domain' and 'instances'", str(path), 1)
    unknown = sorted(set(map(str, document)) - {"domain", "instances", "probes"})
    if unknown:
        raise InputError(f"unknown key {unknown[0]!r} (a ladder has 'domain', 'instances' and 'probes')", str(path),
                         document.line_of(unknown[0]))
    if "domain" not in document:
        raise InputError("no 'domain' (a|b|c|m|md)", str(path), document.line)
    try:
        domain = Domain.parse(str(document["domain"]))
    except InputError as error:
        raise InputError(error.message, str(path), document.line_of("domain")) from None
    items = document.get("instances")
    if not isinstance(items, YamlList) or not items:
        raise InputError("'instances' is a list of instances (file, minimum, established)", str(path),
                         document.line_of("instances"))
    rungs = tuple(_rung(path, item, line) for item, line in zip(items, items.item_lines, strict=True))
    probes = read_probes(path, document["probes"], document.line_of("probes")) if "probes" in document else ()
    return Ladder(domain, path, rungs, probes=probes)


def _rung(manifest: Path, item: object, line: int) -> Rung:
    where = (str(manifest), line)
    if not isinstance(item, YamlMapping):
        raise InputError("an instance is a mapping with file, minimum and established", *where)
    unknown = sorted(set(map(str, item)) - _KEYS)
    if unknown:
        raise InputError(f"unknown key {unknown[0]!r} (an instance has {', '.join(sorted(_KEYS))})", str(manifest),
                         item.line_of(unknown[0]))
    missing = [key for key in ("file", "minimum", "established") if key not in item]
    if missing:
        raise InputError(f"the instance has no {missing[0]!r}", *where)
    file = manifest.parent / str(item["file"])
    if not file.is_file():
        raise InputError(f"no such instance file: {file}", str(manifest), item.line_of("file"))
    minimum = item["minimum"]
    if not isinstance(minimum, int) or isinstance(minimum, bool) or minimum < 0:
        raise InputError(f"the minimum is a makespan (a whole number >= 0), got {minimum!r}", str(manifest),
                         item.line_of("minimum"))
    checked = item.get("cross-checked", [])
    checked = (checked,) if isinstance(checked, str) else tuple(map(str, checked or ()))
    return Rung(file, minimum, str(item["established"]), checked)

