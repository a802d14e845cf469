"""The ``pendulab`` command line: thin, it parses, calls the library and renders.

Subcommands live in small modules loaded on demand, so ``pendulab --help`` and
``pendulab period`` never import numba, scipy or matplotlib.
"""
from __future__ import annotations

import importlib
import sys

import click

from .._version import __version__
from ..errors import MissingExtraError, PendulabError

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
    "key": "key:key",
    "serve": "serve:serve",
    "approximations": "beyond:approximations",
    "sweep": "beyond:sweep",
}


class LazyGroup(click.Group):
    """A group that imports a subcommand's module only when it is needed."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return [name for name in COMMANDS if self._load(name) is not None]

    def get_command(self, ctx: click.Context, name: str) -> click.Command | None:
        return self._load(name)

    @staticmethod
    def _load(name: str) -> click.Command | None:
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


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="pendulab")
def cli() -> None:
    """pendulab: the nonlinear simple pendulum and the numerical methods taught with it.

    Exact periods by the arithmetic-geometric mean, the coursework's Taylor
    simulation, the period recovered from a simulation, and the report.
    Every command takes --json for one machine-readable JSON document on stdout.
    """


def main(argv: list[str] | None = None) -> int:
    """Entry point: bad input becomes one line on stderr and exit status 2."""
    args = sys.argv[1:] if argv is None else list(argv)
    sub = next((a for a in args if not a.startswith("-")), None)
    where = f"pendulab {sub}" if sub in COMMANDS else "pendulab"
    try:
        cli.main(args=args, prog_name="pendulab", standalone_mode=False)
    except click.exceptions.NoArgsIsHelpError as exc:  # `pendulab` alone: the help, as click prints it
        click.echo(exc.ctx.get_help())
        return 2
    except click.exceptions.Exit as exc:
        return exc.exit_code
    except click.exceptions.Abort:
        click.echo(f"{where}: aborted", err=True)
        return 130
    except click.BadParameter as exc:
        # Our parameter types already name the option, the value and the range.
        opts = tuple(exc.param.opts) if exc.param is not None else ()
        msg = exc.message if opts and exc.message.startswith(opts) else exc.format_message()
        click.echo(f"{where}: error: {' '.join(msg.split())}", err=True)
        return 2
    except click.ClickException as exc:
        click.echo(f"{where}: error: {' '.join(exc.format_message().split())}", err=True)
        return 2
    except PendulabError as exc:
        click.echo(f"{where}: error: {_cli_message(exc, sub)}", err=True)
        return 2
    except MissingExtraError as exc:
        click.echo(f"{where}: error: {exc}", err=True)
        return 2
    except KeyboardInterrupt:
        click.echo(f"{where}: interrupted", err=True)
        return 130
    return 0


def _cli_message(exc: PendulabError, command: str | None) -> str:
    """A library error in the CLI's words: the argument is named as the command spells it.

    ``t_max`` becomes ``--t-max`` when the command has that option, ``NUMBERS`` for an
    argument; a name the command does not have stays the library's, without dashes.
    """
    from ..errors import InputError
    from ._common import option_name

    if not isinstance(exc, InputError):
        return " ".join(str(exc).split())
    name = exc.name
    cmd = LazyGroup._load(command) if command in COMMANDS else None
    flag = "--" + name.replace("_", "-")
    for p in cmd.params if cmd is not None else ():
        if p.name == name or flag in getattr(p, "opts", ()):
            name = option_name(p)
            break
    return " ".join(str(exc).replace(exc.name, name, 1).split())


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
