"""Vessel 3-D models generated in code from dimensions, and user meshes from files.

Body frame: x forward, y starboard, z down; origin at the vessel's reference point on the
calm waterline (the point a scenario trajectory gives), heights above water as ``z < 0``.

Dimensions and their sources (the thesis gives the exact figures only inside its figures
3.5 and 3.7, which are images; the text gives the rest):

* **milliAmpere** (thesis 3.2.1): NTNU's bidirectional autonomous passenger ferry, two
  azimuth thrusters, a roof over the deck and the EMR sensor rig on top of it (Fig. 3.6),
  GNSS antennas 2.03 m apart on the roof. Overall 5.0 m × 2.8 m (published size of the
  milliAmpere prototype); freeboard 0.55 m, roof at 2.1–2.3 m, rig mast to 2.85 m and the
  lidar's centre at 3.0 m above the water (assumed from the photos' proportions).
* **Havfruen** (thesis 3.2.2): a medium cabin cruiser with two GNSS rigs on its cabin
  roof 2.01 m apart (thesis 3.3.2). Modelled 8.0 m × 2.8 m, freeboard 1.0 m (bow 1.3 m),
  cabin roof 2.4 m, a small rig on the roof to 2.6 m (assumed typical of the class; the
  same nominal size as ``seatwin.scenario.defaults.NOMINAL_DIMENSIONS``).
* **Finn** (thesis 3.2.2): a small open fishing boat, GNSS units at bow and stern 2.93 m
  apart (thesis 3.3.2), so a hull of about 4.3 m (4.6 m overall with the outboard motor at
  the transom); beam 1.8 m, freeboard 0.65 m, a console to 1.2 m (assumed).
* **generic**: any :class:`~seatwin.scenario.model.Dimensions` (length, beam, height):
  a hull with a cabin over the middle 40 % reaching ``height``.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import trimesh

from seatwin.errors import InputError
from seatwin.geo.frames import FLU_TO_FRD, yaw_matrix
from seatwin.mesh_placement import MeshPlacement, is_mesh_path
from seatwin.world.shapes import block, hull, merge, prism

REFLECTIVITY = {
    "vessel": 0.55,
    "quay": 0.30,
    "pier": 0.25,
    "building": 0.35,
    "moored_boat": 0.50,
}
"""Default diffuse reflectivity (0–1) per object label: painted fibreglass / aluminium hulls
are brighter than concrete quays and timber piers."""


@dataclass(frozen=True)
class VesselModel:
    """A vessel's mesh in its body frame, with its reflectivity and nominal size."""

    name: str
    mesh: trimesh.Trimesh
    reflectivity: float = REFLECTIVITY["vessel"]

    @property
    def length(self) -> float:
        return float(np.ptp(self.mesh.vertices[:, 0]))

    @property
    def beam(self) -> float:
        return float(np.ptp(self.mesh.vertices[:, 1]))

    @property
    def height(self) -> float:
        """Highest point above the water."""
        return float(-self.mesh.vertices[:, 2].min())

    @property
    def radius(self) -> float:
        """Horizontal radius of the footprint about the body origin."""
        return float(np.hypot(self.mesh.vertices[:, 0], self.mesh.vertices[:, 1]).max())

    def outline(self) -> np.ndarray:
        """Closed horizontal outline (x forward, y starboard) of the footprint's convex hull."""
        from scipy.spatial import ConvexHull

        xy = self.mesh.vertices[:, :2]
        ring = xy[ConvexHull(xy).vertices]
        return np.vstack([ring, ring[:1]])


MILLIAMPERE_LIDAR_HEIGHT = 3.0
"""Height of the VLP-16's optical centre above the water on milliAmpere's rig [m] (assumed)."""


def milliampere() -> VesselModel:
    """The ownship milliAmpere (5.0 × 2.8 m, bidirectional, roof and sensor rig)."""
    parts = [hull(5.0, 2.8, 0.55, draft=0.45, bow=0.12, stern=0.12)]
    for x in (-1.7, 1.7):  # roof pillars
        for y in (-1.1, 1.1):
            parts.append(block(x - 0.05, x + 0.05, y - 0.05, y + 0.05, 2.1, 0.5))
    parts.append(block(-1.9, 1.9, -1.25, 1.25, 2.3, 2.1))  # roof
    parts.append(prism([(0.15, 0.15), (0.15, -0.15), (-0.15, 0.15), (-0.15, -0.15)], 2.7, 2.3))  # rig mast
    # Camera ring of the rig (5 cameras around the azimuth axis, Fig. 3.6), below the lidar.
    ring = [(0.28 * np.cos(a), 0.28 * np.sin(a)) for a in np.linspace(0, 2 * np.pi, 10, endpoint=False)]
    parts.append(prism(ring, 2.85, 2.7))
    return VesselModel("milliampere", merge(parts))


