"""One configuration style: pydantic models with a description per field, validated into one clear error.

A :class:`Settings` model built with a bad value raises :class:`ParameterError` naming the field
(library calls: the CLI shows the flag); :func:`validated` builds one from a mapping and, for a
file's mapping, raises an :class:`InputError` naming the file and field instead.
"""

from __future__ import annotations

from os import PathLike
from typing import Annotated, Any, TypeVar, get_args, get_origin

from pydantic import AfterValidator, BaseModel, ConfigDict, ValidationError

from seatwin.errors import InputError, ParameterError

M = TypeVar("M", bound=BaseModel)


def shown(value: Any) -> str:
    """A value as a user typed it: ``1,2`` for a tuple, ``0`` for 0.0, ``'fog'`` for a string — no Python reprs."""
    if isinstance(value, (tuple, list)):
        return ",".join(shown(v).strip("'") for v in value)
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, str):
        return repr(value)
    return str(value)


def _in_words(msg: str) -> str:
    """pydantic's message without its prefixes, said as what is expected ("Input should be >1" → "expected a value >1")."""
    msg = msg.removeprefix("Value error, ").removeprefix("Assertion failed, ")
    if msg.startswith("Input should be "):
        rest = msg.removeprefix("Input should be ")
        return f"expected {'a value ' if rest.startswith(('greater', 'less', 'a multiple')) else ''}{rest}"
    return msg


def _tuple_length(model: type[BaseModel] | None, field: str) -> int | None:
    """The fixed length of ``model.field`` when it is a ``tuple[X, Y, Z]``, else None."""
    info = model.model_fields.get(field) if model is not None else None
    args = get_args(info.annotation) if info is not None and get_origin(info.annotation) is tuple else ()
    return len(args) if args and Ellipsis not in args else None


def parameter_error(exc: ValidationError, model: str, cls: type[BaseModel] | None = None) -> ParameterError:
    """pydantic's first error as one :class:`ParameterError` naming the (top-level) field, in words: an item of a
    list is "item 2", a missing item of a fixed-length tuple (of ``cls``) says how many values were expected."""
    err = exc.errors()[0]
    original = (err.get("ctx") or {}).get("error")
    loc = [str(p) for p in err["loc"]]
    if isinstance(original, ParameterError):  # a validator or a nested model that already named its parameter
        if not loc:
            return original
        return ParameterError(loc[0], f"{'.'.join([*loc[1:], original.param])}: {original.detail}")
    n = _tuple_length(cls, loc[0]) if loc else None
    if err["type"] == "missing" and len(loc) == 2 and isinstance(err["loc"][1], int) and n is not None:
        return ParameterError(loc[0], f"expected {n} values, got {err['loc'][1]}")
    if err["type"] == "too_long" and len(loc) == 1 and isinstance(err.get("input"), (tuple, list)):
        return ParameterError(loc[0], f"expected {n or 'fewer'} values, got {len(err['input'])}")
    msg = _in_words(err["msg"])
    if "input" in err and err["type"] != "missing" and shown(err["input"]) not in msg:
        msg = f"{msg}, got {shown(err['input'])}"
    where = [f"item {p + 1}" if isinstance(p, int) else str(p) for p in err["loc"][1:]]
    if where:
        msg = f"{'.'.join(where)}: {msg}"
    return ParameterError(loc[0] if loc else model, msg)


class Settings(BaseModel):
    """Base of every settings model: unknown fields are errors, numbers are finite, instances are immutable."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    def __init__(self, **data: Any) -> None:
        try:
            super().__init__(**data)
        except ValidationError as exc:
            raise parameter_error(exc, type(self).__name__, type(self)) from None

    def with_(self: M, **changes: Any) -> M:
        """A validated copy with ``changes``."""
        return validated(type(self), {**self.model_dump(), **changes})


def validated(model: type[M], values: dict[str, Any], source: str | PathLike[str] | None = None) -> M:
    """``model(**values)``, or one :class:`ParameterError` (``source`` None) / :class:`InputError` naming the field."""
    try:
        try:
            return model.model_validate(values)
        except ValidationError as exc:
            raise parameter_error(exc, model.__name__, model) from None
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
