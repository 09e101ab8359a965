"""Arguments shared by the command-line tools: argparse ``type=`` callables and the
options of every command that reads data (``--allow-rules``, ``--limit NAME=N``)."""

from __future__ import annotations

import argparse
import math

from .domain import Domain
from .errors import InputError
from .limits import NAMES, Limits, parse_option
from .memory import check_memory_limit


def domain_argument(text: str) -> Domain:
    """``--domain`` values: a|b|c|m|md."""
    try:
        return Domain.parse(text)
    except InputError as error:
        raise argparse.ArgumentTypeError(error.message) from None


def port_argument(text: str) -> int:
    """``--port`` values: 0 (any free port) to 65535."""
    try:
        port = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a port number: {text!r}") from None
    if not 0 <= port <= 65535:
        raise argparse.ArgumentTypeError(f"a port is 0..65535, got {port}")
    return port


def seconds_argument(text: str) -> float:
    """Time limits: a positive, finite number of seconds."""
    try:
        seconds = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number of seconds: {text!r}") from None
    if not math.isfinite(seconds) or seconds <= 0:
        raise argparse.ArgumentTypeError(f"must be a positive number of seconds, got {text}")
    return seconds


def megabytes_argument(text: str) -> int:
    """Memory limits of child processes: a whole number of megabytes that this process can
    give a child (:func:`asprilo.memory.check_memory_limit`)."""
    try:
        megabytes = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number of megabytes: {text!r}") from None
    if megabytes <= 0:
        raise argparse.ArgumentTypeError(f"must be a positive number of megabytes, got {megabytes}")
    try:
        check_memory_limit(megabytes)
    except InputError as error:
        raise argparse.ArgumentTypeError(error.message) from None
    return megabytes


def limit_argument(text: str) -> str:
    """``--limit NAME=N``, checked when the command line is read."""
    try:
        parse_option(text)
    except InputError as error:
        raise argparse.ArgumentTypeError(error.message) from None
    return text


def add_reading_options(parser: argparse.ArgumentParser) -> None:
    """``--allow-rules`` and ``--limit NAME=N`` (see README: "Reading data")."""
    defaults = Limits()
    group = parser.add_argument_group("reading data", "instances and plans hold facts; see README, Reading data")
    group.add_argument("--allow-rules", action="store_true",
                       help="read rules in data files too, grounded under the rule-seconds and rule-mb limits")
    shown = ", ".join(f"{name.replace('_', '-')}={getattr(defaults, name)}" for name in NAMES)
    group.add_argument("--limit", action="append", default=[], type=limit_argument, metavar="NAME=N",
                       help=f"raise (or lower) a limit on data (repeatable); defaults: {shown}")


def reading_limits(args: argparse.Namespace) -> Limits:
    """The limits the reading options of ``args`` ask for."""
    return Limits().with_options(getattr(args, "limit", []) or [], getattr(args, "allow_rules", False))


# --- rule variants (docs/VARIANTS.md) ---------------------------------------------------------

def add_variant_option(parser: argparse.ArgumentParser) -> None:
    """``--variant NAME|FILE``, repeatable: the rule variants a command follows."""
    parser.add_argument("--variant", action="append", default=[], metavar="NAME|FILE",
                        help="change the rules with a variant: diagonal, visit-anytime, energy, sides or a variant "
                             "file (repeat to compose; docs/VARIANTS.md)")


def loaded_variants(args: argparse.Namespace) -> list:
    """The variants ``--variant`` names, loaded once (their attributes made known to the
    reader: call this before reading instances)."""
    names = getattr(args, "variant", None) or []
    if names and "loaded_variants" not in vars(args):
        from .domain.variants import load_variant  # YAML: only for a command that names a variant
        args.loaded_variants = [load_variant(name) for name in names]
    return vars(args).get("loaded_variants", [])


def chosen_domain(args: argparse.Namespace, detected: Domain | None = None) -> Domain | None:
    """The domain a command works in: ``--domain`` (else ``detected``, else ``None``: the tool
    detects it), changed by the ``--variant`` files in turn."""
    domain = getattr(args, "domain", None) or detected
    variants = loaded_variants(args)
    if not variants:
        return domain
    if domain is None:
        raise InputError("a variant changes a domain: name it (--domain a|b|c|m|md)")
    from .domain.variants import with_variants
    return with_variants(domain, variants)
