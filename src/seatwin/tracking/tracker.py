"""The JIPDA multi-target tracker with extended Kalman filters (thesis ch. 5.1.3, Algorithm 2).

Per scan: predict every track (constant velocity, existence × P_S), gate (eq. 5.23), solve
the joint association per cluster (:mod:`.association`: exact where cheap, belief propagation
beyond), update each track with
the probability-weighted mixture of its EKF corrections (moment-matched to one Gaussian),
update existence, confirm/terminate by thresholds, delete tracks that cannot be boats (a
confirmed track whose speed is inconsistent with ``v_max``: :func:`too_fast`; a track faster than
``v_max`` + margin for more than ``speed_gate_scans`` scans; with a water mask, a track on land for
more than ``land_scans`` scans, and none is confirmed on land), then start tracks from pairs of
unassociated measurements of the same sensor within ``d = v_max·ΔT`` (thesis 5.1.3); a measurement
inside a track's exclusion gate counts as unassociated when the JIPDA says it is probably not that
track's (``init_association_max``: two boats close together get two tracks).

All tracks live in stacked arrays (``x`` (T, 4), ``P`` (T, 4, 4), ``r`` (T,)) so that each
step is a handful of vectorised numpy operations whatever the number of tracks.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError
from seatwin.perception.map_mask import WaterMask
from seatwin.perception.measurements import MeasurementKind, Scan, polar_to_cartesian
from seatwin.tracking import ekf
from seatwin.tracking.association import existence_posterior, gate_threshold, jipda_marginals
from seatwin.tracking.config import SensorTuning, TrackerConfig
from seatwin.tracking.models import MeasurementModel, cv_process_noise, cv_transition, model_for_scan

Array = NDArray[np.float64]

COLUMNS = (
    ["time", "track_id", "existence", "north", "v_north", "east", "v_east"]
    + [f"P{i}{j}" for i in range(4) for j in range(4)]
    + ["confirmed"]
)
"""Columns of the track table (one row per time and live track)."""

_LOG_2PI = math.log(2.0 * math.pi)


@dataclass
class TrackTable:
    """Track estimates, one row per (scan time, live track)."""

    time: Array
    track_id: NDArray[np.int64]
    existence: Array
    x: Array
    """(N, 4) north, v_north, east, v_east."""
    P: Array
    """(N, 4, 4)."""
    confirmed: NDArray[np.bool_]

    def __len__(self) -> int:
        return int(self.time.shape[0])

    def matrix(self) -> Array:
        """(N, 24) in :data:`COLUMNS` order (``confirmed`` as 0/1)."""
        return np.column_stack(
            (self.time, self.track_id, self.existence, self.x, self.P.reshape(-1, 16), self.confirmed.astype(float))
        )

    @classmethod
    def concatenate(cls, parts: list[TrackTable]) -> TrackTable:
        if not parts:
            return cls(np.zeros(0), np.zeros(0, np.int64), np.zeros(0), np.zeros((0, 4)), np.zeros((0, 4, 4)), np.zeros(0, bool))
        return cls(
            *(np.concatenate([getattr(p, f) for p in parts]) for f in ("time", "track_id", "existence", "x", "P", "confirmed"))
        )


def _position_covariance(scan: Scan, z: Array, tuning: SensorTuning) -> Array:
    """(M, 2, 2) north/east covariance of positional measurements (polar noise mapped by its Jacobian)."""
    M = z.shape[0]
    if scan.kind is MeasurementKind.CARTESIAN:
        return np.repeat((np.eye(2) * tuning.r_cartesian)[None], M, axis=0)
    r, b = z[:, 0], z[:, 1]
    c, s = np.cos(b), np.sin(b)
    J = np.empty((M, 2, 2))
    J[:, 0, 0], J[:, 0, 1], J[:, 1, 0], J[:, 1, 1] = c, -r * s, s, r * c
    return J @ np.diag([tuning.r_range, tuning.r_bearing]) @ np.swapaxes(J, 1, 2)


def speed_excess(x: Array, P: Array, v_max: float) -> tuple[Array, Array]:
    """Each track's estimated speed above ``v_max`` [m/s] and the standard deviation of its speed
    estimate (the velocity covariance along the velocity direction): ``(|v̂| − v_max, σ_|v|)``."""
    v = x[:, [1, 3]]
    speed = np.hypot(v[:, 0], v[:, 1])
    u = v / np.where(speed > 0, speed, 1.0)[:, None]
    Pv = P[:, [1, 3]][:, :, [1, 3]]
    var = np.einsum("ti,tij,tj->t", u, Pv, u)
    return speed - v_max, np.sqrt(np.maximum(var, 0.0))


def too_fast(x: Array, P: Array, config: TrackerConfig) -> NDArray[np.bool_]:
    """Tracks whose speed is inconsistent with the tuning's ``v_max``: beyond it by more than
    ``speed_gate_margin`` + ``speed_gate_sigma`` standard deviations of the speed estimate, or faster
    than ``speed_gate_limit`` × ``v_max`` (all False when ``speed_gate_sigma`` is None: the gate is off)."""
    c = config
    if c.speed_gate_sigma is None or not x.shape[0]:
        return np.zeros(x.shape[0], dtype=bool)
    excess, sigma = speed_excess(x, P, c.v_max)
    tolerance = np.minimum(c.speed_gate_margin + c.speed_gate_sigma * sigma, (c.speed_gate_limit - 1.0) * c.v_max)
    return excess > tolerance


class JIPDATracker:
    """Multi-target JIPDA tracker; feed it :class:`Scan` objects in time order with :meth:`step`."""

    def __init__(self, config: TrackerConfig, water: WaterMask | None = None):
        """``water``: the map's water mask; with it (and ``config.land_scans`` set) tracks on land are neither
        confirmed nor kept (:meth:`_manage`)."""
        self.config = config
        self.water = water
        self.x = np.zeros((0, 4))
        self.P = np.zeros((0, 4, 4))
        self.r = np.zeros(0)
        self.ids = np.zeros(0, dtype=np.int64)
        self.confirmed = np.zeros(0, dtype=bool)
        self.fast_scans = np.zeros(0, dtype=np.int64)
        """Consecutive scans each track has been faster than ``v_max`` + ``speed_gate_margin``."""
        self.land_scans = np.zeros(0, dtype=np.int64)
        """Consecutive scans each track's estimate has been on land."""
        self.time: float | None = None
        self._next_id = 1
        self.deleted_too_fast = 0
        """Tracks deleted so far for a speed beyond ``v_max`` (:func:`too_fast`, ``speed_gate_scans``)."""
        self.deleted_on_land = 0
        """Tracks deleted so far for staying on land (``land_scans``)."""
        # Unassociated positional measurements of each sensor's previous scan: (time, pos, cov, unexplained).
        self._pending: dict[str, tuple[float, Array, Array, Array]] = {}
        self._gates: dict[int, tuple[float, float]] = {}
        self._excl: dict[int, float] = {}
        self._excl_pg: dict[int, float] = {}
        self._R_cache: dict[tuple[str, str], Array] = {}
        self._FQ: tuple[float, Array, Array] | None = None

    # -- helpers ---------------------------------------------------------------------------
    def _gate(self, dim: int) -> tuple[float, float]:
        if dim not in self._gates:
            c = self.config
            self._gates[dim] = gate_threshold(dim, g=c.gate_g, probability=c.gate_probability)
            excl = gate_threshold(dim, probability=c.init_exclusion_probability)
            self._excl[dim], self._excl_pg[dim] = max(self._gates[dim], excl)
        return self._gates[dim]

    def _R(self, scan: Scan, tuning: SensorTuning) -> Array:
        key = (scan.sensor, scan.kind.value)
        R = self._R_cache.get(key)
        if R is None:
            if scan.kind is MeasurementKind.RANGE_BEARING:
                R = np.diag([tuning.r_range, tuning.r_bearing])
            elif scan.kind is MeasurementKind.BEARING:
                R = np.array([[tuning.r_bearing]])
            else:
                R = np.eye(2) * tuning.r_cartesian
            self._R_cache[key] = R
        return R

    def _predict(self, t: float) -> None:
        if self.time is None:
            self.time = t
            return
        dt = t - self.time
        if dt < 0:
            raise ValueError(f"scans must come in time order: {t} after {self.time}")
        if dt > 0 and self.r.size:
            c = self.config
            if self._FQ is None or self._FQ[0] != dt:
                self._FQ = (dt, cv_transition(dt), cv_process_noise(dt, c.q_north, c.q_east))
            self.x, self.P = ekf.predict(self.x, self.P, self._FQ[1], self._FQ[2])
            self.r = self.r * c.survival_per_second**dt
        self.time = t

    # -- one scan -------------------------------------------------------------------------
    def step(self, scan: Scan) -> TrackTable:
        """Process one scan; return the estimates of all live tracks at the scan time.

        A scan earlier than the last one, a non-finite time or non-finite measurements are an
        :class:`InputError` (the tracker's state is left as it was).
        """
        c = self.config
        if not math.isfinite(scan.time):
            raise InputError("scans", f"scan time must be finite, got {scan.time!r}")
        if self.time is not None and scan.time < self.time:
            raise InputError("scans", f"scans out of time order: a {scan.sensor} scan at {scan.time!r} after {self.time!r}")
        if not np.isfinite(scan.z).all():
            raise InputError("scans", f"{scan.sensor} scan at {scan.time!r} has non-finite measurements")
        tuning = c.sensor(scan.sensor)
        free_inside = c.init_association_max is not None and scan.sensor in c.init_association_sensors
        self._predict(scan.time)
        z = scan.z
        if tuning.bearing_bias and scan.kind is not MeasurementKind.CARTESIAN and z.shape[0]:
            z = z.copy()
            ai = 1 if scan.kind is MeasurementKind.RANGE_BEARING else 0
            z[:, ai] -= tuning.bearing_bias
        R = self._R(scan, tuning)
        dim = scan.kind.dim
        g2, pg = self._gate(dim)
        pd_pg = tuning.p_detect * pg
        T, M = self.r.size, z.shape[0]
        unexplained = np.ones(M)
        if T:
            model = model_for_scan(scan, R)
            if M:
                unexplained = self._update(model, z, R, g2, pd_pg, tuning, free_inside)
            else:
                self.r = existence_posterior(self.r, np.ones(T), pd_pg)[0]
            self._manage()
        if scan.kind is not MeasurementKind.BEARING:
            free = unexplained > 0
            self._initiate(scan, z[free], tuning, unexplained[free])
        return self.snapshot()

    def _update(
        self, model: MeasurementModel, z: Array, R: Array, g2: float, pd_pg: float, tuning: SensorTuning, free_inside: bool
    ) -> Array:
        """Update the tracks with one scan's measurements ``z``; return each measurement's probability of coming from
        no existing track as far as initiation is concerned (:meth:`_explained`; ``free_inside``: whether this scan's
        sensor may start tracks inside a track's exclusion gate, ``init_association_sensors``)."""
        x, P, r = self.x, self.P, self.r
        zhat, H = model.predict(x)
        S = ekf.innovation_covariance(P, H, R)
        S_inv = ekf.inverse_small(S)
        v = model.residual(z, zhat)  # (T, M, d)
        d2 = ekf.mahalanobis2(v, S_inv)
        gated = d2 < g2
        log_norm = -0.5 * (ekf.log_det_small(S) + z.shape[1] * _LOG_2PI)
        lam = model.clutter_density(z, tuning.clutter_density)
        if not gated.any():
            self.r = existence_posterior(r, np.ones(r.size), pd_pg)[0]
            return self._explained(r, d2, log_norm, lam, z.shape[1], tuning, free_inside)
        L = _likelihood_ratio(gated, d2, log_norm, lam, tuning.p_detect)
        c = self.config
        beta0, beta = jipda_marginals(r, L, gated, pd_pg, c.max_hypotheses, c.association, c.max_frontier_work)
        reuse = beta if self._excl[z.shape[1]] == g2 else None
        unexplained = self._explained(r, d2, log_norm, lam, z.shape[1], tuning, free_inside, reuse)
        r_post, w0 = existence_posterior(r, beta0, pd_pg)
        # Mixture of the EKF corrections, conditional on existence.
        W = ekf.gain(P, H, S_inv)  # (T, 4, d)
        xj = x[:, None, :] + v @ np.swapaxes(W, 1, 2)  # (T, M, 4)
        wj = beta / np.where(r_post > 0, r_post, 1.0)[:, None]
        x_new = w0[:, None] * x + (wj[:, None, :] @ xj)[:, 0, :]
        P_upd = ekf.update_covariance(P, W, H)
        dx0 = x - x_new
        dxj = xj - x_new[:, None, :]
        P_new = (
            w0[:, None, None] * (P + dx0[:, :, None] * dx0[:, None, :])
            + (1.0 - w0)[:, None, None] * P_upd
            + np.swapaxes(dxj * wj[:, :, None], 1, 2) @ dxj
        )
        self.x = x_new
        self.P = 0.5 * (P_new + np.swapaxes(P_new, 1, 2))
        self.r = r_post
        return unexplained

    def _explained(
        self,
        r: Array,
        d2: Array,
        log_norm: Array,
        lam: Array,
        dim: int,
        tuning: SensorTuning,
        free_inside: bool,
        beta: Array | None = None,
    ) -> Array:
        """(M,) each measurement's weight for initiation (thesis 5.1.3: only unassociated measurements start tracks):
        0 where existing tracks explain it (it starts nothing), else the probability that no existing track produced
        it (1 outside every track's exclusion gate). ``d2`` (T, M) squared Mahalanobis distances, ``log_norm`` (T,) the
        Gaussians' log normalisers, ``lam`` (M,) clutter densities; ``beta``: the JIPDA marginals when the
        validation gate is the exclusion gate (then reused).

        A measurement outside every track's exclusion gate is free. Inside one, without ``free_inside``
        (``init_association_max`` null or a sensor not in ``init_association_sensors``: the thesis's rule) it is
        explained; otherwise it is explained when the JIPDA posterior probability that an existing track produced
        it, Σ_t β_tj with the marginals solved over the exclusion gate, is at least ``init_association_max``, and
        free with weight 1 − Σ_t β_tj below it. A track takes at most one measurement a scan, so of two plots in one gate that one
        track cannot both explain (a second boat 20 m away), the less likely one stays free to start a track,
        whereas a track's own detection, alone in its gate, is explained unless it lies so far out that its
        likelihood is down to the clutter density's.
        """
        c = self.config
        inside = d2 < self._excl[dim]
        if not free_inside or not inside.any():
            return (~inside.any(axis=0)).astype(float)
        if beta is None:
            L = _likelihood_ratio(inside, d2, log_norm, lam, tuning.p_detect)
            pd_pg = tuning.p_detect * self._excl_pg[dim]
            beta = jipda_marginals(r, L, inside, pd_pg, c.max_hypotheses, c.association, c.max_frontier_work)[1]
        explained = np.clip(beta.sum(axis=0), 0.0, 1.0)
        return np.where(explained >= c.init_association_max, 0.0, 1.0 - explained)

    def _manage(self) -> None:
        """Confirm by existence (not on land); delete tracks below the termination threshold, confirmed tracks
        too fast for the tuning's ``v_max`` (:func:`too_fast`), tracks faster than ``v_max`` + ``speed_gate_margin``
        for more than ``speed_gate_scans`` consecutive scans, and tracks on land for more than ``land_scans``."""
        c = self.config
        over, on_land = self._over_limits(self.x)
        self.fast_scans = np.where(over, self.fast_scans + 1, 0)
        self.land_scans = np.where(on_land, self.land_scans + 1, 0)
        self.confirmed |= (self.r >= c.confirm_threshold) & ~on_land
        fast = self.confirmed & too_fast(self.x, self.P, c)
        if c.speed_gate_scans is not None:
            fast |= self.fast_scans > c.speed_gate_scans
        land = (self.land_scans > c.land_scans) & ~fast if c.land_scans is not None else np.zeros(self.r.size, dtype=bool)
        self.deleted_too_fast += int(fast.sum())
        self.deleted_on_land += int(land.sum())
        keep = (self.r >= c.terminate_threshold) & ~fast & ~land
        if not keep.all():
            self.x, self.P, self.r, self.ids, self.confirmed, self.fast_scans, self.land_scans = (
                self.x[keep],
                self.P[keep],
                self.r[keep],
                self.ids[keep],
                self.confirmed[keep],
                self.fast_scans[keep],
                self.land_scans[keep],
            )

    def _over_limits(self, x: Array) -> tuple[NDArray[np.bool_], NDArray[np.bool_]]:
        """Which states ``x`` are faster than ``v_max`` + ``speed_gate_margin``, and which lie on land (never
        without a water mask or with ``land_scans`` null)."""
        c = self.config
        over = np.hypot(x[:, 1], x[:, 3]) > c.v_max + c.speed_gate_margin
        on_land = np.zeros(x.shape[0], dtype=bool)
        if self.water is not None and c.land_scans is not None and x.shape[0]:
            on_land = ~np.asarray(self.water.is_water(x[:, 0], x[:, 2]), dtype=bool)
        return over, on_land

    def _initiate(self, scan: Scan, z: Array, tuning: SensorTuning, unexplained: Array) -> None:
        """Two-point initiation from unassociated measurements within d = v_max·ΔT (+ margin); a new track's
        existence is ``initial_existence`` × both measurements' ``unexplained`` probabilities (1 outside every
        track's exclusion gate: the thesis's initiation)."""
        pos = polar_or_cartesian(scan, z)
        cov = _position_covariance(scan, z, tuning) if z.shape[0] else np.zeros((0, 2, 2))
        prev = self._pending.get(scan.sensor)
        unused = np.ones(pos.shape[0], dtype=bool)
        if prev is not None and pos.shape[0] and prev[1].shape[0]:
            t0, pos0, cov0, u0 = prev
            dt = scan.time - t0
            if dt > 0:
                d_max = self.config.v_max * dt + self.config.init_margin
                dist = np.hypot(pos[:, None, 0] - pos0[None, :, 0], pos[:, None, 1] - pos0[None, :, 1])
                pairs = np.argwhere(dist <= d_max)
                if pairs.size:
                    order = np.argsort(dist[pairs[:, 0], pairs[:, 1]], kind="stable")
                    used0 = np.zeros(pos0.shape[0], dtype=bool)
                    new_i, new_k = [], []
                    for i, k in pairs[order]:
                        if unused[i] and not used0[k]:
                            unused[i] = False
                            used0[k] = True
                            new_i.append(i)
                            new_k.append(k)
                    r0 = self.config.initial_existence * unexplained[new_i] * u0[new_k]
                    self._add_tracks(pos[new_i], cov[new_i], pos0[new_k], cov0[new_k], dt, r0)
        self._pending[scan.sensor] = (scan.time, pos[unused], cov[unused], unexplained[unused])

    def _add_tracks(self, p1: Array, c1: Array, p0: Array, c0: Array, dt: float, r0: Array) -> None:
        n = p1.shape[0]
        if not n:
            return
        vel = (p1 - p0) / dt
        x = np.column_stack((p1[:, 0], vel[:, 0], p1[:, 1], vel[:, 1]))
        P = np.zeros((n, 4, 4))
        pos_i, vel_i = [0, 2], [1, 3]
        P[np.ix_(range(n), pos_i, pos_i)] = c1
        P[np.ix_(range(n), vel_i, vel_i)] = (c1 + c0) / dt**2
        P[np.ix_(range(n), pos_i, vel_i)] = c1 / dt
        P[np.ix_(range(n), vel_i, pos_i)] = c1 / dt
        self.x = np.concatenate((self.x, x))
        self.P = np.concatenate((self.P, P))
        self.r = np.concatenate((self.r, r0))
        self.ids = np.concatenate((self.ids, np.arange(self._next_id, self._next_id + n)))
        self.confirmed = np.concatenate((self.confirmed, np.zeros(n, dtype=bool)))
        # A new track's own scan counts: its first estimate may already be too fast or on land.
        fast, land = self._over_limits(x)
        self.fast_scans = np.concatenate((self.fast_scans, fast.astype(np.int64)))
        self.land_scans = np.concatenate((self.land_scans, land.astype(np.int64)))
        self._next_id += n

    def snapshot(self) -> TrackTable:
        """The live tracks now; a confirmed track whose estimate is on land (kept for up to ``land_scans`` scans,
        one noisy estimate beside a quay) is reported unconfirmed there, so no confirmed row is ever on land."""
        n = self.r.size
        return TrackTable(
            np.full(n, self.time if self.time is not None else np.nan),
            self.ids.copy(),
            self.r.copy(),
            self.x.copy(),
            self.P.copy(),
            self.confirmed & (self.land_scans == 0),
        )

    def run(self, scans: Iterable[Scan]) -> TrackTable:
        """Process all scans (:func:`run_tracker`'s rule for same-instant scans); the track table."""
        return run_tracker(self, scans).table


