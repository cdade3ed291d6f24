"""Counter-based random numbers keyed by (seed, stream, frame).

Every random draw in seatwin (ray drop, noise, clutter) comes from a Philox generator
whose key is derived from the scenario seed and a stream name, and whose counter starts at
the frame index. A frame's draws therefore do not depend on which frames were computed
before it or on which worker computed it: runs are bit-identical however parallelised.
"""

from __future__ import annotations

import hashlib

import numpy as np


def stream_key(seed: int, stream: str) -> int:
    """A 64-bit key for ``stream`` (e.g. ``"lidar/drop"``) under ``seed``, stable across runs and platforms."""
    digest = hashlib.blake2b(f"{int(seed)}/{stream}".encode(), digest_size=8).digest()
    return int.from_bytes(digest, "little")


def frame_rng(seed: int, stream: str, frame: int) -> np.random.Generator:
    """The generator for one ``frame`` of one ``stream``: independent of every other frame and stream."""
    if frame < 0:
        raise ValueError(f"frame index must be non-negative, got {frame}")
    bits = np.random.Philox(key=stream_key(seed, stream), counter=[0, 0, int(frame), 0])
    return np.random.Generator(bits)
