"""A small joyride-like dataset made by the radar model itself (known parameters) — for tests and demos.

The project may not ship the real joyride file; this makes one of the same layout (and writes it
as a ``.mat`` file) so that the fit and the whole fidelity method can be checked where the true
radar parameters are known.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from seatwin.fidelity.joyride import JoyrideData, simulate_replica

if TYPE_CHECKING:
    from seatwin.sensors.radar import RadarConfig

TOY_RADAR = {
    "noise": {"range_sigma_m": 5.0, "range_bias_m": 0.0, "bearing_sigma_deg": 0.5, "bearing_bias_deg": -0.5},
    "clutter": {"kind": "uniform", "density_per_km2": 0.3},
    "detection": {"snr_ref_db": 15.0, "pd_max": 0.9},
    "max_range_m": 1500.0,
}
"""The radar parameters the toy dataset is simulated with."""


def toy_dataset(n: int = 120, seed: int = 11) -> JoyrideData:
    """Ownship on a straight line, target on a gentle curve; plots simulated with :data:`TOY_RADAR`."""
    t = 1.5e9 + 2.5 * np.arange(n)
    s = t - t[0]
    own = np.column_stack([2.0 * s, np.full(n, 2.0), 0.5 * s, np.full(n, 0.5)])
    ang = 0.004 * s
    tgt = np.column_stack([300 + 400 * np.sin(ang), 400 * 0.004 * np.cos(ang), 200 + 4.0 * s, np.full(n, 4.0)])
    return simulated(JoyrideData(t, [np.empty((0, 2))] * n, tgt, own, "<toy>"), TOY_RADAR, seed)


def orbit_dataset(
    radar: dict[str, Any] | RadarConfig,
    n: int = 200,
    seed: int = 11,
    radius: float = 300.0,
    centre_east: float = 150.0,
    speed: float = 5.0,
    phase: float = 0.0,
) -> JoyrideData:
    """A "real" recording made by a known ``radar`` model: the ownship drifting north at 0.5 m/s, the target
    circling at ``speed`` m/s on a ``radius`` m circle centred ``centre_east`` m east of the ownship's start, starting
    ``phase`` rad round it (defaults: ranges ~150–450 m, every aspect), ``n`` scans 2.5 s apart."""
    t = 1.5e9 + 2.5 * np.arange(n)
    s = t - t[0]
    own = np.column_stack([0.5 * s, np.full(n, 0.5), np.zeros(n), np.zeros(n)])
    w = speed / radius
    a = w * s + phase
    tgt = np.column_stack([radius * np.sin(a), radius * w * np.cos(a), centre_east + radius * np.cos(a), -radius * w * np.sin(a)])
    return simulated(JoyrideData(t, [np.empty((0, 2))] * n, tgt, own, "<orbit>"), radar, seed)


def simulated(data: JoyrideData, radar: dict[str, Any] | RadarConfig, seed: int) -> JoyrideData:
    """``data`` with its plots replaced by the replica's scans under ``radar`` (:func:`simulate_replica`, ``seed``)."""
    from seatwin.sensors.radar import RadarConfig, RadarModel

    config = radar if isinstance(radar, RadarConfig) else RadarConfig(**radar)
    data.plots = [sc.positions for sc in simulate_replica(data, RadarModel(config, seed=seed))]
    return data


def write_joyride_mat(data: JoyrideData, path: str | Path, invalid_rows: int = 0) -> Path:
    """Write ``data`` in the joyride ``.mat`` layout (``invalid_rows`` inf rows appended to scan 0)."""
    import scipy.io

    cells = np.empty((len(data), 1), dtype=object)
    for k, p in enumerate(data.plots):
        cells[k, 0] = np.asarray(p, float).reshape(-1, 2)
    if invalid_rows:
        cells[0, 0] = np.vstack([cells[0, 0], np.full((invalid_rows, 2), np.inf)])
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    scipy.io.savemat(p, {"time": data.time[:, None], "measurements": cells, "target": data.target, "telemetron": data.ownship})
    return p
