"""The count search's first radius on a cluster, exactly as one machine computes it.

One machine starts the search from the diagonal of the box holding the middle 98% of the points on each
axis (vcg_ext's GeodesicPoissonLod::CoreDiagonal: the coordinates of rank n/100 and n - 1 - n/100; the
whole box below 100 points or where that box is flat). Here those order statistics are found without
gathering the coordinates: each file counts its coordinates in the bins of a histogram, the bins
holding the wanted ranks are cut again until each holds few values, and those values are gathered.
Each pass decodes every file once; most clouds need two.
"""
from __future__ import annotations

import math
from typing import Sequence

import numpy as np

BINS = 4096
FEW = 200_000  # values gathered from a bin at most


def _member(x: np.ndarray, chain) -> np.ndarray:
    """Which values fall in the bin reached through `chain`, a list of (lo, hi, bin) histograms."""
    keep = np.ones(len(x), bool)
    for lo, hi, b in chain:
        keep &= _bin_of(x, lo, hi) == b
    return keep


def _bin_of(x: np.ndarray, lo: float, hi: float) -> np.ndarray:
    if not hi > lo:
        return np.zeros(len(x), np.int64)
    return np.clip(np.floor((x - lo) / (hi - lo) * BINS), 0, BINS - 1).astype(np.int64)


def file_pass(read_xyz, targets: Sequence[tuple], gather: bool):
    """A Dask task on one file: per target (axis, chain, lo, hi), its values' histogram over [lo, hi] among
    those in the chain's bin, or (gather) the values themselves; with the file's count, mins and maxs."""
    counts = [np.zeros(BINS, np.int64) for _ in targets]
    values = [[] for _ in targets]
    n, mins, maxs = 0, np.full(3, np.inf), np.full(3, -np.inf)
    for xyz in read_xyz():
        n += len(xyz)
        if len(xyz):
            mins, maxs = np.minimum(mins, xyz.min(axis=0)), np.maximum(maxs, xyz.max(axis=0))
        for k, (axis, chain, lo, hi) in enumerate(targets):
            x = xyz[:, axis]
            x = x[_member(x, chain)]
            if gather:
                values[k].append(np.unique(x, return_counts=True))
            else:
                counts[k] += np.bincount(_bin_of(x, lo, hi), minlength=BINS)
    out = [merge_unique(v) for v in values] if gather else counts
    return out, n, mins, maxs


def merge_unique(parts) -> tuple:
    """(distinct values, their counts) of several (values, counts) pairs."""
    if not parts:
        return np.empty(0), np.empty(0, np.int64)
    v, inverse = np.unique(np.concatenate([p[0] for p in parts]), return_inverse=True)
    return v, np.bincount(inverse, weights=np.concatenate([p[1] for p in parts]), minlength=len(v)).astype(np.int64)


def core_diagonal(run_pass, n: int, lo: np.ndarray, hi: np.ndarray) -> float:
    """CoreDiagonal of n points in the box [lo, hi] (approximate bounds: values beyond fall in the end bins),
    given run_pass(targets, gather) -> the per-file results of file_pass summed over the files:
    (list per target of counts or values, n, mins, maxs)."""
    cut = 0 if n < 100 else n // 100
    # One target per axis and side: the rank wanted and the chain of bins that hold it.
    wants = [(axis, rank) for axis in range(3) for rank in (cut, n - 1 - cut)]
    chains = [[] for _ in wants]
    ranges = [(float(lo[a]), float(hi[a])) for a, _ in wants]
    ranks = [r for _, r in wants]
    inside = [n] * len(wants)
    mins = maxs = None
    first = True
    while True:
        open_ = [k for k in range(len(wants)) if first or (inside[k] > FEW and ranges[k][1] > ranges[k][0]
                                                           and len(chains[k]) < 8)]
        if not open_:
            break
        counts, _, mins, maxs = run_pass([(wants[k][0], chains[k], *ranges[k]) for k in open_], False)
        for k, c in zip(open_, counts):
            lo_k, hi_k = ranges[k]
            if not hi_k > lo_k:  # bounds that say flat: the points' own, if they are not
                a = wants[k][0]
                ranges[k] = (float(mins[a]), float(maxs[a]))
                continue
            cum = np.cumsum(c)
            b = int(np.searchsorted(cum, ranks[k], side="right"))
            ranks[k] -= int(cum[b - 1]) if b else 0
            inside[k] = int(c[b])
            chains[k] = chains[k] + [(lo_k, hi_k, b)]
            # The end bins also hold the values beyond the bounds: cut them again over the values' own range.
            a = wants[k][0]
            low = lo_k + (hi_k - lo_k) * b / BINS if b > 0 else min(lo_k, float(mins[a]))
            high = lo_k + (hi_k - lo_k) * (b + 1) / BINS if b < BINS - 1 else max(hi_k, float(maxs[a]))
            ranges[k] = (low, high)
        first = False
    values, _, _, _ = run_pass([(wants[k][0], chains[k], *ranges[k]) for k in range(len(wants))], True)
    picked = [float(v[int(np.searchsorted(np.cumsum(c), r, side="right"))]) for (v, c), r in zip(values, ranks)]
    d2 = 0.0
    for axis in range(3):
        low, high = picked[2 * axis], picked[2 * axis + 1]
        d2 += (high - low) * (high - low)
    if d2 > 0 or cut == 0:
        return math.sqrt(d2)
    d2 = 0.0
    for axis in range(3):
        d2 += (float(maxs[axis]) - float(mins[axis])) * (float(maxs[axis]) - float(mins[axis]))
    return math.sqrt(d2)
