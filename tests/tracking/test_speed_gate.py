"""Confirmed tracks stay consistent with the tuning's v_max: a return sliding along a quay is not a 36 m/s boat."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.perception import MeasurementKind
from seatwin.perception.measurements import Scan
from seatwin.tracking import JIPDATracker, TrackerConfig, load_tuning
from seatwin.tracking.gnn import GNNTracker
from seatwin.tracking.tracker import speed_excess, too_fast


def _config(gate: bool = True, sustained: int | None = None) -> TrackerConfig:
    """The σ gate (``gate``) and, when ``sustained`` is set, the rule on ``sustained`` consecutive scans over
    v_max + margin (off by default here: these tests are about the σ gate)."""
    return TrackerConfig(
        q_north=1.0,
        q_east=1.0,
        gate_g=None,
        gate_probability=0.999,
        v_max=10.0,
        init_margin=2.0,
        speed_gate_sigma=3.0 if gate else None,
        speed_gate_scans=sustained,
        sensors={"radar": {"r_range": 4.0, "r_bearing": 1e-4, "r_cartesian": 4.0, "p_detect": 0.9, "clutter_density": 1e-5}},
    )


def _quay_slide(n: int = 40, dt: float = 0.5, accel: float = 2.0) -> list[Scan]:
    """One return per scan from a quay face (east 30 m) whose point slides north ever faster (2 m/s²)."""
    t = np.arange(n) * dt
    return [Scan(100.0 + ti, "radar", MeasurementKind.CARTESIAN, [[0.5 * accel * ti**2, 30.0]]) for ti in t]


def _boat(speed: float, n: int = 60, dt: float = 0.5) -> list[Scan]:
    t = np.arange(n) * dt
    return [Scan(100.0 + ti, "radar", MeasurementKind.CARTESIAN, [[speed * ti, -20.0]]) for ti in t]


def _confirmed_speeds(tab) -> np.ndarray:  # noqa: ANN001
    return np.hypot(tab.x[tab.confirmed, 1], tab.x[tab.confirmed, 3])


def test_speed_excess_is_speed_minus_vmax_and_the_along_track_sigma() -> None:
    x = np.array([[0.0, 12.0, 0.0, 5.0], [0.0, 0.0, 0.0, 0.0]])
    P = np.zeros((2, 4, 4))
    P[:, 1, 1], P[:, 3, 3] = 4.0, 9.0  # σ_vn = 2, σ_ve = 3
    excess, sigma = speed_excess(x, P, 10.0)
    assert excess == pytest.approx([3.0, -10.0])  # |(12, 5)| = 13
    u = np.array([12.0, 5.0]) / 13.0
    assert sigma[0] == pytest.approx(np.sqrt(4.0 * u[0] ** 2 + 9.0 * u[1] ** 2))
    cfg = _config()
    # 13 m/s: beyond v_max + 1 m/s + 3σ? σ ≈ 2.1 → tolerance 7.4 m/s: kept; with a tight covariance it is too fast.
    assert too_fast(x, P, cfg).tolist() == [False, False]
    assert too_fast(x, P * 1e-4, cfg).tolist() == [True, False]
    # Whatever the uncertainty, faster than speed_gate_limit × v_max (20 m/s) is too fast.
    assert too_fast(np.array([[0.0, 21.0, 0.0, 0.0]]), P[:1] * 1e6, cfg).tolist() == [True]
    assert too_fast(x, P * 1e-4, _config(gate=False)).tolist() == [False, False]


@pytest.mark.parametrize("tracker", [JIPDATracker, GNNTracker])
def test_a_track_sliding_along_a_quay_is_deleted_once_too_fast(tracker) -> None:  # noqa: ANN001
    scans = _quay_slide()
    ungated = tracker(_config(gate=False))
    free = ungated.run(scans)
    assert _confirmed_speeds(free).max() > 30.0  # without the gate: a confirmed 30+ m/s "boat" on the quay
    assert ungated.deleted_too_fast == 0
    gated = tracker(_config())
    tab = gated.run(scans)
    assert gated.deleted_too_fast == 1
    speeds = _confirmed_speeds(tab)
    assert speeds.size and speeds.max() < 20.0  # confirmed while plausible, deleted before 2 × v_max
    assert tab.time[tab.confirmed].max() < scans[-1].time and len(gated.snapshot()) == 0  # gone, not restarted


@pytest.mark.parametrize("speed", [9.0, 10.8])
def test_a_boat_at_about_vmax_keeps_its_track(speed: float) -> None:
    tracker = JIPDATracker(_config())
    tab = tracker.run(_boat(speed))
    assert tracker.deleted_too_fast == 0
    assert len(np.unique(tab.track_id[tab.confirmed])) == 1
    assert tab.confirmed[tab.time == tab.time.max()].all()
    assert _confirmed_speeds(tab)[-1] == pytest.approx(speed, abs=0.3)


def test_every_preset_has_the_gate_and_a_file_can_turn_it_off(tmp_path) -> None:
    for name in ("synthetic", "real", "joyride", "ravnkloa"):
        cfg = load_tuning(name)
        margin = 3.0 if name == "joyride" else 1.0  # the joyride radar's velocity estimates are noisier
        assert (cfg.speed_gate_sigma, cfg.speed_gate_margin, cfg.speed_gate_limit, cfg.speed_gate_scans) == (3.0, margin, 2.0, 3)
    f = tmp_path / "off.yaml"
    f.write_text("base: real\nspeed_gate_sigma: null\n")
    assert load_tuning(str(f)).speed_gate_sigma is None
    f.write_text("base: real\nspeed_gate_limit: 0.5\n")
    with pytest.raises(Exception, match="speed_gate_limit"):
        load_tuning(str(f))
