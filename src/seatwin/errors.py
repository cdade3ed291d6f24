"""The one error type for bad input: it names the file, the place in it and what was expected.

Every reader and every CLI verb raises :class:`InputError` for bad input; the CLI prints
its message on one line and exits with status 2, never a bare traceback.
"""

from __future__ import annotations

from os import PathLike


class InputError(ValueError):
    """Bad input: ``source`` (a file or an option), ``where`` (line, field) and what was expected."""

    def __init__(self, source: str | PathLike[str] | None, message: str, where: str | None = None):
        self.source = None if source is None else str(source)
        self.where = where
        self.detail = message
        parts = [p for p in (self.source, where) if p]
        super().__init__(f"{': '.join(parts)}: {message}" if parts else message)


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
