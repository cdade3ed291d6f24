"""The ray-casting interface shared by every back end (imports no back end: :mod:`.backends` picks one)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike, NDArray


@dataclass(frozen=True)
class MeshData:
    """A triangle mesh: ``vertices`` float32 (V, 3), ``faces`` int32 (F, 3), one ``object_id``."""

    vertices: NDArray[np.float32]
    faces: NDArray[np.int32]
    object_id: int

    def __post_init__(self) -> None:
        v = np.ascontiguousarray(self.vertices, dtype=np.float32)
        f = np.ascontiguousarray(self.faces, dtype=np.int32)
        if v.ndim != 2 or v.shape[1] != 3 or f.ndim != 2 or f.shape[1] != 3:
            raise ValueError(f"mesh {self.object_id}: vertices must be (V, 3) and faces (F, 3), got {v.shape}, {f.shape}")
        if f.size and (f.min() < 0 or f.max() >= len(v)):
            raise ValueError(f"mesh {self.object_id}: face index out of range 0..{len(v) - 1}")
        object.__setattr__(self, "vertices", v)
        object.__setattr__(self, "faces", f)

    @classmethod
    def from_trimesh(cls, mesh: object, object_id: int) -> MeshData:
        """From a :class:`trimesh.Trimesh`."""
        return cls(np.asarray(mesh.vertices), np.asarray(mesh.faces), object_id)  # type: ignore[attr-defined]

    def transformed(self, rotation: ArrayLike, translation: ArrayLike) -> MeshData:
        """The mesh with vertices ``R @ v + t``."""
        r = np.asarray(rotation, dtype=np.float64)
        t = np.asarray(translation, dtype=np.float64)
        return MeshData((self.vertices.astype(np.float64) @ r.T + t).astype(np.float32), self.faces, self.object_id)

    @property
    def n_triangles(self) -> int:
        return int(len(self.faces))


@dataclass(frozen=True)
class RayHits:
    """Per-ray results: range [m] (inf = miss), object id (−1 = miss), surface normal.

    ``geometric_normal`` is the hit triangle's normal of any length (zero on a miss), as
    back ends produce it; :attr:`normal` is it at unit length (computed on access, so
    callers that need normals of a few hits only pay for those).
    """

    range: NDArray[np.float32]
    object_id: NDArray[np.int32]
    geometric_normal: NDArray[np.float32]

    @property
    def hit(self) -> NDArray[np.bool_]:
        return self.object_id >= 0

    @property
    def normal(self) -> NDArray[np.float32]:
        """Unit normals (N, 3), zero on a miss."""
        return unit_rows(self.geometric_normal)

    def __len__(self) -> int:
        return int(self.range.shape[0])


def unit_rows(v: NDArray[np.float32]) -> NDArray[np.float32]:
    """Rows of ``v`` scaled to unit length (zero rows stay zero)."""
    v = np.asarray(v, dtype=np.float32)
    norm = np.sqrt(v[:, 0] * v[:, 0] + v[:, 1] * v[:, 1] + v[:, 2] * v[:, 2])
    norm[norm == 0] = 1.0
    return v / norm[:, None]


@runtime_checkable
class RayCaster(Protocol):
    """Casts rays against static triangle meshes (the frame of the meshes is the frame of the rays)."""

    def cast(self, origins: ArrayLike, directions: ArrayLike, max_range: ArrayLike = np.inf) -> RayHits:
        """Nearest hit along each ray within ``max_range`` (a scalar or one value per ray);
        ``directions`` must be unit vectors. Normals are the triangles' geometric normals
        (outward for consistently wound closed meshes), unit length."""
        ...
