"""The one error type for bad input: it names the file, the place in it and what was expected.

Every reader and every library function raises :class:`InputError` for bad input; the CLI
prints its message on one line and exits with status 2, never a bare traceback.

Library functions name their own *parameters* (:class:`ParameterError`, e.g. ``duration``),
never command-line flags; the CLI maps a parameter to its flag (``--duration``) when it prints.
"""

from __future__ import annotations

from os import PathLike


class InputError(ValueError):
    """Bad input: ``source`` (a file or a parameter), ``where`` (line, field) and what was expected."""

    def __init__(self, source: str | PathLike[str] | None, message: str, where: str | None = None):
        self.source = None if source is None else str(source)
        self.where = where
        self.detail = message
        super().__init__(self.render())

    def render(self, source: str | None = None) -> str:
        """The one-line message, optionally with ``source`` shown instead of the stored one."""
        parts = [p for p in (source if source is not None else self.source, self.where) if p]
        return f"{': '.join(parts)}: {self.detail}" if parts else self.detail


class ParameterError(InputError):
    """A library function's parameter ``param`` (its Python name, e.g. ``ray_drop``) has a bad value.

    ``str(exc)`` names the parameter; the CLI shows the flag the user typed instead
    (``seatwin.cli.flags.flag_for``).
    """

    def __init__(self, param: str, message: str):
        self.param = param
        super().__init__(param, message)


def parse_finite(text: str, source: str | PathLike[str] | None, field: str, line: int | None = None) -> float:
    """``text`` as a finite float, or an :class:`InputError` naming the source, line and field."""
    where = f"line {line}" if line is not None else None
    try:
        value = float(text)
    except ValueError:
        raise InputError(source, f"expected a number for {field}, got {text!r}", where=where) from None
    if value != value or value in (float("inf"), float("-inf")):
        raise InputError(source, f"expected a finite number for {field}, got {text!r}", where=where)
    return value
