"""Output paths, checked before any work: never an input, never an existing file unless overwriting is
allowed, writable; and files written through a temporary file that is renamed, so a failed or
refused command leaves nothing half-written.

The one place for these rules: every use-case that writes (pipeline, campaign, sweep, fidelity …)
calls :func:`check_output_file`, :func:`check_output_folder` or :func:`check_run_folder` with its
inputs before it starts, and :func:`atomic_output` / :func:`write_text_atomic` when it writes.
Errors name the library parameter (``out``); the CLI shows the flag.
"""

from __future__ import annotations

import contextlib
import itertools
import os
import secrets
import shutil
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path

from seatwin.errors import ParameterError

PathLike = str | os.PathLike[str]
_counter = itertools.count()


class OutputExistsError(ParameterError):
    """An output ``path`` exists and overwriting was not allowed (the CLI adds how to allow it)."""

    def __init__(self, param: str, path: PathLike, what: str = "exists already"):
        self.path = Path(path)
        super().__init__(param, f"{path} {what}, not replaced")


def _real(path: PathLike) -> Path:
    return Path(os.path.realpath(path))


def _input_folders(inp: Path) -> list[Path]:
    """The folders an input occupies: itself if a folder, and the run or rosbag2 folder a bag file lies in."""
    real = _real(inp)
    if os.path.isdir(real):
        return [real]
    out = []
    for parent in list(real.parents)[:2]:
        if any(os.path.lexists(parent / n) for n in ("manifest.json", "metadata.yaml")):
            out.append(parent)
    return out


def refuse_inputs(path: PathLike, param: str, inputs: Iterable[PathLike | None]) -> None:
    """Refuse an output ``path`` that is an input (the same file, after symlinks and hard links) or lies
    inside an input's folder (a run or bag folder): one error naming both."""
    out = _real(path)
    for inp in inputs:
        if inp is None or not os.path.lexists(inp):
            continue
        real = _real(inp)
        if out == real or (os.path.lexists(out) and _same_file(out, real)):
            raise ParameterError(param, f"{path} is the input {inp}; an output never replaces an input")
        for folder in _input_folders(Path(inp)):
            if out == folder or out.is_relative_to(folder):
                where = f"the input {inp}" if folder == real else f"{folder}, the run or bag folder of the input {inp}"
                verb = "is" if out == folder else "lies inside"
                raise ParameterError(param, f"{path} {verb} {where}; write outputs outside it")


def _same_file(a: Path, b: Path) -> bool:
    try:
        return os.path.samefile(a, b)
    except OSError:
        return False


def _first_existing(path: Path) -> tuple[Path, list[str]]:
    """The nearest existing ancestor of ``path`` (or itself) and the names below it still to be made."""
    missing: list[str] = []
    here = Path(os.path.abspath(path))
    while not os.path.lexists(here) and here != here.parent:
        missing.insert(0, here.name)
        here = here.parent
    return here, missing


def probe_folder(folder: Path) -> None:
    """Create and remove a file in ``folder``: an ``OSError`` if nothing can be written there."""
    probe = folder / f".seatwin-probe-{os.getpid()}-{secrets.token_hex(4)}"
    fd = os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    os.close(fd)
    os.unlink(probe)


def check_writable(path: PathLike, param: str) -> None:
    """Refuse, writing nothing, a ``path`` that cannot be created: a name longer than the file system
    allows, a folder on the way that is a file, or a folder that cannot be written (read-only, no permission).
    Folders still missing on the way are fine (they are made when writing)."""
    path = Path(path)
    base, missing = _first_existing(path)
    if missing and not os.path.isdir(base):
        raise ParameterError(param, f"cannot write {path}: {base} is not a folder")
    if not missing:  # the path itself exists: write into its folder
        base = base.parent
    try:
        name_max = os.pathconf(base, "PC_NAME_MAX")
        path_max = os.pathconf(base, "PC_PATH_MAX")
    except (OSError, ValueError):
        name_max, path_max = 255, 4096
    for name in [*missing, path.name]:
        if len(os.fsencode(name)) > name_max:
            shown = str(path) if len(str(path)) <= 100 else f"{str(path)[:60]}…{str(path)[-20:]}"
            raise ParameterError(
                param, f"cannot write {shown}: a name of {len(os.fsencode(name))} bytes, longer than the {name_max} allowed"
            )
    if len(os.fsencode(os.path.abspath(path))) >= path_max:
        raise ParameterError(param, f"cannot write {path}: the path is longer than the {path_max} bytes allowed")
    try:
        probe_folder(base)
    except OSError as exc:
        raise ParameterError(param, f"cannot write {path}: {base}: {exc.strerror or exc}") from None


