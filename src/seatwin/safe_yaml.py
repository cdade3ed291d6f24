"""The one YAML loader for every YAML file a user hands seatwin (scenario, campaign, tuning, radar, raster).

``yaml.safe_load`` builds no arbitrary objects, but it still expands aliases (a 425-byte "billion
laughs" file becomes gigabytes), recurses once per nesting level (``RecursionError``), turns a
5,000-digit integer into Python's int-string ``ValueError`` and ``1e999`` into ``inf``. This loader
refuses all of them, each with one :class:`InputError` naming the file and line:

* anchors and aliases (``&name``, ``*name``, merge keys ``<<: *name``): a seatwin input is data
  written out in full, so they are refused outright rather than expanded under a budget;
* nesting deeper than :data:`MAX_DEPTH` levels;
* integers outside 64 bits, and numbers that are not finite (``.inf``, ``.nan``, ``1e999``):
  no seatwin setting takes them;
* files larger than :data:`MAX_BYTES` (seatwin's YAML files are a few kilobytes).
"""

from __future__ import annotations

import math
import os
from os import PathLike
from typing import Any

import yaml
from yaml.events import AliasEvent, CollectionStartEvent
from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode
from yaml.reader import ReaderError

from seatwin.errors import InputError, read_text

MAX_DEPTH = 64
"""Deepest nesting of sequences and mappings accepted (seatwin's own files need fewer than 6)."""
INT_RANGE = (-(2**63), 2**64 - 1)
"""Smallest and largest integer accepted (signed or unsigned 64 bits)."""
MAX_BYTES = 4 * 1024 * 1024
"""Largest YAML file read."""
_MAX_NUMBER_CHARS = 64
"""A number literal longer than this is refused before it is converted (no quadratic int parsing)."""


class _Refused(yaml.MarkedYAMLError):
    """A construct this loader does not accept, at ``problem_mark``."""


class _Loader(yaml.SafeLoader):
    """PyYAML's safe loader without aliases, deep nesting, huge integers or non-finite numbers."""

    def __init__(self, stream: str) -> None:
        super().__init__(stream)
        self._depth = 0

    def compose_node(self, parent: Node | None, index: Any) -> Node | None:
        event = self.peek_event()
        if isinstance(event, AliasEvent) or getattr(event, "anchor", None) is not None:
            kind = f"alias *{event.anchor}" if isinstance(event, AliasEvent) else f"anchor &{event.anchor}"
            raise _Refused(
                problem=f"{kind}: YAML anchors and aliases are not accepted (they can expand without bound); write the value out",
                problem_mark=event.start_mark,
            )
        if not isinstance(event, CollectionStartEvent):
            return super().compose_node(parent, index)
        self._depth += 1
        if self._depth > MAX_DEPTH:
            raise _Refused(problem=f"nested deeper than {MAX_DEPTH} levels", problem_mark=event.start_mark)
        try:
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1

    def construct_object(self, node: Node, deep: bool = False) -> Any:
        try:
            return super().construct_object(node, deep=deep)
        except yaml.YAMLError:
            raise
        except (ValueError, TypeError, KeyError, IndexError, AttributeError, OverflowError):
            # PyYAML's own constructors fail this way on explicitly tagged junk (``!!int ''``, ``!!bool x``).
            tag = str(node.tag).removeprefix("tag:yaml.org,2002:")
            value = node.value if isinstance(node, ScalarNode) else "…"
            raise _Refused(problem=f"{value!r} is not a valid !!{tag}", problem_mark=node.start_mark) from None

    def construct_yaml_str(self, node: ScalarNode) -> str:
        value = str(super().construct_yaml_str(node))
        if node.style is None and value != value.strip():
            # YAML strips blanks around a plain value, but not a no-break space (U+00A0) and the like,
            # which would then hide in a name or be dropped silently when the value is read as a number.
            odd = value[0] if value[0].isspace() else value[-1]
            raise _Refused(
                problem=f"value {value!r} starts or ends with the space character U+{ord(odd):04X}: "
                "remove it (or quote the value)",
                problem_mark=node.start_mark,
            )
        return value

    def construct_yaml_int(self, node: ScalarNode) -> int:
        text = str(node.value)
        if len(text) > _MAX_NUMBER_CHARS:
            raise _Refused(
                problem=f"integer of {len(text)} characters is too large (at most 64 bits)", problem_mark=node.start_mark
            )
        value = super().construct_yaml_int(node)
        if not INT_RANGE[0] <= value <= INT_RANGE[1]:
            raise _Refused(problem=f"integer {text} is too large (at most 64 bits)", problem_mark=node.start_mark)
        return value

    def construct_yaml_float(self, node: ScalarNode) -> float:
        text = str(node.value)
        if len(text) > _MAX_NUMBER_CHARS:
            raise _Refused(problem=f"number of {len(text)} characters is too long", problem_mark=node.start_mark)
        value = super().construct_yaml_float(node)
        if not math.isfinite(value):
            raise _Refused(problem=f"expected a finite number, got {text}", problem_mark=node.start_mark)
        return value


