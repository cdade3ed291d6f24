"""Ray casting back ends: triangle meshes in, per-ray range / object id / surface normal out.

The interface is deliberately narrow so that a GPU back end (e.g. Warp) can be added:

* :class:`MeshData` — one triangle mesh (float32 vertices, int32 faces) with an object id.
* :class:`RayHits` — per ray: ``range`` float32 (``inf`` on a miss), ``object_id`` int32
  (−1 on a miss), ``normal`` float32 (N, 3) unit geometric normal in the rays' frame
  (zero on a miss).
* :class:`RayCaster` — ``cast(origins, directions, max_range=inf) -> RayHits``.
* :func:`make_caster` — build a caster over meshes with a named back end (``"embree"``).
"""

from seatwin.engine.backends import make_caster
from seatwin.engine.base import MeshData, RayCaster, RayHits
from seatwin.engine.embree import EmbreeCaster

__all__ = ["EmbreeCaster", "MeshData", "RayCaster", "RayHits", "make_caster"]
