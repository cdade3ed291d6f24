"""What ``seatwin view`` and the live view (``--live``) share: the ``foxglove-sdk`` WebSocket server and
ROS 2 channels (schema = the message type's ``.msg`` text, encoding ``ros2msg``; messages CDR)."""

from __future__ import annotations

from typing import Any

from seatwin.errors import InputError, ParameterError

DEFAULT_PORT = 8765
"""Foxglove's default WebSocket port."""


def foxglove_sdk() -> Any:
    """The ``foxglove`` module (one clear error if ``foxglove-sdk`` is missing)."""
    try:
        import foxglove
    except ImportError:  # pragma: no cover - foxglove-sdk is a dependency
        raise InputError("foxglove-sdk", "not installed: pip install foxglove-sdk (seatwin's dependencies list it)") from None
    return foxglove


def check_port(port: int) -> int:
    if not 0 <= port <= 65535:
        raise ParameterError("port", f"expected 0 (any free port) to 65535, got {port}")
    return port


def ros2_channel(store: Any, topic: str, msgtype: str, context: Any = None) -> Any:
    """A Foxglove channel for ``topic``: CDR messages of ``msgtype``, its ROS 2 definition from ``store``."""
    foxglove = foxglove_sdk()
    text, _ = store.generate_msgdef(msgtype, ros_version=2)
    schema = foxglove.Schema(name=msgtype, encoding="ros2msg", data=text.encode())
    return foxglove.Channel(topic, schema=schema, message_encoding="cdr", context=context)


def start_server(name: str, host: str, port: int, **options: Any) -> Any:
    """Start the SDK's WebSocket server; a port that cannot be bound is a :class:`ParameterError` naming ``port``."""
    foxglove = foxglove_sdk()
    check_port(port)
    try:
        return foxglove.start_server(name=name, host=host, port=port, **options)
    except Exception as exc:  # noqa: BLE001 - the SDK's bind failure: one clear line
        raise ParameterError("port", f"cannot listen on {host}:{port}: {exc}") from None
