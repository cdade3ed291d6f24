"""rosbag2 metadata as YAML text, the same text rosbags writes (ruamel's safe dumper, block style).

rosbags dumps ``metadata.yaml`` (twice: the file and the copy inside the bag) and every
connection's QoS profiles with ruamel's pure-Python emitter, ~1 ms a document; for a short run
that was a tenth of the recording time. :func:`dump_yaml` writes the same text directly for the
shapes rosbag2 metadata has — nested mappings (keys sorted), sequences, integers, booleans,
``null`` and plain strings, with ruamel's rule that a word which does not fit on an 80-column
line starts a line of its own — and hands anything else (a string that would need quotes, a
sequence of sequences…) to ruamel itself. ``tests/recording/test_storage.py`` compares both.
"""

from __future__ import annotations

import re
from io import StringIO
from typing import Any

WIDTH = 80
"""ruamel's ``best_width``."""

_PLAIN = re.compile(r"[A-Za-z_/][A-Za-z0-9_/.\-]*\Z")
_RESERVED = {"y", "n", "yes", "no", "on", "off", "true", "false", "null"}


class _NeedsRuamel(Exception):
    """The data holds something this emitter does not write the way ruamel would."""


def dump_yaml(data: Any) -> str:
    """``data`` as ruamel's ``YAML(typ="safe")`` with ``default_flow_style = False`` dumps it."""
    try:
        if isinstance(data, dict) and data:
            lines: list[str] = []
            _mapping(data, 0, lines, first_prefix="")
            return "\n".join(lines) + "\n"
        if isinstance(data, list) and data:
            lines = []
            _sequence(data, 0, lines)
            return "\n".join(lines) + "\n"
        if data == {} or data == []:
            return ("{}" if isinstance(data, dict) else "[]") + "\n"
    except _NeedsRuamel:
        pass
    return _ruamel(data)


def _ruamel(data: Any) -> str:
    from ruamel.yaml import YAML

    yaml = YAML(typ="safe")
    yaml.default_flow_style = False
    out = StringIO()
    yaml.dump(data, out)
    return out.getvalue()


def _scalar(value: Any) -> str:
    if value is None:
        return "null"
    if value is True:
        return "true"
    if value is False:
        return "false"
    if type(value) is int:
        return str(value)
    if type(value) is str:
        if value == "":
            return "''"
        if _PLAIN.match(value) and value.lower() not in _RESERVED:
            return value
    raise _NeedsRuamel


def _mapping(data: dict[str, Any], indent: int, lines: list[str], first_prefix: str) -> None:
    """Keys at column ``indent``; the first line starts with ``first_prefix`` (``- `` in a sequence)."""
    for i, key in enumerate(sorted(data)):
        if type(key) is not str or len(key) > 100:  # ruamel writes long keys as complex keys ("? ")
            raise _NeedsRuamel
        head = (first_prefix if i == 0 else " " * indent) + _scalar(key) + ":"
        value = data[key]
        if isinstance(value, dict) and value:
            lines.append(head)
            _mapping(value, indent + 2, lines, " " * (indent + 2))
        elif isinstance(value, list) and value:
            lines.append(head)
            _sequence(value, indent, lines)
        elif value == {} and isinstance(value, dict):
            lines.append(head + " {}")
        elif value == [] and isinstance(value, list):
            lines.append(head + " []")
        else:
            text = _scalar(value)
            if text != "''" and len(head) + 1 + len(text) > WIDTH:  # ruamel: a plain word too long for the line gets its own
                lines.append(head + " ")
                lines.append(" " * (indent + 2) + text)
            else:
                lines.append(head + " " + text)


def _sequence(items: list[Any], indent: int, lines: list[str]) -> None:
    """Items ``- …`` at column ``indent`` (ruamel does not indent a sequence inside a mapping)."""
    for item in items:
        if isinstance(item, dict) and item:
            _mapping(item, indent + 2, lines, " " * indent + "- ")
        elif isinstance(item, (dict, list)):
            raise _NeedsRuamel
        else:
            text = _scalar(item)
            if indent + 2 + len(text) > WIDTH:
                raise _NeedsRuamel
            lines.append(" " * indent + "- " + text)
