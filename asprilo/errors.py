"""The one exception type for bad input: it names the file (and line) at fault."""

from __future__ import annotations


class InputError(Exception):
    """Bad input that a user can fix: missing file, syntax error, wrong fact shape, ...

    ``str(error)`` reads ``FILE[:LINE]: what is wrong``, the form every command prints
    after ``error: ``.
    """

    def __init__(self, message: str, file: str | None = None, line: int | None = None):
        super().__init__(message)
        self.message = message
        self.file = file
        self.line = line

    def __reduce__(self):  # pickled whole (file and line too): errors come back from child processes
        return InputError, (self.message, self.file, self.line)

    def at(self, file: str | None, line: int | None = None) -> InputError:
        """Return this error located in ``file`` (and ``line``) unless it has a place already."""
        if self.file is None:
            self.file, self.line = file, line
        return self

    def __str__(self) -> str:
        if self.file is None:
            return self.message
        place = self.file if self.line is None else f"{self.file}:{self.line}"
        return f"{place}: {self.message}"


class InputWarning(UserWarning):
    """Input read, with something ignored: ``str(warning)`` reads ``FILE[:LINE]: what``."""
