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
import errno
import json
import os
import shutil
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from seatwin.errors import InputError

MANIFEST_NAME = "manifest.json"
MANIFEST_VERSION = 1
RUN_SCENARIO_FILES = ("scenario.yaml", "scenario.csv")
"""The scenario a simulated run records beside its bag (the YAML and its Gemini CSV)."""


def write_manifest(run_dir: Path, data: dict[str, Any]) -> None:
    """Atomically write ``run_dir/manifest.json``. On a full disk, where even the small temporary file cannot be
    written, it is removed and the manifest is rewritten in place when the blocks it has hold the new text
    (a run that fails writes its error this way); otherwise the ``OSError`` is raised, the old manifest intact."""
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
    """Rewrite ``path`` in place, only when the blocks it has already hold ``data`` (no new space needed);
    otherwise an ``OSError`` and the file as it was."""
    if len(data) > path.stat().st_blocks * 512:
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(path))
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


def check_new_run(
    run_dir: str | os.PathLike[str],
    param: str,
    *,
    inputs: Iterable[str | os.PathLike[str] | None] = (),
    overwrite: bool = False,
    extra: Iterable[str] = (),
) -> list[Path]:
    """Refuse, before any work, a folder for a new run that is an input or inside one, or that exists and is
    not empty — unless ``overwrite``: then only an earlier run's entries (manifest, bag of any format, the
    scenario files, and ``extra``) are replaced, and only where a seatwin manifest shows seatwin wrote them.
    Returns the earlier entries to remove (:func:`seatwin.outputs.remove_outputs`) once the run's inputs are
    validated."""
    from seatwin.outputs import check_run_folder
    from seatwin.recording.storage import BAG_STEM

    names = (MANIFEST_NAME, MANIFEST_NAME + ".part", BAG_STEM, f"{BAG_STEM}.bag", *RUN_SCENARIO_FILES, *extra)
    return check_run_folder(run_dir, param, names, _is_seatwin_run, inputs=inputs, overwrite=overwrite)


def check_bag_output(target: Path, source: str | os.PathLike[str], overwrite: bool, param: str = "out") -> None:
    """For a command that writes a new run or bag ``target`` (its parameter ``param``) from ``source`` (repair,
    convert, track): refuse an output that is the input or inside it, or that exists (unless ``overwrite``: then
    an earlier seatwin run folder or a bag is removed), or that cannot be written."""
    from seatwin.outputs import OutputExistsError, check_writable, refuse_inputs

    refuse_inputs(target, param, [source])
    if not (target.exists() or target.is_symlink()):
        check_writable(target, param)
        return
    if not overwrite:
        raise OutputExistsError(param, target)
    if target.is_dir() and not target.is_symlink():
        if read_manifest(target) is None and not (target / "metadata.yaml").is_file():
            raise InputError(target, "exists and is not a seatwin run or a rosbag2 bag: not replaced; choose a new output")
        shutil.rmtree(target)
    else:
        target.unlink()


def _is_seatwin_run(run_dir: Path) -> bool:
    try:
        manifest = read_manifest(run_dir)
    except InputError:
        return False
    return manifest is not None and "manifest_version" in manifest


def _default(obj: Any) -> Any:
    if hasattr(obj, "tolist"):
        return obj.tolist()
    if isinstance(obj, Path):
        return str(obj)
    if hasattr(obj, "__dataclass_fields__"):
        from dataclasses import asdict

        return asdict(obj)
    return str(obj)
