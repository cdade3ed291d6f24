"""Euclidean clustering (DBSCAN with min_samples = 1, i.e. single linkage cut at ``eps``).

Pairs closer than ``eps`` come from a k-d tree (``scipy.spatial.cKDTree.query_pairs``); the
clusters are the connected components of that graph (``scipy.sparse.csgraph``). Clusters with
fewer than ``min_points`` points are dropped as noise. Cost O(N log N) for N points.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree


def cluster_labels(points: NDArray[np.float64], eps: float, min_points: int = 1) -> NDArray[np.int64]:
    """Cluster label of each point (0, 1, …), −1 for points in clusters smaller than ``min_points``."""
    n = points.shape[0]
    if n == 0:
        return np.zeros(0, dtype=np.int64)
    pairs = cKDTree(points).query_pairs(eps, output_type="ndarray")
    graph = coo_matrix((np.ones(len(pairs), dtype=np.int8), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, labels = connected_components(graph, directed=False)
    counts = np.bincount(labels)
    keep = counts >= min_points
    remap = np.full(counts.size, -1, dtype=np.int64)
    remap[keep] = np.arange(int(keep.sum()))
    return remap[labels]


def cluster_centroids(
    points: NDArray[np.float64], eps: float, min_points: int = 1
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Centroids (K, dim) of the clusters and their point counts (K,)."""
    centroids, counts, _ = cluster_moments(points, eps, min_points)
    return centroids, counts


def cluster_moments(
    points: NDArray[np.float64], eps: float, min_points: int = 1
) -> tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.float64]]:
    """Centroids (K, dim), point counts (K,) and covariance matrices (K, dim, dim) of the clusters."""
    labels = cluster_labels(points, eps, min_points)
    ok = labels >= 0
    dim = points.shape[1] if points.ndim == 2 else 0
    if not ok.any():
        return np.zeros((0, dim)), np.zeros(0, dtype=np.int64), np.zeros((0, dim, dim))
    k = int(labels.max()) + 1
    lab, pts = labels[ok], points[ok]
    counts = np.bincount(lab, minlength=k)
    centroids = np.stack([np.bincount(lab, weights=pts[:, d], minlength=k) for d in range(dim)], axis=1) / counts[:, None]
    dev = pts - centroids[lab]
    cov = np.empty((k, dim, dim))
    for i in range(dim):
        for j in range(i, dim):
            cov[:, i, j] = cov[:, j, i] = np.bincount(lab, weights=dev[:, i] * dev[:, j], minlength=k) / counts
    return centroids, counts, cov


def minor_spread(cov: NDArray[np.float64]) -> NDArray[np.float64]:
    """The smallest principal standard deviation [m] of each (K, 2, 2) cluster covariance: a cluster's
    thickness across the surface it lies on (range noise thickens it, drop and distance thin it)."""
    if not len(cov):
        return np.zeros(0)
    return np.sqrt(np.maximum(np.linalg.eigvalsh(cov)[:, 0], 0.0))
