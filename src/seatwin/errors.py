"""The one error type for bad input: it names the file, the place in it and what was expected.

Every reader and every library function raises :class:`InputError` for bad input; the CLI
prints its message on one line and exits with status 2, never a bare traceback.

Library functions name their own *parameters* (:class:`ParameterError`, e.g. ``duration``),
never command-line flags; the CLI maps a parameter to its flag (``--duration``) when it prints.
"""

from __future__ import annotations

import csv
import io
import math
import re
from collections.abc import Callable, Iterator
from os import PathLike
from pathlib import Path
from typing import TypeVar

T = TypeVar("T")


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


NUMBER = re.compile(r"[ \t]*[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?[ \t]*")
"""A decimal number in ASCII, optionally between ASCII blanks: what text data formats write."""


def parse_finite(text: str, source: str | PathLike[str] | None, field: str, line: int | None = None) -> float:
    """``text`` as a finite float, or an :class:`InputError` naming the source, line and field.

    Stricter than ``float()``: only an ASCII decimal number (``-12.5``, ``1e-3``), optionally between
    spaces or tabs. ``float()`` also takes ``nan``, ``inf``, ``1_000``, non-ASCII digits and a
    no-break space after the number, none of which a GNSS or CSV file legitimately holds.
    """
    where = f"line {line}" if line is not None else None
    if NUMBER.fullmatch(text) is None:
        word = text.strip(" \t").lstrip("+-").lower()
        kind = "a finite number" if word in ("nan", "inf", "infinity") else "a number"
        raise InputError(source, f"expected {kind} for {field}, got {text!r}", where=where)
    value = float(text)
    if not math.isfinite(value):
        raise InputError(source, f"expected a finite number for {field}, got {text!r}", where=where)
    return value


def read_text(path: str | PathLike[str], expected: str, encoding: str = "utf-8") -> str:
    """The text of ``path``, or one :class:`InputError`: it cannot be opened, or is not ``encoding`` text
    (``expected`` says what the file should be, e.g. "a track file")."""
    try:
        return Path(path).read_text(encoding=encoding)
    except OSError as exc:
        raise InputError(path, f"cannot open: {exc.strerror or exc}") from None
    except UnicodeDecodeError as exc:
        name = "ASCII" if encoding == "ascii" else "UTF-8"
        raise InputError(path, f"not {name} text ({exc.reason} at byte {exc.start}); expected {expected}") from None


def parse_csv(path: str | PathLike[str], text: str, parse: Callable[[Iterator[list[str]]], T]) -> T:
    """``parse(reader)`` over the CSV ``text``; the csv module's own errors become an :class:`InputError` with the line."""
    reader = csv.reader(io.StringIO(text, newline=""))
    try:
        return parse(reader)
    except csv.Error as exc:
        raise InputError(path, f"malformed CSV: {exc}", where=f"line {reader.line_num}") from None
