"""Library parameter names → the command-line flags that set them, for error messages.

Library functions raise :class:`seatwin.errors.ParameterError` naming their Python parameter
(``ray_drop``); the CLI prints the flag a user typed (``--ray-drop``). The default is the
parameter with ``_`` → ``-``; :data:`FLAG_OF` lists the exceptions.
"""

from __future__ import annotations

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
    "report_dir": "--report",
    "tunings": "--tuning",
    "real": "--real/--synthetic",
    "plots_csv": "--out",
    "run_dir": "--out-bag",
    "radar_config": "--radar",
    "n_boot": "--boot",
    "seed0": "--seed",
}


def flag_for(param: str) -> str:
    """The flag of library parameter ``param`` (``ray_drop`` → ``--ray-drop``); a flag is returned as is."""
    if param.startswith("-"):
        return param
    return FLAG_OF.get(param, "--" + param.replace("_", "-"))
