"""The help texts as written: Rich markup is not interpreted, placeholders follow one vocabulary.

Typer renders help with Rich, which reads ``[deg]`` or ``[s]`` as markup tags and drops them.
:class:`PlainHelpGroup`, the root group's class, walks the command tree once it is built and
escapes every help text, so units survive; flags lose the ``<bool>`` placeholder (they take no
value); value placeholders are upper case (``FLOAT``, ``PATH``, ``SCENARIO``) like the
hand-written ones (``DIR``, ``LIST``).
"""

from __future__ import annotations

from typing import Any

from rich.markup import escape
from typer.core import TyperArgument, TyperGroup, TyperOption

__all__ = ["PlainHelpGroup", "escape", "tidy"]

# Typer's ``<type>`` placeholders → the words the hand-written metavars use.
_PLACEHOLDER: dict[str, str] = {"float": "FLOAT", "int": "INT", "str": "TEXT", "path": "PATH"}


def _escaped(text: str | None) -> str | None:
    return escape(text) if text else text


def _tidy_param(param: Any) -> None:
    if isinstance(param, (TyperOption, TyperArgument)):
        param.help = _escaped(param.help)
    if isinstance(param, TyperArgument) and param.metavar is None:
        param.metavar = (param.name or "").upper()
    if isinstance(param, TyperOption) and param.metavar is None:
        if param.is_flag:
            param.metavar = ""
        elif not param.type_descriptor.is_choice:
            bare = "path" if param.type_descriptor.is_path else param.bare_type()
            param.metavar = _PLACEHOLDER.get(bare)


def tidy(command: Any) -> None:
    """Escape the help of ``command``, its parameters and (for a group) every sub-command, in place."""
    command.help = _escaped(command.help)
    command.short_help = _escaped(command.short_help)
    command.epilog = _escaped(command.epilog)
    help_option = command.get_help_option(command.context_class(command))  # built once, cached by the command
    for param in [*command.params, *([help_option] if help_option is not None else [])]:
        _tidy_param(param)
    for sub in getattr(command, "commands", {}).values():
        tidy(sub)


class PlainHelpGroup(TyperGroup):
    """The root group: its command tree's help texts are tidied (:func:`tidy`) when it is built."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        tidy(self)
