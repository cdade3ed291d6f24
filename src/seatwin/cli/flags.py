"""Library parameter names → the command-line flags that set them, for error messages.

Library functions raise :class:`seatwin.errors.ParameterError` naming their Python parameter
(``ray_drop``); the CLI prints the flag a user typed (``--ray-drop``). The default is the
parameter with ``_`` → ``-``; :data:`FLAG_OF` lists the exceptions. Old spellings of renamed flags
stay as hidden options (:func:`old_spelling`, :func:`either`).
"""

from __future__ import annotations

from typing import Any, TypeVar

from seatwin.errors import ParameterError

T = TypeVar("T")

FLAG_OF: dict[str, str] = {
    "fmt": "--format",
    "start_offset": "--offset",
    "harbour_spec": "--harbour",
    "map_spec": "--map",
    "merge_distance": "--radar-merge",
    "radar_kind": "--radar-model",
    "eps": "--cluster-eps",
    "drop_probability": "--ray-drop",
    "preset": "--lidar-preset",
    "vessels": "--vessel",
    "rate_hz": "--rate",
    "eps_threshold_m": "--eps-threshold",
    "max_gap_s": "--max-gap",
    "smooth_s": "--smooth",
    "plots_dir": "--plots",
    "form": "--hellinger-form",
    "json_out": "--json",
    "out_dir": "--out",
    "quality_json": "--quality",
    "report_dir": "--report",
    "tunings": "--tuning",
    "real": "--real/--synthetic",
    "plots_csv": "--out",
    "run_dir": "--out-bag",
    "radar_config": "--radar",
    "lidar_config": "--lidar",
    "n_boot": "--boot",
    "seed0": "--seed",
    "max_step_s": "--max-step",
    "camera_hfov_deg": "--camera-hfov",
}

FLAG_OF_IN_VERB: dict[str, dict[str, str]] = {"serve": {"vessels": "--vessels"}}
"""Where one verb spells a parameter otherwise than :data:`FLAG_OF` (``serve --vessels A,B`` vs ``groundtruth --vessel``)."""


def flag_for(param: str, verb: str | None = None) -> str:
    """The flag of library parameter ``param`` (``ray_drop`` → ``--ray-drop``) in ``verb``; a flag is returned as is."""
    if param.startswith("-"):
        return param
    return FLAG_OF_IN_VERB.get(verb or "", {}).get(param) or FLAG_OF.get(param, "--" + param.replace("_", "-"))


def old_spelling(old: str, new: str) -> Any:
    """A hidden option ``old``, the former spelling of ``new``: it still works, ``--help`` shows only ``new``.

    Declare it beside ``new`` with default None and merge the two with :func:`either`.
    """
    import typer

    return typer.Option(None, old, hidden=True, help=f"Old spelling of {new}.")


def either(value: T, old_value: T | None, default: T, new: str, old: str) -> T:
    """``value`` of flag ``new``, or ``old_value`` when only its old spelling ``old`` was given (both: an error)."""
    if old_value is None:
        return value
    if value != default:
        raise ParameterError(new, f"given twice, as {new} and as its old spelling {old}: give {new} only")
    return old_value
