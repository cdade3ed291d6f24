"""The committed ``*_pb2``/``*_pb2_grpc`` modules are what grpcio-tools makes of the .proto files, and the
messages are Gemini's, field for field (names, numbers, types)."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import seatwin.api.proto as proto_pkg

PROTO_DIR = Path(proto_pkg.__file__).parent
PROTOS = sorted(PROTO_DIR.glob("*.proto"))


def test_generated_modules_match_the_protos(tmp_path):
    pytest.importorskip("grpc_tools")
    dest = tmp_path / "seatwin" / "api" / "proto"
    dest.mkdir(parents=True)
    for p in PROTOS:
        shutil.copy(p, dest / p.name)
    names = [f"seatwin/api/proto/{p.name}" for p in PROTOS]
    cmd = [sys.executable, "-m", "grpc_tools.protoc", f"-I{tmp_path}", f"--python_out={tmp_path}"]
    cmd += [f"--pyi_out={tmp_path}", f"--grpc_python_out={tmp_path}", *names]
    subprocess.run(cmd, check=True, capture_output=True, cwd=tmp_path)
    generated = sorted(q.name for q in dest.iterdir() if "_pb2" in q.name)
    committed = sorted(q.name for q in PROTO_DIR.iterdir() if "_pb2" in q.name)
    assert generated == committed and len(generated) == 3 * len(PROTOS)
    for name in generated:
        assert (dest / name).read_text() == (PROTO_DIR / name).read_text(), f"{name} drifted: regenerate (see seatwin.api.proto)"


def _fields(msg) -> list[tuple[str, int, str, bool]]:
    from google.protobuf.descriptor import FieldDescriptor

    types = {v: k[5:].lower() for k, v in vars(FieldDescriptor).items() if k.startswith("TYPE_")}
    return [
        (f.name, f.number, f.message_type.name if f.message_type else types[f.type], f.is_repeated) for f in msg.DESCRIPTOR.fields
    ]


def test_messages_are_geminis_field_for_field():
    from seatwin.api.proto import gemini_osp_pb2 as g
    from seatwin.api.proto import navigation_pb2 as n
    from seatwin.api.proto import sensorstreaming_pb2 as s

    assert g.DESCRIPTOR.package == "GeminiOSPInterface"
    assert _fields(g.Pose) == [("north", 1, "float", False), ("east", 2, "float", False), ("heading", 3, "float", False)]
    assert _fields(g.StepRequest) == [
        ("VesselPoses", 1, "Pose", True),
        ("time", 2, "float", False),
        ("stepSize", 3, "float", False),
    ]
    assert _fields(g.SetStartTimeRequest) == [("time", 1, "string", False)]
    for m in (g.StepResponse, g.SetStartTimeResponse, n.NavigationResponse, s.LidarStreamingResponse):
        assert _fields(m) == [("success", 1, "bool", False)]
    assert [m.full_name for m in g.DESCRIPTOR.services_by_name["Simulation"].methods] == [
        "GeminiOSPInterface.Simulation.DoStep",
        "GeminiOSPInterface.Simulation.SetStartTime",
    ]
    lidar = _fields(s.LidarStreamingRequest)
    assert [f[:3] for f in lidar] == [
        ("timeInSeconds", 1, "double"),
        ("height", 2, "uint32"),
        ("width", 3, "uint32"),
        ("fields", 4, "PointField"),
        ("isBigEndian", 5, "bool"),
        ("point_step", 6, "uint32"),
        ("row_step", 7, "uint32"),
        ("data", 8, "bytes"),
        ("is_dense", 9, "bool"),
        ("frame_id", 10, "string"),
    ]
    pf = _fields(s.PointField)
    assert [f[0] for f in pf[:8]] == ["INT8", "UINT8", "INT16", "UINT16", "INT32", "UINT32", "FLOAT32", "FLOAT64"]
    assert [f[:2] for f in pf[8:]] == [("name", 9), ("offset", 10), ("datatype", 11), ("count", 12)]
    radar = _fields(s.RadarStreamingRequest)
    assert [f[:3] for f in radar] == [
        ("rangeIncrement", 1, "float"),
        ("rangeStart", 2, "float"),
        ("numSamples", 3, "uint32"),
        ("numSpokes", 4, "uint32"),
        ("minIntensity", 5, "uint32"),
        ("maxIntensity", 6, "uint32"),
        ("timeInSeconds", 7, "double"),
        ("azimuth", 8, "float"),
        ("radarSpokes", 9, "bytes"),
    ]
    assert radar[6][3] and radar[7][3]
    cam = _fields(s.CameraStreamingRequest)
    assert [f[:3] for f in cam] == [
        ("data", 1, "bytes"),
        ("timeStamp", 2, "double"),
        ("width", 3, "uint32"),
        ("height", 4, "uint32"),
        ("frame_id", 5, "string"),
    ]
    nav = _fields(n.NavigationRequest)
    assert [f[:3] for f in nav] == [
        ("timeStamp", 1, "double"),
        ("position", 2, "Vec3"),
        ("orientation", 3, "Quaternion"),
        ("linearVelocity", 4, "Vec3"),
        ("angularVelocity", 5, "Vec3"),
        ("vesselName", 6, "string"),
    ]
    assert _fields(n.Quaternion) == [(c, i + 1, "float", False) for i, c in enumerate("xyzw")]
    assert [m.name for m in s.DESCRIPTOR.services_by_name["SensorStreaming"].methods] == [
        "StreamCameraSensor",
        "StreamLidarSensor",
        "StreamRadarSensor",
    ]