@dataclass
class TrackRun:
    """A tracker's output over a sequence of scans: the track table and the distinct scan instants."""

    table: TrackTable
    scan_times: NDArray[np.float64]


def run_tracker(
    tracker: JIPDATracker, scans: Iterable[Scan], on_scan: Callable[[Scan], None] | None = None, source: str = "<scans>"
) -> TrackRun:
    """Run ``tracker`` over time-ordered ``scans``; the one rule for scans at the same instant.

    Scans of several sensors at one instant are all processed, in the given order, and the
    tracks are recorded once, after the last of them (one row per live track and instant).
    Scans going back in time are an :class:`InputError` naming ``source``.
    """
    parts: list[TrackTable] = []
    times: list[float] = []
    for scan in scans:
        if times and scan.time < times[-1]:
            raise InputError(source, f"scans out of time order: {scan.time!r} after {times[-1]!r}")
        table = tracker.step(scan)
        if times and times[-1] == scan.time:
            parts[-1] = table
        else:
            parts.append(table)
            times.append(scan.time)
        if on_scan is not None:
            on_scan(scan)
    return TrackRun(TrackTable.concatenate(parts), np.asarray(times, dtype=np.float64))


def _likelihood_ratio(gated: NDArray[np.bool_], d2: Array, log_norm: Array, lam: Array, p_detect: float) -> Array:
    """(T, M) ``P_D · N(z_j; ẑ_t, S_t) / λ(z_j)`` where ``gated``, else 0."""
    with np.errstate(under="ignore"):
        return np.where(gated, p_detect * np.exp(log_norm[:, None] - 0.5 * d2) / lam[None, :], 0.0)


def polar_or_cartesian(scan: Scan, z: Array) -> Array:
    """North/east positions of positional measurements ``z`` of ``scan``'s kind."""
    if scan.kind is MeasurementKind.CARTESIAN:
        return z.reshape(-1, 2).copy()
    return polar_to_cartesian(z, (scan.sensor_north, scan.sensor_east))


def track(scans: Iterable[Scan], config: TrackerConfig, water: WaterMask | None = None) -> TrackTable:
    """Run a fresh tracker over ``scans`` (tracks on land of ``water`` handled per ``config.land_scans``)."""
    return JIPDATracker(config, water).run(scans)
