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
5. The unpaired fidelity score (:mod:`seatwin.evaluation.score`) of each model and agent on the
   evaluation window: the real run against all seeds pooled. With ``ablations``, deliberately
   wrong models derived from the fitted one (:mod:`seatwin.fidelity.ablations`) are scored too,
   and the models are ranked by the score.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from seatwin.evaluation.score import in_window
from seatwin.fidelity.ablations import ablated_models
from seatwin.fidelity.jobs import run_agent, tracker_scans
from seatwin.fidelity.joyride import (
    RADAR_CLUTTER_GATE_M,
    TARGET,
    TARGET_SIZE,
    JoyrideData,
    antenna_positions,
    observations,
    replica_scene,
    truth_of,
    untruthed_vessels,
    vessels_truth,
)
from seatwin.fidelity.options import FidelityOptions
from seatwin.fidelity.results import AgentResult, FidelityResult, ModelResult, OffTarget, PlotStatistics, SeedResult, WindowStats
from seatwin.settings import validated

if TYPE_CHECKING:
    from seatwin.evaluation import Evaluation, Tracks, TruthSet
    from seatwin.evaluation.compare import CompareOptions, ComparisonSeries
    from seatwin.evaluation.plot_terms import RadarPlotSample
    from seatwin.evaluation.score import FidelityScore, ScoreOptions
    from seatwin.sensors.radar.config import RadarConfig
    from seatwin.tracking import TrackerConfig


def block_bootstrap_ci(
    values: list[NDArray[np.float64]], n_boot: int, block: int, seed: int = 0, level: float = 0.95
) -> tuple[float, float]:
    """Percentile interval of the mean of all ``values`` (one array per seed, in time order)
    under a circular block bootstrap within each array (blocks of ``block`` consecutive values)."""
    from seatwin.evaluation.bootstrap import circular_block_indices, percentile_interval
    from seatwin.rng import frame_rng

    vals = [np.asarray(v, float) for v in values if len(v)]
    if not vals:
        return (float("nan"), float("nan"))
    rng = frame_rng(seed, "fidelity/bootstrap", 0)
    means = np.empty(n_boot)
    for b in range(n_boot):
        tot, cnt = 0.0, 0
        for v in vals:
            tot += float(v[circular_block_indices(len(v), block, rng)].sum())
            cnt += len(v)
        means[b] = tot / cnt
    return percentile_interval(means, level)  # type: ignore[return-value]


def window_stats(series: ComparisonSeries, window: tuple[float, float], seed: int) -> WindowStats:
    """The comparison ``series`` of one seed restricted to ``window`` (POSIX, inclusive)."""
    w = in_window(series.time, window)
    common = series.has_real & series.has_synthetic & w
    only_r = series.has_real & ~series.has_synthetic & w
    only_s = series.has_synthetic & ~series.has_real & w
    hed = series.hed[common]
    cd = series.covdiff[common]
    return WindowStats(
        hed=hed,
        hed_printed=series.hed_other[common],
        covdiff=cd,
        time=series.time[common],
        ahed=float(np.mean(hed)) if len(hed) else None,
        mean_covdiff=float(np.mean(cd)) if len(cd) else None,
        n_common=int(common.sum()),
        n_only_real=int(only_r.sum()),
        n_only_synthetic=int(only_s.sum()),
        only_real_times=series.time[only_r].tolist(),
        only_synthetic_times=series.time[only_s].tolist(),
        nees_real=series.nees_real[common],
        nees_synthetic=series.nees_synthetic[common],
        rmse_real=series.rmse_real[common],
        rmse_synthetic=series.rmse_synthetic[common],
        seed=seed,
    )


def plot_statistics(
    data: JoyrideData, plots: list[NDArray[np.float64]], idx: NDArray[np.int64], gate_m: float = RADAR_CLUTTER_GATE_M
) -> PlotStatistics:
    """Simple statistics of a recording over scans ``idx``: plots per scan, target detection rate, clutter per scan."""
    n_pl, det, clut = 0, 0, 0
    for k in idx:
        p = plots[k]
        n_pl += len(p)
        d = np.hypot(p[:, 0] - data.target[k, 0], p[:, 1] - data.target[k, 2]) if len(p) else np.empty(0)
        det += int((d <= gate_m).any())
        clut += int((d > gate_m).sum())
    n = max(len(idx), 1)
    return PlotStatistics(n_pl / n, det / n, clut / n)


