"""The ``pendulab`` command line: thin, it parses, calls the library and renders.

Subcommands live in small modules loaded on demand, so ``pendulab --help`` and
``pendulab period`` never import numba, scipy or matplotlib.
"""
from __future__ import annotations

import contextlib
import difflib
import errno
import importlib
import os
import re
import signal
import sys
import threading
from typing import Any

import click

from ..core import interrupt
from ..core.errors import InputError, MissingExtraError, PendulabError, printable
from ..core.interrupt import signal_of
from ..core.streams import WriteError
from ..core.version import __version__
from ._common import TYPED, one_line, option_name
from .examples import epilog

# command name -> "module:function", relative to this package.
COMMANDS = {
    "period": "core:period",
    "simulate": "core:simulate",
    "estimate": "core:estimate",
    "length": "core:length",
    "gravity": "problems:gravity",
    "newton": "problems:newton",
    "fit": "problems:fit",
    "quadrature": "problems:quadrature",
    "report": "report:report",
    "programs": "programs:programs",
    "key": "key:key",
    "mark": "key:mark",
    "serve": "serve:serve",
    "approximations": "beyond:approximations",
    "sweep": "beyond:sweep",
}


#: How ``pendulab --help`` groups the commands; one not listed goes under "Tools".
SECTIONS = {
    "Coursework": ("period", "simulate", "estimate", "length", "gravity", "newton", "fit", "quadrature",
                   "programs"),
    "Beyond the coursework": ("approximations", "sweep"),
    "Tools": ("report", "key", "mark", "serve"),
}

EXAMPLES = """\b
Examples:
  pendulab period -l 75cm -a 30deg          your pendulum's period
  pendulab simulate --plot fig1.png         Figure 3's table and Figure 1
  pendulab estimate --step 1e-2,1e-3,1e-4   problem 3(c)-(d)
  pendulab report --students 262,407,634    the whole coursework, a PDF
  pendulab serve                            the explorer at http://127.0.0.1:8000/
  pendulab COMMAND --help                   a command's options and defaults

Lengths take units (75cm), times too (10ms); amplitudes 0.785, pi/4, 4pi/5, 45deg.
Every command but serve takes --json. Shell completion: see the user guide
(eval "$(_PENDULAB_COMPLETE=bash_source pendulab)")."""


class LazyGroup(click.Group):
    """A group that imports a subcommand's module only when it is needed."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return [name for name in COMMANDS if self._load(name) is not None]

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        """The commands by section, each with the first sentence of its help, whole."""
        names = self.list_commands(ctx)
        width = max(map(len, names), default=0)  # one column for every section
        listed = {n for section in SECTIONS.values() for n in section}
        for title, section in SECTIONS.items():
            members = [n for n in section if n in names]
            if title == "Tools":
                members += [n for n in names if n not in listed]
            rows = []
            for name in members:
                cmd = self._load(name)
                if cmd is not None and not cmd.hidden:
                    rows.append((name.ljust(width), cmd.get_short_help_str(limit=10_000)))
            if rows:
                with formatter.section(f"{title} commands"):
                    formatter.write_dl(rows)

    def get_command(self, ctx: click.Context, name: str) -> click.Command | None:
        return self._load(name)

    def resolve_command(self, ctx: click.Context, args: list[str]) -> tuple[str | None, click.Command | None, list[str]]:
        """The subcommand, a suggestion where its name is misspelt, and its arguments with
        every list option's values joined: ``--step 1e-2 1e-3`` is ``--step 1e-2,1e-3``."""
        name = click.utils.make_str(args[0])
        cmd = self._load(name)
        if cmd is None and not ctx.resilient_parsing and not name.startswith("-"):
            close = difflib.get_close_matches(name, list(COMMANDS), n=3, cutoff=0.6)
            hint = f" Did you mean {' or '.join(close)}?" if close else ""
            ctx.fail(f"No such command {name!r}.{hint} (pendulab --help lists them.)")
        if cmd is None:
            return super().resolve_command(ctx, args)
        return name, cmd, join_lists(cmd, args[1:])

    def invoke(self, ctx: click.Context):
        try:
            return super().invoke(ctx)
        except PendulabError as exc:  # a library error, told in the command's words
            cmd = self._load(ctx.invoked_subcommand or "")
            if cmd is None:
                raise
            raise CliError(in_cli_words(exc, cmd, ctx.meta.get(TYPED, {}))) from exc
        except KeyboardInterrupt as exc:  # before click turns it into Abort (and prints a blank line)
            raise Stopped(signal_of(exc)) from None

    @staticmethod
    def _load(name: str) -> click.Command | None:
        cmd = LazyGroup._import(name)
        if cmd is not None and cmd.epilog is None:
            cmd.epilog = epilog(name)  # examples.EXAMPLES: shown at the end of its --help
        return cmd

    @staticmethod
    def _import(name: str) -> click.Command | None:
        target = COMMANDS.get(name)
        if target is None:
            return None
        module, attr = target.split(":")
        try:
            mod = importlib.import_module(f"{__name__}.{module}")
        except ModuleNotFoundError as exc:  # a command whose module is not written yet
            if exc.name == f"{__name__}.{module}":
                return None
            raise
        return getattr(mod, attr, None)


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]}, epilog=EXAMPLES)
@click.version_option(__version__, prog_name="pendulab")
def cli() -> None:
    """pendulab: the nonlinear simple pendulum and the numerical methods taught with it.

    Periods by the arithmetic-geometric mean, the coursework's Taylor simulation, the
    period recovered from a simulation, the coursework's five problems and its report.
    """