def refuse_same(path: PathLike, param: str, others: Iterable[PathLike | None]) -> None:
    """Refuse an output ``path`` that is another output of the same command (one would replace the other)."""
    real = _real(path)
    for other in others:
        if other is not None and _real(other) == real:
            raise ParameterError(param, f"{path} is given twice as an output (also as {other})")


def check_output_file(
    path: PathLike,
    param: str,
    *,
    inputs: Iterable[PathLike | None] = (),
    overwrite: bool = False,
    outputs: Iterable[PathLike | None] = (),
) -> Path:
    """Refuse, before any work, an output file that is an input or inside one, another of the command's
    ``outputs``, a folder, one that exists (unless ``overwrite``) or cannot be written."""
    path = Path(path)
    refuse_inputs(path, param, inputs)
    refuse_same(path, param, outputs)
    if os.path.isdir(path):
        raise ParameterError(param, f"{path} is a folder; expected a file name")
    if os.path.lexists(path) and not overwrite:
        raise OutputExistsError(param, path)
    check_writable(path, param)
    return path


def check_output_folder(
    path: PathLike,
    param: str,
    names: Iterable[str],
    *,
    inputs: Iterable[PathLike | None] = (),
    overwrite: bool = False,
) -> list[Path]:
    """Refuse, before any work, an output folder that is an input or inside one, or a file; one holding
    any of the entries ``names`` the command writes there, unless ``overwrite``; or one that cannot be
    written. Other entries of the folder are never touched. Returns the entries of ``names`` that exist."""
    path = Path(path)
    inputs = [i for i in inputs if i is not None]
    refuse_inputs(path, param, inputs)
    if os.path.lexists(path) and not os.path.isdir(path):
        raise ParameterError(param, f"{path} exists and is not a folder")
    present = [path / n for n in names if os.path.lexists(path / n)]
    for inp in inputs:
        for entry in present:
            real, target = _real(inp), _real(entry)
            if real == target or real.is_relative_to(target):
                raise ParameterError(param, f"{entry} would replace the input {inp}")
    if present and not overwrite:
        raise OutputExistsError(param, present[0])
    check_writable(path / ".seatwin", param)
    return present


def check_run_folder(
    path: PathLike,
    param: str,
    names: Iterable[str],
    ours: Callable[[Path], bool],
    *,
    inputs: Iterable[PathLike | None] = (),
    overwrite: bool = False,
) -> list[Path]:
    """Refuse, before any work, a folder for a new run that exists and is not empty, unless ``overwrite``:
    then only the entries ``names`` are replaced, and only when ``ours(path)`` says seatwin wrote the run
    there — a user's file of the same name is never replaced. Returns the entries to remove first."""
    path = Path(path)
    if os.path.isdir(path) and not overwrite:
        with os.scandir(path) as entries:
            if any(entries):
                raise OutputExistsError(param, path, "exists and is not empty")
    present = check_output_folder(path, param, names, inputs=inputs, overwrite=True)
    if present and not ours(path):
        raise ParameterError(param, f"{present[0]} was not written by seatwin (no run of seatwin in {path}); not replaced")
    return present


def remove_outputs(paths: Iterable[Path]) -> None:
    """Remove earlier outputs (files or folders) that a run replaces."""
    for p in paths:
        if os.path.isdir(p) and not os.path.islink(p):
            shutil.rmtree(p)
        else:
            Path(p).unlink(missing_ok=True)


@contextlib.contextmanager
def atomic_output(path: PathLike) -> Iterator[Path]:
    """A fresh temporary path beside ``path`` (not yet created) to write the output to; renamed onto ``path``
    when the block ends normally, removed when it raises — never a half-written ``path``."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    suffix = path.suffix if len(path.suffix) <= 16 else ""  # kept: some writers pick the format by it
    tmp = path.parent / f".seatwin-{os.getpid()}-{next(_counter)}-{secrets.token_hex(3)}.part{suffix}"
    try:
        yield tmp
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            if os.path.isdir(tmp):
                shutil.rmtree(tmp)
            else:
                tmp.unlink(missing_ok=True)
        raise


def write_text_atomic(path: PathLike, text: str, encoding: str = "utf-8") -> None:
    """Write ``text`` to ``path`` through a temporary file that is renamed (:func:`atomic_output`)."""
    with atomic_output(path) as tmp:
        tmp.write_text(text, encoding=encoding)


def write_bytes_atomic(path: PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` through a temporary file that is renamed (:func:`atomic_output`)."""
    with atomic_output(path) as tmp:
        tmp.write_bytes(data)
