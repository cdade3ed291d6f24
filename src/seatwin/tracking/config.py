"""Every tracker parameter in one typed config, with where its value comes from.

Named presets: ``synthetic`` and ``real`` are thesis Tables 5.1/5.2 (Q11, Q22, R_li11,
R_li22, R_c11); ``joyride`` is the radar tuning for the real joyride dataset. The thesis
refers to Helgesen's thesis (Table 6.5, not available here) for the other JIPDA parameters;
their values below are our choice, each justified in its description. A tuning FILE (YAML
or JSON) holds the same fields; it may start from a preset with ``base: NAME``.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from seatwin.errors import InputError
from seatwin.safe_yaml import load_yaml


class SensorTuning(BaseModel):
    """Measurement noise, detection and clutter of one sensor."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)

    r_range: float = Field(gt=0, description="Range variance [m²] (thesis R_li,11).")
    r_bearing: float = Field(gt=0, description="Bearing variance [rad²] (thesis R_li,22; R_c,11 for the camera).")
    r_cartesian: float = Field(25.0, gt=0, description="Variance of each Cartesian coordinate [m²] (Cartesian plots).")
    p_detect: float = Field(gt=0, lt=1, description="Detection probability P_D of a target by this sensor.")
    clutter_density: float = Field(
        gt=0, description="Clutter density: false measurements per m² (range-bearing, Cartesian) or per rad (bearing)."
    )
    bearing_bias: float = Field(
        0.0, description="Bearing bias [rad] subtracted from every measured bearing (a calibration; 0 = none)."
    )


