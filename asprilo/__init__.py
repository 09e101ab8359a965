"""asprilo: Answer Set Programming for robotic intra-logistics.

This package is the core: the instance and plan model, reading and writing, the clingo
driver, the domain rules (simulator), bounds and errors.  The tools live in folders of
their own and are installed as ``asprilo.generator``, ``asprilo.checker``,
``asprilo.encodings``, ``asprilo.visualizer``, ``asprilo.bench``, ``asprilo.interop``,
``asprilo.online`` and ``asprilo.cli`` (see docs/ARCHITECTURE.md).
"""

__version__ = "0.1.0"
