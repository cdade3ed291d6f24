"""Command-line helpers shared by the verbs: list options, the ``--overwrite`` option, progress (the output-path
rules themselves are the library's, :mod:`seatwin.outputs`)."""

from __future__ import annotations

import contextlib
import sys
import time
from collections.abc import Callable, Iterator, Sequence
from typing import Any

from seatwin.errors import ParameterError


def split_list(text: str | None, param: str) -> tuple[str, ...] | None:
    """``"lidar,radar"`` → ``("lidar", "radar")``; None stays None; an empty list is an error naming ``param``."""
    if text is None:
        return None
    parts = tuple(p.strip() for p in text.split(",") if p.strip())
    if not parts:
        raise ParameterError(param, f"expected a comma-separated list, got {text!r}")
    return parts


def text_table(header: Sequence[str], rows: Sequence[Sequence[str]], left: int = 1, title: str | None = None) -> str:
    """A plain-text table wide enough for every cell (never cut, whatever the terminal's width): the first ``left``
    columns left-aligned, the others right-aligned, under an optional ``title``."""
    widths = [max(len(str(c)) for c in col) for col in zip(header, *rows, strict=True)]

    def line(cells: Sequence[str]) -> str:
        return "  ".join(str(c).ljust(w) if i < left else str(c).rjust(w) for i, (c, w) in enumerate(zip(cells, widths))).rstrip()

    body = [line(header), "  ".join("-" * w for w in widths), *(line(r) for r in rows)]
    return "\n".join(([title] if title else []) + body)


def overwrite_option() -> Any:
    """``--overwrite``, the one flag of every verb that writes: replace outputs that exist already."""
    import typer

    return typer.Option(
        False, "--overwrite", help="Replace outputs that exist already (never an input, never a file seatwin did not write)."
    )


COMPRESSION_HELP = (
    "Compression of the bag: mcap chunks lz4 (default), zstd (level 1) or none; ros1 chunks lz4 (default), bz2 or none; "
    "sqlite3 none (default), zstd (rosbag2's per-message zstd) or zstd-file (the whole .db3 as .db3.zstd). "
    "Every reader (seatwin, rosbags, mcap, ROS tools) reads them."
)


def compression_option() -> Any:
    """``--compression lz4|zstd|zstd-file|bz2|none`` of every verb that writes a bag (default: the format's own)."""
    import typer

    return typer.Option(None, "--compression", metavar="lz4|zstd|zstd-file|bz2|none", help=COMPRESSION_HELP)


def image_format_option() -> Any:
    """``--image-format raw|jpeg|png`` of every verb that records camera images."""
    import typer

    from seatwin.defaults import DEFAULT_IMAGE_FORMAT, JPEG_QUALITY

    return typer.Option(
        DEFAULT_IMAGE_FORMAT,
        "--image-format",
        metavar="raw|jpeg|png",
        help="Camera images as sensor_msgs/Image bgr8 (raw, as the thesis records them) or sensor_msgs/CompressedImage "
        f"(jpeg, quality {JPEG_QUALITY}, or png) on <image topic>/compressed, as image_transport names it.",
    )


@contextlib.contextmanager
def progress_counter(
    what: str, enabled: bool = True, min_total: int = 200, every_s: float = 10.0
) -> Iterator[Callable[[int, int], None]]:
    """``advance(done, total)``: a rich bar on a terminal; on a pipe or log a line every ``every_s`` seconds."""
    if not enabled:
        yield lambda done, total: None
        return
    if sys.stderr.isatty():
        from rich.console import Console
        from rich.progress import Progress

        bar = Progress(console=Console(stderr=True), transient=True)
        task = None
        with bar:

            def advance(done: int, total: int) -> None:
                nonlocal task
                if total < min_total:
                    return
                if task is None:
                    task = bar.add_task(what, total=total)
                bar.update(task, completed=done)

            yield advance
        return
    last = time.monotonic()

    def log(done: int, total: int) -> None:
        nonlocal last
        now = time.monotonic()
        if now - last >= every_s or done == total and total >= min_total:
            last = now
            print(f"{what}: {done}/{total}", file=sys.stderr, flush=True)

    yield log
