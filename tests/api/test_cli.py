"""``seatwin serve`` and ``seatwin record-stream`` as processes: they listen, serve, and finish the bag on SIGTERM/SIGINT."""

from __future__ import annotations

import json
import re
import signal
import subprocess
import sys

import pytest

from seatwin.api.client import SimulationClient
from seatwin.cli.main import run
from seatwin.recording import open_bag


def _start(args):
    proc = subprocess.Popen(
        [sys.executable, "-c", "from seatwin.cli.main import main; main()", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    line = proc.stdout.readline()
    m = re.search(r"on (127\.0\.0\.1:\d+)", line)
    assert m, line + proc.stderr.read()
    return proc, m.group(1)


@pytest.mark.slow
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_serve_process_finishes_the_bag_on_a_signal(tmp_path, sig, standard_readers):
    proc, address = _start(["serve", "--port", "0", "--out", str(tmp_path / "r"), "--sensors", "none"])
    try:
        with SimulationClient(address) as c:
            assert c.set_start_time(1.6e9)
            for k in range(6):
                assert c.step([(k, 0.0, 0.0), (0.0, k, 90.0), (k, k, 45.0)], k * 0.1)
    finally:
        proc.send_signal(sig)
        out, err = proc.communicate(timeout=60)
    assert proc.returncode == 0, err
    assert "completed: 6 steps (0 refused)" in out
    m = json.loads((tmp_path / "r" / "manifest.json").read_text())
    assert m["completed"] is True
    with open_bag(tmp_path / "r") as bag:
        assert len(bag.ground_truth()["Finn"].time) == 5
    assert standard_readers(tmp_path / "r" / "recording") == m["message_count"]


@pytest.mark.slow
def test_serve_process_refuses_a_step_after_the_signal(tmp_path):
    """A step sent after SIGTERM is refused, not recorded."""
    import time

    import grpc

    proc, address = _start(["serve", "--port", "0", "--out", str(tmp_path / "r"), "--sensors", "none"])
    with SimulationClient(address, timeout_s=30) as c:
        assert c.set_start_time(1.6e9) and c.step([(0.0, 0.0, 0.0)] * 3, 0.0)
        proc.send_signal(signal.SIGTERM)
        time.sleep(1.0)  # the main thread wakes every 0.2 s to run the handler
        with pytest.raises(grpc.RpcError):
            c.step([(1.0, 0.0, 0.0)] * 3, 0.1)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 0, err
    assert "completed: 1 steps" in out
    assert json.loads((tmp_path / "r" / "manifest.json").read_text())["completed"] is True


@pytest.mark.slow
def test_record_stream_process(tmp_path, standard_readers):
    """SIGTERM right after the address is announced: the handlers are installed before it, so the bag is finished."""
    proc, _address = _start(["record-stream", "--port", "0", "--out", str(tmp_path / "r")])
    proc.send_signal(signal.SIGTERM)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 0, err
    assert json.loads((tmp_path / "r" / "manifest.json").read_text())["completed"] is True
    assert standard_readers(tmp_path / "r" / "recording") == 0


@pytest.mark.slow
def test_record_stream_process_finishes_what_it_received_on_sigterm(tmp_path, standard_readers):
    import grpc

    from seatwin.api.proto import navigation_pb2, navigation_pb2_grpc

    proc, address = _start(["record-stream", "--port", "0", "--out", str(tmp_path / "r"), "--format", "mcap"])
    try:
        with grpc.insecure_channel(address) as channel:
            nav = navigation_pb2_grpc.NavigationStub(channel)
            for k in range(5):
                msg = navigation_pb2.NavigationRequest(
                    timeStamp=1.6e9 + 0.1 * k, position=navigation_pb2.Vec3(x=float(k)), vesselName="Finn"
                )
                assert nav.SendNavigationMessage(msg, timeout=30).success
    finally:
        proc.send_signal(signal.SIGTERM)
        out, err = proc.communicate(timeout=60)
    assert proc.returncode == 0, err
    m = json.loads((tmp_path / "r" / "manifest.json").read_text())
    assert m["completed"] is True and m["topics"]["/ground_truth/Finn/pose"]["count"] == 5
    assert standard_readers(tmp_path / "r" / "recording") == m["message_count"]


def test_serve_refuses_a_bad_ownship(tmp_path, capsys):
    assert run(["serve", "--port", "0", "--out", str(tmp_path / "r"), "--ownship", "Nobody"]) == 2
    assert "--ownship" in capsys.readouterr().err


def test_serve_refuses_a_bad_port(tmp_path, capsys):
    assert run(["serve", "--port", "99999", "--out", str(tmp_path / "r"), "--sensors", "none"]) == 2
    assert "--port" in capsys.readouterr().err and not (tmp_path / "r").exists()


def test_serve_refuses_bad_limits(tmp_path, capsys):
    assert run(["serve", "--port", "0", "--out", str(tmp_path / "r"), "--sensors", "none", "--max-step", "0"]) == 2
    assert capsys.readouterr().err.startswith("seatwin: error: --max-step")
    assert run(["serve", "--port", "0", "--out", str(tmp_path / "s"), "--sensors", "none", "--max-message-bytes", "10"]) == 2
    assert "--max-message-bytes" in capsys.readouterr().err
    assert not (tmp_path / "r").exists() and not (tmp_path / "s").exists()  # refused before anything was made
