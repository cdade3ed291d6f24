"""``seatwin bag repair``: a run killed with SIGKILL (each format) is rewritten into a bag the standard readers open."""

from __future__ import annotations

import hashlib
import json
import shutil
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from recording_helpers import write_run
from test_faults import _kill_after

from seatwin.cli.main import run
from seatwin.errors import InputError
from seatwin.recording import open_bag
from seatwin.recording.repair import repair_bag
from seatwin.recording.storage import bag_path


def _digest(folder: Path) -> dict[str, str]:
    """Every file under ``folder`` (or the file) → its SHA-256: to show that nothing was changed."""
    files = [folder] if folder.is_file() else sorted(p for p in folder.rglob("*") if p.is_file())
    return {str(p): hashlib.sha256(p.read_bytes()).hexdigest() for p in files}


def _killed_run(tmp_path: Path, fmt: str) -> Path:
    run_dir = tmp_path / "killed"
    _kill_after(run_dir, fmt, sweeps=12)
    return run_dir


def test_repair_a_killed_run(tmp_path: Path, fmt: str, standard_readers, capsys: pytest.CaptureFixture[str]) -> None:
    killed = _killed_run(tmp_path, fmt)
    with pytest.raises(Exception):  # noqa: B017, PT011 - what standard readers do with it: any refusal
        standard_readers(bag_path(killed, fmt))
    before = _digest(killed)
    probe = tmp_path / "probe"  # seatwin's own reader, on a copy (opening a SQLite3 bag may roll back its journal)
    shutil.copytree(killed, probe)
    with open_bag(probe) as bag:
        assert bag.recovered
        expected = {t: i.count for t, i in bag.topics.items()}

    assert run(["bag", "repair", str(killed)]) == 0
    out_dir = tmp_path / "killed.repaired"
    assert f"{fmt} bag repaired: {sum(expected.values())} messages" in capsys.readouterr().out
    assert _digest(killed) == before  # the original untouched (a SQLite3 journal included)
    assert standard_readers(bag_path(out_dir, fmt)) == sum(expected.values())
    with open_bag(out_dir) as bag:
        assert not bag.recovered and bag.complete is False  # finished bag; the run itself did not complete
        assert {t: i.count for t, i in bag.topics.items()} == expected
        assert len(list(bag.point_clouds("/lidar/points"))) == expected["/lidar/points"] >= 10
    manifest = json.loads((out_dir / "manifest.json").read_text())
    assert manifest["completed"] is False and manifest["repaired"]["messages"] == sum(expected.values())
    assert manifest["topics"]["/lidar/points"] == {"type": "sensor_msgs/msg/PointCloud2", "count": expected["/lidar/points"]}


def test_repair_in_place_and_refusals(tmp_path: Path, standard_readers) -> None:
    killed = _killed_run(tmp_path, "sqlite3")
    shutil.copytree(killed, tmp_path / "probe")
    with open_bag(tmp_path / "probe") as bag:
        n = sum(i.count for i in bag.topics.values())
    other = tmp_path / "taken"
    other.mkdir()
    with pytest.raises(InputError, match="exists already"):
        repair_bag(killed, other)
    with pytest.raises(InputError, match="not both"):
        repair_bag(killed, tmp_path / "x", in_place=True)
    result = repair_bag(killed, in_place=True)
    assert result.out == killed and result.messages == n and not result.was_finished
    assert standard_readers(killed / "recording") == n
    assert not list(tmp_path.glob(".killed*"))  # no staging or replaced copy left behind
    assert json.loads((killed / "manifest.json").read_text())["repaired"]["messages"] == n


def test_repair_a_bare_finished_bag(tmp_path: Path, standard_readers) -> None:
    write_run(tmp_path / "run", "ros1", n_sweeps=3)
    bag = tmp_path / "bare.bag"
    shutil.copy(tmp_path / "run" / "recording.bag", bag)  # a bag outside any run
    result = repair_bag(bag, tmp_path / "copy.bag")
    assert result.was_finished and result.bag == tmp_path / "copy.bag"
    assert standard_readers(tmp_path / "copy.bag") == standard_readers(bag)


@pytest.fixture(scope="module")
def finished_bags(tmp_path_factory: pytest.TempPathFactory) -> dict[str, bytes]:
    root = tmp_path_factory.mktemp("finished")
    out = {}
    for fmt in ("mcap", "ros1"):
        write_run(root / fmt, fmt, n_sweeps=12, flush_interval_s=0.2)
        out[fmt] = (root / fmt / ("recording.bag" if fmt == "ros1" else "recording/recording.mcap")).read_bytes()
    return out


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(fmt=st.sampled_from(["mcap", "ros1"]), fraction=st.floats(0.0, 1.0))
def test_a_bag_cut_at_any_byte_repairs_into_what_the_scanner_reads(
    tmp_path_factory: pytest.TempPathFactory, finished_bags: dict[str, bytes], standard_readers, fmt: str, fraction: float
) -> None:
    tmp = tmp_path_factory.mktemp("cut")
    data = finished_bags[fmt]
    cut = tmp / ("cut.bag" if fmt == "ros1" else "cut.mcap")
    before = data[: max(int(len(data) * fraction), 64)]
    cut.write_bytes(before)
    try:
        with open_bag(cut) as bag:
            expected = {t: i.count for t, i in bag.topics.items() if i.count}
    except InputError:
        with pytest.raises(InputError):  # what seatwin cannot read, it does not "repair" either
            repair_bag(cut, tmp / "fixed")
        return
    result = repair_bag(cut, tmp / ("fixed.bag" if fmt == "ros1" else "fixed"))
    assert {t: n for t, n in result.topics.items() if n} == expected
    assert standard_readers(result.bag) == sum(expected.values())
    assert cut.read_bytes() == before  # the input untouched


def test_cli_out_in_place_and_refusals(tmp_path: Path, standard_readers, capsys: pytest.CaptureFixture[str]) -> None:
    write_run(tmp_path / "run", "sqlite3", n_sweeps=3)
    n = standard_readers(tmp_path / "run" / "recording")
    assert run(["bag", "repair", str(tmp_path / "run"), "--out", str(tmp_path / "fixed")]) == 0
    assert "sqlite3 bag was finished already; rewritten" in capsys.readouterr().out
    assert standard_readers(tmp_path / "fixed" / "recording") == n
    assert run(["bag", "repair", str(tmp_path / "run"), "--out", str(tmp_path / "fixed")]) == 2
    assert capsys.readouterr().err == (
        f"seatwin: error: --out: {tmp_path / 'fixed'} exists already, not replaced (give --overwrite to replace it)\n"
    )
    assert run(["bag", "repair", str(tmp_path / "run"), "--out", str(tmp_path / "fixed"), "--overwrite"]) == 0
    assert standard_readers(tmp_path / "fixed" / "recording") == n
    capsys.readouterr()
    assert run(["bag", "repair", str(tmp_path / "run" / "recording"), "--in-place"]) == 0  # the run it belongs to
    assert standard_readers(tmp_path / "run" / "recording") == n and "repaired" in json.loads(
        (tmp_path / "run" / "manifest.json").read_text()
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fixed", "run"]
    assert run(["bag", "repair", str(tmp_path / "nothing")]) == 2
    assert "no such file or directory" in capsys.readouterr().err
