"""The fidelity sweep: AHED ranks with the strength of a degraded sensor model; CLI, files, bad input."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from seatwin.cli.main import run
from seatwin.cli.sweep import parse_strengths
from seatwin.errors import ParameterError
from seatwin.recording.messages import quaternion_from_matrix
from seatwin.sensors.lidar_config import MILLIAMPERE_LIDAR_MOUNT
from seatwin.sim import SimulationSettings
from seatwin.sweep import DEGRADATIONS, SweepSettings, degradation, degradations, run_sweep
from seatwin.sweep.results import SweepResult, SweepRow, spearman_by_kind


@pytest.fixture(scope="module")
def small_sweep(tmp_path_factory):
    """A small sweep through the CLI: noise and mount, two strengths each, two seeds, 20 s."""
    out = tmp_path_factory.mktemp("sweep")
    code = run(
        [
            "sweep",
            "ferry_crossing",
            "--out",
            str(out),
            "--kinds",
            "noise,mount",
            "--strengths",
            "noise=0.1,0.4;mount=1,3",
            "--seeds",
            "2",
            "--duration",
            "20",
            "--no-progress",
        ]
    )
    assert code == 0
    return out


@pytest.mark.slow
def test_ahed_ranks_with_degradation(small_sweep):
    table = json.loads((small_sweep / "sweep.json").read_text())
    for kind in ("noise", "mount"):
        rho = table["spearman"][kind]
        assert rho["rho_points"] >= 0.9, (kind, rho)
        assert rho["rho_means"] >= 0.9, (kind, rho)
        means = [s["ahed_mean"] for s in table["summary"][kind]]
        assert means[0] == 0.0  # the seed-matched reference against itself
        assert all(b > a for a, b in zip(means, means[1:])), (kind, means)


@pytest.mark.slow
def test_sweep_files(small_sweep):
    rows = list(csv.DictReader((small_sweep / "sweep.csv").open()))
    kinds = [r["kind"] for r in rows]
    assert kinds.count("reference") == 2 and kinds.count("seed-to-seed") == 1
    assert kinds.count("noise") == 4 and kinds.count("mount") == 4
    assert all(int(r["n_common"]) > 0 for r in rows)
    assert (small_sweep / "sweep.png").stat().st_size > 10_000
    assert len(list((small_sweep / "tracks").glob("*.csv"))) == 2 * (1 + 2 + 2)
    table = json.loads((small_sweep / "sweep.json").read_text())
    assert table["settings"]["comparison"]["reference"] == "the seed-matched reference run"
    assert table["seed_to_seed_floor"]["mean"] > 0
    # an earlier sweep is never overwritten
    assert run(["sweep", "--out", str(small_sweep), "--kinds", "noise", "--seeds", "1", "--duration", "1"]) == 2


def test_biased_mount_is_simulated_but_nominal_mount_recorded(tmp_path):
    from seatwin.recording import open_bag
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.sim import simulate_scenario

    simulate_scenario(builtin_scenario("ferry_crossing"), tmp_path / "r", duration=0.3, mount_yaw_bias_deg=5.0, progress=False)
    with open_bag(tmp_path / "r") as rec:
        st = [s for s in rec.static_transforms() if s.child == "lidar"]
        sensors = (rec.manifest or {}).get("sensors")
    assert len(st) == 1
    q = np.asarray(quaternion_from_matrix(MILLIAMPERE_LIDAR_MOUNT.rotation()))
    assert min(np.abs(np.asarray(st[0].rotation) - q).max(), np.abs(np.asarray(st[0].rotation) + q).max()) < 1e-9
    text = json.dumps(sensors)
    assert "mount_simulated" in text and str(MILLIAMPERE_LIDAR_MOUNT.yaw_deg + 5.0) in text


def test_degradation_settings_and_parsing():
    assert DEGRADATIONS["noise"].settings(0.2) == {"range_noise": 0.2}
    assert DEGRADATIONS["mount"].settings(2.0) == {"mount_yaw_bias_deg": 2.0}
    assert DEGRADATIONS["dissipation"].settings(1.0) == {"dissipation": True}
    assert DEGRADATIONS["drop"].reference == pytest.approx(0.8)
    for d in DEGRADATIONS.values():  # every kind sets fields of SimulationSettings, validly
        for s in d.default_strengths:
            SimulationSettings().with_(**d.settings(s))
    with pytest.raises(ParameterError) as exc:
        DEGRADATIONS["drop"].settings(0.5)  # below the reference model's drop: not a degradation
    assert exc.value.param == "strengths"
    with pytest.raises(ParameterError) as exc:
        degradation("blur")
    assert exc.value.param == "kinds"
    with pytest.raises(ParameterError):
        degradations(["noise", "noise"])
    kinds = ("noise", "mount")
    assert parse_strengths("noise=0.1,0.2; mount=1", kinds) == {"noise": (0.1, 0.2), "mount": (1.0,)}
    assert parse_strengths("0.3", ("noise",)) == {"noise": (0.3,)}
    with pytest.raises(ParameterError):
        parse_strengths("0.3", kinds)
    with pytest.raises(ParameterError):
        parse_strengths("drop=0.9", kinds)


@pytest.mark.parametrize(
    ("changes", "param"),
    [
        ({"kinds": ()}, "kinds"),
        ({"kinds": ("blur",)}, "kinds"),
        ({"kinds": ("noise", "noise")}, "kinds"),
        ({"seeds": ()}, "seeds"),
        ({"seeds": (1, 1)}, "seeds"),
        ({"duration": 0.0}, "duration"),
        ({"offset": -1.0}, "offset"),
        ({"kinds": ("noise",), "strengths": {"noise": (0.01,)}}, "strengths"),
        ({"kinds": ("noise",), "strengths": {"mount": (1.0,)}}, "strengths"),
        ({"kinds": ("noise",), "strengths": {"noise": (0.1, 0.1)}}, "strengths"),
    ],
)
def test_sweep_settings_name_the_bad_parameter(changes, param):
    with pytest.raises(ParameterError) as exc:
        SweepSettings().with_(**changes)
    assert exc.value.param == param and "--" not in str(exc.value)


def test_window_outside_the_scenario_names_the_parameter(tmp_path):
    with pytest.raises(ParameterError) as exc:
        run_sweep(tmp_path / "a", kinds=("mount",), duration=1e5)
    assert exc.value.param == "duration"
    with pytest.raises(ParameterError) as exc:
        run_sweep(tmp_path / "b", kinds=("mount",), duration=10.0, offset=1e5)
    assert exc.value.param == "offset"
    assert not (tmp_path / "a" / "tracks").exists()


def test_spearman_by_kind_hand_values():
    settings = SweepSettings(kinds=("noise",), strengths={"noise": (1.0, 2.0)})
    rows = [SweepRow("reference", 0.0, s, s, 0.0, 10, 0.0, 1) for s in (1, 2)]
    rows += [SweepRow("noise", x, s, s, a, 10, 0.0, 1) for x, s, a in [(1, 1, 0.2), (1, 2, 0.3), (2, 1, 0.25), (2, 2, 0.5)]]
    rho = spearman_by_kind(SweepResult(settings, rows))["noise"]
    assert rho.rho_means == pytest.approx(1.0)
    # points: strength ranks (1.5,1.5,3.5,3.5,5.5,5.5), AHED ranks (1.5,1.5,3,5,4,6) → 14/√(16·17)
    assert rho.rho_points == pytest.approx(14 / np.sqrt(16 * 17))
    # degraded only: ranks (1.5,1.5,3.5,3.5) and (1,3,2,4) → 2/√(4·5)
    assert rho.rho_degraded == pytest.approx(2 / np.sqrt(20))


def test_cli_bad_input(tmp_path, capsys):
    assert run(["sweep", "--out", str(tmp_path / "a"), "--kinds", "blur"]) == 2
    assert run(["sweep", "--out", str(tmp_path / "b"), "--seeds", "0"]) == 2
    assert run(["sweep", "--out", str(tmp_path / "c"), "--kinds", "noise", "--strengths", "noise=abc"]) == 2
    assert run(["sweep", "--out", str(tmp_path / "d"), "--kinds", "mount", "--duration", "500"]) == 2
    assert run(["sweep", "--out", str(tmp_path / "e"), "--kinds", "noise", "--strengths", "noise=0.001"]) == 2
    err = capsys.readouterr().err
    assert "blur" in err and "--seeds" in err and "abc" in err and "--duration" in err and "--strengths" in err
    assert err.count("\n") == 5
