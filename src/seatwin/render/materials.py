"""Plausible colours per object label (linear RGB, 0–1), varied per object by its name.

Quays are concrete grey, piers weathered wood, buildings brick, ochre or white render; vessels
and moored boats take a hull colour from a small palette picked by a hash of their name, so the
same scenario always looks the same.
"""

from __future__ import annotations

import zlib

import numpy as np
from numpy.typing import NDArray

LABEL_COLOURS: dict[str, tuple[tuple[float, float, float], ...]] = {
    "quay": ((0.50, 0.50, 0.48), (0.46, 0.45, 0.43)),
    "pier": ((0.42, 0.33, 0.24), (0.36, 0.29, 0.22)),
    "building": ((0.62, 0.26, 0.18), (0.78, 0.62, 0.34), (0.85, 0.83, 0.78), (0.55, 0.22, 0.20), (0.33, 0.42, 0.50)),
    "moored_boat": ((0.90, 0.90, 0.88), (0.20, 0.30, 0.55), (0.70, 0.15, 0.12), (0.85, 0.75, 0.30)),
    "vessel": ((0.92, 0.92, 0.90), (0.80, 0.18, 0.12), (0.95, 0.70, 0.10), (0.15, 0.35, 0.70), (0.20, 0.55, 0.30)),
}
"""Palettes by label; an object picks one entry by the CRC-32 of its name."""

DEFAULT_COLOUR = (0.55, 0.55, 0.55)


def object_colour(label: str, name: str) -> NDArray[np.float32]:
    """The RGB colour of object ``name`` with ``label`` (deterministic)."""
    palette = LABEL_COLOURS.get(label)
    if not palette:
        return np.asarray(DEFAULT_COLOUR, np.float32)
    return np.asarray(palette[zlib.crc32(name.encode()) % len(palette)], np.float32)
