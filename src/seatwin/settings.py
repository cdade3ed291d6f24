"""One configuration style: pydantic models with a description per field, validated into one clear error.

A :class:`Settings` model built with a bad value raises :class:`ParameterError` naming the field
(library calls: the CLI shows the flag); :func:`validated` builds one from a mapping and, for a
file's mapping, raises an :class:`InputError` naming the file and field instead.
"""

from __future__ import annotations

from os import PathLike
from typing import Annotated, Any, TypeVar

from pydantic import AfterValidator, BaseModel, ConfigDict, ValidationError

from seatwin.errors import InputError, ParameterError

M = TypeVar("M", bound=BaseModel)


def parameter_error(exc: ValidationError, model: str) -> ParameterError:
    """pydantic's first error as one :class:`ParameterError` naming the (top-level) field."""
    err = exc.errors()[0]
    original = (err.get("ctx") or {}).get("error")
    loc = [str(p) for p in err["loc"]]
    if isinstance(original, ParameterError):  # a validator or a nested model that already named its parameter
        if not loc:
            return original
        return ParameterError(loc[0], f"{'.'.join([*loc[1:], original.param])}: {original.detail}")
    msg = err["msg"].removeprefix("Value error, ")
    if "input" in err and err["type"] != "missing":
        msg = f"{msg}, got {err['input']!r}"
    if len(loc) > 1:
        msg = f"{'.'.join(loc[1:])}: {msg}"
    return ParameterError(loc[0] if loc else model, msg)


class Settings(BaseModel):
    """Base of every settings model: unknown fields are errors, numbers are finite, instances are immutable."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    def __init__(self, **data: Any) -> None:
        try:
            super().__init__(**data)
        except ValidationError as exc:
            raise parameter_error(exc, type(self).__name__) from None

    def with_(self: M, **changes: Any) -> M:
        """A validated copy with ``changes``."""
        return validated(type(self), {**self.model_dump(), **changes})


def validated(model: type[M], values: dict[str, Any], source: str | PathLike[str] | None = None) -> M:
    """``model(**values)``, or one :class:`ParameterError` (``source`` None) / :class:`InputError` naming the field."""
    try:
        try:
            return model.model_validate(values)
        except ValidationError as exc:
            raise parameter_error(exc, model.__name__) from None
    except ParameterError as exc:
        if source is None:
            raise
        raise InputError(source, exc.detail, where=exc.param) from None


def _distinct_seeds(v: tuple[int, ...]) -> tuple[int, ...]:
    if len(set(v)) != len(v):
        raise ValueError("expected distinct seeds")
    return v


Seeds = Annotated[tuple[int, ...], AfterValidator(_distinct_seeds)]
"""A settings field of seeds, none repeated (sweeps and campaigns: every point repeated with each)."""
