"""The ``seatwin`` command: a typer app that each ``seatwin.cli.<verb>`` module registers into.

Bad input anywhere raises :class:`seatwin.errors.InputError`; :func:`main` prints its one-line
message and exits with status 2 instead of a traceback.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Sequence

import typer
from typer._click.exceptions import NoArgsIsHelpError

from seatwin import __version__
from seatwin.cli.flags import flag_for
from seatwin.cli.helptext import PlainHelpGroup
from seatwin.errors import InputError, ParameterError

app = typer.Typer(
    name="seatwin",
    cls=PlainHelpGroup,
    help="seatwin — a digital twin for testing how autonomous ships perceive the world.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)

# Each module has ``register(app)``; keep their imports light (heavy imports inside commands)
# so that ``seatwin --help`` stays fast.
COMMAND_MODULES: list[str] = [
    "bag",
    "groundtruth",
    "scenario",
    "evaluate",
    "compare",
    "track",
    "importers",
    "errors",
    "lidar",
    "simulate",
    "radar",
    "fidelity",
    "demo",
    "sweep",
    "campaign",
    "camera",
    "labels",
    "serve",
    "record_stream",
    "cosim",
]


def _version(value: bool) -> None:
    if value:
        typer.echo(f"seatwin {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: bool = typer.Option(False, "--version", callback=_version, is_eager=True, help="Print the version and exit."),
) -> None:
    """seatwin — a digital twin for testing how autonomous ships perceive the world."""


for _name in COMMAND_MODULES:
    importlib.import_module(f"seatwin.cli.{_name}").register(app)


def run(argv: Sequence[str] | None = None) -> int:
    """Run the CLI with ``argv``; return the exit status (used by ``main`` and by tests)."""
    try:
        # Without standalone mode, a command's typer.Exit(n) comes back as the return value, not an exception.
        code = app(args=list(argv) if argv is not None else None, prog_name="seatwin", standalone_mode=False)
    except ParameterError as exc:
        typer.echo(f"seatwin: error: {exc.render(flag_for(exc.param))}", err=True)
        return 2
    except InputError as exc:
        typer.echo(f"seatwin: error: {exc}", err=True)
        return 2
    except typer.Exit as exc:
        return exc.exit_code
    except typer.Abort:
        typer.echo("seatwin: aborted", err=True)
        return 130
    except KeyboardInterrupt:
        typer.echo("seatwin: interrupted", err=True)
        return 130
    except NoArgsIsHelpError as exc:  # bare ``seatwin`` or ``seatwin bag``: the help (Rich has printed it already)
        if exc.format_message().strip():
            typer.echo(exc.format_message())
        return 0
    except typer.TyperException as exc:  # usage errors: unknown verb or option, bad value, missing option
        typer.echo(f"seatwin: error: {exc.format_message()}", err=True)
        return 2 if exc.exit_code in (1, 2) else exc.exit_code
    return code if isinstance(code, int) else 0


def main() -> None:
    sys.exit(run())


if __name__ == "__main__":
    main()
