"""``seatwin track`` and ``seatwin import``: recordings in, TRACKS.csv out; real joyride data."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.cli.main import run
from seatwin.evaluation import evaluate, load_truth, read_tracks
from seatwin.evaluation.tracks_io import COLUMNS as EVAL_COLUMNS
from seatwin.tracking import COLUMNS


def test_columns_agree_with_the_track_file() -> None:
    assert tuple(COLUMNS) == tuple(EVAL_COLUMNS)
    assert COLUMNS[:7] == ["time", "track_id", "existence", "north", "v_north", "east", "v_east"]
    assert COLUMNS[7] == "P00" and COLUMNS[22] == "P33" and COLUMNS[-1] == "confirmed"


def _lidar_recording(run_dir, n_scans: int = 40, dt: float = 0.1):
    """A small recording: ownship at rest, a boat crossing the channel, a VLP-16-like sensor frame."""
    from seatwin.recording import StaticTransform, VesselPose, mount_rotation, open_recording

    rng = np.random.default_rng(0)
    with open_recording(run_dir, "mcap") as w:
        body = w.topics.body("ownship")
        w.write_static_transforms(0.0, [StaticTransform(body, "lidar", (1.0, 0.0, -2.0), mount_rotation("flu"))])
        topic = w.topics.topic("lidar", sensor="lidar")
        for k in range(n_scans):
            t = 1.6e9 + k * dt
            own = VesselPose("ownship", 0.0, 0.0, 0.3, ownship=True)
            boat = VesselPose("boat", 30.0 + 2.0 * k * dt, 10.0 - 1.0 * k * dt, 0.0, v_north=2.0, v_east=-1.0)
            w.write_ground_truth(t, [own, boat])
            # boat returns: a 3 m × 2 m box of points around its position, in the lidar (FLU) frame
            pts_w = np.column_stack(
                (rng.uniform(-1.5, 1.5, 150) + boat.north, rng.uniform(-1, 1, 150) + boat.east, rng.uniform(-1.5, -0.2, 150))
            )
            c, s = np.cos(own.heading), np.sin(own.heading)
            rb = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
            body_pts = (pts_w - [own.north, own.east, 0.0]) @ rb  # world → body (FRD)
            sens = (body_pts - [1.0, 0.0, -2.0]) * [1.0, -1.0, -1.0]  # body → FLU sensor frame
            n = len(sens)
            w.write_sweep(topic, "lidar", t, sens[:, 0], sens[:, 1], sens[:, 2], np.ones(n), np.zeros(n, int), np.zeros(n))


def test_track_lidar_recording(tmp_path) -> None:
    rd = tmp_path / "run"
    _lidar_recording(rd)
    out = tmp_path / "tracks.csv"
    assert (
        run(
            [
                "track",
                str(rd),
                "--sensors",
                "lidar",
                "--tuning",
                "synthetic",
                "--map",
                "harbour",
                "--out",
                str(out),
                "--no-progress",
            ]
        )
        == 0
    )
    tr = read_tracks(out)
    assert len(tr.scan_times) == 40 and tr.scan_times[0] == pytest.approx(1.6e9)
    conf = tr.confirmed
    assert conf.any()
    last = conf & (tr.time == tr.time.max())
    truth = np.array([30.0 + 2.0 * 3.9, 10.0 - 3.9])
    d = np.hypot(tr.state[last, 0] - truth[0], tr.state[last, 2] - truth[1])
    assert d.min() < 3.0
    ev = evaluate(tr, load_truth(str(rd)), gate=10.0)
    assert ev.summaries[0].coverage > 0.8


@pytest.mark.parametrize(
    "args,msg",
    [
        (["--sensors", "camera"], "no camera labels"),
        (["--sensors", "sonar"], "expected 'lidar', 'radar' or 'camera'"),
        (["--tuning", "nope"], "not a tuning preset"),
        (["--sensors", "radar"], "no radar topics"),
        (["--map", "/nonexistent/map.yaml"], "map raster"),
    ],
)
def test_track_bad_input(tmp_path, capsys, args, msg) -> None:
    rd = tmp_path / "run"
    _lidar_recording(rd, n_scans=3)
    code = run(["track", str(rd), "--out", str(tmp_path / "t.csv"), *args])
    assert code == 2
    assert msg in capsys.readouterr().err


def test_track_missing_recording(tmp_path, capsys) -> None:
    assert run(["track", str(tmp_path / "none"), "--out", str(tmp_path / "t.csv")]) == 2


@pytest.mark.slow
def test_joyride_import_and_track(shared_data, tmp_path) -> None:
    """The real joyride radar data: times kept, the target tracked (coverage at 50 m, docs/validation)."""
    from scipy.io import loadmat

    rd = tmp_path / "joyride"
    assert run(["import", "joyride", str(shared_data / "joyride" / "joyride.mat"), "--out", str(rd)]) == 0
    out = tmp_path / "tracks.csv"
    assert run(["track", str(rd), "--sensors", "radar", "--out", str(out), "--no-progress"]) == 0
    tr = read_tracks(out)
    times = loadmat(shared_data / "joyride" / "joyride.mat")["time"].ravel()
    assert np.allclose(tr.scan_times, times, atol=1e-6, rtol=0)  # POSIX seconds kept
    truth = load_truth(str(rd))
    assert truth.names == ["target"]
    s = evaluate(tr, truth, gate=50.0).summaries[0]
    assert s.coverage >= 0.9 and s.rmse_position <= 25.0


@pytest.mark.slow
def test_ravnkloa_import_and_track(shared_data, tmp_path) -> None:
    folder = shared_data / "ravnkloa"
    csv = sorted((folder / "radar-2023").glob("*.csv"))[0]
    rd = tmp_path / "rv"
    assert (
        run(["import", "ravnkloa-radar", str(csv), "--out", str(rd), "--map", str(folder / "ravnkloa_radar_base_map.yaml")]) == 0
    )
    out = tmp_path / "tracks.csv"
    assert run(["track", str(rd), "--out", str(out), "--no-progress"]) == 0
    tr = read_tracks(out)
    n_conf = len(np.unique(tr.track_id[tr.confirmed]))
    assert 3 <= n_conf <= 60


def test_import_bad_files(tmp_path, capsys) -> None:
    bad = tmp_path / "x.mat"
    bad.write_text("not matlab")
    assert run(["import", "joyride", str(bad), "--out", str(tmp_path / "o")]) == 2
    csv = tmp_path / "2023-01-01-00-00-00.csv"
    csv.write_text("scan_time_s,north_m,east_m\n0,1,2\n1,x,3\n")
    assert run(["import", "ravnkloa-radar", str(csv), "--out", str(tmp_path / "o2")]) == 2
    assert "line 3" in capsys.readouterr().err


@pytest.mark.slow
def test_joyride_cartesian_radar_model(shared_data, tmp_path) -> None:
    rd = tmp_path / "joyride"
    assert run(["import", "joyride", str(shared_data / "joyride" / "joyride.mat"), "--out", str(rd)]) == 0
    out = tmp_path / "tracks.csv"
    assert run(["track", str(rd), "--sensors", "radar", "--radar-model", "cartesian", "--out", str(out), "--no-progress"]) == 0
    s = evaluate(read_tracks(out), load_truth(str(rd)), gate=50.0).summaries[0]
    assert s.coverage > 0.7
    assert run(["track", str(rd), "--radar-model", "polar", "--out", str(out)]) == 2
