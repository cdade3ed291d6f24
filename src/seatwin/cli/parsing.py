"""Command-line value syntax → typed library values; errors name the flag the user typed.

The library takes typed values (:class:`~seatwin.geo.GeodeticOrigin`,
:class:`~seatwin.groundtruth.VesselSpec`); only the CLI knows ``LAT,LON[,HEIGHT]`` or
``NAME=BOW,STERN[,BASELINE_M]``. Light to import: the library types load when a parser runs.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

from seatwin.errors import InputError

if TYPE_CHECKING:
    from seatwin.geo import GeodeticOrigin
    from seatwin.groundtruth.vessel import VesselSpec


def parse_origin(text: str, flag: str = "--origin") -> GeodeticOrigin:
    """``LAT,LON[,HEIGHT]`` (degrees, metres) → a :class:`GeodeticOrigin`."""
    from seatwin.geo import GeodeticOrigin

    parts = [p.strip() for p in text.split(",")]
    if len(parts) not in (2, 3):
        raise InputError(flag, f"expected LAT,LON[,HEIGHT], got {text!r}")
    try:
        values = [float(p) for p in parts]
    except ValueError:
        raise InputError(flag, f"expected numbers LAT,LON[,HEIGHT], got {text!r}") from None
    try:
        return GeodeticOrigin(*values)
    except ValueError as exc:
        raise InputError(flag, str(exc)) from None


def parse_vessel(text: str, flag: str = "--vessel") -> VesselSpec:
    """``NAME=BOW,STERN[,BASELINE_M]`` or ``NAME=FILE`` → a :class:`VesselSpec`."""
    from seatwin.groundtruth.vessel import VesselSpec

    syntax = f"expected NAME=BOW,STERN[,BASELINE_M] or NAME=FILE, got {text!r}"
    name, sep, rest = text.partition("=")
    name = name.strip()
    if not sep or not name or not rest.strip():
        raise InputError(flag, syntax)
    parts = [p.strip() for p in rest.split(",")]
    if any(not p for p in parts) or len(parts) > 3:
        raise InputError(flag, syntax)
    baseline = None
    if len(parts) == 3:
        try:
            baseline = float(parts[2])
        except ValueError:
            raise InputError(flag, f"baseline must be a number of metres, got {parts[2]!r} in {text!r}") from None
        if not math.isfinite(baseline) or baseline <= 0:
            raise InputError(flag, f"baseline must be a positive number of metres, got {parts[2]!r} in {text!r}")
    return VesselSpec(name, tuple(Path(p) for p in parts[:2]), baseline)
