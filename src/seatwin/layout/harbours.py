"""Harbours by name or file: ``default`` (the built-in layout), ``ravnkloa`` (the real land raster), ``none``, a raster.

The Ravnkloa land raster (``ravnkloa/ravnkloa_radar_base_map.yaml`` + ``.bin``) is real data that
the project does not ship: it is looked for in ``$SEATWIN_DATA``, then in ``shared/data`` beside or
inside the current directory and the repository root (:func:`data_search_dirs`).

A raster harbour carries its alignment to the scenario frame (:mod:`seatwin.layout.alignment`):
``ravnkloa`` the one fitted to the Gemini scenarios and shipped beside this module
(:data:`RAVNKLOA_ALIGNMENT`); a raster file ``NAME.yaml`` the one in ``NAME.alignment.yaml`` beside
it, if there is one (else none).
"""

from __future__ import annotations

import os
from dataclasses import fields, replace
from pathlib import Path

import numpy as np

from seatwin.errors import InputError
from seatwin.layout.alignment import IDENTITY, Alignment, read_alignment
from seatwin.layout.model import DEFAULT_LAYOUT, HarbourLayout, MooredBoat
from seatwin.layout.raster import LandRaster, read_land_raster
from seatwin.safe_yaml import load_yaml

HARBOUR_NAMES = ("default", "ravnkloa", "none")
"""Harbours known by name (besides a raster file ``NAME.yaml``/``NAME.bin``)."""
_ALIASES = {"harbour": "default", "open": "none", "open_water": "none"}
RASTER_SUFFIXES = (".bin", ".yaml", ".yml")

DATA_ENV = "SEATWIN_DATA"
"""Environment variable naming the real-data folder (the one holding ``ravnkloa/``)."""
RAVNKLOA_RASTER = Path("ravnkloa") / "ravnkloa_radar_base_map.yaml"
"""The Ravnkloa land raster, relative to the data folder."""
_REPO_ROOT = Path(__file__).resolve().parents[3]
RAVNKLOA_ALIGNMENT = Path(__file__).with_name("ravnkloa_alignment.yaml")
RAVNKLOA_MOORED = Path(__file__).with_name("ravnkloa_moored.yaml")
"""The Ravnkloa twin's moored boats (made up, in the raster's frame; see the file)."""
"""The Ravnkloa raster's alignment to the Gemini scenarios' frame, with its fit's provenance."""
ALIGNMENT_SUFFIX = ".alignment.yaml"


def harbour_name(spec: object) -> str | None:
    """The name of a named harbour (``default``, ``ravnkloa``, ``none``; case and the aliases
    ``harbour``, ``open`` are accepted), or None when ``spec`` is not one (a path, a layout…)."""
    if spec is None:
        return "none"
    if not isinstance(spec, str):
        return None
    key = spec.strip().lower()
    key = _ALIASES.get(key, key)
    return key if key in HARBOUR_NAMES else None


def is_raster_path(spec: object) -> bool:
    """True for a path (str or Path) ending in .bin, .yaml or .yml."""
    return isinstance(spec, str | os.PathLike) and Path(spec).suffix.lower() in RASTER_SUFFIXES


def check_harbour_spec(spec: str) -> str:
    """``spec`` if it names a harbour or a raster file (the file is not read here), else a :class:`ValueError`
    saying what is expected (a settings validator)."""
    if harbour_name(spec) is None and not is_raster_path(spec):
        raise ValueError(f"expected a harbour name ({', '.join(HARBOUR_NAMES)}) or a land raster .bin/.yaml path")
    return spec


def data_search_dirs() -> list[Path]:
    """Where real data is looked for, in order: ``$SEATWIN_DATA``, then ``../shared/data`` and
    ``shared/data`` from the current directory and from the repository root (duplicates once)."""
    dirs: list[Path] = []
    env = os.environ.get(DATA_ENV)
    if env:
        dirs.append(Path(env).expanduser())
    for base in (Path.cwd(), _REPO_ROOT):
        dirs += [base.parent / "shared" / "data", base / "shared" / "data"]
    seen: set[Path] = set()
    out = []
    for d in dirs:
        key = d.resolve()
        if key not in seen:
            seen.add(key)
            out.append(key)
    return out


def find_data_file(relative: str | Path, what: str) -> Path:
    """The first ``dir/relative`` of :func:`data_search_dirs` that exists; an :class:`InputError`
    naming ``what``, every place searched and how to point at the data otherwise."""
    dirs = data_search_dirs()
    for d in dirs:
        if (d / relative).is_file():
            return d / relative
    searched = ", ".join(str(d / relative) for d in dirs)
    env = f" ({DATA_ENV}={os.environ[DATA_ENV]!r})" if os.environ.get(DATA_ENV) else ""
    raise InputError(
        None,
        f"{what} not found; searched {searched}{env}. Set {DATA_ENV} to the folder holding {relative}, "
        "or choose another harbour ('default', 'none' or a raster file)",
    )


