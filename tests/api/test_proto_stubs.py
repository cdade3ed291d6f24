"""The committed ``*_pb2``/``*_pb2_grpc`` modules are what grpcio-tools makes of the .proto files, and the
messages are Gemini's, field for field (names, numbers, types); seatwin's own ``agent_link.proto`` carries doubles."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import seatwin.api.proto as proto_pkg

PROTO_DIR = Path(proto_pkg.__file__).parent
SEATWINS = ("agent_link.proto",)
"""seatwin's own protos (not Gemini's) beside Gemini's in the folder."""
ALL_PROTOS = sorted(PROTO_DIR.glob("*.proto"))
PROTOS = [p for p in ALL_PROTOS if p.name not in SEATWINS]


def test_generated_modules_match_the_protos(tmp_path):
    pytest.importorskip("grpc_tools")
    from seatwin.api.proto.generate import generate

    generated = sorted(q.name for q in generate(tmp_path))
    committed = sorted(q.name for q in PROTO_DIR.iterdir() if "_pb2" in q.name)
    assert generated == committed and len(generated) == 3 * len(ALL_PROTOS)
    for name in generated:
        assert (tmp_path / name).read_text() == (PROTO_DIR / name).read_text(), f"{name} drifted: regenerate"


# Gemini's file names, packages and the SHA-256 of each serialized FileDescriptorProto that grpcio-tools
# makes of Gemini's own .proto files (Gemini-team/Gemini at ce538df, API/Protobuf/ProtoFiles/<name>/<name>.proto,
# compiled as its API README says: ``-I.`` in the folder). Equal bytes are what lets one process import both.
GEMINI = {
    "simulation.proto": ("GeminiOSPInterface", "1761c25aa050d45d195e70452ae092c799b0720bb78d2500651db403729d1489"),
    "sensor_streaming.proto": ("sensorstreaming", "8e86aac0c33fe57c302e8563a62a5e3262dcd709cc01bb25c9c4e76add3a2daf"),
    "navigation.proto": ("navigation", "7b7d53964df6526c3d56ee49208cf6f0f25ee2e25a9938171137eb986f1c5462"),
    "force_control.proto": ("gemini.forcecontrol", "f2d4bf40a094224d5fe20bad7fd3a019594eb0a3d4c5595543ab920346738713"),
    "sensordata.proto": ("sensordata", "5b1529b19c41d016e32298c7a9f7431faf9e5d0235a3bf4ea8215c4bea8390e3"),
    "sensormanagement.proto": ("sensormanagement", "e36ae736feaf543d78559556a39dd238757245a27817521c247cc2e449d0cfd4"),
}


def _modules() -> dict:
    import importlib

    return {name: importlib.import_module(f"seatwin.api.proto.{name[:-6]}_pb2") for name in GEMINI}


def test_descriptors_are_geminis_byte_for_byte():
    import hashlib

    from google.protobuf import descriptor_pb2

    assert sorted(p.name for p in PROTOS) == sorted(GEMINI)
    for name, module in _modules().items():
        fd = descriptor_pb2.FileDescriptorProto()
        module.DESCRIPTOR.CopyToProto(fd)
        assert (fd.name, fd.package) == (name, GEMINI[name][0])
        assert hashlib.sha256(fd.SerializeToString()).hexdigest() == GEMINI[name][1], name


def test_geminis_modules_and_seatwins_import_in_one_process(tmp_path):
    """Generate the protos as a Gemini user does (top-level ``simulation_pb2`` …, sibling imports), import those
    first in a fresh interpreter, then seatwin's: no duplicate symbol, and the classes are the same ones."""
    pytest.importorskip("grpc_tools")
    for p in PROTOS:
        shutil.copy(p, tmp_path / p.name)
    cmd = [sys.executable, "-m", "grpc_tools.protoc", "-I.", "--python_out=.", "--grpc_python_out=.", *sorted(GEMINI)]
    subprocess.run(cmd, check=True, capture_output=True, cwd=tmp_path)
    script = (
        "import sys; sys.path.insert(0, sys.argv[1])\n"
        "import simulation_pb2, simulation_pb2_grpc, sensor_streaming_pb2_grpc, navigation_pb2_grpc\n"
        "import force_control_pb2_grpc, sensordata_pb2_grpc, sensormanagement_pb2_grpc\n"
        "from seatwin.api.proto import simulation_pb2 as ours, sensor_streaming_pb2_grpc as s, force_control_pb2_grpc\n"
        "from seatwin.api import server, streaming\n"
        "assert ours.StepRequest is simulation_pb2.StepRequest\n"
        "print('ok')\n"
    )
    out = subprocess.run([sys.executable, "-c", script, str(tmp_path)], capture_output=True, text=True)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr


def _fields(msg) -> list[tuple[str, int, str, bool]]:
    from google.protobuf.descriptor import FieldDescriptor

    types = {v: k[5:].lower() for k, v in vars(FieldDescriptor).items() if k.startswith("TYPE_")}
    return [
        (f.name, f.number, f.message_type.name if f.message_type else types[f.type], f.is_repeated) for f in msg.DESCRIPTOR.fields
    ]


def test_messages_are_geminis_field_for_field():
    from seatwin.api.proto import navigation_pb2 as n
    from seatwin.api.proto import sensor_streaming_pb2 as s
    from seatwin.api.proto import simulation_pb2 as g

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


def test_seatwins_agent_link_carries_doubles():
    """Every number of the agent link that seatwin computes with is a double, so nothing is rounded on the wire."""
    from google.protobuf.descriptor import FieldDescriptor

    from seatwin.api.proto import agent_link_pb2 as a

    assert a.DESCRIPTOR.package == "seatwin.agentlink" and a.DESCRIPTOR.name in SEATWINS
    for msg in (a.Mission, a.State, a.Target, a.VelocityRequest, a.ForceRequest, a.ThrustRequest, a.Track, a.RadarPlots):
        for f in msg.DESCRIPTOR.fields:
            assert f.type not in (FieldDescriptor.TYPE_FLOAT,), f"{msg.DESCRIPTOR.name}.{f.name} is a float"
    assert _fields(a.Step)[3] == ("navigation", 4, "NavigationRequest", False)
    assert [m.name for m in a.DESCRIPTOR.services_by_name["AgentLink"].methods] == [
        "Observe",
        "SetVelocity",
        "ApplyForce",
        "ApplyThrust",
        "Act",
    ]
