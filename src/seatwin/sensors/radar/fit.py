"""Fit the radar's parameters from a real recording's statistics, each with its uncertainty.

Input: per scan the real plots (world ``[north, east]``), the antenna position and the
ground-truth positions of the targets. Steps:

1. **Association.** A plot is target-originated when it lies within ``gate_m`` of a target;
   robust (median/MAD) range and bearing residuals then narrow the gate to ``k_sigma``
   standard deviations (so clutter near the target does not inflate the noise).
2. **Noise.** Bias and standard deviation of range and bearing residuals of the plot nearest
   each target.
3. **Detection.** Per (scan, target): detected or not; the rate per range bin (Wilson 95 %
   interval) and a maximum-likelihood fit of the Swerling model's ``snr_ref_db`` and
   ``pd_max`` (:mod:`.detection`) given each target's visible area.
4. **Clutter.** Plots not target-originated inside the coverage annulus: a uniform density
   (exact Poisson 95 % interval) and a world-fixed density map (counts over exposure).
5. **Uncertainty.** A bootstrap over scans (resampling whole scans) of every estimate:
   standard error and percentile 95 % interval.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.errors import InputError, ParameterError
from seatwin.geo.angles import wrap_to_pi
from seatwin.sensors.radar.clutter import annulus_area
from seatwin.sensors.radar.config import ClutterMap, DetectionConfig, RadarConfig
from seatwin.sensors.radar.detection import detection_probability


@dataclass
class RadarObservations:
    """Real radar plots with ground truth, one entry per scan."""

    time: NDArray[np.float64]
    plots: list[NDArray[np.float64]]
    """Per scan (m_k, 2) world ``[north, east]``."""
    antenna: NDArray[np.float64]
    """(n, 2) antenna ``[north, east]``."""
    truth: NDArray[np.float64]
    """(n, J, 2) target ``[north, east]`` (NaN where a target is absent)."""
    target_area_m2: NDArray[np.float64] = field(default_factory=lambda: np.array(10.0))
    """Visible area of each target, broadcastable to (n, J)."""
    source: str = "<memory>"

    def __post_init__(self) -> None:
        self.time = np.asarray(self.time, float).reshape(-1)
        n = len(self.time)
        self.antenna = np.asarray(self.antenna, float).reshape(n, 2)
        self.truth = np.asarray(self.truth, float)
        if self.truth.ndim == 2:
            self.truth = self.truth[:, None, :]
        if self.truth.shape[0] != n or self.truth.shape[2] != 2:
            raise InputError(self.source, f"truth must be (scans, targets, 2), got {self.truth.shape} for {n} scans")
        if len(self.plots) != n:
            raise InputError(self.source, f"{len(self.plots)} scans of plots for {n} scan times")
        self.plots = [np.asarray(p, float).reshape(-1, 2) for p in self.plots]
        area = np.asarray(self.target_area_m2, float)
        if area.ndim == 1 and area.shape[0] == n and self.truth.shape[1] != n:
            area = area[:, None]  # one value per scan
        self.target_area_m2 = np.broadcast_to(area, self.truth.shape[:2]).copy()

    def __len__(self) -> int:
        return int(self.time.shape[0])

    def subset(self, idx: ArrayLike) -> RadarObservations:
        i = np.asarray(idx)
        return RadarObservations(
            self.time[i], [self.plots[k] for k in i], self.antenna[i], self.truth[i], self.target_area_m2[i], self.source
        )


SNR_DB_BOUNDS = (-30.0, 80.0)
"""Search bounds of the fitted reference SNR [dB]."""


def polar_residuals(
    plots: NDArray[np.float64], antenna: NDArray[np.float64], target: NDArray[np.float64]
) -> tuple[NDArray, NDArray, float]:
    """Range [m] and bearing [rad] residuals of plots about a target seen from the antenna; the target's range."""
    dp = plots - antenna
    dt = target - antenna
    r_t = float(np.hypot(*dt))
    dr = np.hypot(dp[:, 0], dp[:, 1]) - r_t
    db = wrap_to_pi(np.arctan2(dp[:, 1], dp[:, 0]) - math.atan2(dt[1], dt[0]))
    return dr, db, r_t


@dataclass
class Association:
    """Per (scan, target): range, detected flag, residuals of the nearest plot; the clutter plots."""

    range_m: NDArray[np.float64]
    detected: NDArray[np.bool_]
    dr: NDArray[np.float64]
    db: NDArray[np.float64]
    n_plots: NDArray[np.int64]
    """Target-originated plots per (scan, target)."""
    clutter: list[NDArray[np.float64]]


