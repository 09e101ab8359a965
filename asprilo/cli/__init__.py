"""The command line: ``asprilo`` and its stand-alone twins ``gen``, ``check`` and ``viz``.

Each subcommand lives in a module with ``configure(parser)`` and ``run(args) -> int``;
the module is imported only when its subcommand runs, so ``asprilo --help`` stays quick
and only ``viz`` loads Qt.  Bad input (:class:`InputError`) becomes one line
``error: FILE[:LINE]: what is wrong`` on stderr and exit status 2; input read with
something ignored (:class:`InputWarning`) one line ``warning: FILE[:LINE]: ...``.  Every
command that reads data takes ``--allow-rules`` and ``--limit NAME=N`` (README: "Reading
data").  Standard output that cannot be written (a full disk) is one line ``error: standard
output: ...`` and exit status 2; a reader that goes away (``| head``) ends the command quietly.
With ``--json`` a refusal is also a JSON object on standard output, ``{"error": ..., "exit": 2}``
(``file`` and ``line`` too where the error has them), so that a script reading JSON always gets
one.  SIGTERM and SIGHUP (``timeout``, a closed terminal, a cluster's ``scancel``, a service manager)
stop a command as Ctrl-C does: what it found so far is kept, its children end, exit status 130
(:mod:`asprilo.exits`: the one table of exit statuses).
"""

from __future__ import annotations

import argparse
import contextlib
import errno
import importlib
import os
import signal
import sys
import threading
import warnings
from collections.abc import Callable, Iterator, Sequence

from asprilo import __version__
from asprilo.arguments import add_reading_options, reading_limits
from asprilo.errors import InputError, InputWarning
from asprilo.exits import INTERRUPTED, deferring, keeping_lost_stops
from asprilo.limits import using

#: name -> (module, one-line summary); a command is listed here once it works.
COMMANDS: dict[str, tuple[str, str]] = {
    # each summary is the first line of the command's own description (its module's docstring)
    "demo": ("asprilo.cli.demo", "run the whole tool chain on a small warehouse: generate, solve, check, render"),
    "info": ("asprilo.cli.info", "summarise an instance (and a plan): counts, standard file name, domain, horizon"),
    "check": ("asprilo.cli.check", "check a plan with the ASP checker: broken rules in plain words, metrics, lower "
              "bounds; --watch: again on every save"),
    "gen": ("asprilo.generator.cli", "generate instances with multi-shot ASP: random, structured (-H) and template "
            "(-T) layouts, YAML batches (-j)"),
    "viz": ("asprilo.visualizer.cli", "show a warehouse, animate a plan (valid or not), edit the layout; or export "
            "pictures and animations"),
    "bench": ("asprilo.bench.cli", "run benchmark suites under time and memory limits, report tables and plots, "
              "export for btool"),
    "convert": ("asprilo.interop.convert", "convert between asprilo and the MAPF world: MovingAI maps and scenarios, "
                "LaCAM results, domains M and Md"),
    "online": ("asprilo.online.cli", "run a warehouse online without a window: orders released over time, a planner "
               "asked for the next actions"),
    "serve": ("asprilo.online.serve", "serve the online link: a solver that re-plans as orders arrive, or a simulator "
              "releasing orders over time"),
    "solve": ("asprilo.encodings.cli", "find a plan fast and prove its makespan minimal: reference encodings, your "
              "own, anytime, max-flow"),
    "grade": ("asprilo.encodings.grade", "grade your encoding on a ladder of instances: is each plan valid, is "
              "it minimal?"),
}
#: the commands that read no data files
WITHOUT_DATA = {"demo"}
#: what standard output is called in messages
STANDARD_OUTPUT = "standard output"


def _parser(name: str, prog: str, summary: str, parent=None) -> argparse.ArgumentParser:
    module = importlib.import_module(COMMANDS[name][0])
    kwargs = dict(description=(module.__doc__ or summary).strip(),
                  formatter_class=argparse.RawDescriptionHelpFormatter)
    parser = parent.add_parser(name, help=summary, **kwargs) if parent else \
        _Parser(prog=prog, **kwargs)
    module.configure(parser)
    if name not in WITHOUT_DATA:
        add_reading_options(parser)
    parser.set_defaults(run=module.run)
    return parser


def run_command(run: Callable[[argparse.Namespace], int | None], args: argparse.Namespace) -> int:
    """Run a command within the limits its options ask for, turning bad input and
    interruptions into messages and exit codes."""
    with using(reading_limits(args)), warnings.catch_warnings(), _stops_as_interrupts():
        warnings.simplefilter("always", InputWarning)
        warnings.showwarning = _show_warning
        stdout = sys.stdout
        sys.stdout = _StandardOutput(stdout)
        try:
            return _run(run, args)
        finally:
            sys.stdout = stdout


