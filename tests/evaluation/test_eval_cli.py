"""``seatwin evaluate`` and ``seatwin compare``: JSON shape, tables, errors as exit 2."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from seatwin.cli.main import run
from seatwin.evaluation.tracks_io import write_tracks
from seatwin.scenario import Role, Scenario, Trajectory, Vessel
from seatwin.scenario.load import save_scenario

T0 = 1.6e9


@pytest.fixture
def scenario_file(tmp_path: Path) -> Path:
    t = T0 + np.arange(0.0, 20.01, 0.1)
    z = np.zeros_like(t)
    scen = Scenario(
        "eval",
        [
            Vessel("own", Role.OWNSHIP, Trajectory(t, z - 50.0, z, z)),
            Vessel("A", Role.TARGET, Trajectory(t, (t - T0) * 1.0, z, z)),
            Vessel("B", Role.TARGET, Trajectory(t, z, z + 100.0, z)),
        ],
    )
    path, _ = save_scenario(scen, tmp_path / "scen.yaml")
    return path


@pytest.fixture
def track_files(tmp_path: Path, tracks_factory) -> tuple[Path, Path]:
    scans = [T0 + k for k in range(21)]
    real = tracks_factory([(T0 + k, 1, k + 0.5, 0.0) for k in range(0, 18)], scan_times=scans)
    synt = tracks_factory(
        [(T0 + k, 3, k - 0.5, 0.0) for k in range(2, 20)] + [(T0 + k, 4, 1.0, 99.0) for k in range(5, 10)], scan_times=scans
    )
    paths = tmp_path / "real.csv", tmp_path / "synt.csv"
    write_tracks(paths[0], real)
    write_tracks(paths[1], synt)
    return paths


def test_evaluate_json(scenario_file: Path, track_files, tmp_path: Path, capsys) -> None:
    out = tmp_path / "ev.json"
    assert run(["evaluate", str(track_files[0]), "--truth", str(scenario_file), "--json", str(out)]) == 0
    data = json.loads(out.read_text())
    names = [t["target"] for t in data["targets"]]
    assert names == ["A", "B"]  # the ownship is excluded
    a = data["targets"][0]
    for key in (
        "coverage",
        "first_time",
        "last_time",
        "track_switches",
        "rmse",
        "anees",
        "anees_lower",
        "anees_upper",
        "n_valid",
    ):
        assert key in a
    assert a["n_valid"] == 18 and a["coverage"] == pytest.approx(18 / 21) and a["first_time"] == pytest.approx(T0)
    assert a["anees"] == pytest.approx(1.25)
    assert "A" in capsys.readouterr().out


def test_compare_json_two_tunings(scenario_file: Path, track_files, tmp_path: Path) -> None:
    out = tmp_path / "cmp.json"
    real, synt = map(str, track_files)
    code = run(
        [
            "compare",
            "--real",
            real,
            "--synthetic",
            synt,
            "--real",
            real,
            "--synthetic",
            real,
            "--truth",
            str(scenario_file),
            "--tuning",
            "synthetic,real",
            "--json",
            str(out),
        ]
    )
    assert code == 0
    data = json.loads(out.read_text())
    rows = {(t["target"], t["tuning"]): t for t in data["targets"]}
    assert set(rows) == {("A", "synthetic"), ("B", "synthetic"), ("A", "real"), ("B", "real")}
    a = rows[("A", "synthetic")]
    assert (a["n_common"], a["n_only_real"], a["n_only_synthetic"]) == (16, 2, 2)
    assert a["ahed"] == pytest.approx(np.sqrt(1 - np.exp(-1 / 8)))
    assert rows[("B", "synthetic")]["n_only_synthetic"] == 5 and rows[("B", "synthetic")]["ahed"] is None
    assert rows[("A", "real")]["ahed"] == pytest.approx(0.0, abs=1e-7)
    assert set(data) >= {"targets", "ahed_mean", "ahed_mean_by_tuning", "conventions"}
    for key in ("ahed", "n_common", "n_only_real", "n_only_synthetic", "mean_covdiff", "tuning", "target"):
        assert key in a


@pytest.mark.parametrize(
    ("extra", "needle"),
    [
        (["--hellinger-form", "odd"], "--hellinger-form"),
        (["--both-missing", "x"], "--both-missing"),
        (["--tuning", "synthetic,real"], "already tracked with one tuning"),
    ],
)
def test_compare_bad_options(scenario_file: Path, track_files, extra: list[str], needle: str, capsys) -> None:
    real, synt = map(str, track_files)
    assert run(["compare", "--real", real, "--synthetic", synt, "--truth", str(scenario_file), *extra]) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1


def test_evaluate_errors(scenario_file: Path, tmp_path: Path, capsys, tracks_factory) -> None:
    assert run(["evaluate", str(tmp_path / "none.csv"), "--truth", str(scenario_file)]) == 2
    assert "cannot open" in capsys.readouterr().err
    far = tmp_path / "far.csv"
    write_tracks(far, tracks_factory([(5.0, 1, 0.0, 0.0)]))
    assert run(["evaluate", str(far), "--truth", str(scenario_file)]) == 2
    assert "no common time" in capsys.readouterr().err


def test_compare_bad_recording(scenario_file: Path, track_files, tmp_path: Path, capsys) -> None:
    rec = tmp_path / "run.mcap"
    rec.write_bytes(b"not a bag")
    assert run(["compare", "--real", str(rec), "--synthetic", str(track_files[1]), "--truth", str(scenario_file)]) == 2
    err = capsys.readouterr().err
    assert "run.mcap" in err and err.count("\n") == 1
    assert (
        run(["compare", "--real", str(tmp_path / "absent"), "--synthetic", str(track_files[1]), "--truth", str(scenario_file)])
        == 2
    )
    assert "no such track file" in capsys.readouterr().err


@pytest.mark.slow
def test_compare_recordings_end_to_end_on_joyride(shared_data: Path, tmp_path: Path) -> None:
    """Real joyride radar imported as a recording, tracked by ``compare`` itself: a dataset against itself gives 0."""
    run_dir = tmp_path / "joyride"
    assert run(["import", "joyride", str(shared_data / "joyride" / "joyride.mat"), "--out", str(run_dir)]) == 0
    out = tmp_path / "cmp.json"
    assert (
        run(
            [
                "compare",
                "--real",
                str(run_dir),
                "--synthetic",
                str(run_dir),
                "--truth",
                str(run_dir),
                "--tuning",
                "joyride",
                "--gate",
                "50",
                "--json",
                str(out),
            ]
        )
        == 0
    )
    data = json.loads(out.read_text())
    (line,) = data["targets"]
    assert line["tuning"] == "joyride" and line["n_common"] > 100
    assert line["n_only_real"] == 0 and line["n_only_synthetic"] == 0
    assert line["ahed"] == pytest.approx(0.0, abs=1e-6)


@pytest.mark.slow
def test_compare_writes_report(scenario_file: Path, track_files, tmp_path: Path) -> None:
    real, synt = map(str, track_files)
    out = tmp_path / "rep"
    assert (
        run(
            [
                "compare",
                "--real",
                real,
                "--synthetic",
                synt,
                "--truth",
                str(scenario_file),
                "--report",
                str(out),
                "--map",
                "none",
                "--hellinger-form",
                "printed",
                "--both-missing",
                "zero",
            ]
        )
        == 0
    )
    text = (out / "index.html").read_text()
    assert "AHED (printed)" in text and "<code>zero</code>" in text and 'src="data:image/png;base64,' in text


def test_pairing_of_runs_and_tunings() -> None:
    from seatwin.errors import InputError
    from seatwin.pipeline.compare import comparison_pairs as _pairs

    assert _pairs(["a.csv"], ["b.csv"], []) == [("a.csv", "b.csv", None, "")]
    assert _pairs(["a.csv", "c.csv"], ["b.csv", "d.csv"], []) == [
        ("a.csv", "b.csv", None, "pair1"),
        ("c.csv", "d.csv", None, "pair2"),
    ]
    assert _pairs(["rec"], ["rec2"], ["synthetic", "real"]) == [
        ("rec", "rec2", "synthetic", "synthetic"),
        ("rec", "rec2", "real", "real"),
    ]
    with pytest.raises(InputError, match="as many"):
        _pairs(["a.csv"], [], [])
    with pytest.raises(InputError, match="2 tunings for 3"):
        _pairs(["a.csv"] * 3, ["b.csv"] * 3, ["x", "y"])


def test_compare_dont_care_vessels_are_left_out_of_the_score(scenario_file: Path, tracks_factory, tmp_path: Path, capsys):
    """A boat without ground truth (C, e.g. known from AIS) that only the real tracker follows: a false track
    for the score unless given as --dont-care; the target terms do not change."""
    scans = [T0 + k for k in range(21)]
    real_rows = [(T0 + k, 1, k + 0.5, 0.0) for k in range(18)] + [(T0 + k, 2, 300.0, 300.0) for k in range(21)]
    real = tracks_factory(real_rows, scan_times=scans)
    synt = tracks_factory([(T0 + k, 3, k - 0.5, 0.0) for k in range(2, 20)], scan_times=scans)
    paths = tmp_path / "real_c.csv", tmp_path / "synt_c.csv"
    write_tracks(paths[0], real)
    write_tracks(paths[1], synt)
    t = T0 + np.arange(0.0, 20.01, 0.1)
    z = np.zeros_like(t)
    boat = Scenario("ais", [Vessel("C", Role.TARGET, Trajectory(t, z + 300.0, z + 300.0, z))])
    ais, _ = save_scenario(boat, tmp_path / "ais.yaml")
    base = ["compare", "--real", str(paths[0]), "--synthetic", str(paths[1]), "--truth", str(scenario_file)]
    runs = {}
    for name, extra in (("charged", []), ("spared", ["--dont-care", str(ais)])):
        out = tmp_path / f"{name}.json"
        assert run([*base, *extra, "--json", str(out)]) == 0
        runs[name] = json.loads(out.read_text())
    false_tracks = {k: v["score_by_tuning"][""]["false_tracks"]["value"] for k, v in runs.items()}
    assert false_tracks["charged"] > 0.3 and false_tracks["spared"] == 0.0
    assert runs["spared"]["dont_care"] == {"source": str(ais), "vessels": ["C"]} and "dont_care" not in runs["charged"]
    assert [t["score"] for t in runs["spared"]["targets"]] == [t["score"] for t in runs["charged"]["targets"]]
    assert "don't-care vessels (fidelity score): C" in capsys.readouterr().out
    # a file whose vessels are all targets already leaves nothing out: refused, naming it
    assert run([*base, "--dont-care", str(scenario_file)]) == 2
    err = capsys.readouterr().err
    assert str(scenario_file) in err and "no vessel here beyond the ground truth's targets (A, B)" in err