def associate(
    obs: RadarObservations,
    gate_m: float,
    centre: tuple[float, float] = (0.0, 0.0),
    scale: tuple[float, float] | None = None,
    k_sigma: float = 4.0,
) -> Association:
    """Split plots into target-originated (within ``gate_m``, and within ``k_sigma`` of ``centre``
    in (range, bearing) when ``scale`` is given) and clutter."""
    n, J = obs.truth.shape[:2]
    rng = np.full((n, J), np.nan)
    det = np.zeros((n, J), bool)
    dr = np.full((n, J), np.nan)
    db = np.full((n, J), np.nan)
    npl = np.zeros((n, J), np.int64)
    clutter = []
    for k in range(n):
        p = obs.plots[k]
        used = np.zeros(len(p), bool)
        for j in range(J):
            t = obs.truth[k, j]
            if not np.isfinite(t).all():
                continue
            r, b, rt = polar_residuals(p, obs.antenna[k], t)
            rng[k, j] = rt
            if not len(p):
                continue
            ok = np.hypot(p[:, 0] - t[0], p[:, 1] - t[1]) <= gate_m
            if scale is not None:
                zr = (r - centre[0]) / max(scale[0], 1e-9)
                zb = (b - centre[1]) / max(scale[1], 1e-12)
                ok &= (np.abs(zr) <= k_sigma) & (np.abs(zb) <= k_sigma)
                d = np.hypot(zr, zb)
            else:
                d = np.hypot(r, b * rt)
            if ok.any():
                i = int(np.argmin(np.where(ok, d, np.inf)))
                det[k, j] = True
                dr[k, j], db[k, j] = r[i], b[i]
                npl[k, j] = int(ok.sum())
                used |= ok
        clutter.append(p[~used])
    return Association(rng, det, dr, db, npl, clutter)


def _robust(x: NDArray[np.float64]) -> tuple[float, float]:
    x = x[np.isfinite(x)]
    if len(x) < 2:
        return 0.0, 1.0
    med = float(np.median(x))
    return med, float(1.4826 * np.median(np.abs(x - med))) or float(np.std(x)) or 1.0


def fit_pd(
    range_m: NDArray[np.float64], area: NDArray[np.float64], detected: NDArray[np.bool_], base: DetectionConfig
) -> DetectionConfig:
    """Maximum-likelihood ``snr_ref_db`` and ``pd_max`` of the Swerling model (Bernoulli likelihood)."""
    from scipy.optimize import minimize

    ok = np.isfinite(range_m)
    r, a, y = range_m[ok], area[ok], detected[ok]

    def cfg(th: NDArray[np.float64]) -> DetectionConfig:
        return base.model_copy(update={"snr_ref_db": float(th[0]), "pd_max": float(1.0 / (1.0 + math.exp(-th[1])))})

    def nll(th: NDArray[np.float64]) -> float:
        p = np.clip(detection_probability(r, a, cfg(th).model_copy()), 1e-9, 1 - 1e-9)
        return -float(np.sum(np.where(y, np.log(p), np.log1p(-p))))

    best = None
    for s0 in (0.0, 15.0, 30.0, 45.0):
        res = minimize(nll, np.array([s0, 2.0]), method="Nelder-Mead", options={"xatol": 1e-4, "fatol": 1e-6, "maxiter": 2000})
        if best is None or res.fun < best.fun:
            best = res
    th = best.x
    th[0] = float(np.clip(th[0], *SNR_DB_BOUNDS))
    th[1] = float(np.clip(th[1], -10.0, 10.0))
    return cfg(th)