class _StandardOutput:
    """Standard output whose write errors name it (``filename`` is ``standard output``), so
    that a full disk there is told apart from other failures; everything else is the stream's.

    A long text goes to the byte stream until all of it is written: Python's text stream drops
    the rest of a long write that the system takes only in part (a disk filling up), silently."""

    LONG = 8192

    def __init__(self, stream):
        self._stream = stream

    def write(self, text: str) -> int:
        try:
            if len(text) <= self.LONG or not hasattr(self._stream, "buffer"):
                return self._stream.write(text)
            self._stream.flush()
            data = memoryview(text.encode(self._stream.encoding or "utf-8", self._stream.errors or "strict"))
            while data:
                written = self._stream.buffer.write(data)
                if not written:
                    raise OSError(errno.EIO, os.strerror(errno.EIO))
                data = data[written:]
            return len(text)
        except OSError as error:
            raise _named(error) from None

    def writelines(self, lines) -> None:
        for line in lines:
            self.write(line)

    def flush(self) -> None:
        try:
            self._stream.flush()
        except OSError as error:
            raise _named(error) from None

    def __getattr__(self, name: str):
        return getattr(self._stream, name)


@contextlib.contextmanager
def _stops_as_interrupts() -> Iterator[None]:
    """While a command runs, SIGTERM and SIGHUP do what Ctrl-C (SIGINT) does at that moment:
    its handler runs (``solve`` stops its search and answers with the best plan so far), or
    KeyboardInterrupt is raised.  A signal the process was started to ignore (``nohup``)
    stays ignored.  One that comes while code runs that cannot raise (clingo's logger, a
    destructor, a finalizer) is handled right after it."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def as_ctrl_c(_signal: int, frame) -> None:
        handler = signal.getsignal(signal.SIGINT)
        if not callable(handler):  # SIGINT ignored or default: a stop request stops all the same
            raise KeyboardInterrupt
        handler(signal.SIGINT, frame)  # signal.default_int_handler raises KeyboardInterrupt

    previous = {stop: signal.getsignal(stop) for stop in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)}
    for stop, handler in previous.items():
        if stop == signal.SIGINT:
            if handler is signal.default_int_handler:
                signal.signal(stop, deferring(handler))
        elif handler != signal.SIG_IGN:
            signal.signal(stop, deferring(as_ctrl_c))
    try:
        with keeping_lost_stops():
            yield
    finally:
        for stop, handler in previous.items():
            signal.signal(stop, handler if handler is not None else signal.SIG_DFL)


def _named(error: OSError) -> OSError:
    """The error as one of standard output (EPIPE stays a BrokenPipeError)."""
    return OSError(error.errno, error.strerror, STANDARD_OUTPUT) if error.errno else error


def _run(run: Callable[[argparse.Namespace], int | None], args: argparse.Namespace) -> int:
    try:
        code = run(args) or 0
        sys.stdout.flush()  # here, so that a full disk or a closed pipe is said, not met at exit
        return code
    except InputError as error:
        return _refuse(args, f"error: {error}", 2, error)
    except MemoryError as error:
        return _out_of_memory(args, error)
    except KeyboardInterrupt:
        return _refuse(args, "interrupted", INTERRUPTED)
    except BrokenPipeError:
        # the reader went away (e.g. `| head`): stop quietly
        _silence_stdout()
        return 0
    except OSError as error:
        if error.filename != STANDARD_OUTPUT:
            raise
        # e.g. a full disk: one line, and what is still buffered is dropped
        print(f"error: {STANDARD_OUTPUT}: cannot be written ({error.strerror or error})", file=sys.stderr)
        _silence_stdout()
        return 2


#: what a command was doing when it ran out of memory, by the modules the error came through:
#: the first phase one of them names (a module or the package it is in), in this order
MEMORY_PHASES = [
    ("reading the input", ("asprilo.reader", "asprilo.sources", "asprilo.parse")),
    ("computing the lower bound", ("asprilo.bounds", "asprilo.encodings.solving.bounds")),
    ("checking the plan", ("asprilo.checker", "asprilo.simulate")),
    ("generating the instance", ("asprilo.generator",)),
    ("writing the output", ("asprilo.writer",)),
    ("grounding", ("asprilo.solver.ground",)),
    ("solving", ("asprilo.solver", "asprilo.encodings")),
]
#: the commands whose exit status 1 says "nothing found within the limits" (memory is one)
SEARCHES = {"asprilo.encodings.cli", "asprilo.generator.cli"}


def _out_of_memory(args: argparse.Namespace, error: MemoryError) -> int:
    """``error: out of memory while PHASE``: exit status 2 while reading (the data is beyond
    this machine: README, Reading data, gives the limits), 1 in a search for a plan or an
    instance (nothing found within the limits, as when a child process runs out of memory),
    else 2 (nothing done)."""
    passed, frame = [], error.__traceback__
    while frame is not None:
        module = frame.tb_frame.f_globals.get("__name__", "")
        passed += [module, f"{module}.{frame.tb_frame.f_code.co_name}"]
        frame = frame.tb_next
    phase = next((phase for phase, names in MEMORY_PHASES
                  if any(module == name or module.startswith(name + ".") for module in passed for name in names)), None)
    if phase is None:
        return _refuse(args, "error: out of memory", 2)
    if phase == "reading the input":
        return _refuse(args, f"error: out of memory while {phase} (the limits on data are in README, Reading data)", 2)
    searching = getattr(getattr(args, "run", None), "__module__", None) in SEARCHES
    return _refuse(args, f"error: out of memory while {phase}", 1 if searching else 2)


def _refuse(args: argparse.Namespace, sentence: str, code: int, error: InputError | None = None) -> int:
    """Say ``sentence`` on standard error and, with ``--json``, as a JSON object on standard
    output; return the exit status ``code``."""
    print(sentence, file=sys.stderr)
    if getattr(args, "json", False):
        _print_json_refusal(sentence.removeprefix("error: "), code, error)
    return code


def _print_json_refusal(message: str, code: int, error: InputError | None = None) -> None:
    import json

    answer: dict[str, object] = {"error": message}
    if error is not None and error.file is not None:
        answer.update(file=error.file, line=error.line)
    answer["exit"] = code
    try:
        print(json.dumps(answer, indent=2), flush=True)
    except OSError:  # standard output is gone too: the line on standard error stays
        _silence_stdout()


def _silence_stdout() -> None:
    """Send what is left for standard output nowhere (so that exiting does not fail on it)."""
    try:
        descriptor = sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):
        return  # not a file (e.g. captured by a test)
    os.dup2(os.open(os.devnull, os.O_WRONLY), descriptor)


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    if issubclass(category, InputWarning):
        print(f"warning: {message}", file=sys.stderr, flush=True)
    else:
        sys.stderr.write(warnings.formatwarning(message, category, filename, lineno, line))


def main(argv: Sequence[str] | None = None) -> int:
    """``asprilo COMMAND ...``."""
    argv = list(sys.argv[1:] if argv is None else argv)
    parser = _Parser(
        prog="asprilo",
        description="asprilo: experimenting with robotic intra-logistics in Answer Set Programming.")
    parser.add_argument("--version", action="version", version=f"asprilo {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")
    chosen = next((word for word in argv if not word.startswith("-")), None)
    for name, (_module, summary) in COMMANDS.items():
        if name == chosen:
            _parser(name, name, summary, commands)
        else:
            commands.add_parser(name, help=summary)
    args = _parse(parser, argv, chosen)
    if args.command is None:
        parser.print_help()
        return 2
    return run_command(args.run, args)


class _Parser(argparse.ArgumentParser):
    """argparse's parser, whose usage errors are raised (:class:`_UsageError`) rather than
    printed, so that :func:`_parse` can also answer them in JSON (its subcommands' parsers are
    of this class too)."""

    def error(self, message: str):
        raise _UsageError(self, message)


class _UsageError(Exception):
    def __init__(self, parser: argparse.ArgumentParser, message: str):
        super().__init__(message)
        self.parser = parser


def _parse(parser: argparse.ArgumentParser, argv: list[str], chosen: str | None) -> argparse.Namespace:
    """The arguments; a command that runs clingo on a user's program (its module says
    ``CLINGO_OPTIONS = True``) gets the options asprilo does not know as ``clingo_options``,
    for clingo to accept or refuse.  A usage error is said as argparse says it (exit status
    2), and with ``--json`` also as a JSON object."""
    try:
        return _parse_arguments(parser, argv, chosen)
    except _UsageError as error:
        error.parser.print_usage(sys.stderr)
        sentence = f"{error.parser.prog}: error: {error}"
        print(sentence, file=sys.stderr)
        options = argv[:argv.index("--")] if "--" in argv else argv
        if "--json" in options:
            _print_json_refusal(sentence, 2)
        raise SystemExit(2) from None


def _parse_arguments(parser: argparse.ArgumentParser, argv: list[str], chosen: str | None) -> argparse.Namespace:
    module = importlib.import_module(COMMANDS[chosen][0]) if chosen in COMMANDS else None
    if not getattr(module, "CLINGO_OPTIONS", False):
        return parser.parse_args(argv)
    args, unknown = parser.parse_known_args(argv)
    stray = [word for word in unknown if not word.startswith("-")]
    if stray:
        parser.error(f"unrecognized arguments: {' '.join(stray)} (clingo's options are given as --name=value)")
    args.clingo_options = unknown
    return args


def _standalone(name: str) -> int:
    parser = _parser(name, name, COMMANDS[name][1])
    args = _parse(parser, sys.argv[1:], name)
    return run_command(args.run, args)


def gen_main() -> int:
    return _standalone("gen")


def check_main() -> int:
    return _standalone("check")


def viz_main() -> int:
    return _standalone("viz")


if __name__ == "__main__":
    sys.exit(main())
