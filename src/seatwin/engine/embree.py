"""Exact CPU ray casting with Embree (``embreex``), batches split over a thread pool.

``embreex``'s ``EmbreeScene.run`` releases the GIL while Embree traverses (measured: a
Python thread keeps running during a cast), so chunks of one batch run on all cores. Each
worker also does its own post-processing (miss → inf, geometry → object id, normal
normalisation: numpy ufuncs release the GIL too) and writes into slices of preallocated
outputs, so a multithreaded cast returns exactly the single-threaded result.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Sequence
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from numpy.typing import ArrayLike

from seatwin.engine.base import MeshData, RayHits

MIN_CHUNK = 4096
"""Rays per thread chunk below which splitting does not pay."""

_POOL: ThreadPoolExecutor | None = None
_POOL_LOCK = threading.Lock()


def default_threads() -> int:
    """Worker threads: ``SEATWIN_THREADS`` or the number of usable cores."""
    env = os.environ.get("SEATWIN_THREADS")
    if env:
        return max(1, int(env))
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def _pool(n: int) -> ThreadPoolExecutor:
    global _POOL
    with _POOL_LOCK:
        if _POOL is None or _POOL._max_workers < n:  # noqa: SLF001
            _POOL = ThreadPoolExecutor(max_workers=n, thread_name_prefix="seatwin-embree")
        return _POOL


class EmbreeCaster:
    """A committed Embree scene over static meshes; :meth:`cast` is thread-safe."""

    def __init__(self, meshes: Sequence[MeshData], threads: int | None = None):
        from embreex.mesh_construction import TriangleMesh
        from embreex.rtcore_scene import EmbreeScene

        self.threads = default_threads() if threads is None else max(1, int(threads))
        self.meshes = [m for m in meshes if m.n_triangles]
        ids = [m.object_id for m in self.meshes]
        # geomID -> object id; index -1 (miss) maps to the last entry, -1.
        self._ids = np.asarray([*ids, -1], dtype=np.int32)
        self._identity_ids = ids == list(range(len(ids)))
        self._scene = EmbreeScene() if self.meshes else None
        self._keep = []
        for m in self.meshes:
            self._keep.append(TriangleMesh(self._scene, m.vertices, m.faces))
        if self._scene is not None:
            # Embree builds its BVH on the first query; do it now, not inside a timed cast.
            self._scene.run(np.zeros((1, 3), np.float32), np.float32([[0.0, 0.0, 1.0]]), output=1)

    @property
    def n_triangles(self) -> int:
        return sum(m.n_triangles for m in self.meshes)

    def cast(self, origins: ArrayLike, directions: ArrayLike, max_range: ArrayLike = np.inf) -> RayHits:
        """Nearest hit of each ray (unit ``directions``) within ``max_range`` (scalar or per ray)."""
        o = np.ascontiguousarray(origins, dtype=np.float32).reshape(-1, 3)
        d = np.ascontiguousarray(directions, dtype=np.float32).reshape(-1, 3)
        if o.shape != d.shape:
            raise ValueError(f"origins {o.shape} and directions {d.shape} differ in shape")
        n = len(o)
        if n == 0 or self._scene is None:
            return RayHits(np.full(n, np.inf, np.float32), np.full(n, -1, np.int32), np.zeros((n, 3), np.float32))
        # Embree writes each hit's distance into the ``dists`` it is given: hand it slices
        # of the output range array, filled with the limits, so no copy is needed afterwards.
        if np.ndim(max_range) > 0:
            rng = np.array(max_range, dtype=np.float32).reshape(-1)
            if rng.shape != (n,):
                raise ValueError(f"max_range has {rng.shape[0]} values for {n} rays")
        else:
            rng = np.full(n, min(float(max_range), 3e38), np.float32)
        k = min(self.threads, max(1, n // MIN_CHUNK))

        def run(a: int, b: int) -> tuple[np.ndarray, np.ndarray]:
            res = self._scene.run(o[a:b], d[a:b], dists=rng[a:b], output=1)
            if res["tfar"].base is not rng:
                rng[a:b] = res["tfar"]  # a wrapper that copied ``dists``
            geom = res["geomID"]
            np.copyto(rng[a:b], np.float32(np.inf), where=geom < 0)
            return (geom if self._identity_ids else self._ids[geom]), res["Ng"]

        if k == 1:
            oid, nrm = run(0, n)
            return RayHits(rng, oid, nrm)
        oid = np.empty(n, np.int32)
        nrm = np.empty((n, 3), np.float32)
        bounds = np.linspace(0, n, k + 1).astype(int)

        def work(j: int) -> None:
            a, b = int(bounds[j]), int(bounds[j + 1])
            oid[a:b], nrm[a:b] = run(a, b)

        # The calling thread takes the first chunk itself (one thread hand-off fewer).
        futures = [_pool(self.threads).submit(work, j) for j in range(1, k)]
        work(0)
        for f in futures:
            f.result()
        return RayHits(rng, oid, nrm)
