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
