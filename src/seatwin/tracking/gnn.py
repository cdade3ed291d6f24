"""A global-nearest-neighbour (GNN) tracker with the same EKF, models and track management as JIPDA.

The second, simpler "agent" for the fidelity question: if real and synthetic data look
alike to two different trackers, the distance measured is a property of the data, not of
one tracker's quirks.

It differs from :class:`~seatwin.tracking.tracker.JIPDATracker` only in the data association:
per scan one hard assignment of measurements to tracks (``scipy.optimize.linear_sum_assignment``
on the negative log of the same likelihood ratios, with a "missed" option per track), then a
plain EKF update of each track with its one measurement (:func:`seatwin.tracking.ekf.update`)
and no update for a missed track. Existence uses the same IPDA formula as JIPDA, restricted
to the chosen pair (``β₀ = miss / (miss + r·L)``). Prediction, gating, initiation,
confirmation and termination are inherited unchanged (same tuning file).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from seatwin.tracking import ekf
from seatwin.tracking.association import existence_posterior
from seatwin.tracking.config import SensorTuning
from seatwin.tracking.models import MeasurementModel
from seatwin.tracking.tracker import JIPDATracker, TrackTable

Array = NDArray[np.float64]
_LOG_2PI = math.log(2.0 * math.pi)
_FORBIDDEN = 1e12


def gnn_assign(log_ratio: Array, gated: NDArray[np.bool_], log_miss: Array) -> NDArray[np.int64]:
    """Best joint assignment: ``out[t]`` is the measurement of track t, or −1 for none.

    Maximises ``Σ log_ratio[t, j]`` over assigned pairs plus ``Σ log_miss[t]`` over missed
    tracks; only gated pairs may be assigned, each measurement to at most one track.
    """
    from scipy.optimize import linear_sum_assignment

    T, M = log_ratio.shape
    cost = np.full((T, M + T), _FORBIDDEN)
    cost[:, :M] = np.where(gated, -log_ratio, _FORBIDDEN)
    cost[np.arange(T), M + np.arange(T)] = -log_miss
    rows, cols = linear_sum_assignment(cost)
    out = np.full(T, -1, np.int64)
    ok = cols < M
    ok &= cost[rows, cols] < _FORBIDDEN / 2
    out[rows[ok]] = cols[ok]
    return out


class GNNTracker(JIPDATracker):
    """JIPDATracker with global-nearest-neighbour association (hard decisions)."""

    def _update(
        self, model: MeasurementModel, z: Array, R: Array, g2: float, pd_pg: float, tuning: SensorTuning, free_inside: bool
    ) -> Array:
        x, P, r = self.x, self.P, self.r
        zhat, H = model.predict(x)
        S = ekf.innovation_covariance(P, H, R)
        S_inv = ekf.inverse_small(S)
        v = model.residual(z, zhat)
        d2 = ekf.mahalanobis2(v, S_inv)
        gated = d2 < g2
        log_norm = -0.5 * (ekf.log_det_small(S) + z.shape[1] * _LOG_2PI)
        lam = model.clutter_density(z, tuning.clutter_density)
        # Initiation: the same rule as the JIPDA agent (soft marginals over the exclusion gate).
        unexplained = self._explained(r, d2, log_norm, lam, z.shape[1], tuning, free_inside)
        if not gated.any():
            self.r = existence_posterior(r, np.ones(r.size), pd_pg)[0]
            return unexplained
        log_L = math.log(tuning.p_detect) + log_norm[:, None] - 0.5 * d2 - np.log(lam)[None, :]
        miss = 1.0 - r * pd_pg
        choice = gnn_assign(np.log(np.maximum(r, 1e-300))[:, None] + log_L, gated, np.log(np.maximum(miss, 1e-300)))
        hit = choice >= 0
        beta0 = np.ones(r.size)
        if hit.any():
            t = np.flatnonzero(hit)
            det = r[t] * np.exp(np.clip(log_L[t, choice[t]], -700.0, 700.0))
            beta0[t] = miss[t] / (miss[t] + det)
            x_new, P_new, _ = ekf.update(x[t], P[t], v[t, choice[t]], H[t], R)
            self.x = x.copy()
            self.P = P.copy()
            self.x[t] = x_new
            self.P[t] = P_new
        self.r = existence_posterior(r, beta0, pd_pg)[0]
        return unexplained


def track_gnn(scans, config) -> TrackTable:  # noqa: ANN001
    """Run a fresh GNN tracker over ``scans`` (same tuning as :func:`seatwin.tracking.track`)."""
    return GNNTracker(config).run(scans)
