"""asprilo: Answer Set Programming for robotic intra-logistics."""

from pathlib import Path as _Path

__version__ = "0.1.0"

# The tools live in their own folders next to this package (generator/, checker/, ...)
# and are installed as asprilo.generator, asprilo.checker, ... .  In a source checkout
# that is not installed (or when the checkout shadows an installed copy, as with
# ``python -m pytest`` from the repository root), find them in those folders.
_checkout = _Path(__file__).resolve().parent.parent
if not (_Path(__file__).parent / "generator").is_dir() and (_checkout / "generator" / "__init__.py").is_file():
    __path__.append(str(_checkout))