#: The parameter types whose value is a list (``1e-2,1e-3``): after their option, the values
#: up to the next option may also be given as separate words.
LIST_TYPES = ("list", "methods")
#: A word that is a negative number (``-1``, ``-.5``), not an option: a list's (bad) item.
_NUMBER = re.compile(r"-\.?[0-9]")


def join_lists(cmd: click.Command, args: list[str]) -> list[str]:
    """``args`` with the words after a list option, up to the next option, joined by commas.

    ``estimate --step 1e-2 1e-3`` becomes ``estimate --step 1e-2,1e-3``: one list syntax
    (commas or spaces) for every list option, as ``report --students 1234 5678`` takes it.
    A word starting with ``-`` ends the list, unless it is a number (``-1``: an item, refused
    by the list's parser with the option's name).
    """
    flags = {opt for p in cmd.params if isinstance(p, click.Option) and getattr(p.type, "name", "") in LIST_TYPES
             for opt in p.opts}
    out: list[str] = []
    i = 0
    while i < len(args):
        word = args[i]
        out.append(word)
        i += 1
        if word == "--":
            out += args[i:]
            break
        if (word in flags and i < len(args)) or (word.partition("=")[0] in flags and "=" in word):
            values = [] if "=" in word else [args[i]]  # the option's value, whatever it is (as click takes it)
            i += 0 if "=" in word else 1
            while (i < len(args) and (not args[i].startswith("-") or _NUMBER.match(args[i]))
                   and not (values and values[0].startswith("-"))):
                values.append(args[i])
                i += 1
            if "=" in word:
                out[-1] = ",".join([word, *values])
            elif values:
                out.append(",".join(values))
    return out


class Stopped(Exception):
    """A signal (Ctrl+C's SIGINT, SIGTERM, SIGHUP, SIGQUIT) ended the command; raised after the cleanup ran."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = int(signum)


class StdoutError(Exception):
    """Standard output cannot be written (a full disk, a closed pipe). Not an ``OSError``:
    no handler of file errors on the way catches it for one of its own."""

    def __init__(self, exc: OSError | WriteError):
        reason = exc.reason if isinstance(exc, WriteError) else exc.strerror
        super().__init__(reason or str(exc))
        self.errno = exc.errno


class _GuardedStdout:
    """``sys.stdout`` while a command runs: its write errors become :class:`StdoutError`."""

    def __init__(self, stream: Any):
        self._stream = stream

    def write(self, text: str) -> int:
        try:
            return self._stream.write(text)
        except (OSError, WriteError) as exc:
            raise StdoutError(exc) from None

    def flush(self) -> None:
        try:
            self._stream.flush()
        except (OSError, WriteError) as exc:
            raise StdoutError(exc) from None

    def write_bytes(self, data: bytes) -> None:
        """Bytes through the checked stream, or the binary buffer of another one (a test's capture)."""
        try:
            if hasattr(self._stream, "write_bytes"):
                self._stream.write_bytes(data)
            else:
                self._stream.flush()
                self._stream.buffer.write(data)
                self._stream.buffer.flush()
        except (OSError, WriteError) as exc:
            raise StdoutError(exc) from None

    def __getattr__(self, name: str) -> Any:
        return getattr(self._stream, name)


def _silence_stdout() -> None:
    """Point standard output at the null device: what is still buffered goes nowhere, and
    Python's final flush at exit does not fail a second time with a traceback."""
    discard = getattr(sys.stdout, "discard", None)
    if discard is not None:  # the checked writer's buffer (pendulab.core.streams.CheckedText)
        discard()
    try:
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, sys.stdout.fileno())
        os.close(null)
    except (OSError, ValueError, AttributeError):  # no file descriptor (a test's capture)
        pass


