"""Fit the lidar model to a recording with ground truth by the lidar sensor-level distance: ``seatwin lidar fit``.

The fitted parameters are the ones the sensor-level terms (S7, :mod:`seatwin.evaluation.lidar_terms`) speak
about: range noise σ (depth and thickness of the returns), ray-drop probability and the range dissipation's
half range (detection probability and points per return, per range bin). A candidate model is simulated along
the scenario that made the recording, at the recording's own sweep instants, clustered by the same perception
(:func:`seatwin.perception.lidar.lidar_scan`, the same water mask and clustering) and compared with the
recording by the score's own combined distance (:func:`seatwin.evaluation.lidar_terms.combined_distance`); the
fit is the candidate with the smallest distance, so fit and score agree by construction.

Search (:func:`fit_lidar`): a coarse grid over the three parameters, then rounds of a 1-D refinement per
parameter around the best candidate (the others held), plus joint moves of ray drop and half range (they trade
off: one-at-a-time moves stall on their ridge), each round halving the step. Every candidate is
simulated with the same seeds (common random numbers: the distance changes smoothly with the parameters).
Intervals: block bootstrap of the terms (:func:`bootstrap_best`): each replicate resamples the real and the
simulated scans in circular blocks (the score's block rule), takes the candidate nearest to it among all
candidates simulated, and the 95 % interval of a parameter is the 2.5–97.5 % range of the replicates' best
values, widened by half the search's final step on each side (the resolution of the search).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError, ParameterError

if TYPE_CHECKING:
    from seatwin.evaluation.lidar_terms import LidarReturnSample
    from seatwin.evaluation.truth import TruthSet
    from seatwin.perception.lidar import LidarClustering
    from seatwin.perception.map_mask import WaterMask
    from seatwin.perception.measurements import Scan
    from seatwin.scenario import Scenario
    from seatwin.sensors.lidar_config import LidarConfig

PARAMETERS = ("range_noise_m", "drop_probability", "dissipation_half_range_m")
"""The fitted parameters: σ of the range noise [m] (``range_accuracy`` = 2σ), the ray-drop probability, and the
half range of the range dissipation [m] (its width is the base configuration's, default 8 m)."""
BOUNDS = {"range_noise_m": (0.002, 0.25), "drop_probability": (0.0, 0.97), "dissipation_half_range_m": (10.0, 250.0)}
"""The search's limits per parameter: wider than any VLP-16-like sensor (±3 cm data sheet, thesis drop 0.8, the
thesis's dissipation near 60 m); a fit at a limit says the limit, not the sensor, stopped it."""
COARSE = {
    "range_noise_m": (0.01, 0.03, 0.09),
    "drop_probability": (0.5, 0.7, 0.9),
    "dissipation_half_range_m": (30.0, 60.0, 120.0),
}
"""The coarse grid (27 candidates). σ and the half range are searched on a log scale, the drop on a linear one."""
LOG_SCALE = {"range_noise_m": True, "drop_probability": False, "dissipation_half_range_m": True}
FIRST_STEP = {"range_noise_m": np.log(3.0) / 2, "drop_probability": 0.1, "dissipation_half_range_m": np.log(2.0) / 2}
"""Step of the first refinement round (in log units where :data:`LOG_SCALE`): half the coarse grid's spacing."""


def candidate_config(base: LidarConfig, params: dict[str, float]) -> LidarConfig:
    """``base`` with the fitted parameters ``params`` (those of :data:`PARAMETERS` it names)."""
    from seatwin.sensors.lidar_config import RangeDissipation

    changes: dict[str, Any] = {}
    if "range_noise_m" in params:
        changes["range_accuracy"] = 2.0 * float(params["range_noise_m"])
    if "drop_probability" in params:
        changes["drop_probability"] = float(params["drop_probability"])
    if "dissipation_half_range_m" in params:
        width = base.dissipation.width if base.dissipation is not None else RangeDissipation().width
        changes["dissipation"] = RangeDissipation(half_range=float(params["dissipation_half_range_m"]), width=width)
    return base.with_(**changes)


def config_parameters(config: LidarConfig) -> dict[str, float]:
    """The fitted parameters of ``config`` (a half range of +inf without dissipation)."""
    half = config.dissipation.half_range if config.dissipation is not None else float("inf")
    return {
        "range_noise_m": config.range_noise_std,
        "drop_probability": config.drop_probability,
        "dissipation_half_range_m": half,
    }


# ---------------------------------------------------------------------------------------------- samples


def scan_samples(scans: Sequence[Scan], truth: TruthSet, dont_care: TruthSet | None = None) -> dict[str, LidarReturnSample]:
    """Per truthed target, the returns of clustered lidar ``scans``
    (:func:`~seatwin.evaluation.lidar_terms.lidar_return_samples`)."""
    from seatwin.evaluation.lidar_terms import lidar_return_samples
    from seatwin.evaluation.tracks_io import PlotLog
    from seatwin.perception.lidar import cluster_moment_rows

    log = PlotLog(
        np.array([s.time for s in scans], dtype=float),
        tuple(s.positions() for s in scans),
        None,
        np.array([s.sensor_position for s in scans], dtype=float).reshape(-1, 2),
        tuple(cluster_moment_rows(s) for s in scans),
    )
    out = lidar_return_samples(log, truth, dont_care)
    if out is None:
        raise InputError(truth.source, "no clustered lidar sweep to fit")
    return out


@dataclass
class FitSetup:
    """What every candidate is simulated and clustered with: the scenario, the real sweeps' instants, the water mask,
    the clustering, the truth (targets and don't-care vessels), the range model and the seeds."""

    scenario: Scenario
    starts: NDArray[np.float64]
    frames: NDArray[np.int64]
    truth: TruthSet
    dont_care: TruthSet | None = None
    mask: WaterMask | None = None
    clustering: LidarClustering | None = None
    lidar_mode: str = "raycast"
    seeds: tuple[int, ...] = (0, 1)
    _scene: Any = field(default=None, repr=False)
    ranged: dict[int, Any] = field(default_factory=dict, repr=False)
    """Per seed, every beam of the sweeps ranged once (:meth:`seatwin.sensors.lidar.Lidar.ranged`)."""

    @property
    def scene(self) -> Any:
        from seatwin.world.scene import Scene

        if self._scene is None:
            self._scene = Scene.from_scenario(self.scenario)
        return self._scene


def simulated_samples(setup: FitSetup, config: LidarConfig, seed: int) -> dict[str, LidarReturnSample]:
    """One seed's returns of the lidar ``config`` along ``setup``'s scenario at its sweep instants: each sweep posed
    with the ownship's pose at its start and the simulated mount, as
    :func:`seatwin.perception.from_recording.scans_from_recording` poses a recorded one, and clustered the same
    way. The beams are ranged once per seed (the ranging does not depend on the fitted parameters) and redrawn per
    candidate (:meth:`seatwin.sensors.lidar.Lidar.redraw`)."""
    import dataclasses

    from seatwin.perception.frames import Mount, sensor_pose
    from seatwin.perception.lidar import lidar_scan
    from seatwin.sensors.lidar import lidar_for_scenario

    sc = dataclasses.replace(setup.scenario, seed=int(seed))
    lidar = lidar_for_scenario(sc, setup.scene, config=config, range_model=setup.lidar_mode)
    mount = Mount(tuple(float(v) for v in lidar.mount.translation), lidar.mount.rotation())  # type: ignore[arg-type]
    own = sc.ownship.name  # type: ignore[union-attr]
    poses = setup.scene.pose(own, setup.starts)
    scans = []
    if seed not in setup.ranged:
        setup.ranged[seed] = lidar.ranged(list(setup.starts), list(setup.frames))
    for k, sweep in enumerate(lidar.redraw(setup.ranged[seed])):
        pose = sensor_pose(float(poses.north[k]), float(poses.east[k]), float(poses.heading[k]), mount)
        scans.append(lidar_scan(sweep.xyz, sweep.stamp, pose, setup.mask, setup.clustering))
    return scan_samples(scans, setup.truth, setup.dont_care)


# ---------------------------------------------------------------------------------------------- the fit


def _series(samples: Sequence[dict[str, LidarReturnSample]]) -> dict[str, list[NDArray[np.float64]]]:
    from seatwin.evaluation.lidar_terms import flatten_samples, term_series

    return term_series(flatten_samples(samples))


@dataclass
class Candidate:
    """One simulated candidate: its parameters, its terms' series (every seed) and its distance to the real run."""

    params: dict[str, float]
    series: dict[str, list[NDArray[np.float64]]]
    distance: float
    terms: dict[str, float]


@dataclass
class LidarFit:
    """The fitted lidar model, per parameter its estimate and 95 % interval, and how the fit went."""

    config: LidarConfig
    parameters: dict[str, dict[str, Any]]
    """Per fitted parameter: ``estimate``, ``ci95`` (block-bootstrap interval, see the module) and the search's final
    spacing (``step``, or ``step_factor`` for a parameter searched on a log scale)."""
    distance: float
    """The fitted model's combined lidar distance to the real run (the seeds of the search)."""
    terms: dict[str, float]
    """The fitted model's distance per term."""
    candidates: list[dict[str, Any]]
    """Every candidate simulated: parameters and distance, in the order tried."""
    n_sweeps: int
    seeds: tuple[int, ...]
    n_boot: int
    block: int
    """Block length [scans] of the bootstrap."""

    def report(self) -> dict[str, Any]:
        """What is written under ``fit:`` beside the fitted configuration."""
        return {
            "method": "lidar sensor-level distance (S7), coarse grid + refinement (1-D and drop/half range together); "
            "intervals: block bootstrap of the terms",
            "parameters": self.parameters,
            "distance": self.distance,
            "terms": self.terms,
            "n_sweeps": self.n_sweeps,
            "seeds": list(self.seeds),
            "n_boot": self.n_boot,
            "block": self.block,
            "n_candidates": len(self.candidates),
        }


def _key(params: dict[str, float]) -> tuple[float, ...]:
    return tuple(round(float(params[p]), 9) for p in PARAMETERS)


def _move(name: str, value: float, step: float) -> float:
    lo, hi = BOUNDS[name]
    v = float(np.exp(np.log(value) + step)) if LOG_SCALE[name] else value + step
    return float(f"{np.clip(v, lo, hi):.6g}")  # 6 digits: 0.8, not 0.7999999999999999


RIDGE = ("drop_probability", "dissipation_half_range_m")
"""The pair that trades off (more drop and a shorter half range both thin the returns: one makes up for the other):
the refinement also moves them together, along and across their ridge, where one-at-a-time moves stall."""
PASSES = 3
"""At most this many passes of the moves per refinement round, while a pass still improves (to follow the ridge)."""


def _moves(step: dict[str, float]) -> list[dict[str, float]]:
    """One pass of the refinement: ±1, ±2 steps of each parameter alone, then of the :data:`RIDGE` pair together
    (both signs alike and opposite)."""
    out = [{name: m * step[name]} for name in PARAMETERS for m in (-2, -1, 1, 2)]
    a, b = RIDGE
    out += [{a: m * step[a], b: sign * m * step[b]} for m in (-2, -1, 1, 2) for sign in (1, -1)]
    return out


def fit_lidar(
    real: Sequence[dict[str, LidarReturnSample]],
    setup: FitSetup,
    base: LidarConfig,
    *,
    rounds: int = 2,
    n_boot: int = 200,
    seed: int = 0,
    n_min: int = 10,
    progress: Callable[[int], None] | None = None,
) -> LidarFit:
    """Fit :data:`PARAMETERS` of ``base`` so that the simulated returns (``setup``) are nearest to the ``real`` ones
    (runs of target → :class:`LidarReturnSample`) in the lidar sensor-level distance: the coarse grid
    :data:`COARSE`, then ``rounds`` rounds of refinement (:func:`_moves`: ±1, ±2 steps of each parameter about the
    best, and of the :data:`RIDGE` pair together; up to :data:`PASSES` passes while one improves; the step halves
    each round). Intervals from ``n_boot`` block-bootstrap replicates (module docstring; ``seed``).
    Deterministic for the same inputs. ``progress(n)`` is called after each candidate."""
    from seatwin.evaluation.lidar_terms import combined_distance, flatten_samples, returns_block_length

    if rounds < 0:
        raise ParameterError("rounds", f"expected 0 or more refinement rounds, got {rounds}")
    if n_boot < 0:
        raise ParameterError("n_boot", f"expected 0 or more bootstrap resamples, got {n_boot}")
    ser_r = _series(real)
    if not any(np.isfinite(x).any() for xs in ser_r.values() for x in xs):
        raise InputError(setup.truth.source, "the recording has no lidar return near any target: nothing to fit")
    tried: dict[tuple[float, ...], Candidate] = {}

    def evaluate(params: dict[str, float]) -> Candidate:
        k = _key(params)
        if k not in tried:
            cfg = candidate_config(base, params)
            ser_s = _series([simulated_samples(setup, cfg, s) for s in setup.seeds])
            d, terms = combined_distance(ser_r, ser_s, n_min)
            tried[k] = Candidate(dict(params), ser_s, d if np.isfinite(d) else np.inf, terms)
            if progress is not None:
                progress(len(tried))
        return tried[k]

    best = min(
        (
            evaluate({"range_noise_m": a, "drop_probability": b, "dissipation_half_range_m": c})
            for a in COARSE["range_noise_m"]
            for b in COARSE["drop_probability"]
            for c in COARSE["dissipation_half_range_m"]
        ),
        key=lambda c: c.distance,
    )
    if not np.isfinite(best.distance):
        raise InputError(setup.truth.source, f"no lidar term has {n_min} values in both the recording and the simulation")
    step = dict(FIRST_STEP)
    for _ in range(rounds):
        for _ in range(PASSES):
            start = best
            for move in _moves(step):
                c = evaluate({k: _move(k, best.params[k], move.get(k, 0.0)) for k in PARAMETERS})
                if c.distance < best.distance:
                    best = c
            if best is start:
                break
        step = {k: v / 2 for k, v in step.items()}
    cands = list(tried.values())
    # The score's block rule (lidar_returns_score), on the real series.
    block = returns_block_length(flatten_samples(real))
    reps = bootstrap_best(ser_r, cands, n_boot, seed, n_min, block) if n_boot else []
    params: dict[str, dict[str, Any]] = {}
    for name in PARAMETERS:
        est = best.params[name]
        half = step[name]  # the last round's step, halved once more: half the final spacing
        lo_hi = (est, est) if not reps else tuple(np.percentile([r[name] for r in reps], [2.5, 97.5]))
        ci = [_move(name, float(lo_hi[0]), -half), _move(name, float(lo_hi[1]), half)]
        res = {"step_factor": float(np.exp(2 * half))} if LOG_SCALE[name] else {"step": float(2 * half)}
        params[name] = {"estimate": est, "ci95": ci if reps else None, **res}
    return LidarFit(
        candidate_config(base, best.params),
        params,
        best.distance,
        best.terms,
        [{**c.params, "distance": c.distance} for c in cands],
        len(setup.starts),
        tuple(setup.seeds),
        n_boot,
        block,
    )


def bootstrap_best(
    ser_r: dict[str, list[NDArray[np.float64]]],
    candidates: Sequence[Candidate],
    n_boot: int,
    seed: int,
    n_min: int,
    block: int,
) -> list[dict[str, float]]:
    """Per block-bootstrap replicate, the parameters of the candidate nearest to it. A replicate resamples every
    real (run, target) series and every simulated one in circular blocks of ``block`` scans; all candidates share
    the replicate's indices (their series have the same lengths: the same sweeps and seeds)."""
    from seatwin.evaluation.bootstrap import circular_block_indices
    from seatwin.evaluation.lidar_terms import combined_distance
    from seatwin.rng import frame_rng

    def lengths(ser: dict[str, list[NDArray[np.float64]]]) -> list[int]:
        return [len(x) for x in next(iter(ser.values()))]

    len_r, len_s = lengths(ser_r), lengths(candidates[0].series)
    rng = frame_rng(seed, "fit/lidar/bootstrap", 0)
    out = []
    for _ in range(n_boot):
        ir = [circular_block_indices(n, block, rng) for n in len_r]
        js = [circular_block_indices(n, block, rng) for n in len_s]
        d = [combined_distance(ser_r, c.series, n_min, ir, js)[0] for c in candidates]
        d = [x if np.isfinite(x) else np.inf for x in d]
        out.append(candidates[int(np.argmin(d))].params)
    return out


# ---------------------------------------------------------------------------------------------- the use-case


def fit_lidar_to_recording(
    recording: str | Path,
    scenario: str | None = None,
    *,
    base: str | Path | None = None,
    map_spec: str | None = None,
    lidar_mode: str = "raycast",
    start_offset: float = 0.0,
    duration: float | None = 20.0,
    every: int = 1,
    seeds: int = 2,
    rounds: int = 2,
    n_boot: int = 200,
    seed: int = 0,
    progress: Callable[[int], None] | None = None,
) -> LidarFit:
    """Fit the lidar model to ``recording`` (a run directory or bag with a lidar PointCloud2 topic and the ownship's
    ground truth) made along ``scenario`` (file or built-in name; default: the scenario beside the recording), over
    the sweeps ``start_offset`` to ``start_offset + duration`` seconds after the recording's first sweep (None: to
    the end), every ``every``-th of them (a longer span of ranges at the same cost). The candidates start from
    ``base`` (a lidar YAML; default the VLP-16 preset) and are simulated with ``lidar_mode`` and ``seeds`` seeds;
    both sides are clustered with the water mask of ``map_spec`` (default: the recording's). See :func:`fit_lidar`."""
    from seatwin.evaluation.truth import truth_from_scenario
    from seatwin.perception.from_recording import scans_from_recording
    from seatwin.perception.lidar import LidarClustering
    from seatwin.pipeline.track import harbour_of, moored_vessels, vessel_truth
    from seatwin.recording import open_bag
    from seatwin.scenario.load import load_scenario
    from seatwin.sensors.lidar_config import VLP16, load_lidar_config
    from seatwin.sensors.rangemodel import range_model_names

    if lidar_mode not in range_model_names():
        raise ParameterError("lidar_mode", f"unknown range model {lidar_mode!r}; known: {', '.join(range_model_names())}")
    if every < 1:
        raise ParameterError("every", f"expected 1 or more (use every n-th sweep), got {every}")
    if seeds < 1:
        raise ParameterError("seeds", f"expected 1 or more seeds, got {seeds}")
    if duration is not None and not duration > 0:
        raise ParameterError("duration", f"expected a positive number of seconds, got {duration:g}")
    if not start_offset >= 0:
        raise ParameterError("start_offset", f"expected 0 or more seconds, got {start_offset:g}")
    path = Path(recording)
    if not path.exists():
        raise InputError(path, "no such recording")
    cfg = load_lidar_config(base) if base else VLP16
    clustering = LidarClustering()
    mask, moored = harbour_of(map_spec, path)
    with open_bag(path) as rec:
        if scenario is None:
            beside = rec.scenario_file()
            if beside is None:
                raise ParameterError("scenario", "the recording has no scenario beside it: give the scenario that made it")
            scenario = str(beside)
        found = scans_from_recording(rec, ("lidar",), mask=mask, lidar=clustering, truth=vessel_truth(rec))
        if not found.topics.get("lidar"):
            raise InputError(path, "no lidar PointCloud2 topic in the recording")
        scans = list(found.scans)
    if not scans:
        raise InputError(path, "the lidar topic has no sweep")
    sc = load_scenario(str(scenario))
    times = np.array([s.time for s in scans])
    t0 = times[0] + start_offset
    keep = (times >= t0) & ((times < t0 + duration) if duration is not None else True)
    keep &= (times >= sc.start) & (times <= sc.end - cfg.period)
    if not keep.any():
        raise ParameterError(
            "start_offset",
            f"no sweep of the recording within the window and the scenario's span ({sc.start:.1f}–{sc.end:.1f} s)",
        )
    scans = [s for s, k in zip(scans, keep) if k][::every]
    truth = truth_from_scenario(sc)
    dont_care = moored_vessels(moored, truth, times)
    real = scan_samples(scans, truth, dont_care)
    starts = np.array([s.time for s in scans])
    rate = cfg.rate_hz
    frames = np.rint((starts - sc.start) * rate).astype(np.int64)
    setup = FitSetup(sc, starts, frames, truth, dont_care, mask, clustering, lidar_mode, tuple(range(seed, seed + seeds)))
    return fit_lidar([real], setup, cfg, rounds=rounds, n_boot=n_boot, seed=seed, progress=progress)
