"""``seatwin lidar snapshot``."""

from __future__ import annotations

from seatwin.cli.main import run


def test_snapshot_of_a_builtin_scenario(tmp_path, capsys) -> None:
    out = tmp_path / "sweep.png"
    assert run(["lidar", "snapshot", "ferry_crossing", "--time", "20", "-o", str(out), "--drop", "0"]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "points" in capsys.readouterr().out


def test_snapshot_bad_input_exits_2(tmp_path, capsys) -> None:
    out = tmp_path / "x.png"
    assert run(["lidar", "snapshot", "ferry_crossing", "--time", "9999", "-o", str(out)]) == 2
    assert "outside the scenario" in capsys.readouterr().err
    assert run(["lidar", "snapshot", "ferry_crossing", "--preset", "hdl64", "-o", str(out)]) == 2
    assert run(["lidar", "snapshot", "no_such_scenario", "-o", str(out)]) == 2
    assert run(["lidar", "snapshot", "ferry_crossing", "--drop", "1.5", "-o", str(out)]) == 2
    assert not out.exists()


def test_help_lists_the_command(capsys) -> None:
    assert run(["lidar", "--help"]) == 0
    assert "snapshot" in capsys.readouterr().out
