"""What a fidelity run measured: per radar model, per agent, per seed; ``fidelity.json`` is written from these."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field, fields
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from seatwin.evaluation import Comparison, Tracks
    from seatwin.fidelity.joyride import JoyrideData


@dataclass(frozen=True)
class PlotStatistics:
    """Simple statistics of a recording over the evaluation window."""

    plots_per_scan: float
    detection_rate: float
    """Share of scans with a plot within the gate of the target."""
    clutter_per_scan: float
    """Plots farther than the gate from the target, per scan."""

    @classmethod
    def mean(cls, items: list[PlotStatistics]) -> PlotStatistics:
        """The mean of each statistic over ``items`` (e.g. over seeds)."""
        return cls(*(float(np.mean([getattr(s, f.name) for s in items])) for f in fields(cls)))


@dataclass(frozen=True)
class OffTarget:
    """Confirmed tracks away from the target in the window: un-truthed vessels or persistent clutter."""

    tracks: int
    track_instants: int


@dataclass(frozen=True)
class WindowStats:
    """One real-versus-synthetic comparison over the evaluation window (one seed, one agent)."""

    hed: NDArray[np.float64]
    """HED (5.30, standard form) at the instants both datasets track the target, in time order."""
    hed_printed: NDArray[np.float64]
    covdiff: NDArray[np.float64]
    time: NDArray[np.float64]
    ahed: float | None
    mean_covdiff: float | None
    n_common: int
    n_only_real: int
    n_only_synthetic: int
    only_real_times: list[float]
    only_synthetic_times: list[float]
    nees_real: NDArray[np.float64]
    nees_synthetic: NDArray[np.float64]
    rmse_real: NDArray[np.float64]
    rmse_synthetic: NDArray[np.float64]
    seed: int


@dataclass(frozen=True)
class SeedResult:
    """What ``fidelity.json`` keeps of one seed's comparison."""

    ahed: float | None
    n_common: int
    n_only_real: int
    n_only_synthetic: int
    only_real_times: list[float]
    only_synthetic_times: list[float]
    seed: int

    @classmethod
    def of(cls, s: WindowStats) -> SeedResult:
        return cls(s.ahed, s.n_common, s.n_only_real, s.n_only_synthetic, s.only_real_times, s.only_synthetic_times, s.seed)


@dataclass(frozen=True)
class AgentResult:
    """One agent on one radar model: AHED with its interval and spread over seeds, the floor, the counts.

    Counts (``n_common`` …) and off-target figures of the synthetic side are means over seeds.
    """

    ahed: float | None
    ahed_ci: tuple[float, float]
    ahed_per_seed: list[float]
    ahed_printed: float | None
    ahed_seed_std: float
    ahed_seed_range: tuple[float, float] | None
    mean_covdiff: float | None
    off_target_tracks_synthetic: float
    off_target_instants_synthetic: float
    off_target_tracks_real: int
    off_target_instants_real: int
    floor_ahed: float | None
    """AHED between synthetic recordings of seeds s and s+1: what independent noise alone produces."""
    floor_ahed_ci: tuple[float, float] | None
    floor_pairs: int
    floor_n_common: float
    n_common: float
    n_only_real: float
    n_only_synthetic: float
    nees_real_mean: float | None
    nees_synthetic_mean: float | None
    rmse_real_mean: float | None
    rmse_synthetic_mean: float | None
    per_seed: list[SeedResult]
    score: float | None = None
    """The unpaired fidelity score (S5, :mod:`seatwin.evaluation.score`) on the evaluation window, all seeds
    pooled against the real run (0 = the same error distributions, coverage, clutter and false tracks); None
    when refused (``score_reason``)."""
    score_ci: tuple[float, float] | None = None
    score_reason: str | None = None
    """Why the score is refused, or which plot-level terms it is without."""
    score_parts: dict[str, Any] = field(default_factory=dict)
    """:meth:`seatwin.evaluation.score.FidelityScore.to_dict`: per target, clutter and false-track terms with their counts."""

    @property
    def only_one_fraction(self) -> float:
        """Share of the instants with a track in only one dataset (NaN without instants)."""
        tot = self.n_common + self.n_only_real + self.n_only_synthetic
        return (self.n_only_real + self.n_only_synthetic) / tot if tot else float("nan")


@dataclass
class ModelResult:
    """One radar model (default or fitted) against the real recording."""

    label: str
    radar: dict[str, Any]
    """The radar configuration (JSON form)."""
    agents: dict[str, AgentResult]
    synthetic_statistics: list[PlotStatistics]
    """Per seed."""
    comparisons: dict[str, Comparison] = field(default_factory=dict)
    """Per agent, the first seed's comparison over the whole recording (for the HTML report)."""
    example_plots: list[NDArray[np.float64]] | None = None
    """The first seed's plots per scan."""
    plot_terms: dict[str, Any] = field(default_factory=dict)
    """The radar plot-level terms on the evaluation window, all seeds pooled against the real recording
    (:func:`seatwin.evaluation.plot_terms.radar_plot_terms`, as dicts): per term real, model, signed difference."""
    sensor_score: dict[str, Any] = field(default_factory=dict)
    """The radar sensor score on the evaluation window, seeds pooled
    (:meth:`seatwin.evaluation.plot_terms.SensorScore.to_dict`): overall, parts, weights, block length."""
    plot_samples: list[Any] = field(default_factory=list, repr=False)
    """Per seed, the :class:`seatwin.evaluation.plot_terms.RadarPlotSample` the terms were computed from."""

    @property
    def synthetic_statistics_mean(self) -> PlotStatistics:
        return PlotStatistics.mean(self.synthetic_statistics)

    def to_json(self) -> dict[str, Any]:
        return {
            "agents": {a: asdict(d) for a, d in self.agents.items()},
            "synthetic_statistics_mean": asdict(self.synthetic_statistics_mean),
            "plot_terms": self.plot_terms,
            "sensor_score": self.sensor_score,
            "radar": self.radar,
        }