def wilson(k: int, n: int, z: float = 1.959964) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion."""
    if n == 0:
        return (0.0, 1.0)
    p = k / n
    den = 1 + z * z / n
    c = (p + z * z / (2 * n)) / den
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / den
    return (max(0.0, c - h), min(1.0, c + h))


def poisson_ci(k: int, z_level: float = 0.95) -> tuple[float, float]:
    """Exact (Garwood) interval of a Poisson count."""
    from scipy.stats import chi2

    a = 1 - z_level
    lo = 0.0 if k == 0 else float(chi2.ppf(a / 2, 2 * k) / 2)
    hi = float(chi2.ppf(1 - a / 2, 2 * k + 2) / 2)
    return lo, hi


def clutter_map(
    clutter: list[NDArray[np.float64]], antenna: NDArray[np.float64], cell_m: float, rmin: float, rmax: float
) -> ClutterMap:
    """World-fixed clutter density: counts per cell over (scans in which the cell was covered × cell area)."""
    pts = np.vstack([c for c in clutter if len(c)] or [np.empty((0, 2))])
    lo = antenna.min(0) - rmax
    hi = antenna.max(0) + rmax
    n0, e0 = np.floor(lo / cell_m) * cell_m
    rows = int(math.ceil((hi[0] - n0) / cell_m))
    cols = int(math.ceil((hi[1] - e0) / cell_m))
    counts = np.zeros((rows, cols))
    if len(pts):
        r = np.floor((pts[:, 0] - n0) / cell_m).astype(int)
        c = np.floor((pts[:, 1] - e0) / cell_m).astype(int)
        ok = (r >= 0) & (r < rows) & (c >= 0) & (c < cols)
        np.add.at(counts, (r[ok], c[ok]), 1)
    cn = n0 + (np.arange(rows) + 0.5) * cell_m
    ce = e0 + (np.arange(cols) + 0.5) * cell_m
    exposure = np.zeros((rows, cols))
    for a in antenna:
        d = np.hypot(cn[:, None] - a[0], ce[None, :] - a[1])
        exposure += (d >= rmin) & (d <= rmax)
    dens = np.where(exposure > 0, counts / np.maximum(exposure, 1) / cell_m**2, 0.0)
    return ClutterMap(north0_m=float(n0), east0_m=float(e0), cell_m=cell_m, density=dens.tolist(), outside_density=0.0)


def _estimates(
    obs: RadarObservations, base: RadarConfig, gate_m: float, k_sigma: float, range_bins: NDArray[np.float64]
) -> tuple[dict[str, float], Association, DetectionConfig]:
    a0 = associate(obs, gate_m)
    cr, sr = _robust(a0.dr.ravel())
    cb, sb = _robust(a0.db.ravel())
    a = associate(obs, gate_m, (cr, cb), (sr, sb), k_sigma)
    dr, db = a.dr[a.detected], a.db[a.detected]
    est: dict[str, float] = {
        "range_bias_m": float(np.mean(dr)) if len(dr) else 0.0,
        "range_sigma_m": float(np.std(dr, ddof=1)) if len(dr) > 1 else base.noise.range_sigma_m,
        "bearing_bias_deg": math.degrees(float(np.mean(db))) if len(db) else 0.0,
        "bearing_sigma_deg": math.degrees(float(np.std(db, ddof=1))) if len(db) > 1 else base.noise.bearing_sigma_deg,
        "detection_rate": float(a.detected[np.isfinite(a.range_m)].mean()),
        "plots_per_detection": float(a.n_plots[a.detected].mean()) if a.detected.any() else 0.0,
    }
    det = fit_pd(a.range_m, obs.target_area_m2, a.detected, base.detection)
    est["snr_ref_db"] = det.snr_ref_db
    est["pd_max"] = det.pd_max
    rmin, rmax = base.min_range_m, base.max_range_m
    n_cl = 0
    for k, c in enumerate(a.clutter):
        d = np.hypot(c[:, 0] - obs.antenna[k, 0], c[:, 1] - obs.antenna[k, 1])
        n_cl += int(((d >= rmin) & (d <= rmax)).sum())
    est["clutter_count"] = float(n_cl)
    est["clutter_per_scan"] = n_cl / len(obs)
    est["clutter_density_per_km2"] = n_cl / (len(obs) * annulus_area(rmin, rmax)) * 1e6
    rr = a.range_m[np.isfinite(a.range_m)]
    yy = a.detected[np.isfinite(a.range_m)]
    idx = np.digitize(rr, range_bins) - 1
    for b in range(len(range_bins) - 1):
        m = idx == b
        est[f"pd_bin_{b}"] = float(yy[m].mean()) if m.any() else float("nan")
    return est, a, det


def _stat(x: NDArray[np.float64], est: float) -> dict[str, Any]:
    x = x[np.isfinite(x)]
    if len(x) < 2:
        return {"estimate": est, "se": float("nan"), "ci95": [float("nan"), float("nan")]}
    return {
        "estimate": est,
        "se": float(np.std(x, ddof=1)),
        "ci95": [float(np.percentile(x, 2.5)), float(np.percentile(x, 97.5))],
    }


@dataclass
class RadarFit:
    """The fitted configuration and the report of the fit (estimates, standard errors, intervals)."""

    config: RadarConfig
    report: dict[str, Any]


def fit_radar(
    obs: RadarObservations,
    base: RadarConfig | None = None,
    gate_m: float = 60.0,
    k_sigma: float = 4.0,
    n_boot: int = 200,
    seed: int = 0,
    range_bin_m: float = 200.0,
    clutter: str = "uniform",
    map_cell_m: float = 250.0,
    fit_max_range: bool = True,
) -> RadarFit:
    """Fit noise, detection and clutter of ``base`` to ``obs``; uncertainty by a bootstrap over scans.

    ``clutter`` is ``"uniform"`` or ``"map"`` (a world-fixed density map of ``map_cell_m`` cells).
    With ``fit_max_range`` the maximum range becomes the farthest real plot (rounded up to 100 m).
    """
    from seatwin.rng import frame_rng

    base = base or RadarConfig()
    if len(obs) < 4:
        raise InputError(obs.source, f"a radar fit needs at least 4 scans, got {len(obs)}")
    if clutter not in ("uniform", "map"):
        raise ParameterError("clutter", f"expected 'uniform' or 'map', got {clutter!r}")
    if fit_max_range:
        far = max((float(np.hypot(*(p - obs.antenna[k]).T).max()) for k, p in enumerate(obs.plots) if len(p)), default=0.0)
        if far > base.min_range_m:
            base = base.model_copy(update={"max_range_m": float(math.ceil(far / 100.0) * 100.0)})
    bins = np.arange(0.0, base.max_range_m + range_bin_m, range_bin_m)
    est, assoc, det = _estimates(obs, base, gate_m, k_sigma, bins)
    rng = frame_rng(seed, "radar/fit/bootstrap", 0)
    boots: dict[str, list[float]] = {k: [] for k in est}
    for _ in range(n_boot):
        idx = rng.integers(0, len(obs), len(obs))
        try:
            e, _, _ = _estimates(obs.subset(idx), base, gate_m, k_sigma, bins)
        except (ValueError, FloatingPointError):  # pragma: no cover - degenerate resample
            continue
        for k in boots:
            boots[k].append(e.get(k, float("nan")))
    report: dict[str, Any] = {
        "source": obs.source,
        "n_scans": len(obs),
        "n_targets": int(obs.truth.shape[1]),
        "gate_m": gate_m,
        "k_sigma": k_sigma,
        "n_boot": n_boot,
        "max_range_m": base.max_range_m,
        "estimates": {k: _stat(np.asarray(v, float), est[k]) for k, v in boots.items() if not k.startswith("pd_bin_")},
    }
    notes = []
    ci = report["estimates"]["snr_ref_db"]["ci95"]
    if ci[0] == ci[0] and (ci[1] >= SNR_DB_BOUNDS[1] - 0.1 or ci[0] <= SNR_DB_BOUNDS[0] + 0.1):
        notes.append(
            "snr_ref_db is weakly identified (its interval reaches the search bound): the detection "
            "rate hardly changes over the ranges seen, so pd_max carries the detection model there"
        )
    report["notes"] = notes
    yy = assoc.detected[np.isfinite(assoc.range_m)]
    rr = assoc.range_m[np.isfinite(assoc.range_m)]
    table = []
    for b in range(len(bins) - 1):
        m = (rr >= bins[b]) & (rr < bins[b + 1])
        if not m.any():
            continue
        k, n = int(yy[m].sum()), int(m.sum())
        lo, hi = wilson(k, n)
        table.append(
            {
                "range_m": [float(bins[b]), float(bins[b + 1])],
                "scans": n,
                "detected": k,
                "rate": k / n,
                "wilson95": [lo, hi],
                "model": float(np.mean(detection_probability(rr[m], obs.target_area_m2[np.isfinite(assoc.range_m)][m], det))),
            }
        )
    report["detection_vs_range"] = table
    n_cl = int(est["clutter_count"])
    lo, hi = poisson_ci(n_cl)
    scale = 1e6 / (len(obs) * annulus_area(base.min_range_m, base.max_range_m))
    report["clutter_density_per_km2_poisson95"] = [lo * scale, hi * scale]
    noise = base.noise.model_copy(
        update={
            "range_bias_m": est["range_bias_m"],
            "range_sigma_m": max(est["range_sigma_m"], 0.0),
            "bearing_bias_deg": est["bearing_bias_deg"],
            "bearing_sigma_deg": max(est["bearing_sigma_deg"], 0.0),
        }
    )
    if clutter == "map":
        cmap = clutter_map(assoc.clutter, obs.antenna, map_cell_m, base.min_range_m, base.max_range_m)
        ccfg = base.clutter.model_copy(update={"kind": "map", "map": cmap, "density_per_km2": est["clutter_density_per_km2"]})
    else:
        ccfg = base.clutter.model_copy(update={"kind": "uniform", "density_per_km2": est["clutter_density_per_km2"], "map": None})
    cfg = base.model_copy(update={"noise": noise, "detection": det, "clutter": ccfg, "fit": _jsonable(report)})
    # Re-validate (model_copy does not).
    cfg = RadarConfig.model_validate(cfg.model_dump())
    return RadarFit(cfg, report)


def _jsonable(x: Any) -> Any:
    if isinstance(x, dict):
        return {str(k): _jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    if isinstance(x, (np.floating, float)):
        v = float(x)
        return None if not math.isfinite(v) else v
    if isinstance(x, (np.integer,)):
        return int(x)
    return x
