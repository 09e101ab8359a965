"""Argument types shared by the command-line tools (argparse ``type=`` callables)."""

from __future__ import annotations

import argparse

from .domain import Domain
from .errors import InputError


def domain_argument(text: str) -> Domain:
    """``--domain`` values: a|b|c|m|md."""
    try:
        return Domain.parse(text)
    except InputError as error:
        raise argparse.ArgumentTypeError(error.message) from None