def off_target_tracks(
    tracks: Tracks, data: JoyrideData, window: tuple[float, float], gate_m: float = RADAR_CLUTTER_GATE_M
) -> OffTarget:
    """Confirmed tracks away from the target (> ``gate_m``) in the window: un-truthed vessels or persistent clutter."""
    t = tracks.time
    m = tracks.confirmed & in_window(t, window)
    if not m.any():
        return OffTarget(0, 0)
    tn = np.interp(t[m], data.time, data.target[:, 0])
    te = np.interp(t[m], data.time, data.target[:, 2])
    off = np.hypot(tracks.state[m, 0] - tn, tracks.state[m, 2] - te) > gate_m
    ids = tracks.track_id[m][off]
    return OffTarget(int(len(np.unique(ids))), int(off.sum()))


def floor_stats(
    synthetic: list[Tracks], seed0: int, truth: TruthSet, window: tuple[float, float], tuning: str
) -> list[WindowStats]:
    """The method's floor: the synthetic recordings of seeds s and s+1 (``synthetic[s - seed0]``) compared
    as if the first were real — the distance that independent noise alone produces."""
    from seatwin.evaluation import CompareOptions, compare

    return [
        window_stats(compare(a, b, truth, tuning, CompareOptions(score=None)).series[TARGET], window, seed0 + k + 1)
        for k, (a, b) in enumerate(zip(synthetic, synthetic[1:]))
    ]


def window_plot_sample(
    data: JoyrideData,
    plots: list[NDArray[np.float64]],
    config: RadarConfig,
    window: tuple[float, float],
    dont_care: TruthSet | None = None,
) -> RadarPlotSample:
    """The radar plot-level sample (:func:`seatwin.evaluation.plot_terms.radar_plot_sample`) of a recording's
    ``plots`` inside ``window``: errors from ``config``'s antenna, clutter beyond the method's gate from the target
    and the ``dont_care`` vessels."""
    from seatwin.evaluation.plot_terms import radar_plot_sample

    idx = np.flatnonzero(in_window(data.time, window))
    antenna = antenna_positions(data, config)[idx]
    return radar_plot_sample(
        data.time[idx], antenna, [plots[k] for k in idx], truth_of(data), TARGET, RADAR_CLUTTER_GATE_M, dont_care
    )


def window_evaluation(tracks: Tracks, truth: TruthSet, window: tuple[float, float], options: CompareOptions) -> Evaluation:
    """:func:`seatwin.evaluation.evaluate` of the track rows inside ``window`` (so that false tracks, too,
    are counted there only), with the comparison's conventions."""
    from seatwin.evaluation import evaluate

    inside = tracks.select(in_window(tracks.time, window))
    return evaluate(inside, truth, options.gate, options.confirmed_only, options.confidence)


def score_options(opts: FidelityOptions) -> ScoreOptions:
    """The score's conventions for a fidelity run: its bootstrap size and seed; block lengths chosen from the data
    (``opts.block`` is AHED's)."""
    from seatwin.evaluation.score import ScoreOptions

    return ScoreOptions(n_boot=opts.n_boot, block=None, seed=opts.seed0, clutter_gate=RADAR_CLUTTER_GATE_M)


def window_score(
    real: Tracks,
    synthetic: list[Tracks],
    truth: TruthSet,
    window: tuple[float, float],
    options: ScoreOptions,
    dont_care: TruthSet | None = None,
) -> FidelityScore:
    """The unpaired fidelity score (:func:`seatwin.evaluation.sensor_score.score_runs_with_sensor_terms`) of the synthetic runs
    (all seeds pooled) against the real run, on ``window``: target errors and coverage, clutter plots per
    scan and plot shapes (from the runs' plot logs; radar plots carry no shape) and false tracks, all
    inside the window."""
    from seatwin.evaluation import CompareOptions
    from seatwin.evaluation.sensor_score import score_runs_with_sensor_terms

    copts = CompareOptions(score=options)
    evals_real = [window_evaluation(real, truth, window, copts)]
    evals_synth = [window_evaluation(s, truth, window, copts) for s in synthetic]
    return score_runs_with_sensor_terms([real], synthetic, truth, evals_real, evals_synth, options, window, dont_care)


