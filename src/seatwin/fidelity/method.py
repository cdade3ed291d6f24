"""The thesis's fidelity method (ch. 5.2) on the joyride dataset, end to end.

1. Read the dataset; build the synthetic replica (ownship and target from the ground truth,
   the radar model, the same scan times).
2. The radar model is the default one (or a given file), or fitted on the first half of the
   recording (``fit_on="first-half"``: no peeking — AHED is then reported on the second half
   only) or on all of it (``"all"``, for reference).
3. The same tracker with the same tuning runs on the real and on each synthetic recording
   (one per seed); two agents: JIPDA (:mod:`seatwin.tracking`) and GNN
   (:mod:`seatwin.tracking.gnn`), both with the same EKF and tuning (``calibrate_bias``: the tuning's
   radar bearing bias set to the fitted one, for both datasets).
4. :func:`seatwin.evaluation.compare` gives HED (5.30), COVDIFF (5.31) per common instant;
   AHED (5.34) is averaged over the evaluation window, with a circular block bootstrap 95 %
   interval (blocks of consecutive instants, pooled over seeds) and its spread over seeds.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError
from seatwin.fidelity.joyride import TARGET, TARGET_SIZE, JoyrideData, heading_from_velocity, observations, replica_scene, simulate_replica

FIT_ON = ("none", "first-half", "all")
AGENTS = ("jipda", "gnn")


@dataclass
class FidelityOptions:
    """Every choice of a fidelity run (the CLI's options)."""

    tuning: str = "joyride"
    fit_on: str = "none"
    seeds: int = 5
    n_boot: int = 1000
    block: int = 10
    """Bootstrap block length [instants] (HED is autocorrelated over a few scans)."""
    fit_boot: int = 200
    radar: str | None = None
    """A radar YAML to start from (default: the built-in default model)."""
    clutter: str = "uniform"
    """Clutter form of the fit: ``uniform`` or ``map``."""
    agents: tuple[str, ...] = AGENTS
    seed0: int = 0
    calibrate_bias: bool = False
    """Set the tuning's radar ``bearing_bias`` to the fitted bearing bias (both datasets, every model;
    estimated on the fit's scans only, so no peeking with ``first-half``)."""

    def __post_init__(self) -> None:
        if self.fit_on not in FIT_ON:
            raise InputError("--fit-on", f"expected one of {', '.join(FIT_ON)}, got {self.fit_on!r}")
        if self.calibrate_bias and self.fit_on == "none":
            raise InputError("--calibrate-bias", "needs a fit: use it with --fit-on first-half or all")
        if self.seeds < 1:
            raise InputError("--seeds", f"expected at least 1, got {self.seeds}")
        bad = [a for a in self.agents if a not in AGENTS]
        if bad:
            raise InputError("--agents", f"unknown agent(s) {bad}; expected {', '.join(AGENTS)}")


def tracker_scans(time: NDArray[np.float64], plots: list[NDArray[np.float64]], antenna: NDArray[np.float64]) -> list:
    """Range–bearing radar scans for the tracker (world frame, about the antenna; no land mask, no
    merging: the joyride recording's own hint), through :func:`seatwin.perception.radar.radar_scan`."""
    from seatwin.perception.radar import radar_scan

    return [radar_scan(p, float(t), float(a[0]), float(a[1])) for t, p, a in zip(time, plots, antenna)]


def run_agent(scans: list, tuning, agent: str):  # noqa: ANN001, ANN201
    """Run agent ``jipda`` or ``gnn`` over ``scans``; a :class:`seatwin.evaluation.Tracks`."""
    from seatwin.evaluation import Tracks
    from seatwin.tracking import JIPDATracker
    from seatwin.tracking.gnn import GNNTracker

    tracker = JIPDATracker(tuning) if agent == "jipda" else GNNTracker(tuning)
    table = tracker.run(scans)
    return Tracks(table.time, table.track_id, table.existence, table.x, table.P, table.confirmed,
                  scan_times=np.array([s.time for s in scans]))


def truth_of(data: JoyrideData):  # noqa: ANN201
    from seatwin.evaluation import TruthSet, TruthTrack

    tr = TruthTrack(TARGET, data.time, data.target[:, 0], data.target[:, 2], data.target[:, 1], data.target[:, 3], data.source)
    return TruthSet({TARGET: tr}, data.source)


def block_bootstrap_ci(values: list[NDArray[np.float64]], n_boot: int, block: int, seed: int = 0, level: float = 0.95) -> tuple[float, float]:
    """Percentile interval of the mean of all ``values`` (one array per seed, in time order)
    under a circular block bootstrap within each array (blocks of ``block`` consecutive values)."""
    from seatwin.rng import frame_rng

    vals = [np.asarray(v, float) for v in values if len(v)]
    if not vals:
        return (float("nan"), float("nan"))
    rng = frame_rng(seed, "fidelity/bootstrap", 0)
    means = np.empty(n_boot)
    for b in range(n_boot):
        tot, cnt = 0.0, 0
        for v in vals:
            n = len(v)
            L = max(1, min(block, n // 3))  # blocks shorter than the series, or the resample is a rotation
            k = int(np.ceil(n / L))
            starts = rng.integers(0, n, k)
            idx = ((starts[:, None] + np.arange(L)[None, :]) % n).ravel()[:n]  # circular: no edge bias
            tot += float(v[idx].sum())
            cnt += n
        means[b] = tot / cnt
    a = (1 - level) / 2
    return (float(np.quantile(means, a)), float(np.quantile(means, 1 - a)))


def _window_stats(series, t0: float, t1: float) -> dict[str, Any]:  # noqa: ANN001
    w = (series.time >= t0 - 1e-9) & (series.time <= t1 + 1e-9)
    common = series.has_real & series.has_synthetic & w
    only_r = series.has_real & ~series.has_synthetic & w
    only_s = series.has_synthetic & ~series.has_real & w
    hed = series.hed[common]
    cd = series.covdiff[common]
    return {
        "hed": hed,
        "hed_printed": series.hed_other[common],
        "covdiff": cd,
        "time": series.time[common],
        "ahed": float(np.mean(hed)) if len(hed) else None,
        "mean_covdiff": float(np.mean(cd)) if len(cd) else None,
        "n_common": int(common.sum()),
        "n_only_real": int(only_r.sum()),
        "n_only_synthetic": int(only_s.sum()),
        "only_real_times": series.time[only_r].tolist(),
        "only_synthetic_times": series.time[only_s].tolist(),
        "nees_real": series.nees_real[common],
        "nees_synthetic": series.nees_synthetic[common],
        "rmse_real": series.rmse_real[common],
        "rmse_synthetic": series.rmse_synthetic[common],
    }


def plot_statistics(data: JoyrideData, plots: list[NDArray[np.float64]], antenna: NDArray[np.float64], idx: NDArray[np.int64], gate_m: float = 60.0) -> dict[str, float]:
    """Simple statistics of a recording over scans ``idx``: plots per scan, target detection rate, clutter per scan."""
    n_pl, det, clut = 0, 0, 0
    for k in idx:
        p = plots[k]
        n_pl += len(p)
        d = np.hypot(p[:, 0] - data.target[k, 0], p[:, 1] - data.target[k, 2]) if len(p) else np.empty(0)
        det += int((d <= gate_m).any())
        clut += int((d > gate_m).sum())
    n = max(len(idx), 1)
    return {"plots_per_scan": n_pl / n, "detection_rate": det / n, "clutter_per_scan": clut / n}


def off_target_tracks(tracks, data: JoyrideData, window: tuple[float, float], gate_m: float = 60.0) -> dict[str, float]:  # noqa: ANN001
    """Confirmed tracks away from the target (> ``gate_m``) in the window: un-truthed vessels or persistent clutter."""
    t = tracks.time
    m = tracks.confirmed & (t >= window[0] - 1e-9) & (t <= window[1] + 1e-9)
    if not m.any():
        return {"tracks": 0, "track_instants": 0}
    tn = np.interp(t[m], data.time, data.target[:, 0])
    te = np.interp(t[m], data.time, data.target[:, 2])
    off = np.hypot(tracks.state[m, 0] - tn, tracks.state[m, 2] - te) > gate_m
    ids = tracks.track_id[m][off]
    return {"tracks": int(len(np.unique(ids))), "track_instants": int(off.sum())}


def evaluate_model(data: JoyrideData, config, opts: FidelityOptions, window: tuple[float, float], real_tracks: dict,  # noqa: ANN001
                   tuning, scene=None, label: str = "") -> dict[str, Any]:  # noqa: ANN001
    """Simulate ``opts.seeds`` synthetic recordings with radar ``config``; AHED per agent in ``window``."""
    from seatwin.evaluation import CompareOptions, compare
    from seatwin.sensors.radar.model import RadarModel

    scene = scene or replica_scene(data)
    truth = truth_of(data)
    idx_w = np.flatnonzero((data.time >= window[0] - 1e-9) & (data.time <= window[1] + 1e-9))
    out: dict[str, Any] = {"label": label, "agents": {}, "synthetic_statistics": []}
    per_agent: dict[str, list[dict[str, Any]]] = {a: [] for a in opts.agents}
    hed_series: dict[str, list] = {a: [] for a in opts.agents}
    example_plots = None
    synth_tracks: dict[str, list] = {a: [] for a in opts.agents}
    out["comparisons"] = {}
    for s in range(opts.seeds):
        seed = opts.seed0 + s
        scans = simulate_replica(data, RadarModel(config, seed=seed), scene)
        plots = [sc.positions for sc in scans]
        antenna = np.array([[sc.antenna.north, sc.antenna.east] for sc in scans])
        if example_plots is None:
            example_plots = plots
        out["synthetic_statistics"].append(plot_statistics(data, plots, antenna, idx_w))
        tscans = tracker_scans(data.time, plots, antenna)
        for agent in opts.agents:
            tr = run_agent(tscans, tuning, agent)
            synth_tracks[agent].append(tr)
            comp = compare(real_tracks[agent], tr, truth, opts.tuning, CompareOptions())
            if s == 0:
                out["comparisons"][agent] = comp
            out.setdefault("off_target", {}).setdefault(agent, []).append(off_target_tracks(tr, data, window))
            st = _window_stats(comp.series[TARGET], *window)
            st["seed"] = seed
            per_agent[agent].append(st)
            hed_series[agent].append((st["time"], st["hed"]))
    # The method's floor: two synthetic recordings of the same model (seeds s and s+1) compared
    # as if one were real — the distance that independent noise alone produces.
    floor: dict[str, list[float]] = {a: [] for a in opts.agents}
    floor_hed: dict[str, list] = {a: [] for a in opts.agents}
    for agent in opts.agents:
        tl = synth_tracks[agent]
        for s in range(len(tl) - 1):
            st = _window_stats(compare(tl[s], tl[s + 1], truth, opts.tuning, CompareOptions()).series[TARGET], *window)
            floor_hed[agent].append(st["hed"])
            if st["ahed"] is not None:
                floor[agent].append(st["ahed"])
    for agent in opts.agents:
        runs = per_agent[agent]
        vals = [r["ahed"] for r in runs if r["ahed"] is not None]
        ci = block_bootstrap_ci([r["hed"] for r in runs], opts.n_boot, opts.block, seed=opts.seed0)
        all_hed = np.concatenate([r["hed"] for r in runs]) if runs else np.empty(0)
        all_cd = np.concatenate([r["covdiff"] for r in runs]) if runs else np.empty(0)
        out["agents"][agent] = {
            "ahed": float(np.mean(all_hed)) if len(all_hed) else None,
            "ahed_ci": list(ci),
            "ahed_per_seed": vals,
            "ahed_printed": _nanmean([r["hed_printed"] for r in runs]),
            "ahed_seed_std": float(np.std(vals, ddof=1)) if len(vals) > 1 else 0.0,
            "ahed_seed_range": [float(min(vals)), float(max(vals))] if vals else None,
            "mean_covdiff": float(np.mean(all_cd)) if len(all_cd) else None,
            "off_target_tracks_synthetic": float(np.mean([o["tracks"] for o in out["off_target"][agent]])),
            "off_target_instants_synthetic": float(np.mean([o["track_instants"] for o in out["off_target"][agent]])),
            "off_target_tracks_real": off_target_tracks(real_tracks[agent], data, window)["tracks"],
            "off_target_instants_real": off_target_tracks(real_tracks[agent], data, window)["track_instants"],
            "floor_ahed": float(np.mean(np.concatenate(floor_hed[agent]))) if floor_hed[agent] and len(np.concatenate(floor_hed[agent])) else None,
            "floor_ahed_ci": list(block_bootstrap_ci(floor_hed[agent], opts.n_boot, opts.block, seed=opts.seed0 + 1)) if floor_hed[agent] else None,
            "floor_pairs": len(floor[agent]),
            "floor_n_common": float(np.mean([len(h) for h in floor_hed[agent]])) if floor_hed[agent] else 0.0,
            "n_common": float(np.mean([r["n_common"] for r in runs])),
            "n_only_real": float(np.mean([r["n_only_real"] for r in runs])),
            "n_only_synthetic": float(np.mean([r["n_only_synthetic"] for r in runs])),
            "nees_real_mean": _nanmean([r["nees_real"] for r in runs]),
            "nees_synthetic_mean": _nanmean([r["nees_synthetic"] for r in runs]),
            "rmse_real_mean": _nanmean([r["rmse_real"] for r in runs]),
            "rmse_synthetic_mean": _nanmean([r["rmse_synthetic"] for r in runs]),
            "per_seed": [{k: v for k, v in r.items() if k in ("seed", "ahed", "n_common", "n_only_real", "n_only_synthetic", "only_real_times", "only_synthetic_times")} for r in runs],
        }
    out["hed_series"] = hed_series
    out["example_plots"] = example_plots
    return out


def _nanmean(parts: list[NDArray[np.float64]]) -> float | None:
    x = np.concatenate(parts) if parts else np.empty(0)
    x = x[np.isfinite(x)]
    return float(np.mean(x)) if len(x) else None


def run_fidelity(path: str, opts: FidelityOptions) -> dict[str, Any]:
    """The whole method on ``joyride.mat``; returns everything the report and ``fidelity.json`` need."""
    from seatwin.fidelity.joyride import load_joyride
    from seatwin.sensors.radar.config import RadarConfig, load_radar_config
    from seatwin.sensors.radar.fit import fit_radar
    from seatwin.tracking import load_tuning

    data = load_joyride(path)
    base = load_radar_config(opts.radar) if opts.radar else RadarConfig()
    scene = replica_scene(data)
    n = len(data)
    half = n // 2
    if opts.fit_on == "first-half":
        fit_idx = np.arange(half)
        window = (float(data.time[half]), float(data.time[-1]))
    else:
        fit_idx = np.arange(n)
        window = (float(data.time[0]), float(data.time[-1]))
    models: dict[str, Any] = {"default": base}
    fit_report = None
    if opts.fit_on != "none":
        obs = observations(data, base, scene).subset(fit_idx)
        fit = fit_radar(obs, base, n_boot=opts.fit_boot, clutter=opts.clutter, seed=opts.seed0)
        models["fitted"] = fit.config
        fit_report = fit.report
    tuning = load_tuning(opts.tuning)
    if opts.calibrate_bias:
        radar_t = tuning.sensor("radar").model_copy(update={"bearing_bias": float(np.radians(models["fitted"].noise.bearing_bias_deg))})
        tuning = tuning.model_copy(update={"sensors": {**tuning.sensors, "radar": radar_t}})
    own_h = heading_from_velocity(data.ownship[:, 1], data.ownship[:, 3])
    antenna = data.ownship[:, [0, 2]] + np.column_stack([
        base.mount_x_m * np.cos(own_h) - base.mount_y_m * np.sin(own_h),
        base.mount_x_m * np.sin(own_h) + base.mount_y_m * np.cos(own_h),
    ])
    real_scans = tracker_scans(data.time, data.plots, antenna)
    real_tracks = {a: run_agent(real_scans, tuning, a) for a in opts.agents}
    idx_w = np.flatnonzero((data.time >= window[0] - 1e-9) & (data.time <= window[1] + 1e-9))
    result: dict[str, Any] = {
        "dataset": str(path),
        "n_scans": n,
        "fit_on": opts.fit_on,
        "seeds": opts.seeds,
        "tuning": opts.tuning + (" (bearing bias calibrated by the fit)" if opts.calibrate_bias else ""),
        "tracker_bearing_bias_deg": float(np.degrees(tuning.sensor("radar").bearing_bias)),
        "window": list(window),
        "n_window_scans": int(len(idx_w)),
        "real_statistics": plot_statistics(data, data.plots, antenna, idx_w),
        "n_invalid_plots_dropped": data.n_invalid,
        "assumptions": {
            "heading": "from velocity (the dataset has none); held below 0.5 m/s",
            "target_size_m": list(TARGET_SIZE),
            "scan_posing": f"radar pose_at={base.pose_at!r} ('scan': world posed once per scan at its stamp)",
        },
    }
    result["radar_fit"] = fit_report
    result["models"] = {}
    for label, cfg in models.items():
        result["models"][label] = evaluate_model(data, cfg, opts, window, real_tracks, tuning, scene, label)
        result["models"][label]["radar"] = cfg.model_dump(mode="json", exclude={"fit"})
    primary = "fitted" if "fitted" in models else "default"
    result["primary_model"] = primary
    result["primary_agent"] = opts.agents[0]
    result["real_tracks"] = real_tracks
    result["real_plots"] = data.plots
    result["data"] = data
    return result


def fidelity_json(result: dict[str, Any]) -> dict[str, Any]:
    """The ``fidelity.json`` content (primary model and agent at top level; every model and agent below)."""
    prim = result["models"][result["primary_model"]]["agents"][result["primary_agent"]]
    summary: dict[str, Any] = {
        "ahed": prim["ahed"],
        "ahed_ci": prim["ahed_ci"],
        "n_common": prim["n_common"],
        "n_only_real": prim["n_only_real"],
        "n_only_synthetic": prim["n_only_synthetic"],
        "fit_on": result["fit_on"],
        "seeds": result["seeds"],
        "model": result["primary_model"],
        "agent": result["primary_agent"],
        "window": result["window"],
        "tuning": result["tuning"],
        "tracker_bearing_bias_deg": result.get("tracker_bearing_bias_deg", 0.0),
        "ahed_seed_std": prim["ahed_seed_std"],
        "ahed_per_seed": prim["ahed_per_seed"],
        "real_statistics": result["real_statistics"],
        "models": {},
    }
    for label, m in result["models"].items():
        summary["models"][label] = {
            "agents": {a: dict(d) for a, d in m["agents"].items()},
            "synthetic_statistics_mean": {k: float(np.mean([s[k] for s in m["synthetic_statistics"]])) for k in m["synthetic_statistics"][0]},
            "radar": m["radar"],
        }
    if result.get("radar_fit") is not None:
        summary["radar_fit"] = result["radar_fit"]
    return summary
