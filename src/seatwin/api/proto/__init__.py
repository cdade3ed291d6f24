"""Gemini's protobuf API (``*.proto``: Gemini's declarations and options, so the compiled descriptors are
Gemini's byte for byte) and the modules ``grpcio-tools`` generates from them.

Files, packages and services, as Gemini names them: ``simulation.proto`` (``GeminiOSPInterface.Simulation``),
``sensor_streaming.proto`` (``sensorstreaming.SensorStreaming``), ``navigation.proto``
(``navigation.Navigation``), ``force_control.proto`` (``gemini.forcecontrol.ForceControl``),
``sensordata.proto`` (``sensordata.Sensordata``), ``sensormanagement.proto``
(``sensormanagement.SensorManagement``). The ``*_pb2.py``/``*_pb2_grpc.py`` modules are committed;
``tests/api/test_proto_stubs.py`` regenerates them and fails when they drift. Regenerate with
``python -m seatwin.api.proto.generate``.
"""
