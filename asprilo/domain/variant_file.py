"""Reading a variant file (YAML): every key checked, every problem one line naming the file
and the line (docs/VARIANTS.md describes the keys)."""

from __future__ import annotations

import re
import string
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import InputError
from ..model import Cell
from ..yamlfile import YamlList, YamlMapping, load_yaml, shown
from .templates import KINDS, Resource, Words

#: the keys of a variant file, in the order docs/VARIANTS.md explains them
KEYS = ("variant", "summary", "domains", "moves", "rules", "replace", "restricts", "constants", "kinds",
        "attributes", "generate", "resource", "encodings", "messages")
#: what a declared attribute's values may be
SHAPES = ("integer", "term")
#: the actions a resource's costs name
COSTED = ("move", "carrying move", "pickup", "putdown", "deliver")
_NAME = re.compile(r"[a-z][a-z0-9-]*\Z")
_IDENTIFIER = re.compile(r"[a-z][A-Za-z0-9_]*\Z")
_BUILTIN_DOMAINS = ("a", "b", "c", "m", "md")


@dataclass(frozen=True)
class VariantFile:
    """A variant as its file says it (paths made absolute)."""

    name: str
    summary: str
    path: Path
    domains: tuple[str, ...] = ()
    moves: tuple[Cell, ...] = ()
    rules: tuple[Path, ...] = ()
    replace: tuple[tuple[str, Path | None], ...] = ()
    restricts: bool = False
    constants: tuple[tuple[str, int], ...] = ()
    kinds: tuple[str, ...] = ()                               # new placed kinds: an id at a cell
    attributes: tuple[tuple[str, str, str], ...] = ()       # (kind, attribute, shape)
    generated: tuple[tuple[str, str, int, int], ...] = ()   # (kind, attribute, least, most)
    resource: Resource | None = None
    encodings: tuple[tuple[str, Path], ...] = ()
    messages: tuple[tuple[tuple[str, str], Words], ...] = ()

    def encodings_for(self, domain: str) -> list[Path]:
        """The model solution the variant names for the built-in domain ``domain`` (none or one)."""
        return [program for name, program in self.encodings if name == domain]


def read_variant(path: str | Path) -> VariantFile:
    """The variant of the file ``path`` (:class:`InputError` for anything wrong in it)."""
    return _Reader(Path(path)).variant(load_yaml(path))


