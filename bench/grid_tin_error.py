"""The vertical error of a TIN over a grid's nodes, as the height-field benchmark measures an LOD and the
tests check the greedy choice: |z - TIN(x, y)| at every node, each triangle against the nodes of its box,
numpy only."""
import numpy as np


def grid_tin_error(points, size, origin, step, vertices, triangles, chunk=1 << 20):
    """|z - TIN(x, y)| at every node of a size x size grid (node r * size + c of `points` at x = origin[0]
    + c * step[0], y = origin[1] + r * step[1]; a step may be negative) and the number of nodes no
    triangle covers (their error NaN), the TIN being `triangles` over `vertices` (any triangulation),
    a chunk of (triangle, node) pairs at a time."""
    lod = np.full(size * size, np.nan)
    a, b, c = (np.asarray(vertices, float)[np.asarray(triangles)[:, v]] for v in range(3))
    lo, hi = np.minimum(np.minimum(a, b), c), np.maximum(np.maximum(a, b), c)

    def nodes_between(axis):  # a thousandth of a cell of slack for float32 coordinates, clipped to the grid
        ends = (lo[:, axis] - origin[axis]) / step[axis], (hi[:, axis] - origin[axis]) / step[axis]
        first = np.clip(np.ceil(np.minimum(*ends) - 1e-3), 0, size).astype(np.int64)
        last = np.clip(np.floor(np.maximum(*ends) + 1e-3), -1, size - 1).astype(np.int64)
        return first, np.maximum(last - first + 1, 0)
    c0, width = nodes_between(0)
    r0, height = nodes_between(1)
    pairs = width * height
    ends = np.cumsum(pairs)
    start = 0
    while start < len(pairs):  # triangles [start, stop) hold about `chunk` pairs
        stop = max(start + 1, int(np.searchsorted(ends, ends[start] - pairs[start] + chunk, "right")))
        t = np.repeat(np.arange(start, stop), pairs[start:stop])
        local = np.arange(len(t)) - np.repeat(ends[start:stop] - pairs[start:stop] - (ends[start] - pairs[start]),
                                              pairs[start:stop])
        nodes = (r0[t] + local // width[t]) * size + c0[t] + local % width[t]
        p, ta, tb, tc = points[nodes], a[t], b[t], c[t]
        det = (tb[:, 0] - ta[:, 0]) * (tc[:, 1] - ta[:, 1]) - (tc[:, 0] - ta[:, 0]) * (tb[:, 1] - ta[:, 1])
        with np.errstate(divide="ignore", invalid="ignore"):  # flat triangles cover nothing
            wb = ((p[:, 0] - ta[:, 0]) * (tc[:, 1] - ta[:, 1]) - (tc[:, 0] - ta[:, 0]) * (p[:, 1] - ta[:, 1])) / det
            wc = ((tb[:, 0] - ta[:, 0]) * (p[:, 1] - ta[:, 1]) - (p[:, 0] - ta[:, 0]) * (tb[:, 1] - ta[:, 1])) / det
        wa = 1 - wb - wc
        inside = (det != 0) & (wa >= -1e-6) & (wb >= -1e-6) & (wc >= -1e-6)
        lod[nodes[inside]] = (wa * ta[:, 2] + wb * tb[:, 2] + wc * tc[:, 2])[inside]
        start = stop
    return np.abs(points[:, 2] - lod), int(np.isnan(lod).sum())