@dataclass
class FidelityResult:
    """The whole method's outcome; the primary model and agent are the headline."""

    dataset: str
    n_scans: int
    fit_on: str
    seeds: int
    seed0: int
    tuning: str
    """The tuning's name (noting a calibrated bearing bias)."""
    tracker_bearing_bias_deg: float
    window: tuple[float, float]
    """Evaluation window [POSIX s]."""
    n_window_scans: int
    real_statistics: PlotStatistics
    n_invalid_plots_dropped: int
    assumptions: dict[str, Any]
    radar_fit: dict[str, Any] | None
    models: dict[str, ModelResult]
    primary_model: str
    primary_agent: str
    real_tracks: dict[str, Tracks]
    data: JoyrideData
    dont_care: bool = True
    """Whether the un-truthed vessels were don't-care regions of the score's plot terms."""
    plot_term_leads: dict[str, dict[str, dict]] = field(default_factory=dict)
    """Per other model, per radar plot-level term, the primary model's lead (:func:`seatwin.fidelity.method.plot_term_leads`)."""

    @property
    def primary(self) -> AgentResult:
        return self.models[self.primary_model].agents[self.primary_agent]

    def ranking(self, agent: str | None = None) -> list[dict[str, Any]]:
        """The models ranked by ``agent``'s (default: the primary agent's) fidelity score, best (lowest) first;
        models with a refused score last, with the reason. Each row: model, score with its interval, AHED and
        its instant counts (means over seeds), the score's parts (target mean, clutter, false tracks)."""
        agent = agent or self.primary_agent
        rows = []
        for label, m in self.models.items():
            d = m.agents[agent]
            parts = d.score_parts
            rows.append(
                {
                    "model": label,
                    "score": d.score,
                    "ci_low": d.score_ci[0] if d.score_ci else None,
                    "ci_high": d.score_ci[1] if d.score_ci else None,
                    "ahed": d.ahed,
                    "n_common": d.n_common,
                    "n_only_real": d.n_only_real,
                    "n_only_synthetic": d.n_only_synthetic,
                    "targets": parts.get("score", {}).get("counts", {}).get("targets_mean"),
                    "clutter": parts.get("clutter", {}).get("value"),
                    "radar_sensor": parts.get("radar_sensor", {}).get("value"),
                    "false_tracks": parts.get("false_tracks", {}).get("value"),
                    "reason": d.score_reason,
                }
            )
        return sorted(rows, key=lambda r: (r["score"] is None, r["score"] if r["score"] is not None else 0.0))

    def to_json(self) -> dict[str, Any]:
        """The ``fidelity.json`` document (primary model and agent at top level; every model and agent below)."""
        prim = self.primary
        out: dict[str, Any] = {
            "ahed": prim.ahed,
            "ahed_ci": list(prim.ahed_ci),
            "n_common": prim.n_common,
            "n_only_real": prim.n_only_real,
            "n_only_synthetic": prim.n_only_synthetic,
            "score": prim.score,
            "score_ci": prim.score_ci,
            "score_reason": prim.score_reason,
            "fit_on": self.fit_on,
            "seeds": self.seeds,
            "model": self.primary_model,
            "agent": self.primary_agent,
            "window": list(self.window),
            "tuning": self.tuning,
            "tracker_bearing_bias_deg": self.tracker_bearing_bias_deg,
            "ahed_seed_std": prim.ahed_seed_std,
            "ahed_per_seed": prim.ahed_per_seed,
            "real_statistics": asdict(self.real_statistics),
            "assumptions": self.assumptions,
            "ranking": self.ranking(),
            "plot_term_leads": self.plot_term_leads,
            "models": {label: m.to_json() for label, m in self.models.items()},
        }
        if self.radar_fit is not None:
            out["radar_fit"] = self.radar_fit
        out["dataset"] = self.dataset
        return clean_json(out)


def clean_json(x: Any) -> Any:
    """``x`` with numpy values as Python ones, tuples as lists and non-finite floats as None."""
    if isinstance(x, dict):
        return {str(k): clean_json(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [clean_json(v) for v in x]
    if isinstance(x, np.ndarray):
        return clean_json(x.tolist())
    if isinstance(x, (np.floating, float)):
        v = float(x)
        return v if math.isfinite(v) else None
    if isinstance(x, np.integer):
        return int(x)
    return x