class _Reader:
    def __init__(self, path: Path):
        self.path = path
        self.folder = path.resolve().parent

    def fail(self, message: str, node: Any = None, key: Any = None) -> InputError:
        line = node.line_of(key) if isinstance(node, YamlMapping) and key is not None else getattr(node, "line", None)
        return InputError(message, str(self.path), line or None)

    def variant(self, data: Any) -> VariantFile:
        if not isinstance(data, YamlMapping):
            raise self.fail("a variant file is a mapping (variant: NAME, summary: ..., see docs/VARIANTS.md)")
        unknown = [key for key in data if key not in KEYS]
        if unknown:
            raise self.fail(f"unknown key {shown(unknown[0])} (the keys: {', '.join(KEYS)})", data, unknown[0])
        for key in ("variant", "summary"):
            if key not in data:
                raise self.fail(f"'{key}:' is missing", data)
        name = self.text(data, "variant")
        if not _NAME.match(name):
            raise self.fail(f"the variant's name {shown(name)} is not a name (lower-case letters, digits and '-', "
                            "a letter first)", data, "variant")
        kinds = self.kinds(data)
        attributes = self.attributes(data, kinds)
        resource = self.resource(data, attributes)
        constants = self.constants(data)
        if resource is not None:
            constants = (*resource.constants(), *constants)
        return VariantFile(
            name=name, summary=self.text(data, "summary"), path=self.path, domains=self.domains(data),
            moves=self.moves(data), rules=tuple(self.file(data, "rules", item, index)
                                                for index, item in enumerate(self.listed(data, "rules"))),
            replace=self.replace(data), restricts=self.flag(data, "restricts"), constants=constants,
            kinds=kinds, attributes=attributes, generated=self.generated(data, attributes), resource=resource,
            encodings=self.encodings(data), messages=self.messages(data))

    # --- plain values ---------------------------------------------------------------------

    def text(self, data: YamlMapping, key: str) -> str:
        value = data[key]
        if not isinstance(value, str) or not value.strip():
            raise self.fail(f"'{key}:' must be a text, got {shown(value)}", data, key)
        return value.strip()

    def flag(self, data: YamlMapping, key: str) -> bool:
        value = data.get(key, False)
        if not isinstance(value, bool):
            raise self.fail(f"'{key}:' must be true or false, got {shown(value)}", data, key)
        return value

    def listed(self, data: YamlMapping, key: str) -> list:
        value = data.get(key, YamlList())
        if not isinstance(value, list):
            raise self.fail(f"'{key}:' must be a list, got {shown(value)}", data, key)
        return value

    def mapping(self, data: YamlMapping, key: str) -> YamlMapping:
        value = data.get(key, YamlMapping())
        if not isinstance(value, YamlMapping):
            raise self.fail(f"'{key}:' must be a mapping, got {shown(value)}", data, key)
        return value

    def integer(self, value: Any, where: str, node: Any, key: Any) -> int:
        if type(value) is not int or abs(value) > 2**31 - 1:
            raise self.fail(f"{where} must be an integer, got {shown(value)}", node, key)
        return value

    def file(self, node: Any, where: str, value: Any, key: Any) -> Path:
        """An ASP file named relative to the variant file: it must exist."""
        if not isinstance(value, str) or not value.endswith(".lp"):
            raise self.fail(f"'{where}:' names logic program files (NAME.lp), got {shown(value)}", node, key)
        path = (self.folder / value).resolve()
        if not path.is_file():
            raise self.fail(f"'{where}:' names {value}, which is not a file beside {self.path.name}", node, key)
        return path

    # --- the keys -------------------------------------------------------------------------

    def domains(self, data: YamlMapping) -> tuple[str, ...]:
        names = []
        for index, name in enumerate(self.listed(data, "domains")):
            if not isinstance(name, str) or name.lower() not in _BUILTIN_DOMAINS:
                raise self.fail(f"'domains:' lists built-in domains ({', '.join(_BUILTIN_DOMAINS)}), got {shown(name)}",
                                data["domains"], index)
            names.append(name.lower())
        return tuple(names)

    def moves(self, data: YamlMapping) -> tuple[Cell, ...]:
        moves: list[Cell] = []
        for index, move in enumerate(self.listed(data, "moves")):
            if (not isinstance(move, list) or len(move) != 2 or any(type(d) is not int or abs(d) > 1 for d in move)
                    or move == [0, 0]):
                raise self.fail(f"a move is [DX, DY], each -1, 0 or 1 and not both 0, got {shown(move)}",
                                data["moves"], index)
            if tuple(move) in moves:
                raise self.fail(f"the move {shown(move)} is listed twice", data["moves"], index)
            moves.append((move[0], move[1]))
        return tuple(moves)

    def replace(self, data: YamlMapping) -> tuple[tuple[str, Path | None], ...]:
        entries = self.mapping(data, "replace")
        return tuple((str(name), None if program is None else self.file(entries, "replace", program, name))
                     for name, program in entries.items())

    def constants(self, data: YamlMapping) -> tuple[tuple[str, int], ...]:
        entries = self.mapping(data, "constants")
        for name in entries:
            if not isinstance(name, str) or not _IDENTIFIER.match(name):
                raise self.fail(f"a constant's name starts with a lower-case letter, got {shown(name)}", entries, name)
        return tuple((name, self.integer(value, f"constant {name}", entries, name)) for name, value in entries.items())

    def kinds(self, data: YamlMapping) -> tuple[str, ...]:
        from ..objects import KINDS as OBJECT_KINDS

        names = []
        for index, name in enumerate(self.listed(data, "kinds")):
            if not isinstance(name, str) or not _IDENTIFIER.match(name):
                raise self.fail(f"'kinds:' lists names of object kinds, got {shown(name)}", data["kinds"], index)
            if name in OBJECT_KINDS and OBJECT_KINDS[name].table is not None:
                raise self.fail(f"'kinds:' lists new kinds; {name} is one of SPEC.md's", data["kinds"], index)
            names.append(name)
        return tuple(names)

    def attributes(self, data: YamlMapping, kinds: tuple[str, ...]) -> tuple[tuple[str, str, str], ...]:
        found = []
        for kind, attributes in self.mapping(data, "attributes").items():
            if kind not in kinds:
                self.kind(data["attributes"], kind)
            if not isinstance(attributes, YamlMapping):
                raise self.fail(f"the attributes of {kind} are a mapping NAME: {' | '.join(SHAPES)}",
                                data["attributes"], kind)
            for attribute, shape in attributes.items():
                if not isinstance(attribute, str) or not _IDENTIFIER.match(attribute):
                    raise self.fail(f"an attribute's name starts with a lower-case letter, got {shown(attribute)}",
                                    attributes, attribute)
                if shape not in SHAPES:
                    raise self.fail(f"attribute {attribute} of {kind}: its values are {' or '.join(SHAPES)}, "
                                    f"got {shown(shape)}", attributes, attribute)
                found.append((kind, attribute, shape))
        return tuple(found)

    def kind(self, node: Any, kind: Any) -> None:
        from ..objects import KINDS as OBJECT_KINDS

        if kind not in OBJECT_KINDS:
            raise self.fail(f"unknown object kind {shown(kind)} (the kinds: {', '.join(OBJECT_KINDS)})", node, kind)

    def generated(self, data: YamlMapping, declared: tuple[tuple[str, str, str], ...]) -> tuple:
        found = []
        integers = {(kind, attribute) for kind, attribute, shape in declared if shape == "integer"}
        for kind, attributes in self.mapping(data, "generate").items():
            for attribute, span in (attributes.items() if isinstance(attributes, YamlMapping) else ()):
                if (kind, attribute) not in integers:
                    raise self.fail(f"'generate:' draws attribute {attribute} of {kind}, which 'attributes:' does "
                                    "not declare as an integer", attributes, attribute)
                if not (isinstance(span, list) and len(span) == 2 and all(type(v) is int for v in span)
                        and 0 <= span[0] <= span[1] <= 2**31 - 1):
                    raise self.fail(f"'generate:' draws {attribute} from [LEAST, MOST], two integers with 0 <= LEAST "
                                    f"<= MOST, got {shown(span)}", attributes, attribute)
                found.append((kind, attribute, span[0], span[1]))
        return tuple(found)

    def resource(self, data: YamlMapping, declared: tuple[tuple[str, str, str], ...]) -> Resource | None:
        if "resource" not in data:
            return None
        entry = self.mapping(data, "resource")
        attribute = entry.get("attribute")
        if ("robot", attribute, "integer") not in declared:
            raise self.fail(f"'resource:' names an attribute of robots that 'attributes:' declares as an integer "
                            f"(robot: {{{attribute}: integer}}), got {shown(attribute)}", entry, "attribute")
        costs = self.mapping(entry, "costs")
        for action in costs:
            if action not in COSTED:
                raise self.fail(f"'costs:' names the actions {', '.join(COSTED)}, got {shown(action)}", costs, action)
        return Resource(str(attribute), tuple((action, self.integer(cost, f"the cost of {action}", costs, action))
                                              for action, cost in costs.items()),
                        self.integer(entry.get("least", 0), "'least:'", entry, "least"))

    def encodings(self, data: YamlMapping) -> tuple[tuple[str, Path], ...]:
        entries = self.mapping(data, "encodings")
        for name in entries:
            if name not in _BUILTIN_DOMAINS:
                raise self.fail(f"'encodings:' names a file per built-in domain ({', '.join(_BUILTIN_DOMAINS)}), "
                                f"got {shown(name)}", entries, name)
        return tuple((name, self.file(entries, "encodings", program, name)) for name, program in entries.items())

    def messages(self, data: YamlMapping) -> tuple[tuple[tuple[str, str], Words], ...]:
        found = []
        for check, entry in self.mapping(data, "messages").items():
            entries = data["messages"]
            parts = check.split("/") if isinstance(check, str) else []
            if len(parts) != 2 or not all(_IDENTIFIER.match(part) for part in parts):
                raise self.fail(f"a message is named MODULE/CHECK after its err(MODULE,CHECK,Params) atom, got "
                                f"{shown(check)}", entries, check)
            if not isinstance(entry, YamlMapping) or set(entry) != {"params", "text"}:
                raise self.fail(f"message {check} is a mapping with 'params:' and 'text:'", entries, check)
            params = self.params(entry, check)
            text = self.text(entry, "text")
            names = {name for _, name, _, _ in string.Formatter().parse(text) if name is not None}
            missing = names - {name for name, _ in params}
            if missing:
                raise self.fail(f"message {check} says {{{sorted(missing)[0]}}}, which 'params:' does not name",
                                entry, "text")
            found.append(((parts[0], parts[1]), Words(params, text)))
        return tuple(found)

    def params(self, entry: YamlMapping, check: str) -> tuple[tuple[str, str], ...]:
        params = entry["params"]
        if not isinstance(params, YamlMapping) or not params:
            raise self.fail(f"message {check}: 'params:' names the parameters of the err/3 atom in order, with "
                            f"their kinds ({', '.join(KINDS)}), e.g. {{R: robot, T: step}}", entry, "params")
        for name, kind in params.items():
            if kind not in KINDS:
                raise self.fail(f"message {check}: parameter {name} is a {shown(kind)}; the kinds: {', '.join(KINDS)}",
                                params, name)
        return tuple((str(name), str(kind)) for name, kind in params.items())