_Loader.add_constructor("tag:yaml.org,2002:str", _Loader.construct_yaml_str)
_Loader.add_constructor("tag:yaml.org,2002:int", _Loader.construct_yaml_int)
_Loader.add_constructor("tag:yaml.org,2002:float", _Loader.construct_yaml_float)


Lines = dict[tuple[Any, ...], int]
"""Where each value is: its path (mapping keys and sequence indices from the top) → 1-based line."""


def _collect_lines(node: Node, path: tuple[Any, ...], out: Lines) -> None:
    out[path] = node.start_mark.line + 1
    if isinstance(node, MappingNode):
        for key, value in node.value:
            _collect_lines(value, (*path, key.value if isinstance(key, ScalarNode) else None), out)
    elif isinstance(node, SequenceNode):
        for i, value in enumerate(node.value):
            _collect_lines(value, (*path, i), out)


def line_of(lines: Lines, path: tuple[Any, ...]) -> int | None:
    """The line of ``path`` (a pydantic error location, say), or of its nearest enclosing value found."""
    for n in range(len(path), 0, -1):
        if path[:n] in lines:
            return lines[path[:n]]
    return None


def parse_yaml(text: str, source: str | PathLike[str] | None, lines: Lines | None = None) -> Any:
    """The data of the YAML ``text`` (one document), or one :class:`InputError` naming ``source`` and the line.

    ``lines``, when given, is filled with the line of every value (:func:`line_of` finds one), so a
    later check of the data can name the line too.
    """
    loader = None
    try:
        loader = _Loader(text)  # checks the characters first
        node = loader.get_single_node()
        if node is None:
            return None
        if lines is not None:
            _collect_lines(node, (), lines)
        return loader.construct_document(node)
    except ReaderError as exc:
        line = text.count("\n", 0, exc.position) + 1
        raise InputError(source, f"not valid YAML: character {exc.character:#06x} is not allowed", where=f"line {line}") from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"line {mark.line + 1}, column {mark.column + 1}" if mark is not None else None
        problem = getattr(exc, "problem", None) or str(exc)
        problem = " ".join(str(problem).replace('in "<unicode string>", ', "at ").split())
        prefix = "" if isinstance(exc, _Refused) else "not valid YAML: "
        raise InputError(source, f"{prefix}{problem}", where=where) from None
    finally:
        if loader is not None:
            loader.dispose()


def load_yaml(path: str | PathLike[str], expected: str, lines: Lines | None = None) -> Any:
    """The data of the YAML file ``path`` (``expected`` says what it should be, e.g. "a campaign YAML file");
    ``lines`` as for :func:`parse_yaml`."""
    try:
        size = os.stat(path).st_size
    except OSError as exc:
        raise InputError(path, f"cannot open: {exc.strerror or exc}") from None
    if size > MAX_BYTES:
        raise InputError(path, f"{size} bytes is too large for {expected} (at most {MAX_BYTES} bytes)")
    return parse_yaml(read_text(path, expected), path, lines)
