"""One configuration style: pydantic models with a description per field, validated into one clear error.

:func:`validated` builds a settings model from keyword values (a library call) or from a
file's mapping; a bad value becomes a :class:`ParameterError` naming the field (library
calls: the CLI shows the flag) or an :class:`InputError` naming the file and field.
"""

from __future__ import annotations

from os import PathLike
from typing import Any, TypeVar

from pydantic import BaseModel, ConfigDict, ValidationError

from seatwin.errors import InputError, ParameterError

M = TypeVar("M", bound=BaseModel)


class Settings(BaseModel):
    """Base of every settings model: unknown fields are errors, instances are immutable."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    def with_(self: M, **changes: Any) -> M:
        """A validated copy with ``changes``."""
        return validated(type(self), {**self.model_dump(), **changes})


def validated(model: type[M], values: dict[str, Any], source: str | PathLike[str] | None = None) -> M:
    """``model(**values)``, or one :class:`ParameterError` (``source`` None) / :class:`InputError` naming the field."""
    try:
        return model.model_validate(values)
    except ValidationError as exc:
        err = exc.errors()[0]
        loc = [str(p) for p in err["loc"]]
        field = loc[0] if loc else model.__name__
        message = f"{err['msg']}, got {err['input']!r}" if "input" in err and err["type"] != "missing" else err["msg"]
        if len(loc) > 1:
            message = f"{'.'.join(loc[1:])}: {message}"
        if source is None:
            raise ParameterError(field, message) from None
        raise InputError(source, message, where=field) from None
