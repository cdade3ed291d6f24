"""Gemini's protobuf API, field for field (``*.proto``), and the modules ``grpcio-tools`` generates from them.

The ``*_pb2.py``/``*_pb2_grpc.py`` modules are committed; ``tests/api/test_proto_stubs.py`` regenerates
them and fails when they drift from the ``.proto`` files. Regenerate with::

    python -m grpc_tools.protoc -Isrc --python_out=src --pyi_out=src --grpc_python_out=src src/seatwin/api/proto/*.proto
"""
