"""The fidelity sweep: the fidelity score ranks wrong sensor models (degraded or cleaner) against a reference run of
another seed; CLI, files, bad input."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from seatwin.cli.main import run
from seatwin.cli.sweep import parse_strengths
from seatwin.errors import ParameterError
from seatwin.perception.frames import recording_mounts
from seatwin.sensors.lidar_config import MILLIAMPERE_LIDAR_MOUNT
from seatwin.sim import SimulationSettings
from seatwin.sweep import DEGRADATIONS, SweepSettings, degradation, degradations, run_sweep
from seatwin.sweep.results import SweepResult, SweepRow, spearman_by_kind


@pytest.fixture(scope="module")
def small_sweep(tmp_path_factory):
    """A small sweep through the CLI: noise (one cleaner, one noisier model) and mount (two), two seeds, 20 s."""
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
            "noise=0,0.8;mount=1,3",
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
def test_score_ranks_wrong_models_with_unmatched_seeds(small_sweep):
    table = json.loads((small_sweep / "sweep.json").read_text())
    rho = table["spearman"]["score"]
    assert set(rho["noise"]) == {"degraded", "cleaner"} and set(rho["mount"]) == {"degraded"}
    for kind, by_dir in rho.items():
        for direction, r in by_dir.items():
            assert r["seed_min"] >= 0.9, (kind, direction, r)  # every seed on its own
    floor = table["floor"]["score"]["mean"]
    for kind in ("noise", "mount"):
        means = {s["strength"]: s["mean"] for s in table["summary"]["score"][kind]}
        ref = means.pop(DEGRADATIONS[kind].reference)
        assert ref == pytest.approx(floor)
        assert all(v > ref for v in means.values()), (kind, ref, means)


@pytest.mark.slow
def test_sweep_files(small_sweep):
    rows = list(csv.DictReader((small_sweep / "sweep.csv").open()))
    kinds = [r["kind"] for r in rows]
    assert kinds.count("reference") == 2 and kinds.count("noise") == 4 and kinds.count("mount") == 4
    assert all(int(r["n_common"]) > 0 and r["score"] for r in rows)
    assert {r["reference_seed"] for r in rows} == {"1001", "1002"}
    assert all(float(r["score_ci_low"]) <= float(r["score"]) <= float(r["score_ci_high"]) for r in rows)
    # the sensor-level part (S7) beside S5, with its own interval: what ranks sensor models (evaluation 12)
    assert all(float(r["sensor_ci_low"]) <= float(r["sensor"]) <= float(r["sensor_ci_high"]) for r in rows)
    assert all(0.0 <= float(r["sensor"]) <= float(r["score"]) for r in rows)  # S5 ≥ each of its factors
    assert (small_sweep / "sweep.png").stat().st_size > 10_000
    assert len(list((small_sweep / "jobs").glob("*.json"))) == 2 * (2 + 2 + 2)  # per seed: reference, model, 4 copies
    table = json.loads((small_sweep / "sweep.json").read_text())
    assert table["settings"]["comparison"]["reference"] == "the reference run of seed s + 1000"
    assert table["settings"]["reference_model"]["range_noise"] == DEGRADATIONS["noise"].reference
    assert table["floor"]["score"]["mean"] > 0
    assert set(table["spearman"]) == {"score", "sensor", "ahed"} and table["floor"]["sensor"]["mean"] > 0
    # the same command again resumes: every job is found finished, the files come out the same
    before = (small_sweep / "sweep.csv").read_bytes()
    args = [
        "sweep",
        "ferry_crossing",
        "--out",
        str(small_sweep),
        "--kinds",
        "noise,mount",
        "--strengths",
        "noise=0,0.8;mount=1,3",
    ]
    assert run([*args, "--seeds", "2", "--duration", "20", "--no-progress"]) == 0
    assert (small_sweep / "sweep.csv").read_bytes() == before


def test_biased_mount_is_simulated_but_nominal_mount_recorded(tmp_path):
    from seatwin.recording import open_bag
    from seatwin.scenario.builtin import builtin_scenario
    from seatwin.sim import simulate_scenario

    simulate_scenario(
        builtin_scenario("ferry_crossing"),
        tmp_path / "r",
        duration=0.3,
        mount_yaw_bias_deg=5.0,
        progress=False,
        sensors=("lidar",),
    )
    with open_bag(tmp_path / "r") as rec:
        mounts = recording_mounts(rec.static_transforms())
        sensors = (rec.manifest or {}).get("sensors")
    np.testing.assert_allclose(mounts["milliAmpere/lidar"].rotation, MILLIAMPERE_LIDAR_MOUNT.rotation(), atol=1e-9)
    text = json.dumps(sensors)
    assert "mount_simulated" in text and str(MILLIAMPERE_LIDAR_MOUNT.yaw_deg + 5.0) in text


def test_degradation_settings_and_parsing():
    from seatwin.sweep.degradations import reference_model

    base = reference_model()
    assert base == {"range_noise": 0.1, "ray_drop": 0.8, "dissipation": False, "mount_yaw_bias_deg": 0.0}
    assert DEGRADATIONS["noise"].settings(0.2) == {**base, "range_noise": 0.2}
    assert DEGRADATIONS["noise"].settings(0.0) == {**base, "range_noise": 0.0}  # cleaner than the reference
    assert DEGRADATIONS["mount"].settings(2.0) == {**base, "mount_yaw_bias_deg": 2.0}
    assert DEGRADATIONS["dissipation"].settings(1.0) == {**base, "dissipation": True}
    assert DEGRADATIONS["drop"].reference == pytest.approx(0.8)
    assert DEGRADATIONS["drop"].direction(0.5) == "cleaner" and DEGRADATIONS["drop"].direction(0.9) == "degraded"
    for d in DEGRADATIONS.values():  # every kind sets fields of SimulationSettings, validly
        for s in d.default_strengths:
            SimulationSettings().with_(**d.settings(s))
    with pytest.raises(ParameterError) as exc:
        DEGRADATIONS["drop"].settings(0.8)  # the reference itself is not a swept strength
    assert exc.value.param == "strengths"
    with pytest.raises(ParameterError):
        DEGRADATIONS["mount"].settings(-1.0)  # mount has no cleaner side
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
        ({"kinds": ("noise",), "strengths": {"noise": (-0.01,)}}, "strengths"),
        ({"kinds": ("noise",), "strengths": {"noise": (0.1,)}}, "strengths"),
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
    assert not (tmp_path / "a" / "jobs").exists()


def test_spearman_by_kind_hand_values():
    settings = SweepSettings(kinds=("noise",), strengths={"noise": (0.0, 0.2, 0.4)})

    def row(kind, x, seed, score):
        return SweepRow(kind, x, seed, seed + 1000, score, score, score, 0.1, 10, 0.0, 1)

    rows = [row("reference", 0.0, s, v) for s, v in ((1, 0.1), (2, 0.2))]
    rows += [row("noise", x, s, v) for x, s, v in [(0.2, 1, 0.3), (0.2, 2, 0.25), (0.4, 1, 0.5), (0.4, 2, 0.6)]]
    rows += [row("noise", 0.0, s, v) for s, v in ((1, 0.4), (2, 0.15))]
    rho = spearman_by_kind(SweepResult(settings, rows))["noise"]
    deg, clean = rho["degraded"], rho["cleaner"]
    # degraded, distances (0, 0, .1, .1, .3, .3) ranks (1.5,1.5,3.5,3.5,5.5,5.5); scores (.1,.2,.3,.25,.5,.6) ranks (1,2,4,3,5,6)
    assert deg.rho_points == pytest.approx(16 / np.sqrt(16 * 17.5))
    assert deg.rho_per_seed == {1: pytest.approx(1.0), 2: pytest.approx(1.0)} and deg.seed_min == pytest.approx(1.0)
    assert deg.rho_means == pytest.approx(1.0)
    # cleaner: seed 1 rises (0.1 → 0.4), seed 2 falls (0.2 → 0.15): two points give ±1
    assert clean.rho_per_seed == {1: pytest.approx(1.0), 2: pytest.approx(-1.0)}
    assert (clean.seed_min, clean.seed_max) == (pytest.approx(-1.0), pytest.approx(1.0))


def test_sweep_row_metrics_by_name():
    r = SweepRow("noise", 0.2, 1, 1001, 0.4, 0.3, 0.5, 0.2, 10, 0.0, 1, 0.05, 0.01, 0.09)
    assert (r.value("score"), r.value("sensor"), r.value("ahed")) == (0.4, 0.05, 0.2)
    with pytest.raises(ValueError, match="unknown sweep metric 'S9'.*score, sensor, ahed"):
        r.value("S9")


def test_cli_bad_input(tmp_path, capsys):
    assert run(["sweep", "--out", str(tmp_path / "a"), "--kinds", "blur"]) == 2
    assert run(["sweep", "--out", str(tmp_path / "b"), "--seeds", "0"]) == 2
    assert run(["sweep", "--out", str(tmp_path / "c"), "--kinds", "noise", "--strengths", "noise=abc"]) == 2
    assert run(["sweep", "--out", str(tmp_path / "d"), "--kinds", "mount", "--duration", "500"]) == 2
    assert run(["sweep", "--out", str(tmp_path / "e"), "--kinds", "noise", "--strengths", "noise=-0.1"]) == 2
    err = capsys.readouterr().err
    assert "blur" in err and "--seeds" in err and "abc" in err and "--duration" in err and "--strengths" in err
    assert err.count("\n") == 5


@pytest.mark.parametrize("kinds", [("noise",), ("noise", "drop", "mount")])
def test_sweep_figure_title_and_legend_inside_and_off_the_points(kinds):
    """Issue 25, item 12: sweep.png's title was cut on both sides, its legend covered the strength-0 point."""
    import matplotlib.pyplot as plt

    from seatwin.sweep.figure import sweep_figure

    settings = SweepSettings(kinds=kinds, seeds=(1, 2, 3, 4, 5))

    def row(kind, x, seed, score):
        return SweepRow(kind, x, seed, seed + 1000, score, score, score, 0.1, 10, 0.0, 1)

    rows = [row("reference", 0.0, s, 0.3) for s in settings.seeds]
    for kind in kinds:
        strengths = settings.strengths_of(degradation(kind))
        rows += [row(kind, x, s, 0.9 - 0.1 * k) for k, x in enumerate(strengths) for s in settings.seeds]
    fig = sweep_figure(SweepResult(settings, rows))
    fig.set_dpi(110)  # as plot_sweep saves it: text grows a little faster than the page
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    page = fig.bbox
    title = fig._suptitle.get_window_extent(renderer)
    assert page.x0 <= title.x0 and title.x1 <= page.x1 and title.y1 <= page.y1
    (legend,) = fig.legends
    box = legend.get_window_extent(renderer)
    assert page.x0 <= box.x0 and box.x1 <= page.x1 and page.y0 <= box.y0
    for ax in fig.axes:
        if ax.get_visible():
            assert not box.overlaps(ax.get_window_extent(renderer))  # below the panels, not on a point
    plt.close(fig)
