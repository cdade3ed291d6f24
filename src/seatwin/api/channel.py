"""Client channel options shared by seatwin's gRPC clients (a light module: a client fails fast, before the simulator loads)."""

from __future__ import annotations

MAX_MESSAGE_BYTES = 256 * 1024 * 1024
"""Clients' message-size limit both ways (what they send is bounded by the server they talk to)."""

GRPC_OPTIONS = [
    ("grpc.max_receive_message_length", MAX_MESSAGE_BYTES),
    ("grpc.max_send_message_length", MAX_MESSAGE_BYTES),
]