def havfruen() -> VesselModel:
    """Target Havfruen, a medium cabin cruiser (8.0 × 2.8 m)."""
    parts = [hull(8.0, 2.8, 1.0, draft=0.6, bow=0.3, stern=0.04, sheer=0.3)]
    parts.append(prism([(1.5, -1.0), (1.5, 1.0), (0.7, -1.1), (0.7, 1.1), (-1.9, -1.1), (-1.9, 1.1)], 2.4, 0.9))
    parts.append(block(-0.4, 0.4, -0.7, 0.7, 2.6, 2.4))  # GNSS rigs / rail on the roof
    return VesselModel("havfruen", merge(parts))


def finn() -> VesselModel:
    """Target Finn, a small open fishing boat (4.3 m hull, 4.6 m with the outboard, × 1.8 m)."""
    parts = [hull(4.3, 1.8, 0.65, draft=0.35, bow=0.3, stern=0.04, sheer=0.15)]
    parts.append(block(-0.6, -0.1, -0.3, 0.3, 1.2, 0.5))  # console
    parts.append(block(-2.45, -2.1, -0.2, 0.2, 1.05, -0.3))  # outboard motor
    return VesselModel("finn", merge(parts))


def generic(length: float = 6.0, beam: float = 2.4, height: float = 2.0, name: str = "generic") -> VesselModel:
    """A plain boat of the given overall size (hull plus a cabin over the middle 40 %)."""
    if min(length, beam, height) <= 0:
        raise ValueError(f"vessel dimensions must be positive, got {length} × {beam} × {height}")
    freeboard = min(0.45 * height, 1.0)
    parts = [hull(length, beam, freeboard, draft=0.1 * length, bow=0.25, stern=0.05)]
    if height > freeboard + 0.05:
        parts.append(block(-0.25 * length, 0.15 * length, -0.35 * beam, 0.35 * beam, height, freeboard * 0.8))
    return VesselModel(name, merge(parts))


BUILTIN_MODELS = {"milliampere": milliampere, "havfruen": havfruen, "finn": finn, "generic": generic}
_ALIASES = {"milli_ampere": "milliampere", "milli-ampere": "milliampere", "ownship": "milliampere", "": "generic"}


def load_mesh(
    path: str | Path,
    scale: float = 1.0,
    offset: tuple[float, float, float] = (0.0, 0.0, 0.0),
    yaw_deg: float = 0.0,
    z_up: bool = True,
) -> trimesh.Trimesh:
    """A user mesh (OBJ, STL, PLY, GLB, ...) in the body frame.

    The file is taken as x forward, y left, z up (``z_up``; the usual CAD / REP-103 frame)
    and turned into x forward, y starboard, z down; then scaled by ``scale``, turned by
    ``yaw_deg`` (clockwise seen from above) and moved by ``offset`` (body metres, z down).
    """
    p = Path(path)
    if not p.is_file():
        raise InputError(p, "mesh file not found")
    try:
        loaded = trimesh.load(p, force="mesh")
    except Exception as exc:  # trimesh raises many kinds
        raise InputError(p, f"cannot read mesh: {exc}") from exc
    if not isinstance(loaded, trimesh.Trimesh) or len(loaded.faces) == 0:
        raise InputError(p, "the file holds no triangles")
    mesh = loaded.copy()
    v = np.asarray(mesh.vertices, dtype=float) * float(scale)
    if z_up:
        v = v * np.diag(FLU_TO_FRD)  # z-up (x forward, y left) → z-down
    v = v @ yaw_matrix(np.radians(yaw_deg)).T + np.asarray(offset, dtype=float)
    # (y, z) → (−y, −z) is a half turn about x, not a mirror: the winding stays outward.
    return trimesh.Trimesh(v, np.asarray(mesh.faces), process=False)


def vessel_model(
    model: str, dimensions: object | None = None, source: str | None = None, mesh: MeshPlacement | None = None
) -> VesselModel:
    """The model named ``model`` (built-in name, case-insensitive) or loaded from a mesh file, placed in the body
    frame by ``mesh`` (:class:`~seatwin.scenario.model.MeshPlacement`: scale, yaw, offset, axes).

    ``generic`` (or an unknown-but-empty name) uses ``dimensions`` (length, beam, height) when given.
    """
    if mesh is not None and not is_mesh_path(model):
        raise InputError(source, f"mesh placement (scale, yaw, offset) given for model {model!r}, which is not a mesh file")
    key = _ALIASES.get(model.strip().lower(), model.strip().lower())
    if key == "generic":
        if dimensions is not None:
            d = dimensions
            return generic(float(d.length), float(d.beam), float(d.height))  # type: ignore[attr-defined]
        return generic()
    if key in BUILTIN_MODELS:
        return BUILTIN_MODELS[key]()
    if is_mesh_path(model):
        m = mesh or MeshPlacement()
        return VesselModel(Path(model).stem, load_mesh(model, m.scale, m.offset, m.yaw_deg, m.z_up))
    raise InputError(
        source,
        f"unknown vessel model {model!r}; expected one of {sorted(BUILTIN_MODELS)} or a mesh file (.obj/.stl/.ply/.glb)",
        where="model",
    )
