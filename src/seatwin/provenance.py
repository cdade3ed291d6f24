"""Which code produced a result: a fingerprint of the installed seatwin package's own files.

A cached result (a campaign's job file) is reused only if the code that made it is the code running
now, and a Ray worker on another node must run the driver's code: the package version alone does
not say so while the source is being edited (an editable install keeps its version).
"""

from __future__ import annotations

import hashlib
from functools import lru_cache
from pathlib import Path

import seatwin

FINGERPRINT_LENGTH = 16


@lru_cache(maxsize=1)
def code_fingerprint() -> str:
    """First 16 hex digits of the SHA-256 over every file of the seatwin package (sorted relative path and
    bytes; compiled ``__pycache__`` files excluded): equal exactly when the package's source is."""
    root = Path(seatwin.__file__).resolve().parent
    h = hashlib.sha256()
    files = sorted(p for p in root.rglob("*") if p.is_file() and "__pycache__" not in p.parts)
    for path in files:
        rel = path.relative_to(root).as_posix().encode()
        data = path.read_bytes()
        h.update(len(rel).to_bytes(4, "little") + rel + len(data).to_bytes(8, "little") + data)
    return h.hexdigest()[:FINGERPRINT_LENGTH]
