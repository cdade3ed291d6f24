"""The ``seatwin`` command: a typer app that each ``seatwin.cli.<verb>`` module registers into.

Bad input anywhere raises :class:`seatwin.errors.InputError`; :func:`main` prints its one-line
message and exits with status 2 instead of a traceback. As a last resort, an ``OSError``,
``RecursionError``, ``MemoryError`` or ``OverflowError`` that no reader caught is printed the same way
(naming the file when the error has one); anything else is a bug and keeps its traceback.
"""

from __future__ import annotations

import importlib
import sys
import warnings
from collections.abc import Sequence

import typer

from seatwin import __version__
from seatwin.cli.flags import flag_for
from seatwin.cli.helptext import PlainHelpGroup
from seatwin.errors import InputError, ParameterError
from seatwin.outputs import OutputExistsError

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
    "harbour",
    "view",
    "verify",
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


def _show_warning(message: Warning | str, category: type[Warning], filename: str, lineno: int, *_: object) -> None:
    """A library warning as one line on stderr (no Python source location)."""
    typer.echo(f"seatwin: warning: {message}", err=True)


def run(argv: Sequence[str] | None = None) -> int:
    """Run the CLI with ``argv``; return the exit status (used by ``main`` and by tests)."""
    with warnings.catch_warnings():
        warnings.showwarning = _show_warning
        return _run(argv)


def _run(argv: Sequence[str] | None) -> int:
    from seatwin.interrupts import Interrupted, interrupts_raise

    try:
        # Without standalone mode, a command's typer.Exit(n) comes back as the return value, not an exception.
        # SIGTERM stops a verb as Ctrl-C does (a KeyboardInterrupt), never in the middle of a frame.
        with interrupts_raise() as raised:
            code = app(args=list(argv) if argv is not None else None, prog_name="seatwin", standalone_mode=False)
    except ParameterError as exc:
        hint = f" (give {flag_for('overwrite')} to replace it)" if isinstance(exc, OutputExistsError) else ""
        typer.echo(f"seatwin: error: {exc.render(flag_for(exc.param, _verb(argv)))}{hint}", err=True)
        return 2
    except InputError as exc:
        typer.echo(f"seatwin: error: {exc}", err=True)
        return 2
    except typer.Exit as exc:
        return exc.exit_code
    except typer.Abort:
        typer.echo("seatwin: aborted", err=True)
        return 130
    except KeyboardInterrupt as exc:
        return _interrupted(exc)
    except typer.TyperException as exc:  # usage errors: unknown verb or option, bad value, missing option
        if _is_no_args_help(exc):  # bare ``seatwin`` or ``seatwin bag``: the help (Rich has printed it already)
            if exc.format_message().strip():
                typer.echo(exc.format_message())
            return 0
        typer.echo(f"seatwin: error: {exc.format_message()}", err=True)
        return 2 if exc.exit_code in (1, 2) else exc.exit_code
    except (OSError, RecursionError, MemoryError, OverflowError) as exc:  # the last resort: one line, no traceback
        typer.echo(f"seatwin: error: {last_resort_message(exc)}", err=True)
        return 2
    if code == 130 and raised() is not None:  # typer returns a KeyboardInterrupt as 130, silently: say which signal
        return _interrupted(Interrupted(raised()))  # type: ignore[arg-type]
    return code if isinstance(code, int) else 0


def _is_no_args_help(exc: Exception) -> bool:
    """Click's ``NoArgsIsHelpError``, by name: typer vendors click privately (``typer._click``), so the class has no
    public import path that holds across typer versions."""
    return any(c.__name__ == "NoArgsIsHelpError" for c in type(exc).__mro__)


def _verb(argv: Sequence[str] | None) -> str | None:
    """The verb of the command line (its first word that is not an option), for :func:`flag_for`."""
    args = list(argv) if argv is not None else sys.argv[1:]
    return next((a for a in args if not a.startswith("-")), None)


def last_resort_message(exc: BaseException) -> str:
    """One line for an error no reader turned into an :class:`InputError`: the file (``OSError.filename``) and
    what went wrong."""
    if isinstance(exc, OSError):
        names = [str(n) for n in (exc.filename, exc.filename2) if n is not None]
        reason = exc.strerror or str(exc) or type(exc).__name__
        return f"{' → '.join(names)}: {reason}" if names else reason
    if isinstance(exc, RecursionError):
        return f"input nested too deeply to handle ({exc})"
    if isinstance(exc, MemoryError):
        return f"out of memory{f' ({exc})' if str(exc) else ''}"
    return f"a number too large to handle ({exc})"


def _interrupted(exc: KeyboardInterrupt) -> int:
    """``seatwin: interrupted (Ctrl-C)`` or ``(SIGTERM)`` on stderr; status 130 either way."""
    typer.echo(f"seatwin: interrupted ({exc or 'Ctrl-C'})", err=True)
    return 130


def main() -> None:
    sys.exit(run())


if __name__ == "__main__":
    main()
