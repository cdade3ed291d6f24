"""Pick a ray-casting back end by name (the one place that knows the back ends)."""

from __future__ import annotations

from collections.abc import Sequence

from seatwin.engine.base import MeshData, RayCaster

BACKENDS = ("embree",)
"""Known back ends."""


def make_caster(meshes: Sequence[MeshData], backend: str = "embree", threads: int | None = None) -> RayCaster:
    """A caster over ``meshes`` with the named back end (``"embree"``)."""
    if backend == "embree":
        from seatwin.engine.embree import EmbreeCaster

        return EmbreeCaster(meshes, threads=threads)
    raise ValueError(f"unknown ray-casting back end {backend!r}; known: {', '.join(map(repr, BACKENDS))}")