class TrackerConfig(BaseModel):
    """JIPDA + EKF tracker parameters (thesis ch. 5.1.2–5.1.3)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)

    name: str = "custom"
    q_north: float = Field(gt=0, description="Process noise intensity north [m²/s³] (thesis Q11, eq. 5.24).")
    q_east: float = Field(gt=0, description="Process noise intensity east [m²/s³] (thesis Q22, eq. 5.24).")
    sensors: dict[str, SensorTuning] = Field(description="Tuning per sensor name (lidar, radar, camera).")
    gate_g: float | None = Field(1.0, description="Validation gate g of eq. 5.23 (thesis: g = 1); or null.")
    gate_probability: float | None = Field(
        None, description="Alternative to gate_g: the χ² gate probability P_G (g² = χ²_d quantile)."
    )
    survival_per_second: float = Field(
        0.999,
        gt=0,
        le=1,
        description="Target survival probability over one second; P_S(Δt) = this^Δt. Our choice: targets "
        "rarely vanish within a scenario, so existence decays mainly through missed detections.",
    )
    initial_existence: float = Field(
        0.5, gt=0, lt=1, description="Existence probability of a new track. Our choice: no prior either way."
    )
    confirm_threshold: float = Field(
        0.95,
        gt=0,
        lt=1,
        description="A track is confirmed (for good) once its existence reaches this. Our choice: two or "
        "three consistent detections after initiation.",
    )
    terminate_threshold: float = Field(
        0.01, gt=0, lt=1, description="A track is deleted when its existence falls below this. Our choice."
    )
    v_max: float = Field(
        10.0,
        gt=0,
        description="Maximum target speed [m/s]: initiation within d = v_max·ΔT (thesis 5.1.3), and the speed gate "
        "of confirmed tracks (speed_gate_*).",
    )
    speed_gate_sigma: float | None = Field(
        3.0,
        gt=0,
        description="A confirmed track is deleted when its estimated speed exceeds v_max + speed_gate_margin + "
        "this many standard deviations of its speed estimate, or speed_gate_limit × v_max (a track sliding "
        "along a quay face, or following clutter, faster than any target); null: never. Our choice: 3σ "
        "(one-sided 0.13 %) keeps a real target a little faster than v_max while its velocity is uncertain "
        "(the joyride boat reaches 11.3 m/s against v_max 10) and removes tracks surely too fast.",
    )
    speed_gate_margin: float = Field(
        1.0,
        ge=0,
        description="Absolute tolerance [m/s] of the speed gate on top of v_max (a converged track of a target "
        "at about v_max is kept). Our choice: 1 m/s.",
    )
    speed_gate_limit: float = Field(
        2.0,
        gt=1,
        description="Whatever its uncertainty, a confirmed track faster than this × v_max is deleted (a track "
        "with a velocity too uncertain for the σ test can still not sail at 75 m/s). Our choice: 2.",
    )
    speed_gate_scans: int | None = Field(
        3,
        ge=0,
        description="A track (tentative or confirmed) whose estimated speed exceeds v_max + speed_gate_margin for more "
        "than this many consecutive scans is deleted, whatever its uncertainty: a track that cannot be a boat is "
        "not kept (a quay ghost whose velocity swings while it barely moves); null: only the σ test "
        "(speed_gate_sigma, speed_gate_limit). Our choice: 3 scans let a fresh two-point track or a manoeuvre "
        "overshoot briefly.",
    )
    land_scans: int | None = Field(
        1,
        ge=0,
        description="With a water mask (the recording's map), a track whose estimated position is on land is not "
        "confirmed there, and is deleted once on land for more than this many consecutive scans; null: tracks "
        "ignore the map (the thesis's tracker). Our choice: 1 tolerates one noisy estimate beside a quay.",
    )
    init_margin: float = Field(
        0.0,
        ge=0,
        description="Extra distance [m] added to d = v_max·ΔT for measurement noise (thesis: 0).",
    )
    init_exclusion_probability: float = Field(
        0.99,
        gt=0,
        lt=1,
        description="A measurement inside this χ² gate of any track is 'associated' and starts no new track, unless "
        "init_association_max frees it. Our choice: a g = 1 gate alone would let a track's own detections start "
        "duplicates.",
    )
    init_association_max: float | None = Field(
        0.5,
        gt=0,
        le=1,
        description="A measurement inside a track's exclusion gate (init_exclusion_probability) still starts a new "
        "track when the JIPDA posterior probability that it comes from an existing track (the marginals solved over "
        "the exclusion gate) is below this: two plots in one track's gate that one track cannot both explain (a "
        "second boat close by) leave the less likely one free. null: the thesis's rule, every measurement inside "
        "the exclusion gate is 'associated' (two boats closer than the gate share one track). Our choice: 0.5, "
        "a measurement more likely new than explained.",
    )
    init_association_sensors: tuple[str, ...] = Field(
        ("radar",),
        description="The sensors whose scans init_association_max applies to; the others keep the thesis's rule. Our "
        "choice: radar only — a radar plot is one per boat, while the lidar clusters of one boat's hull often fall "
        "apart into several plots a scan, which the rule would start as duplicate tracks (ferry_crossing, 20 s, "
        "lidar, tuning synthetic: 97 confirmed tracks with the rule on lidar, 24 without).",
    )
    max_hypotheses: int = Field(
        10000,
        ge=1,
        description="A cluster whose joint hypotheses are bounded by this (Π(1 + gated measurements)) is enumerated "
        "exactly; a larger one goes to the exact forward–backward pass, then to belief propagation "
        "(tracking.association).",
    )
    max_frontier_work: int = Field(
        20000,
        ge=0,
        description="Work bound (state × option pairs) of the exact forward–backward pass for a cluster too large "
        "to enumerate; beyond it loopy belief propagation (approximate, bounded cost). Our choice: ~10 ms.",
    )
    association: Literal["auto", "exact", "bp"] = Field(
        "auto",
        description="How shared clusters are solved: auto (exact where cheap, belief propagation beyond), exact "
        "(always enumerate: exponential cost), bp (always loopy belief propagation).",
    )

    @model_validator(mode="after")
    def _one_gate(self) -> TrackerConfig:
        if (self.gate_g is None) == (self.gate_probability is None):
            raise ValueError("set exactly one of gate_g and gate_probability")
        return self

    def sensor(self, name: str) -> SensorTuning:
        """The tuning of sensor ``name``."""
        try:
            return self.sensors[name]
        except KeyError:
            raise InputError("tuning", f"tuning {self.name!r} has no sensor {name!r}; it has {sorted(self.sensors)}") from None


def _thesis_preset(name: str, q: float, r_range: float, r_bearing: float, r_camera: float) -> dict[str, Any]:
    return {
        "name": name,
        "q_north": q,
        "q_east": q,
        "gate_g": 1.0,
        "sensors": {
            # P_D, clutter: our choice (Helgesen's Table 6.5 is not available). Lidar: a boat in the
            # channel gives a cluster in nearly every sweep; after the land mask a few false clusters
            # (waves, birds) remain: ~0.5 per sweep over the 150 m × 200 m channel → 2e-5 /m².
            "lidar": {"r_range": r_range, "r_bearing": r_bearing, "p_detect": 0.9, "clutter_density": 2e-5},
            # Radar: thesis has no radar tuning; lidar noise values reused, P_D/clutter as for the lidar.
            "radar": {"r_range": r_range, "r_bearing": r_bearing, "p_detect": 0.9, "clutter_density": 2e-5},
            # Camera: R_c11 from Table 5.2; P_D 0.8 (a detector misses small/far boats); 0.1 false
            # detections per rad (≈ 0.1 per image over a ~1 rad field of view).
            "camera": {"r_range": 1.0, "r_bearing": r_camera, "p_detect": 0.8, "clutter_density": 0.1},
        },
    }


PRESETS: dict[str, dict[str, Any]] = {
    # Thesis Table 5.1 (lidar) and Table 5.2 (camera R_c11), "Synthetic" row.
    "synthetic": _thesis_preset("synthetic", 0.3, 56.0, 0.044, 0.09),
    # Thesis Table 5.1 / 5.2, "Real" row.
    "real": _thesis_preset("real", 0.2, 150.0, 0.04, 0.0026),
    # The thesis's tracker (Table 5.1/5.2 "Real" row) as it was: no speed gate, tracks ignore the map, no
    # measurement inside a track's exclusion gate starts a track.
    "real-thesis": {
        **_thesis_preset("real-thesis", 0.2, 150.0, 0.04, 0.0026),
        "speed_gate_sigma": None,
        "speed_gate_scans": None,
        "land_scans": None,
        "init_association_max": None,
    },
    # Real joyride radar (Telemetron, X-band navigation radar, ~2.5 s per rotation): values from
    # radar characteristics and the target class, not fitted to the dataset's ground truth
    # (reasoning in docs/validation.md, tracking).
    "joyride": {
        "name": "joyride",
        # Bar-Shalom, Li & Kirubarajan (2001) §6.3.2: q ≈ σ_a²·T with σ_a ≈ a_max/2; a small planing
        # boat turning hard reaches a_max ≈ 3 m/s² (0.3 g); T = 2.5 s → q ≈ 5.6 m²/s³.
        "q_north": 5.0,
        "q_east": 5.0,
        "gate_g": None,
        "gate_probability": 0.99,  # g = 1 (P_G = 0.39) drops a target seen with a ~2° bias at 800 m
        "survival_per_second": 0.999,
        "v_max": 10.0,
        "init_margin": 30.0,  # ≈ 2·√2·σ_r: two plots of one boat differ by up to ~28 m from range noise alone
        # The filter's own velocity σ on this radar is ~4 m/s (median over confirmed rows): with 1 m/s the
        # sustained-speed rule (speed_gate_scans) cut the real boat's track at ~11 m/s (docs/validation.md,
        # issue 21); 3 m/s is the smallest of 1, 3, 4, 5 that keeps it.
        "speed_gate_margin": 3.0,
        "sensors": {
            "radar": {
                "r_range": 100.0,  # σ_r = 10 m: range cell of a short pulse plus the extent of a 10 m boat
                "r_bearing": math.radians(2.0) ** 2,  # σ_θ = 2°: about half the beamwidth of a small radome antenna
                "r_cartesian": 400.0,
                "p_detect": 0.8,  # a small boat at 0.2–1 km on a small navigation radar, in sea clutter
                "clutter_density": 1e-7,  # ≈ 1 false plot per scan over a ~3 km × 3 km scene
            }
        },
    },
    # Ravnkloa shore radar (2023, short range ≤ 140 m in the canal; no ground truth). Quays and moored
    # boats are masked by the map raster; what remains is mostly real small craft plus clutter.
    "ravnkloa": {
        "name": "ravnkloa",
        "q_north": 0.5,  # harbour traffic: slow (≤ 5 m/s), gentle manoeuvres (σ_a ≈ 0.5 m/s², T = 1–2 s)
        "q_east": 0.5,
        "gate_g": None,
        "gate_probability": 0.99,
        "survival_per_second": 0.999,
        "v_max": 10.0,
        "init_margin": 5.0,  # ≈ 2·√2·σ_r with σ_r ≈ 2 m
        "sensors": {
            "radar": {
                "r_range": 4.0,  # σ_r = 2 m at ≤ 150 m range
                "r_bearing": math.radians(1.5) ** 2,  # σ_θ = 1.5° (≈ 4 m cross-range at 150 m)
                "r_cartesian": 9.0,
                "p_detect": 0.8,
                "clutter_density": 1e-4,  # a few unmasked plots per scan over ~3·10⁴ m² of water
            }
        },
    },
}


def load_tuning(spec: str | Path) -> TrackerConfig:
    """A preset by name (:data:`PRESETS`) or a YAML/JSON tuning file."""
    text = str(spec)
    if text in PRESETS:
        return TrackerConfig.model_validate(PRESETS[text])
    path = Path(text)
    if not path.is_file():
        raise InputError(text, f"not a tuning preset ({', '.join(PRESETS)}) and not a file")
    try:
        data = json.loads(path.read_text()) if path.suffix == ".json" else load_yaml(path, "a tuning YAML file")
    except InputError:
        raise
    except (OSError, ValueError, RecursionError) as exc:
        raise InputError(path, f"cannot parse tuning file: {exc}") from None
    if not isinstance(data, dict):
        raise InputError(path, "a tuning file must be a mapping of parameter names to values")
    base = data.pop("base", None)
    if base is not None:
        if base not in PRESETS:
            raise InputError(path, f"unknown base preset {base!r}; expected one of {list(PRESETS)}", where="base")
        merged = json.loads(json.dumps(PRESETS[base]))
        merged["name"] = path.stem
        sensors = data.pop("sensors", {}) or {}
        if not isinstance(sensors, dict) or not all(isinstance(v, dict) or v is None for v in sensors.values()):
            raise InputError(path, "sensors must map sensor names to mappings of parameters", where="sensors")
        merged.update(data)
        for name, values in sensors.items():
            merged["sensors"].setdefault(name, {}).update(values or {})
        if "gate_probability" in data and "gate_g" not in data:
            merged["gate_g"] = None
        if "gate_g" in data and "gate_probability" not in data:
            merged["gate_probability"] = None
        data = merged
    data.setdefault("name", path.stem)
    try:
        return TrackerConfig.model_validate(data)
    except ValidationError as exc:
        err = exc.errors()[0]
        where = ".".join(str(p) for p in err["loc"])
        raise InputError(path, f"{err['msg']} (input {err.get('input')!r})", where=where or None) from None