def _stopped(where: str, signum: int) -> int:
    """One line for a command a signal stopped; the exit status 128 + the signal's number."""
    with contextlib.suppress(OSError, ValueError):
        click.echo(f"{where}: {interrupt.word(signum)}", err=True)
    return 128 + signum


def main(argv: list[str] | None = None) -> int:
    """Entry point: bad input becomes one line on stderr and exit status 2.

    Ctrl+C ends a command with one line and 130, SIGTERM with one line and 143, SIGHUP 129,
    SIGQUIT 131, each after the command's cleanup (its temporary files and folders) ran. A
    signal that some code on the way swallowed still ends the command so (no output is
    committed after it: :func:`pendulab.core.interrupt.check_signals`).
    """
    args = sys.argv[1:] if argv is None else list(argv)
    sub = next((a for a in args if not a.startswith("-")), None)
    where = f"pendulab {sub}" if sub in COMMANDS else "pendulab"
    main_thread = threading.current_thread() is threading.main_thread()
    old = {s: signal.getsignal(s) for s in interrupt.ENDING} if main_thread else {}
    if main_thread:
        interrupt.install()
    stdout = sys.stdout
    sys.stdout = _GuardedStdout(stdout)
    try:
        code = _run(args, where)
        if code == 0 and interrupt.received:  # a signal some code swallowed: still the command's end
            code = _stopped(where, interrupt.received[0])
        return code
    finally:
        interrupt.received.clear()  # told: the next call (a test's) starts afresh
        sys.stdout = stdout
        for s, handler in old.items():
            signal.signal(s, handler if handler is not None else signal.SIG_DFL)


def _run(args: list[str], where: str) -> int:
    """:func:`main`'s work: the command, and each way it can end in one line."""
    try:
        from ..core.inputs import source_date_epoch

        # Read by matplotlib and Typst deep inside a run: checked first, as any input.
        source_date_epoch(os.environ.get("SOURCE_DATE_EPOCH"))
        cli.main(args=args, prog_name="pendulab", standalone_mode=False)
        sys.stdout.flush()  # a full disk or a closed pipe found here, not at exit
    except click.exceptions.NoArgsIsHelpError as exc:  # `pendulab` alone: the help, a successful answer
        click.echo(exc.ctx.get_help())
        return 0
    except click.exceptions.Exit as exc:
        return exc.exit_code
    except Stopped as exc:
        return _stopped(where, exc.signum)
    except click.exceptions.Abort as exc:  # Ctrl+C while click parsed or prompted
        cause = exc.__cause__
        return _stopped(where, signal_of(cause) if isinstance(cause, KeyboardInterrupt) else signal.SIGINT)
    except click.BadParameter as exc:
        # Our parameter types already name the option, the value and the range.
        opts = tuple(exc.param.opts) if exc.param is not None else ()
        msg = exc.message if opts and exc.message.startswith(opts) else exc.format_message()
        click.echo(f"{where}: error: {one_line(msg)}", err=True)
        return 2
    except click.ClickException as exc:
        click.echo(f"{where}: error: {one_line(exc.format_message())}", err=True)
        return 2
    except PendulabError as exc:  # raised outside a subcommand (in_cli_words tells the others)
        click.echo(f"{where}: error: {one_line(str(exc))}", err=True)
        return 2
    except MissingExtraError as exc:
        click.echo(f"{where}: error: {exc}", err=True)
        return 2
    except KeyboardInterrupt as exc:
        return _stopped(where, signal_of(exc))
    except StdoutError as exc:
        _silence_stdout()
        return _stdout_error(where, exc.errno, str(exc))
    except WriteError as exc:  # an output file (a full disk, `ulimit -f`)
        with contextlib.suppress(OSError, ValueError):
            click.echo(f"{where}: error: {printable(str(exc))}", err=True)
        return 1
    except OSError as exc:
        if exc.errno not in _DISK_ERRORS:
            raise
        with contextlib.suppress(OSError, ValueError):
            click.echo(f"{where}: error: {printable(_disk_error(exc))}", err=True)
        return 1
    return 0