def _agent_result(
    runs: list[WindowStats],
    floor: list[WindowStats],
    off_synthetic: list[OffTarget],
    off_real: OffTarget,
    opts: FidelityOptions,
    score: FidelityScore | None = None,
) -> AgentResult:
    """Pool one agent's seeds: AHED over every common instant, its block-bootstrap interval, the floor; the score."""
    vals = [r.ahed for r in runs if r.ahed is not None]
    ci = block_bootstrap_ci([r.hed for r in runs], opts.n_boot, opts.block, seed=opts.seed0)
    all_hed = np.concatenate([r.hed for r in runs]) if runs else np.empty(0)
    all_cd = np.concatenate([r.covdiff for r in runs]) if runs else np.empty(0)
    floor_hed = [f.hed for f in floor]
    floor_all = np.concatenate(floor_hed) if floor_hed else np.empty(0)
    return AgentResult(
        ahed=float(np.mean(all_hed)) if len(all_hed) else None,
        ahed_ci=ci,
        ahed_per_seed=vals,
        ahed_printed=_nanmean([r.hed_printed for r in runs]),
        ahed_seed_std=float(np.std(vals, ddof=1)) if len(vals) > 1 else 0.0,
        ahed_seed_range=(float(min(vals)), float(max(vals))) if vals else None,
        mean_covdiff=float(np.mean(all_cd)) if len(all_cd) else None,
        off_target_tracks_synthetic=float(np.mean([o.tracks for o in off_synthetic])),
        off_target_instants_synthetic=float(np.mean([o.track_instants for o in off_synthetic])),
        off_target_tracks_real=off_real.tracks,
        off_target_instants_real=off_real.track_instants,
        floor_ahed=float(np.mean(floor_all)) if len(floor_all) else None,
        floor_ahed_ci=block_bootstrap_ci(floor_hed, opts.n_boot, opts.block, seed=opts.seed0 + 1) if floor_hed else None,
        floor_pairs=sum(1 for f in floor if f.ahed is not None),
        floor_n_common=float(np.mean([len(h) for h in floor_hed])) if floor_hed else 0.0,
        n_common=float(np.mean([r.n_common for r in runs])),
        n_only_real=float(np.mean([r.n_only_real for r in runs])),
        n_only_synthetic=float(np.mean([r.n_only_synthetic for r in runs])),
        nees_real_mean=_nanmean([r.nees_real for r in runs]),
        nees_synthetic_mean=_nanmean([r.nees_synthetic for r in runs]),
        rmse_real_mean=_nanmean([r.rmse_real for r in runs]),
        rmse_synthetic_mean=_nanmean([r.rmse_synthetic for r in runs]),
        per_seed=[SeedResult.of(r) for r in runs],
        score=score and score.overall.value,
        score_ci=None if score is None or score.overall.ci_low is None else (score.overall.ci_low, score.overall.ci_high),
        score_reason=score.overall.reason if score is not None else "not computed",
        score_parts=score.to_dict() if score is not None else {},
    )


def evaluate_model(
    data: JoyrideData,
    config: RadarConfig,
    opts: FidelityOptions,
    window: tuple[float, float],
    real_tracks: dict[str, Tracks],
    seeds: list[tuple[int, list[NDArray[np.float64]], dict[str, Tracks]]],
    label: str = "",
    dont_care: TruthSet | None = None,
    real_sample: RadarPlotSample | None = None,
    coverage_km2: float = 1.0,
) -> ModelResult:
    """AHED and the score per agent in ``window`` of radar ``config``'s synthetic recordings: ``seeds`` holds,
    per seed in order, its plots per scan and its tracks per agent (:mod:`seatwin.fidelity.jobs`); plots and
    tracks near a vessel of ``dont_care`` are left out of the score's plot terms. With ``real_sample`` (the real
    recording's :func:`window_plot_sample`) the radar plot-level terms too
    (:func:`seatwin.evaluation.plot_terms.radar_plot_terms`; clutter per km² over ``coverage_km2``, one area for
    every model and the real radar)."""
    from seatwin.evaluation import CompareOptions, compare

    truth = truth_of(data)
    idx_w = np.flatnonzero(in_window(data.time, window))
    runs: dict[str, list[WindowStats]] = {a: [] for a in opts.agents}
    synth_tracks: dict[str, list[Tracks]] = {a: [] for a in opts.agents}
    off_target: dict[str, list[OffTarget]] = {a: [] for a in opts.agents}
    result = ModelResult(label, config.model_dump(mode="json", exclude={"fit"}), {}, [])
    for s, (seed, plots, tracks) in enumerate(seeds):
        if result.example_plots is None:
            result.example_plots = plots
        result.synthetic_statistics.append(plot_statistics(data, plots, idx_w))
        for agent in opts.agents:
            tr = tracks[agent]
            synth_tracks[agent].append(tr)
            # The score of one seed is shown only in the report of seed 0; the ranking pools the seeds (window_score).
            comp = compare(real_tracks[agent], tr, truth, opts.tuning, CompareOptions() if s == 0 else CompareOptions(score=None))
            if s == 0:
                result.comparisons[agent] = comp
            off_target[agent].append(off_target_tracks(tr, data, window))
            runs[agent].append(window_stats(comp.series[TARGET], window, seed))
    sensor = None
    if real_sample is not None:
        from seatwin.evaluation.plot_terms import radar_plot_terms, radar_sensor_score

        synth_samples = [window_plot_sample(data, plots, config, window, dont_care) for _, plots, _ in seeds]
        result.plot_samples = synth_samples
        terms = radar_plot_terms([real_sample], synth_samples, coverage_km2, score_options(opts))
        result.plot_terms = {k: v.to_dict() for k, v in terms.items()}
        sensor = radar_sensor_score([real_sample], synth_samples, score_options(opts))
        result.sensor_score = sensor.to_dict()
    for agent in opts.agents:
        floor = floor_stats(synth_tracks[agent], opts.seed0, truth, window, opts.tuning)
        score = window_score(real_tracks[agent], synth_tracks[agent], truth, window, score_options(opts), dont_care)
        if sensor is not None and sensor.overall.value is not None:
            from seatwin.evaluation.score import with_sensor_score

            # The radar sensor score's clutter part is S4's clutter rate per range annulus: S4 is not combined again.
            score = with_sensor_score(score, "radar_sensor", sensor.overall, ("clutter",), score_options(opts))
        result.agents[agent] = _agent_result(
            runs[agent], floor, off_target[agent], off_target_tracks(real_tracks[agent], data, window), opts, score
        )
    return result


