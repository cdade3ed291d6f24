"""Fit the radar model to a real recording: the use-case behind ``seatwin radar fit``.

Real plots with the targets' truth come from joyride.mat (truth inside, target area from the
replica's geometry) or from a recording with a radar topic (truth from a scenario or recording).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.errors import InputError, ParameterError
from seatwin.sensors.radar.config import RadarConfig

if TYPE_CHECKING:
    from seatwin.evaluation.plot_terms import RadarPlotSample
    from seatwin.fidelity.joyride import JoyrideData
    from seatwin.sensors.radar.fit import RadarFit, RadarObservations


def radar_observations(recording: Path, truth: str | None, base: RadarConfig, first_half: bool = False) -> RadarObservations:
    """Real plots with the targets' truth: joyride.mat (truth inside) or a recording with a radar topic (truth
    from ``truth`` — a scenario or recording — or the recording itself); only the first half of the scans if asked."""
    from seatwin.sensors.radar.fit import RadarObservations

    if recording.suffix.lower() == ".mat":
        from seatwin.fidelity.joyride import load_joyride, observations

        obs = observations(load_joyride(recording), base)
    else:
        from seatwin.evaluation import load_truth
        from seatwin.perception.from_recording import scans_from_recording
        from seatwin.pipeline.track import vessel_truth
        from seatwin.recording import open_bag

        with open_bag(recording) as rec:
            scans = list(scans_from_recording(rec, ("radar",), truth=vessel_truth(rec)).scans)
        if not scans:
            raise InputError(recording, "no radar scans in the recording")
        ts = load_truth(truth if truth else recording)
        times = np.array([s.time for s in scans])
        states = ts.states_at(times)  # (J, n, 4)
        obs = RadarObservations(
            times,
            [s.positions() for s in scans],
            np.array([s.sensor_position for s in scans]),
            np.transpose(states[:, :, [0, 2]], (1, 0, 2)),
            base.detection.area_ref_m2,
            str(recording),
        )
    if first_half:
        obs = obs.subset(np.arange(len(obs) // 2))
    return obs


def fit_radar_to_recording(
    recording: str | Path,
    *,
    truth: str | None = None,
    base: str | Path | None = None,
    first_half: bool = False,
    gate: float = 60.0,
    boot: int = 200,
    clutter: str = "uniform",
    seed: int = 0,
    by_score: bool = False,
) -> tuple[RadarFit, RadarObservations]:
    """Fit the radar model (starting from ``base`` or the built-in one) to a real recording's statistics. With
    ``by_score`` (joyride.mat only: it needs the replica to simulate), the moment fit is the start of
    :func:`fit_by_score`, whose parameters replace it and whose report is ``report["score_fit"]``."""
    from seatwin.sensors.radar.config import load_radar_config
    from seatwin.sensors.radar.fit import fit_radar

    recording = Path(recording)
    if not recording.exists():
        raise InputError(recording, "no such file or directory")
    if by_score and recording.suffix.lower() != ".mat":
        raise ParameterError("by_score", "a fit by the score simulates the recording's replica: joyride.mat only")
    cfg = load_radar_config(base) if base else RadarConfig()
    obs = radar_observations(recording, truth, cfg, first_half)
    res = fit_radar(obs, cfg, gate_m=gate, n_boot=boot, seed=seed, clutter=clutter)
    if by_score:
        from seatwin.fidelity.joyride import load_joyride

        data = load_joyride(recording)
        refit_by_score(res, data, np.arange(len(data) // 2) if first_half else None, boot, seed)
    return res, obs


def refit_by_score(fit: RadarFit, data: JoyrideData, indices: ArrayLike | None, boot: int, seed: int) -> RadarFit:
    """Replace a moment fit's parameters (in place) by :func:`fit_by_score`'s, started from them; its report goes
    under ``report["score_fit"]``."""
    sf = fit_by_score(data, fit.config, indices, n_boot=max(boot, 1), seed=seed)
    fit.report["score_fit"] = sf.to_dict()
    fit.config = sf.config.model_copy(update={"fit": fit.report})
    return fit


SCORE_FIT_ITERATIONS = 3
"""Moment-matching steps of :func:`fit_by_score` (each: simulate, compare the sensor score's statistics, correct)."""


def _sample_of(data: JoyrideData, plots: list, config: RadarConfig, idx: NDArray[np.int64]) -> RadarPlotSample:
    from seatwin.evaluation.plot_terms import radar_plot_sample
    from seatwin.fidelity.joyride import RADAR_CLUTTER_GATE_M, TARGET, antenna_positions, truth_of

    antenna = antenna_positions(data, config)[idx]
    return radar_plot_sample(data.time[idx], antenna, plots, truth_of(data), TARGET, RADAR_CLUTTER_GATE_M)


def _replica_samples(
    data: JoyrideData, config: RadarConfig, idx: NDArray[np.int64], seeds: Sequence[int]
) -> list[RadarPlotSample]:
    from seatwin.fidelity.joyride import replica_scene, simulate_replica
    from seatwin.sensors.radar import RadarModel

    scene = replica_scene(data)
    out = []
    for s in seeds:
        scans = simulate_replica(data, RadarModel(config, seed=s), scene, indices=idx)
        out.append(_sample_of(data, [sc.positions for sc in scans], config, idx))
    return out


SCORE_FIT_TERMS = {
    "bearing_bias_deg": "bearing_bias",
    "bearing_sigma_deg": "bearing_sigma",
    "range_bias_m": "range_bias",
    "range_sigma_m": "range_sigma",
    "pd_max": "detected",
    "clutter_density_per_km2": "clutter_per_scan",
}
"""Fitted parameter → the sensor-score statistic it is matched on ("detected": the share of scans with a target plot)."""


@dataclass
class ScoreFit:
    """A radar model fitted by the radar sensor score's own statistics (:func:`fit_by_score`)."""

    config: RadarConfig
    parameters: dict[str, dict[str, Any]]
    """Per fitted parameter: ``estimate`` and ``ci95`` (the real statistic's interval carried through the fit)."""
    sensor_score: dict[str, Any]
    """The fitted model's radar sensor score against the fitted scans (fresh seeds)."""
    steps: list[dict[str, Any]] = field(default_factory=list)
    """Per step: the parameters tried and their radar sensor score."""

    def to_dict(self) -> dict[str, Any]:
        return {"parameters": self.parameters, "sensor_score": self.sensor_score, "steps": self.steps}


def fit_by_score(
    data: JoyrideData,
    start: RadarConfig,
    indices: ArrayLike | None = None,
    seeds: int = 2,
    steps: int = SCORE_FIT_ITERATIONS,
    n_boot: int = 200,
    seed: int = 0,
) -> ScoreFit:
    """Fit the radar's noise, Pd cap and clutter density so that the replica's plots match the real ones in the radar
    sensor score's own statistics (clipped bias and σ of the bearing and range errors, share of scans detected,
    clutter plots per scan; docs/fidelity-score.md, *Fit from the score*): from ``start``, ``steps`` times, simulate
    the replica of the fitted scans (``indices``, default all; ``seeds`` seeds), then correct each parameter by the
    real − synthetic gap of its statistic (biases: added; σ, Pd cap, clutter: scaled by real / synthetic). Matching
    every statistic zeroes the signed terms and so minimises the sensor score's parts. The intervals carry the real
    statistic's block-bootstrap interval through the last correction; the fitted model's sensor score is computed on
    fresh seeds."""
    from seatwin.evaluation.plot_terms import clipped_mean, clipped_sigma, radar_sensor_score, signed_term
    from seatwin.evaluation.score import ScoreOptions
    from seatwin.fidelity.controlled import with_noise

    idx = np.arange(len(data)) if indices is None else np.asarray(indices, dtype=np.int64).reshape(-1)
    real = _sample_of(data, [data.plots[k] for k in idx], start, idx)
    opts = ScoreOptions(n_boot=n_boot, seed=seed)

    def series(s: RadarPlotSample, stat: str) -> NDArray[np.float64]:
        return {
            "bearing_bias": s.bearing_error,
            "bearing_sigma": s.bearing_error,
            "range_bias": s.range_error,
            "range_sigma": s.range_error,
            "detected": np.where(np.isfinite(s.target_range), s.detected, np.nan),
            "clutter_per_scan": s.clutter.astype(float),
        }[stat]

    stat_fn = {
        "bearing_bias": clipped_mean,
        "range_bias": clipped_mean,
        "bearing_sigma": clipped_sigma,
        "range_sigma": clipped_sigma,
    }

    def values(samples: list[RadarPlotSample]) -> dict[str, float]:
        out = {}
        for stat in SCORE_FIT_TERMS.values():
            x = np.concatenate([series(s, stat) for s in samples])
            x = x[np.isfinite(x)]
            out[stat] = float(stat_fn.get(stat, np.mean)(x)) if len(x) else float("nan")
        return out

    target = values([real])
    if not all(np.isfinite(v) for v in target.values()):
        raise InputError(data.source, "too few target plots in the fitted scans for a fit by the score")
    cfg = start
    step_log = []
    synth = values(_replica_samples(data, cfg, idx, range(seed, seed + seeds)))
    for k in range(steps):
        n = cfg.noise
        cfg = with_noise(
            cfg,
            bearing_bias_deg=n.bearing_bias_deg + target["bearing_bias"] - synth["bearing_bias"],
            range_bias_m=n.range_bias_m + target["range_bias"] - synth["range_bias"],
            bearing_sigma_deg=n.bearing_sigma_deg * target["bearing_sigma"] / max(synth["bearing_sigma"], 1e-6),
            range_sigma_m=n.range_sigma_m * target["range_sigma"] / max(synth["range_sigma"], 1e-6),
        )
        pd = float(np.clip(cfg.detection.pd_max * target["detected"] / max(synth["detected"], 1e-3), 0.01, 0.999))
        dens = cfg.clutter.density_per_km2 * (
            target["clutter_per_scan"] / synth["clutter_per_scan"] if synth["clutter_per_scan"] > 0 else 2.0
        )
        cfg = cfg.model_copy(
            update={
                "detection": cfg.detection.model_copy(update={"pd_max": pd}),
                "clutter": cfg.clutter.model_copy(update={"density_per_km2": dens}),
            }
        )
        samples = _replica_samples(data, cfg, idx, range(seed + 100 * (k + 1), seed + 100 * (k + 1) + seeds))
        synth = values(samples)
        score = radar_sensor_score([real], samples, ScoreOptions(n_boot=1, seed=seed)).overall.value
        step_log.append({"parameters": _score_fit_params(cfg), "sensor_score": score})
    final = _replica_samples(data, cfg, idx, range(seed + 10_000, seed + 10_000 + seeds))
    sensor = radar_sensor_score([real], final, opts)
    params = _score_fit_params(cfg)
    out: dict[str, dict[str, Any]] = {}
    for name, stat in SCORE_FIT_TERMS.items():
        term = signed_term(stat, "", [series(real, stat)], [series(s, stat) for s in final], stat_fn.get(stat, np.mean), opts)
        est, r = params[name], target[stat]
        ci = term.real_ci
        if ci is None:
            out[name] = {"estimate": est, "ci95": None}
        elif name.endswith("_bias_deg") or name.endswith("_bias_m"):
            out[name] = {"estimate": est, "ci95": [est + ci[0] - r, est + ci[1] - r]}
        else:
            out[name] = {"estimate": est, "ci95": [est * ci[0] / r, est * ci[1] / r] if r > 0 else None}
    cfg = RadarConfig.model_validate(cfg.model_dump())
    return ScoreFit(cfg, out, sensor.to_dict(), step_log)


def _score_fit_params(cfg: RadarConfig) -> dict[str, float]:
    return {
        "bearing_bias_deg": cfg.noise.bearing_bias_deg,
        "bearing_sigma_deg": cfg.noise.bearing_sigma_deg,
        "range_bias_m": cfg.noise.range_bias_m,
        "range_sigma_m": cfg.noise.range_sigma_m,
        "pd_max": cfg.detection.pd_max,
        "clutter_density_per_km2": cfg.clutter.density_per_km2,
    }
