"""JIPDA data association (thesis ch. 5.1.3): the validation gate and exact joint hypotheses.

A joint hypothesis assigns each track either no measurement (0) or one gated measurement,
each measurement to at most one track. Its weight is the product over tracks of

* ``1 − r_t P_D P_G`` if track t is unassigned (missed or non-existent),
* ``r_t · P_D · N(z_j; ẑ_t, S_t) / λ(z_j)`` if track t takes measurement j

(``r`` existence, ``P_D`` detection, ``P_G`` gate probability, ``λ`` clutter density at the
measurement). With ``r = 1`` this is exactly JPDA (Stone Soup's ``JPDA`` with
``PDAHypothesiser`` computes the same numbers; the tests check it to 1e-9).

Tracks that share no gated measurement are independent: the problem splits into clusters
(connected components of the track–measurement gate graph), and each cluster is enumerated
exactly, vectorised with numpy. The number of hypotheses of a cluster is bounded by
``Π_t (1 + m_t)`` (``m_t`` gated measurements of track t). **Approximation beyond the
cap:** if that bound exceeds ``max_hypotheses``, each track keeps only its ``k`` most likely
measurements (largest weight), with ``k`` the largest value for which the bound fits under
the cap; the dropped pairs get association probability 0 (they still count as clutter for
the other tracks). Below the cap the result is exact.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray
from scipy.stats import chi2

Array = NDArray[np.float64]


def gate_threshold(dim: int, g: float | None = None, probability: float | None = None) -> tuple[float, float]:
    """Return ``(g², P_G)`` for the validation gate ``vᵀ S⁻¹ v < g²`` (thesis eq. 5.23).

    Give either ``g`` (thesis: g = 1) or the gate probability ``P_G`` (χ² quantile with
    ``dim`` degrees of freedom). ``P_G`` is the probability that a target's measurement
    falls inside the gate: ``χ²_dim.cdf(g²)``.
    """
    if (g is None) == (probability is None):
        raise ValueError("give exactly one of g and probability")
    if g is not None:
        if g <= 0:
            raise ValueError(f"gate g must be positive, got {g}")
        return float(g * g), float(chi2.cdf(g * g, dim))
    if not 0.0 < probability < 1.0:
        raise ValueError(f"gate probability must be in (0, 1), got {probability}")
    return float(chi2.ppf(probability, dim)), float(probability)


def track_clusters(gated: NDArray[np.bool_]) -> list[list[int]]:
    """Connected components of tracks that share gated measurements (union–find)."""
    T = gated.shape[0]
    parent = list(range(T))

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    if T > 1:
        shared = np.argwhere(gated.sum(axis=0) > 1)[:, 0]
        for j in shared:
            ts = np.flatnonzero(gated[:, j])
            root = find(int(ts[0]))
            for t in ts[1:]:
                rt = find(int(t))
                if rt != root:
                    parent[rt] = root
    groups: dict[int, list[int]] = {}
    for t in range(T):
        groups.setdefault(find(t), []).append(t)
    return list(groups.values())


def _enumerate(options: list[Array], weights: list[Array]) -> tuple[NDArray[np.int64], Array]:
    """All feasible joint hypotheses (rows) and their weights; option 0 = unassigned."""
    hyp = np.zeros((1, 0), dtype=np.int64)
    w = np.ones(1)
    for opts, ow in zip(options, weights):
        n, o = hyp.shape[0], opts.shape[0]
        new = np.repeat(hyp, o, axis=0)
        col = np.tile(opts, n)
        nw = np.repeat(w, o) * np.tile(ow, n)
        if new.shape[1]:
            ok = (col == 0) | ~(new == col[:, None]).any(axis=1)
            new, col, nw = new[ok], col[ok], nw[ok]
        hyp = np.column_stack((new, col))
        w = nw
    return hyp, w


def jipda_marginals(
    existence: Array, likelihood_ratio: Array, gated: NDArray[np.bool_], pd_pg: float, max_hypotheses: int = 10000
) -> tuple[Array, Array]:
    """Marginal association probabilities of all tracks.

    ``existence`` (T,) predicted existence probabilities; ``likelihood_ratio`` (T, M) the
    ``P_D · N(z; ẑ, S) / λ`` of each pair (only read where ``gated``); ``pd_pg`` = P_D·P_G.
    Returns ``(beta0 (T,), beta (T, M))``: the probability that track t takes no
    measurement, and that it takes measurement j; each row sums to 1.
    """
    T, M = likelihood_ratio.shape
    miss = 1.0 - existence * pd_pg
    det = np.where(gated, existence[:, None] * likelihood_ratio, 0.0)
    # Tracks that share no gated measurement with another track: closed form (single-track PDA).
    tot = miss + det.sum(axis=1)
    beta0 = miss / tot
    beta = det / tot[:, None]
    shared = gated.sum(axis=0) > 1
    if not shared.any():
        return beta0, beta
    joint = gated[:, shared].any(axis=1)
    idx = np.flatnonzero(joint)
    for sub in track_clusters(gated[idx]):
        cluster = [int(idx[i]) for i in sub]
        cols = [np.flatnonzero(gated[t]) for t in cluster]
        cols = _cap(cols, [det[t] for t in cluster], max_hypotheses)
        options, weights = [], []
        for t, js in zip(cluster, cols):
            ow = np.concatenate(([miss[t]], det[t, js]))
            options.append(np.concatenate(([0], js + 1)))
            weights.append(ow / ow.max())  # a per-track scale cancels in the normalisation
        hyp, w = _enumerate(options, weights)
        w = w / w.sum()
        for k, t in enumerate(cluster):
            b = np.bincount(hyp[:, k], weights=w, minlength=M + 1)
            beta0[t] = b[0]
            beta[t] = b[1:]
    return beta0, beta


def _cap(cols: list[NDArray[np.int64]], det_rows: list[Array], max_hypotheses: int) -> list[NDArray[np.int64]]:
    """Keep each track's k most likely measurements so that Π (1 + m_t) ≤ max_hypotheses."""
    if math.prod(len(c) + 1 for c in cols) <= max_hypotheses:
        return cols
    longest = max(len(c) for c in cols)
    k = longest
    while k > 1 and math.prod(min(len(c), k) + 1 for c in cols) > max_hypotheses:
        k -= 1
    out = []
    for js, d in zip(cols, det_rows):
        if len(js) > k:
            js = np.sort(js[np.argsort(-d[js], kind="stable")[:k]])
        out.append(js)
    return out


def existence_posterior(existence: Array, beta0: Array, pd_pg: float) -> tuple[Array, Array]:
    """Posterior existence and the weight of 'exists but undetected' (JIPDA, Brekke ch. 7).

    ``r⁺ = (1 − β₀) + β₀ · r(1 − P_D P_G)/(1 − r P_D P_G)``. Returns ``(r⁺, w0)`` where
    ``w0`` is the probability, given existence, that the track took no measurement.
    """
    undetected = beta0 * existence * (1.0 - pd_pg) / (1.0 - existence * pd_pg)
    r_post = (1.0 - beta0) + undetected
    w0 = np.divide(undetected, r_post, out=np.ones_like(r_post), where=r_post > 0)
    return r_post, w0
