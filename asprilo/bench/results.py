"""The results file of a benchmark run: one JSON object per line, appended as runs finish.

Each line is written with a single ``write`` and flushed to disk, so a runner killed at any
moment leaves every finished run on record; a torn last line is ignored when reading.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

from asprilo.errors import InputError
from asprilo.writer import check_output

RESULTS = "results.jsonl"

SOLVED, TIMEOUT, MEMOUT, INVALID, ERROR, NO_MAKESPAN = "solved", "timeout", "memout", "invalid", "error", "no-makespan"
#: every status a run's record may have; only SOLVED counts as solved
STATUSES = (SOLVED, TIMEOUT, MEMOUT, INVALID, ERROR, NO_MAKESPAN)
#: unsolved because a limit ran out (the run's time or memory, or the makespan search's time)
OUT_OF_LIMITS = (TIMEOUT, MEMOUT, NO_MAKESPAN)
#: unsolved because something went wrong: the plan broke a rule, or the run failed
FAILED = (INVALID, ERROR)


def run_key(instance_set: str, instance: str, label: str, encoding: str) -> str:
    """The identity of a run: the same key is never run twice in one results file."""
    return f"{instance_set}/{instance}/{label}/{encoding}"


def load_results(directory: str | Path) -> list[dict]:
    """All complete records of ``directory/results.jsonl`` (none if it does not exist)."""
    path = Path(directory) / RESULTS
    if not path.exists():
        return []
    records = []
    for line in path.read_text(encoding="utf-8").splitlines():
        try:
            record = json.loads(line)
        except ValueError:
            continue  # a line torn by a killed runner
        if isinstance(record, dict) and "key" in record:
            records.append(record)
    return records


def append_result(directory: str | Path, record: dict) -> None:
    """Append one record durably (to a regular file only, as every output: asprilo.writer)."""
    path = Path(directory) / RESULTS
    check_output(path)
    line = json.dumps(record, sort_keys=True) + "\n"
    try:
        with open(path, "a", encoding="utf-8") as stream:
            if stream.tell() > 0 and not _ends_with_newline(path):
                line = "\n" + line  # after a torn line, start afresh
            stream.write(line)
            stream.flush()
            os.fsync(stream.fileno())
    except OSError as error:  # e.g. a full disk: the records before stay
        raise InputError(f"cannot be written ({error.strerror or error})", str(path)) from None


def _ends_with_newline(path: Path) -> bool:
    with open(path, "rb") as stream:
        stream.seek(-1, os.SEEK_END)
        return stream.read(1) == b"\n"
