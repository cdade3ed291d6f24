"""Labelled world objects: a mesh with a name, a label and a reflectivity."""

from __future__ import annotations

from dataclasses import dataclass

import trimesh


@dataclass(frozen=True)
class WorldObject:
    """One static object of the world (world frame NED, z down) or one vessel (its body frame)."""

    name: str
    label: str
    """Class of object: ``vessel``, ``quay``, ``pier``, ``building``, ``moored_boat``."""
    mesh: trimesh.Trimesh
    reflectivity: float