def ravnkloa_raster_path() -> Path:
    """The Ravnkloa land raster's ``.yaml`` (see :func:`find_data_file`)."""
    return find_data_file(RAVNKLOA_RASTER, "the Ravnkloa land raster (harbour 'ravnkloa', a Gemini CSV's default)")


def harbour_file(spec: object) -> Path | None:
    """The raster file a harbour ``spec`` stands for (``ravnkloa`` resolved, a path as given), or None
    for the built-in layout and ``none``; an unknown name is an :class:`InputError`."""
    name = harbour_name(spec)
    if name == "ravnkloa":
        return ravnkloa_raster_path()
    if name is not None:
        return None
    if is_raster_path(spec):
        return Path(spec)  # type: ignore[arg-type]
    raise InputError(
        None,
        f"unknown harbour {spec!r}; expected {', '.join(HARBOUR_NAMES)} or a land raster .bin/.yaml path",
    )


def alignment_file(spec: object) -> Path | None:
    """The alignment file of a raster harbour ``spec`` (``ravnkloa``: :data:`RAVNKLOA_ALIGNMENT`; a raster
    ``NAME.yaml``: ``NAME.alignment.yaml`` beside it when it exists), else None."""
    if harbour_name(spec) == "ravnkloa":
        return RAVNKLOA_ALIGNMENT
    if is_raster_path(spec):
        p = Path(spec)  # type: ignore[arg-type]
        beside = p.with_name(p.stem + ALIGNMENT_SUFFIX)
        return beside if beside.is_file() else None
    return None


def harbour_alignment(spec: object) -> Alignment:
    """The alignment of harbour ``spec`` to the scenario frame (identity for a layout, ``none``, a raster without one)."""
    if isinstance(spec, LandRaster):
        return spec.alignment
    path = alignment_file(spec)
    return IDENTITY if path is None else read_alignment(path)[0]


def harbour_map(spec: object) -> HarbourLayout | LandRaster | None:
    """The 2-D map of a harbour ``spec``: a :class:`HarbourLayout` or :class:`LandRaster` as is,
    ``default`` → :data:`DEFAULT_LAYOUT`, ``none`` → None, ``ravnkloa`` or a raster path → its
    :class:`LandRaster`, aligned to the scenario frame (:func:`harbour_alignment`). Both maps answer
    ``is_water(north, east)`` in the scenario frame."""
    if isinstance(spec, HarbourLayout | LandRaster):
        return spec
    if harbour_name(spec) == "default":
        return DEFAULT_LAYOUT
    path = harbour_file(spec)
    if path is None:
        return None
    raster = read_land_raster(path).aligned(harbour_alignment(spec))
    if harbour_name(spec) == "ravnkloa":
        raster = replace(raster, moored_boats=read_moored_boats(RAVNKLOA_MOORED))
    return raster


def read_moored_boats(path: str | Path) -> tuple[MooredBoat, ...]:
    """The ``moored_boats`` list of a YAML file (name, north, east, heading_deg, length, beam, height each)."""
    p = Path(path)
    data = load_yaml(p, "a moored-boats YAML file")
    rows = data.get("moored_boats") if isinstance(data, dict) else None
    if not isinstance(rows, list):
        raise InputError(p, "expected a mapping with a list 'moored_boats'")
    keys = [f.name for f in fields(MooredBoat)]
    out = []
    for i, row in enumerate(rows):
        if not isinstance(row, dict) or set(row) != set(keys):
            raise InputError(p, f"expected the keys {', '.join(keys)}", where=f"moored_boats[{i}]")
        try:
            out.append(MooredBoat(str(row["name"]), *(float(row[k]) for k in keys[1:])))
        except (TypeError, ValueError):
            raise InputError(p, "expected numbers for the position and size", where=f"moored_boats[{i}]") from None
    return tuple(out)


def harbour_moored_boats(spec: object) -> tuple[MooredBoat, ...]:
    """The moored boats of harbour ``spec`` in the scenario frame (a name, a raster, a layout, or a run's water-mask
    hint such as ``harbour``/``ravnkloa``); none for ``none``. Tracking comparisons treat them as don't-care regions."""
    m = harbour_map(spec)
    if m is None:
        return ()
    return m.moored_boats if isinstance(m, HarbourLayout) else m.moored()


def moored_boat_positions(spec: object) -> np.ndarray:
    """(n, 2) north, east [m] of the moored boats of harbour ``spec`` (:func:`harbour_moored_boats`)."""
    boats = harbour_moored_boats(spec)
    return np.array([[b.north, b.east] for b in boats], dtype=float).reshape(-1, 2)