def _run_seeds(
    path: str,
    models: dict[str, RadarConfig],
    opts: FidelityOptions,
    tuning: TrackerConfig,
    extra: dict[str, NDArray[np.float64]],
    jobs_in: str | Path | None,
    workers: int,
    address: str | None,
    progress: Callable[[int, int], None] | None,
) -> dict[str, list[tuple[int, list[NDArray[np.float64]], dict[str, Tracks]]]]:
    """Every (model, seed) job run by the campaign engine; per model, per seed: (seed, plots, tracks per agent)."""
    import tempfile

    from seatwin.campaign.engine import run_jobs
    from seatwin.errors import InputError
    from seatwin.fidelity.jobs import seed_job, seed_outputs, seed_run

    jobs = {
        (label, seed): seed_job(path, label, cfg, seed, tuning, opts.agents, extra)
        for label, cfg in models.items()
        for seed in range(opts.seed0, opts.seed0 + opts.seeds)
    }
    in_process = workers == 0 and address is None
    with tempfile.TemporaryDirectory(prefix="seatwin-fidelity-") as tmp:
        report = run_jobs(
            list(jobs.values()),
            seed_run,
            jobs_in if jobs_in is not None else tmp,
            engine="sequential" if in_process else "ray",
            workers=0 if in_process else (workers or None),
            address=address,
            progress=progress,
        )
    failed = [r for r in report.records.values() if not r.ok]
    if failed:
        raise InputError(path, f"{len(failed)} of {len(jobs)} synthetic runs failed; the first: {failed[0].error}")
    out: dict[str, list[tuple[int, list[NDArray[np.float64]], dict[str, Tracks]]]] = {label: [] for label in models}
    for (label, seed), job in jobs.items():
        out[label].append((seed, *seed_outputs(report.records[job.id].result)))
    return out


def _nanmean(parts: list[NDArray[np.float64]]) -> float | None:
    x = np.concatenate(parts) if parts else np.empty(0)
    x = x[np.isfinite(x)]
    return float(np.mean(x)) if len(x) else None


