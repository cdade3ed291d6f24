"""Regenerate the ``*_pb2``/``*_pb2_grpc`` modules from the .proto files (``python -m seatwin.api.proto.generate``).

The protos are compiled as Gemini's README does (``-I`` the folder holding them), so each descriptor is
registered under Gemini's file name (``simulation.proto``, ``sensor_streaming.proto``, …) with Gemini's
bytes: a process that has imported Gemini's own generated modules can import seatwin's too (the
descriptor pool accepts a file registered twice when its bytes are equal, and refuses the same symbols
under another file name). grpcio-tools writes the service modules' sibling imports as top-level
imports (``import simulation_pb2``), and so are the message modules of a proto importing another (seatwin's
``agent_link.proto`` imports Gemini's ``navigation.proto``); they are rewritten to import from this package.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

PROTO_DIR = Path(__file__).parent
PACKAGE = "seatwin.api.proto"
_SIBLING_IMPORT = re.compile(r"^import (\w+_pb2) as (\w+)$", re.MULTILINE)


def generate(out_dir: Path, proto_dir: Path = PROTO_DIR) -> list[Path]:
    """Compile every ``*.proto`` in ``proto_dir`` into ``out_dir``; return the files written."""
    protos = sorted(p.name for p in proto_dir.glob("*.proto"))
    cmd = [sys.executable, "-m", "grpc_tools.protoc", f"-I{proto_dir}", f"--python_out={out_dir}", f"--pyi_out={out_dir}"]
    subprocess.run([*cmd, f"--grpc_python_out={out_dir}", *protos], check=True, capture_output=True, cwd=proto_dir)
    for module in Path(out_dir).iterdir():
        if "_pb2" in module.name:
            text = module.read_text()
            module.write_text(_SIBLING_IMPORT.sub(rf"from {PACKAGE} import \1 as \2", text))
    return sorted(q for q in Path(out_dir).iterdir() if "_pb2" in q.name)


if __name__ == "__main__":
    for path in generate(PROTO_DIR):
        print(path)
