"""Client channel options shared by seatwin's gRPC clients (a light module: a client fails fast, before the simulator loads)."""

from __future__ import annotations

MAX_MESSAGE_BYTES = 256 * 1024 * 1024
"""Clients' message-size limit both ways (what they send is bounded by the server they talk to)."""

GRPC_OPTIONS = [
    ("grpc.max_receive_message_length", MAX_MESSAGE_BYTES),
    ("grpc.max_send_message_length", MAX_MESSAGE_BYTES),
]

KEPT_AGENT_OPTIONS = [
    ("grpc.initial_reconnect_backoff_ms", 100),
    ("grpc.min_reconnect_backoff_ms", 100),
    ("grpc.max_reconnect_backoff_ms", 1000),
]
"""Reconnect within a second: an agent that waits (``wait_for_ready``) for the next simulation's server at one
address would otherwise back off exponentially (to 120 s by default) while no server is up, and miss the run's
first-step limit."""