def run_fidelity(
    path: str,
    options: FidelityOptions | None = None,
    *,
    jobs_in: str | Path | None = None,
    workers: int = 0,
    address: str | None = None,
    progress: Callable[[int, int], None] | None = None,
    **changes: object,
) -> FidelityResult:
    """The whole method on ``joyride.mat`` with ``options`` (default :class:`FidelityOptions`, with field ``changes``).

    Every (model, seed) is a job of the campaign engine (:mod:`seatwin.fidelity.jobs`): in this process
    (``workers=0``), on a local Ray instance of ``workers`` CPUs or on the cluster at ``address``, with the
    same results; outcomes are kept in ``jobs_in/jobs`` (a re-run resumes; default: a temporary folder).
    ``progress(done, total)`` is called as jobs finish."""
    from seatwin.fidelity.joyride import load_joyride
    from seatwin.sensors.radar.config import RadarConfig, load_radar_config
    from seatwin.sensors.radar.fit import fit_radar
    from seatwin.tracking import load_tuning

    opts = validated(FidelityOptions, {**(options or FidelityOptions()).model_dump(), **changes})
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
    models: dict[str, RadarConfig] = {"default": base}
    fit_report = None
    if opts.fit_on != "none":
        obs = observations(data, base, scene).subset(fit_idx)
        fit = fit_radar(obs, base, n_boot=opts.fit_boot, clutter=opts.clutter, seed=opts.seed0)
        if opts.fit_by == "score":
            from seatwin.fidelity.radar_fit import refit_by_score

            refit_by_score(fit, data, fit_idx, opts.fit_boot, opts.seed0)
        models["fitted"] = fit.config
        fit_report = fit.report
        if opts.ablations:
            models |= ablated_models(fit.config)
    tuning = load_tuning(opts.tuning)
    if opts.calibrate_bias:
        bias = float(np.radians(models["fitted"].noise.bearing_bias_deg))
        radar_t = tuning.sensor("radar").model_copy(update={"bearing_bias": bias})
        tuning = tuning.model_copy(update={"sensors": {**tuning.sensors, "radar": radar_t}})
    antenna = antenna_positions(data, base)
    real_scans = tracker_scans(data.time, data.plots, antenna)
    real_tracks = {a: run_agent(real_scans, tuning, a) for a in opts.agents}
    extra = untruthed_vessels(real_tracks[opts.agents[0]], data, RADAR_CLUTTER_GATE_M) if opts.untruthed_vessels else {}
    idx_w = np.flatnonzero(in_window(data.time, window))
    seeds = _run_seeds(path, models, opts, tuning, extra, jobs_in, workers, address, progress)
    dont_care = vessels_truth(extra, data.source) if opts.dont_care else None
    real_sample = window_plot_sample(data, data.plots, base, window, dont_care)
    coverage_km2 = float(np.pi * (base.max_range_m**2 - base.min_range_m**2) / 1e6)
    results = {
        label: evaluate_model(data, cfg, opts, window, real_tracks, seeds[label], label, dont_care, real_sample, coverage_km2)
        for label, cfg in models.items()
    }
    primary = "fitted" if "fitted" in models else "default"
    return FidelityResult(
        dataset=str(path),
        n_scans=n,
        fit_on=opts.fit_on,
        seeds=opts.seeds,
        seed0=opts.seed0,
        tuning=opts.tuning + (" (bearing bias calibrated by the fit)" if opts.calibrate_bias else ""),
        tracker_bearing_bias_deg=float(np.degrees(tuning.sensor("radar").bearing_bias)),
        window=window,
        n_window_scans=int(len(idx_w)),
        real_statistics=plot_statistics(data, data.plots, idx_w),
        n_invalid_plots_dropped=data.n_invalid,
        assumptions={
            "heading": "from velocity (the dataset has none); held below 0.5 m/s",
            "target_size_m": list(TARGET_SIZE),
            "scan_posing": f"radar pose_at={base.pose_at!r} ('scan': world posed once per scan at its stamp)",
            "untruthed_vessels": {
                name: {"from": float(rows[0, 0]), "to": float(rows[-1, 0]), "scans": len(rows)} for name, rows in extra.items()
            },
            "score_dont_care": f"plots and confirmed tracks within {RADAR_CLUTTER_GATE_M:g} m of an un-truthed vessel are "
            "neither clutter nor false tracks in the fidelity score (both datasets)"
            if opts.dont_care
            else "off: plots and confirmed tracks of un-truthed vessels count as clutter and false tracks",
        },
        radar_fit=fit_report,
        models=results,
        primary_model=primary,
        primary_agent=opts.agents[0],
        real_tracks=real_tracks,
        data=data,
        dont_care=opts.dont_care,
        plot_term_leads=plot_term_leads(real_sample, results, primary, coverage_km2, score_options(opts)),
    )


def plot_term_leads(
    real: RadarPlotSample, models: dict[str, ModelResult], primary: str, coverage_km2: float, options: ScoreOptions
) -> dict[str, dict[str, dict]]:
    """Per other model, per radar plot-level term, how much closer the ``primary`` model is to the real recording
    (:func:`seatwin.evaluation.plot_terms.lead`, as dicts), and by how much its radar sensor score is lower
    (``radar_sensor_score``: :func:`seatwin.evaluation.plot_terms.sensor_lead`): positive and resolved = the primary
    model is closer."""
    from seatwin.evaluation.plot_terms import lead, radar_term_specs, sensor_lead

    specs = radar_term_specs(coverage_km2)
    a = models[primary].plot_samples
    return {
        label: {k: lead(spec, [real], a, m.plot_samples, options).to_dict() for k, spec in specs.items()}
        | {"radar_sensor_score": sensor_lead([real], a, m.plot_samples, options).to_dict()}
        for label, m in models.items()
        if label != primary
    }
