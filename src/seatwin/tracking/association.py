"""JIPDA data association (thesis ch. 5.1.3): the validation gate, exact joint hypotheses, and BP.

A joint hypothesis assigns each track either no measurement (0) or one gated measurement,
each measurement to at most one track. Its weight is the product over tracks of

* ``1 − r_t P_D P_G`` if track t is unassigned (missed or non-existent),
* ``r_t · P_D · N(z_j; ẑ_t, S_t) / λ(z_j)`` if track t takes measurement j

(``r`` existence, ``P_D`` detection, ``P_G`` gate probability, ``λ`` clutter density at the
measurement). With ``r = 1`` this is exactly JPDA (Stone Soup's ``JPDA`` with
``PDAHypothesiser`` computes the same numbers; the tests check it to 1e-9).

Tracks that share no gated measurement are independent: the problem splits into clusters
(connected components of the track–measurement gate graph). **How each cluster is solved,
chosen automatically per cluster:**

* a track alone: closed form (single-track IPDA);
* ``Π_t (1 + m_t) ≤ max_hypotheses`` (``m_t`` gated measurements of track t, a bound on the
  number of joint hypotheses): **exact** enumeration, vectorised with numpy;
* larger but thin (a row of moored boats: few measurements "open" across any one track in a
  bandwidth-reducing order): the **exact** forward–backward pass :func:`frontier_marginals`,
  if its work stays within ``max_frontier_work``;
* otherwise (wide, dense clusters): **loopy belief propagation** (:func:`bp_marginals`;
  Williams & Lau, "Approximate evaluation of marginal association probabilities with belief
  propagation", IEEE TAES 50(4), 2014), cost ``O(iterations · edges)`` whatever the cluster.
  It is approximate (exact on tree-shaped gate graphs); its measured error against exact
  enumeration is in docs/architecture/tracking.md.
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
    """Connected components of tracks that share gated measurements, each in ascending order,
    ordered by their smallest track."""
    T = gated.shape[0]
    if T < 2 or not (gated.sum(axis=0) > 1).any():
        return [[t] for t in range(T)]
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import connected_components

    t, j = np.nonzero(gated)
    graph = csr_matrix((np.ones(t.size), (t, T + j)), shape=(T + gated.shape[1],) * 2)
    labels = connected_components(graph, directed=False)[1][:T]
    _, first, inverse = np.unique(labels, return_index=True, return_inverse=True)
    rank = np.argsort(np.argsort(first))  # components by their smallest track
    groups: list[list[int]] = [[] for _ in first]
    for k, c in enumerate(rank[inverse]):
        groups[c].append(k)
    return groups


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
    existence: Array,
    likelihood_ratio: Array,
    gated: NDArray[np.bool_],
    pd_pg: float,
    max_hypotheses: int = 10000,
    method: str = "auto",
    max_frontier_work: int = 20000,
) -> tuple[Array, Array]:
    """Marginal association probabilities of all tracks.

    ``existence`` (T,) predicted existence probabilities; ``likelihood_ratio`` (T, M) the
    ``P_D · N(z; ẑ, S) / λ`` of each pair (only read where ``gated``); ``pd_pg`` = P_D·P_G.
    ``method``: ``"auto"`` (per cluster: exact enumeration if its hypothesis bound is at most
    ``max_hypotheses``; else the exact forward–backward pass :func:`frontier_marginals` if its
    work stays within ``max_frontier_work``; else belief propagation), ``"exact"`` (always
    enumerate: cost exponential in the cluster), ``"bp"`` (belief propagation for every shared
    cluster).
    Returns ``(beta0 (T,), beta (T, M))``: the probability that track t takes no
    measurement, and that it takes measurement j; each row sums to 1.
    """
    if method not in ("auto", "exact", "bp"):
        raise ValueError(f"method must be auto, exact or bp, got {method!r}")
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
    approx: list[int] = []
    n_gated = gated.sum(axis=1)
    for sub in track_clusters(gated[idx]):
        cluster = [int(idx[i]) for i in sub]
        if method == "bp":
            approx.extend(cluster)
            continue
        if method == "auto" and math.prod(int(n_gated[t]) + 1 for t in cluster) > max_hypotheses:
            rows = np.asarray(cluster)
            used = np.flatnonzero(gated[rows].any(axis=0))
            out = frontier_marginals(gated[np.ix_(rows, used)], miss[rows], det[np.ix_(rows, used)], max_frontier_work)
            if out is None:
                approx.extend(cluster)
            else:
                beta0[rows] = out[0]
                beta[rows] = 0.0
                beta[np.ix_(rows, used)] = out[1]
            continue
        cols = [np.flatnonzero(gated[t]) for t in cluster]
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
    if approx:
        rows = np.sort(np.asarray(approx))
        cols_used = np.flatnonzero(gated[rows].any(axis=0))
        b0, b = bp_marginals(det[np.ix_(rows, cols_used)] / miss[rows, None])
        beta0[rows] = b0
        beta[rows] = 0.0
        beta[np.ix_(rows, cols_used)] = b
    return beta0, beta


def frontier_marginals(gated: NDArray[np.bool_], miss: Array, det: Array, max_work: int) -> tuple[Array, Array] | None:
    """Exact marginals of one cluster by a forward–backward pass over its tracks; None if too wide.

    ``gated`` (n, m) the cluster's gate matrix, ``miss`` (n,) and ``det`` (n, m) the weights of
    'no measurement' and of each pair (as in :func:`jipda_marginals`). Tracks are taken in
    reverse Cuthill–McKee order (small bandwidth of the track–track graph); the state after k
    tracks is the set of measurements already taken that a later track still gates (the
    "frontier", as in Horridge & Maskell, "Real-time tracking of hundreds of targets with
    efficient exact JPDAF implementation", FUSION 2006). The number of states stays small when
    the cluster is long but thin (a row of boats) even though the joint hypotheses are
    astronomically many. Returns ``(β₀ (n,), β (n, m))``, or ``None`` (cost bounded by
    ``max_work`` (state, option) pairs per pass) if 2^(most measurements open across one step)
    or the forward pass's count of (state, option) pairs exceeds ``max_work``.
    """
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import reverse_cuthill_mckee

    n, m = gated.shape
    rows, cols = np.nonzero(gated)
    inc = csr_matrix((np.ones(rows.size), (rows, cols)), shape=(n, m))
    order = reverse_cuthill_mckee(csr_matrix(inc @ inc.T), symmetric_mode=True)
    pos_of = np.empty(n, dtype=np.int64)
    pos_of[order] = np.arange(n)
    last = np.full(m, -1)
    first = np.full(m, n)
    np.maximum.at(last, cols, pos_of[rows])
    np.minimum.at(first, cols, pos_of[rows])
    # measurements open across each step (gated before and after it): 2^open bounds the states
    ok = last >= 0  # (a column no track gates is never open)
    opened = np.bincount(first[ok], minlength=n)[:n].cumsum() - np.bincount(last[ok], minlength=n)[:n].cumsum()
    if 2.0 ** min(int(opened.max()), 60) > max_work:
        return None
    local = [np.flatnonzero(gated[k]) for k in range(n)]
    weights = []
    for k in range(n):
        ow = np.concatenate(([miss[k]], det[k, local[k]]))
        weights.append(ow / ow.max())
    # Per step (track in order): its option bits (miss first), weights, and the bits that leave
    # the state after it (measurements no later track gates).
    steps = []
    for pos, k in enumerate(order):
        expire = sum(1 << int(c) for c in local[k] if last[c] == pos)
        steps.append(([1 << int(c) for c in local[k]], [float(x) for x in weights[k]], ~expire))
    alphas: list[dict[int, float]] = [{0: 1.0}]  # alphas[pos]: states before step pos
    work = 0
    for bits, w, keep in steps:
        work += len(alphas[-1]) * len(w)
        if work > max_work:
            return None
        nxt: dict[int, float] = {}
        for state, a in alphas[-1].items():
            key = state & keep
            nxt[key] = nxt.get(key, 0.0) + a * w[0]
            for b, wo in zip(bits, w[1:]):
                if not state & b:
                    key = (state | b) & keep
                    nxt[key] = nxt.get(key, 0.0) + a * wo
        top = max(nxt.values())  # rescaled per step (a per-step scale cancels): no underflow
        alphas.append({st: v / top for st, v in nxt.items()} if top > 0 else nxt)
    beta_next: dict[int, float] = {0: 1.0}
    beta0, beta = np.zeros(n), np.zeros((n, m))
    for pos in range(n - 1, -1, -1):
        bits, w, keep = steps[pos]
        marg = np.zeros(len(w))
        beta_here: dict[int, float] = {}
        for state, a in alphas[pos].items():
            c = w[0] * beta_next.get(state & keep, 0.0)
            marg[0] += a * c
            tot = c
            for i, (b, wo) in enumerate(zip(bits, w[1:]), start=1):
                if not state & b:
                    c = wo * beta_next.get((state | b) & keep, 0.0)
                    marg[i] += a * c
                    tot += c
            beta_here[state] = tot
        k = order[pos]
        marg /= marg.sum()
        beta0[k] = marg[0]
        beta[k, local[k]] = marg[1:]
        top = max(beta_here.values())
        beta_next = {st: v / top for st, v in beta_here.items()} if top > 0 else beta_here
    return beta0, beta


def bp_marginals(psi: Array, tol: float = 1e-10, max_iterations: int = 500) -> tuple[Array, Array]:
    """Association marginals by loopy belief propagation (Williams & Lau 2014, eqs. 30–31, 27).

    ``psi`` (T, M): the weight of track t taking measurement j relative to its 'no measurement'
    option (``r·L / (1 − r P_D P_G)`` for JIPDA; 0 where not gated); a measurement taken by no
    track has weight 1 (clutter, already divided out through ``λ``). Messages on the edges of
    the bipartite track–measurement graph, from ``ν = 1``:

    * track → measurement ``μ_tj = ψ_tj / (1 + Σ_{j'≠j} ψ_tj' ν_j't)``,
    * measurement → track ``ν_jt = 1 / (1 + Σ_{t'≠t} μ_t'j)``,

    iterated until no ``ν`` changes by more than ``tol`` (the iteration converges, Williams &
    Lau Thm. 1; ``max_iterations`` bounds the cost). Marginals: ``β_t0 ∝ 1``,
    ``β_tj ∝ ψ_tj ν_jt``. Exact when the gate graph is a tree; approximate when it has loops.
    ``ψ`` is capped at 10⁸ (a pair that much likelier than a miss is certain to ~1e-8), which
    keeps the "sum over the others" (total minus own term, per edge) free of cancellation.
    """
    T, M = psi.shape
    t, j = np.nonzero(psi)
    w = np.minimum(psi[t, j], _PSI_CAP)
    nu = np.ones(w.size)
    for _ in range(max_iterations):
        pn = w * nu
        mu = w / (1.0 + np.bincount(t, weights=pn, minlength=T)[t] - pn)
        nu_new = 1.0 / (1.0 + np.bincount(j, weights=mu, minlength=M)[j] - mu)
        done = np.abs(nu_new - nu).max(initial=0.0) <= tol
        nu = nu_new
        if done:
            break
    pn = w * nu
    tot = 1.0 + np.bincount(t, weights=pn, minlength=T)
    beta = np.zeros((T, M))
    beta[t, j] = pn / tot[t]
    return 1.0 / tot, beta


_PSI_CAP = 1e8


def existence_posterior(existence: Array, beta0: Array, pd_pg: float) -> tuple[Array, Array]:
    """Posterior existence and the weight of 'exists but undetected' (JIPDA, Brekke ch. 7).

    ``r⁺ = (1 − β₀) + β₀ · r(1 − P_D P_G)/(1 − r P_D P_G)``. Returns ``(r⁺, w0)`` where
    ``w0`` is the probability, given existence, that the track took no measurement.
    """
    undetected = beta0 * existence * (1.0 - pd_pg) / (1.0 - existence * pd_pg)
    r_post = (1.0 - beta0) + undetected
    w0 = np.divide(undetected, r_post, out=np.ones_like(r_post), where=r_post > 0)
    return r_post, w0
