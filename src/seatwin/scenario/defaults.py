"""Defaults shared by the scenario readers and the built-ins: origin, vessel names, models, sizes."""

from __future__ import annotations

from seatwin.geo import GeodeticOrigin
from seatwin.scenario.model import Dimensions

RAVNKLOA = GeodeticOrigin(63.4336, 10.3926, 0.0)
"""Approximate geodetic position of Ravnkloa, Trondheim (the thesis location): the origin of a
scenario that gives none (the Gemini CSVs are in a local frame around Ravnkloa)."""

OWNSHIP_NAME, OWNSHIP_MODEL = "milliAmpere", "milliampere"
TARGETS_BY_COLUMN: dict[int, tuple[str, str]] = {1: ("Havfruen", "havfruen"), 2: ("Finn", "finn")}
"""Names and 3-D models of the Gemini CSV's target columns V1 and V2 (the thesis's target boats)."""

NOMINAL_DIMENSIONS: dict[str, Dimensions] = {
    "milliampere": Dimensions(length=5.0, beam=2.8, height=2.6),
    "havfruen": Dimensions(length=8.0, beam=2.8, height=2.6),
    "finn": Dimensions(length=4.6, beam=1.8, height=1.2),
}
"""Nominal overall sizes [m] of the thesis vessels (milliAmpere about 5 × 2.8 m; Havfruen a cabin
cruiser, Finn a small fishing boat), set on the built-ins and on vessels read from a Gemini CSV."""


def model_of_name(name: str) -> tuple[str, Dimensions | None]:
    """The 3-D model and nominal size of a vessel known by ``name`` (case ignored: ``Finn`` → ``finn``), else
    ``("generic", None)``."""
    key = name.lower()
    return (key, NOMINAL_DIMENSIONS[key]) if key in NOMINAL_DIMENSIONS else ("generic", None)
