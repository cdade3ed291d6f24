"""Ctrl-C and SIGTERM, one way everywhere: both stop a run the same way, never in the middle of a frame.

SIGTERM is what ``timeout``, ``docker stop``, systemd and Ray send; seatwin treats it as Ctrl-C.

* :func:`interrupts_raise` (the CLI wraps every verb in it; :func:`seatwin.sim.loop.simulate`
  too): SIGINT and SIGTERM raise :class:`Interrupted`, a :class:`KeyboardInterrupt`, so every
  ``except KeyboardInterrupt`` path finishes the run as on Ctrl-C;
* :func:`deferred_interrupts`: a signal arriving inside it is raised when the block ends — a frame's
  messages are written all or none;
* :func:`interrupts_set_event` (servers): the signal only sets an event the main thread waits on.

Handlers can be installed only in the main thread; elsewhere these are no-ops (the signal then
reaches whatever the main thread installed).
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Callable, Iterator
from types import FrameType

SIGNALS = (signal.SIGINT, signal.SIGTERM)


class Interrupted(KeyboardInterrupt):
    """Ctrl-C or SIGTERM, as a :class:`KeyboardInterrupt`; ``str()`` says which (``Ctrl-C``, ``SIGTERM``)."""

    def __init__(self, signum: int = signal.SIGINT) -> None:
        super().__init__(signal_label(signum))
        self.signum = signum


def signal_label(signum: int) -> str:
    """``Ctrl-C`` for SIGINT, else the signal's name (``SIGTERM``)."""
    return "Ctrl-C" if signum == signal.SIGINT else signal.Signals(signum).name


class _Deferral:
    depth = 0
    pending: int | None = None
    discard = 0
    raised: int | None = None
    """The last signal raised as :class:`Interrupted` (for :func:`interrupts_raise`'s caller)."""


_state = _Deferral()


def _raise(signum: int, frame: FrameType | None) -> None:
    if _state.depth:
        if not _state.discard and _state.pending is None:
            _state.pending = signum
        return
    _state.raised = signum
    raise Interrupted(signum)


_MAIN = threading.main_thread()


def _in_main_thread() -> bool:
    return threading.current_thread() is _MAIN


@contextlib.contextmanager
def _installed(handler: Callable[[int, FrameType | None], None]) -> Iterator[None]:
    if not _in_main_thread():
        yield
        return
    previous = {s: signal.signal(s, handler) for s in SIGNALS}
    try:
        yield
    finally:
        for s, h in previous.items():
            signal.signal(s, h)


@contextlib.contextmanager
def interrupts_raise() -> Iterator[Callable[[], int | None]]:
    """Inside: SIGINT and SIGTERM raise :class:`Interrupted` (deferred inside :func:`deferred_interrupts`);
    the previous handlers are restored on leaving. Yields ``raised()``: the signal raised since entering,
    if any (for a caller whose callee caught the exception, as typer does)."""
    before, _state.raised = _state.raised, None
    try:
        with _installed(_raise):
            yield lambda: _state.raised
    finally:
        if _state.raised is None:
            _state.raised = before


@contextlib.contextmanager
def sigterm_kept() -> Iterator[None]:
    """Put back the SIGTERM handler a library call inside replaced (``ray.init`` installs one that exits
    at once, without finishing anything); in the main thread only."""
    before = signal.getsignal(signal.SIGTERM)
    try:
        yield
    finally:
        if _in_main_thread() and before is not None and signal.getsignal(signal.SIGTERM) is not before:
            signal.signal(signal.SIGTERM, before)


class deferred_interrupts:  # noqa: N801 - used as a function: ``with deferred_interrupts():``
    """A block a signal does not cut: one arriving inside is raised as :class:`Interrupted` when the
    outermost such block ends (``discard``: dropped instead — e.g. while finishing a bag after the
    first Ctrl-C). Only the main thread's blocks defer (signals are handled there). A class, not a
    generator: the loop enters one per frame (about 1 µs)."""

    __slots__ = ("discard", "active")

    def __init__(self, discard: bool = False) -> None:
        self.discard = discard
        self.active = False

    def __enter__(self) -> None:
        self.active = threading.current_thread() is _MAIN
        if self.active:
            _state.depth += 1
            _state.discard += self.discard

    def __exit__(self, *exc: object) -> None:
        if not self.active:
            return
        _state.depth -= 1
        _state.discard -= self.discard
        if self.discard:
            _state.pending = None
        if not _state.depth and _state.pending is not None:
            signum, _state.pending = _state.pending, None
            _state.raised = signum
            raise Interrupted(signum)


@contextlib.contextmanager
def interrupts_set_event() -> Iterator[threading.Event]:
    """Inside: SIGINT and SIGTERM set the yielded event instead of raising — for a server's main thread,
    which installs this *before* it announces its address and then waits on the event (:func:`wait`).
    The previous handlers are restored on leaving."""
    stop = threading.Event()

    def handler(signum: int, frame: FrameType | None) -> None:
        stop.signum = signum  # type: ignore[attr-defined]
        stop.set()

    with _installed(handler):
        yield stop


def wait(stop: threading.Event) -> None:
    """Block until ``stop`` is set (waking regularly, so the signal handler runs promptly)."""
    while not stop.wait(0.2):
        pass
