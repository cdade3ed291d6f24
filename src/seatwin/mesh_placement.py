"""A vessel's mesh file and how it sits in the body frame: data that both :mod:`seatwin.scenario` (which reads it
from a scenario YAML) and :mod:`seatwin.world` (which loads the mesh) use, so it lives below both."""

from __future__ import annotations

from dataclasses import dataclass

MESH_SUFFIXES = (".obj", ".stl", ".ply", ".glb", ".gltf", ".off")
"""File endings of a vessel ``model`` that is a mesh file (anything else is a built-in model's name)."""


def is_mesh_path(model: str) -> bool:
    """True when a vessel ``model`` names a mesh file (by its ending, :data:`MESH_SUFFIXES`)."""
    return model.strip().lower().endswith(MESH_SUFFIXES)


@dataclass(frozen=True)
class MeshPlacement:
    """How a vessel's mesh file sits in its body frame: the file's axes (``z_up``: x forward, y left, z up, the usual
    CAD frame; else already x forward, y starboard, z down), then ``scale`` (file units → metres), ``yaw_deg`` (turned
    clockwise seen from above, so the bow points along +x) and ``offset`` (forward, starboard, down [m] in
    the body frame: put the reference point, the one the trajectory gives, on the waterline)."""

    scale: float = 1.0
    yaw_deg: float = 0.0
    offset: tuple[float, float, float] = (0.0, 0.0, 0.0)
    z_up: bool = True
