"""A headless OpenGL context through EGL (Mesa llvmpipe on a CPU, the vendor driver on a GPU).

A missing EGL or GL library is bad *environment* input: :func:`create_context` raises one
:class:`~seatwin.errors.InputError` naming the Debian packages to install (the Makefile's
``DEB_PACKAGES`` installs them when run as root), never a bare traceback.
"""

from __future__ import annotations

import threading
from typing import Any

from seatwin.errors import InputError

DEBIAN_PACKAGES = "libegl1 libgl1-mesa-dri libgl1"
"""What headless rendering needs on Debian/Ubuntu (``apt-get install`` them)."""

_SHARED = threading.local()
"""One context per thread: an EGL context is current on the thread that created it only."""


def create_context(shared: bool = True) -> Any:
    """A standalone ``moderngl`` context on the EGL back end (OpenGL ≥ 3.3 core).

    ``shared`` returns the calling thread's one context (creating an EGL display is slow, and a
    context works only on the thread that made it: a gRPC worker thread gets its own); every
    renderer owns its own buffers in it. Raises :class:`InputError` when moderngl, EGL or a GL
    driver is missing.
    """
    if shared and getattr(_SHARED, "context", None) is not None:
        return _SHARED.context
    try:
        import moderngl
    except ImportError:  # pragma: no cover - a dependency of the package
        raise InputError("moderngl", "the camera renderer needs moderngl (pip install moderngl)") from None
    try:
        ctx = moderngl.create_context(standalone=True, backend="egl", require=330)
    except Exception as exc:  # noqa: BLE001 - glcontext raises plain Exceptions for a missing library or driver
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise InputError(
            "EGL",
            f"cannot create a headless OpenGL context ({first}); "
            f"install the Debian packages {DEBIAN_PACKAGES} (apt-get install {DEBIAN_PACKAGES}, or `make deb` as root)",
        ) from None
    # GL objects go with their Python objects (a renderer per run would leak ~6 MB otherwise), but are
    # released only by `release_collected` on this thread: Python's collector runs on whichever thread
    # allocates, and a release there deletes the same-numbered object of *that* thread's context.
    ctx.gc_mode = "context_gc"
    if shared:
        _SHARED.context = ctx
    return ctx


def release_collected(ctx: Any) -> int:
    """Release the GL objects of ``ctx`` that Python has collected (on any thread) since the last call;
    returns how many.

    Call it on the thread that owns ``ctx`` (renderers do, when built and before each frame).
    """
    if getattr(ctx, "gc_mode", None) != "context_gc":
        return 0
    queue, released = ctx.objects, 0
    while queue:
        obj = queue.popleft()
        if hasattr(obj, "release"):  # moderngl 5.13 queues explicitly released objects too, as InvalidObject
            obj.release()
            released += 1
    return released


def renderer_name(ctx: Any) -> str:
    """The GL renderer string (``llvmpipe (LLVM …)`` on the CPU, the GPU's name otherwise)."""
    return str(ctx.info.get("GL_RENDERER", "unknown"))