#: Errors of a write to a file that no input can cause or fix: told in one line, exit 1.
_DISK_ERRORS = frozenset(getattr(errno, n) for n in ("ENOSPC", "EFBIG", "EDQUOT", "EIO", "EROFS") if hasattr(errno, n))


def _disk_error(exc: OSError) -> str:
    where = exc.filename if exc.filename is not None else "a file"
    return f"cannot write to {os.fsdecode(where) if isinstance(where, bytes) else where}: {exc.strerror or exc}"


def _stdout_error(where: str, code: int | None, reason: str) -> int:
    """One line for standard output that cannot be written (a full disk): exit 1. A closed
    pipe (``pendulab period | head -1``: the reader has all it wanted) ends silently with
    141, SIGPIPE's status, as ``cat`` or ``seq`` do."""
    if code == errno.EPIPE:
        return 141
    with contextlib.suppress(OSError, ValueError):
        click.echo(f"{where}: error: cannot write to standard output: {reason}", err=True)
    return 1


class CliError(click.ClickException):
    """A library error in the CLI's words: one line, exit status 2."""

    exit_code = 2


def in_cli_words(exc: PendulabError, cmd: click.Command, typed: dict[str, tuple[str, bool]]) -> str:
    """A library error as the command's user typed it.

    The argument is named as the command spells it (``t_max`` is ``--t-max``, ``numbers``
    ``NUMBERS``), its value shown as typed (``1e9``, not ``1000000000``), and the other
    arguments the message names by the library's spelling become options too. An error
    with an ``alternative`` (a limit on the step and ``t_max`` together) blames the
    argument the person typed when the one blamed was left at its default. ``typed``:
    parameter name -> (text, typed by the person), from :class:`._common.Parsed`.
    """
    def param_of(name: str) -> click.Parameter | None:
        flag = "--" + name.replace("_", "-")
        return next((p for p in cmd.params if p.name == name or flag in getattr(p, "opts", ())), None)

    def by_person(p: click.Parameter | None) -> bool:
        return p is not None and p.name in typed and typed[p.name][1]

    def words(text: str, mentions: tuple[str, ...]) -> str:
        def option(m: re.Match) -> str:
            word = m[0]
            p = param_of(word) if word in mentions or _IDENTIFIER.fullmatch(word) else None
            return option_name(p) if p is not None else word

        return _WORD.sub(option, text)

    if not isinstance(exc, InputError):
        return one_line(words(str(exc), ()))
    if exc.alternative is not None and by_person(param_of(exc.alternative.name)) and not by_person(param_of(exc.name)):
        exc = exc.alternative
    p = param_of(exc.name)
    name = option_name(p) if p is not None else exc.name
    value = _as_typed(p, exc.value, typed)
    return one_line(f"{name} = {value} is not allowed: must be {words(exc.allowed, exc.mentions)}")


#: A word that is not part of an option (``--t-max``) or of a number (``1e-05``).
_WORD = re.compile(r"(?<![-\w.])[A-Za-z_]\w*(?![-\w])")
#: A name that is clearly the library's (``t_max``, ``t0``), rewritten even where not mentioned.
_IDENTIFIER = re.compile(r"[a-z]+(?:_[a-z0-9]+)+|[a-z]+[0-9]+")


def _as_typed(param: click.Parameter | None, value: object, typed: dict[str, tuple[str, bool]]) -> str:
    """``value`` as the person typed it: the parameter's text, or the item of its list
    whose value it is; the library's rendering where neither is found."""
    from ..core import inputs
    from ..core.errors import shown_value

    if isinstance(value, str) or param is None or param.name not in typed:
        return shown_value(value)
    text = typed[param.name][0]
    parse = getattr(param.type, "parse", None)
    for candidate in (text, *inputs.SEPARATOR.split(text.strip())):
        try:
            parsed = parse(candidate) if parse is not None else candidate
            if hasattr(parsed, "__len__") and not isinstance(parsed, str) and len(parsed) == 1:
                parsed = parsed[0]
            if float(parsed) == float(value):  # type: ignore[arg-type]
                return inputs.shown(candidate.strip())
        except (PendulabError, TypeError, ValueError, OverflowError):
            continue
    return shown_value(value)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
