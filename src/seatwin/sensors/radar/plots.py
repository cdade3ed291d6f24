"""Plot extraction: cells above threshold (spoke, range sample) → plots (detections).

As in a real radar's plot extractor, cells that touch (within ``merge_gap_spokes`` spokes
and ``merge_gap_samples`` samples, azimuth wrapping round) form one blob, so the returns of
one target merge into one plot; a blob larger than ``max_plot_extent_m`` in range or
cross-range is split into tiles of that size, one plot each (large ships, land).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.geo.angles import circular_mean, wrap_to_2pi, wrap_to_pi
from seatwin.sensors.radar.config import RadarConfig

KIND_VESSEL = 0
KIND_LAND = 1
KIND_CLUTTER = 2
KIND_NAMES = {KIND_VESSEL: "vessel", KIND_LAND: "land", KIND_CLUTTER: "clutter"}


@dataclass
class Cells:
    """Radar cells above threshold in one scan: spoke index, range sample, source object, SNR."""

    spoke: NDArray[np.int64]
    sample: NDArray[np.int64]
    object_id: NDArray[np.int64]
    snr: NDArray[np.float64]

    @classmethod
    def empty(cls) -> Cells:
        return cls(np.empty(0, np.int64), np.empty(0, np.int64), np.empty(0, np.int64), np.empty(0))

    @classmethod
    def concat(cls, parts: list[Cells]) -> Cells:
        parts = [p for p in parts if len(p)]
        if not parts:
            return cls.empty()
        return cls(*(np.concatenate([getattr(p, f) for p in parts]) for f in ("spoke", "sample", "object_id", "snr")))

    def __len__(self) -> int:
        return int(self.spoke.shape[0])

    def unique(self) -> Cells:
        """One entry per (spoke, sample): the strongest return there."""
        if not len(self):
            return self
        order = np.lexsort((-self.snr, self.sample, self.spoke))
        s, r = self.spoke[order], self.sample[order]
        first = np.ones(len(order), bool)
        first[1:] = (s[1:] != s[:-1]) | (r[1:] != r[:-1])
        keep = order[first]
        return Cells(self.spoke[keep], self.sample[keep], self.object_id[keep], self.snr[keep])


@dataclass
class Blobs:
    """Extracted plots in polar form: range centroid [m], azimuth centroid [rad, 0..2π, clockwise
    from the bow], cell count, largest extent [m], the object most of its cells came from."""

    range_m: NDArray[np.float64]
    azimuth: NDArray[np.float64]
    n_cells: NDArray[np.int64]
    extent_m: NDArray[np.float64]
    object_id: NDArray[np.int64]
    snr: NDArray[np.float64]

    def __len__(self) -> int:
        return int(self.range_m.shape[0])


def components(spoke: ArrayLike, sample: ArrayLike, n_spokes: int, gap_spokes: int, gap_samples: int) -> NDArray[np.int64]:
    """Label of the connected blob of each cell (cells within the gaps are neighbours; azimuth wraps)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    a = np.asarray(spoke, float)
    r = np.asarray(sample, float)
    n = a.shape[0]
    if n == 0:
        return np.empty(0, np.int64)
    # Chebyshev distance ≤ 1 after scaling ⇔ |Δspoke| ≤ gap_spokes and |Δsample| ≤ gap_samples.
    pts = np.column_stack([a / gap_spokes, r / gap_samples])
    span = float(r.max() / gap_samples) * 2.0 + 4.0  # larger than any range distance: no wrap in range
    tree = cKDTree(pts, boxsize=[n_spokes / gap_spokes, span])
    pairs = tree.query_pairs(1.0 + 1e-9, p=np.inf, output_type="ndarray")
    g = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n)) if len(pairs) else coo_matrix((n, n))
    _, labels = connected_components(g, directed=False)
    return labels.astype(np.int64)


def extract_plots(cells: Cells, cfg: RadarConfig) -> Blobs:
    """Merge touching cells into blobs, split blobs larger than ``max_plot_extent_m``; one plot each.

    The plot position is the SNR-weighted centroid of its cells (range, and azimuth on the circle).
    """
    cells = cells.unique()
    pc = cfg.plots
    labels = components(cells.spoke, cells.sample, cfg.n_spokes, pc.merge_gap_spokes, pc.merge_gap_samples)
    out: list[tuple[float, float, int, float, int, float]] = []
    rng_m = cfg.range_start_m + (cells.sample + 0.5) * cfg.range_increment_m
    az = (cells.spoke + 0.5) * cfg.spoke_step
    w = np.maximum(cells.snr, 1e-12)
    order = np.argsort(labels, kind="stable")
    bounds = np.flatnonzero(np.diff(labels[order])) + 1
    for idx in np.split(order, bounds):
        if len(idx) < pc.min_cells:
            continue
        a0 = float(wrap_to_2pi(circular_mean(az[idx], w[idx])))
        dev = wrap_to_pi(az[idx] - a0)
        r = rng_m[idx]
        x = dev * r  # cross-range [m]
        ext_r = float(r.max() - r.min()) + cfg.range_increment_m
        ext_x = float(x.max() - x.min()) + cfg.spoke_step * float(r.mean())
        if max(ext_r, ext_x) > pc.max_plot_extent_m:
            tr = np.floor((r - r.min()) / pc.max_plot_extent_m).astype(np.int64)
            tx = np.floor((x - x.min()) / pc.max_plot_extent_m).astype(np.int64)
            tile = tr * (int(tx.max()) + 1) + tx
            groups = [idx[tile == t] for t in np.unique(tile)]
        else:
            groups = [idx]
        for g in groups:
            if len(g) < pc.min_cells:
                continue
            wg = w[g]
            ag = float(wrap_to_2pi(circular_mean(az[g], wg)))
            rg = rng_m[g]
            devg = wrap_to_pi(az[g] - ag)
            xg = devg * rg
            ext = max(
                float(rg.max() - rg.min()) + cfg.range_increment_m, float(xg.max() - xg.min()) + cfg.spoke_step * float(rg.mean())
            )
            ids, counts = np.unique(cells.object_id[g], return_counts=True)
            out.append((float((wg * rg).sum() / wg.sum()), ag, len(g), ext, int(ids[np.argmax(counts)]), float(wg.max())))
    if not out:
        e = np.empty(0)
        return Blobs(e, e.copy(), np.empty(0, np.int64), e.copy(), np.empty(0, np.int64), e.copy())
    arr = list(zip(*out))
    return Blobs(
        np.asarray(arr[0]),
        np.asarray(arr[1]),
        np.asarray(arr[2], np.int64),
        np.asarray(arr[3]),
        np.asarray(arr[4], np.int64),
        np.asarray(arr[5]),
    )
