"""The run manifest (``manifest.json`` beside the bag): what was recorded and whether the run completed.

Written when the recording opens (``completed: false``), refreshed at every flush and rewritten
with ``completed: true`` on a clean close. Each write goes to a temporary file that is renamed, so
the manifest is never half-written; a run killed before its first flush may have none — both
mean *incomplete*. When the disk is full, the temporary file cannot be written: the manifest is
then rewritten in place, compact (no indentation, so it fits in the blocks the last one used), so a
run that failed still says why.
"""

from __future__ import annotations

import contextlib
import json
import os
from pathlib import Path
from typing import Any

from seatwin.errors import InputError

MANIFEST_NAME = "manifest.json"
MANIFEST_VERSION = 1


def write_manifest(run_dir: Path, data: dict[str, Any]) -> None:
    """Atomically write ``run_dir/manifest.json``."""
    path = Path(run_dir) / MANIFEST_NAME
    tmp = path.with_name(path.name + ".part")
    try:
        tmp.write_text(json.dumps(data, indent=2, sort_keys=False, default=_default) + "\n", encoding="utf8")
        os.replace(tmp, path)
    except OSError:
        with contextlib.suppress(OSError):
            tmp.unlink()  # a full disk leaves it empty or cut: never leave it behind
        if not path.is_file():
            raise
        try:
            _overwrite(path, (json.dumps(data, separators=(",", ":"), default=_default) + "\n").encode("utf8"))
        except OSError:
            pass
        else:
            return
        raise


def _overwrite(path: Path, data: bytes) -> None:
    """Rewrite ``path`` in place (its blocks reused: no new space needed when ``data`` is not longer)."""
    with path.open("r+b") as f:
        f.write(data)
        f.truncate(len(data))


def read_manifest(run_dir: Path) -> dict[str, Any] | None:
    """The manifest of a run directory, or None when there is none."""
    path = Path(run_dir) / MANIFEST_NAME
    if not path.is_file():
        return None
    try:
        data = json.loads(path.read_text(encoding="utf8"))
    except (OSError, ValueError) as exc:
        raise InputError(path, f"not a readable JSON manifest: {exc}") from None
    if not isinstance(data, dict):
        raise InputError(path, "expected a JSON object")
    return data


def _default(obj: Any) -> Any:
    if hasattr(obj, "tolist"):
        return obj.tolist()
    if isinstance(obj, Path):
        return str(obj)
    if hasattr(obj, "__dataclass_fields__"):
        from dataclasses import asdict

        return asdict(obj)
    return str(obj)
