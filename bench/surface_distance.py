"""Exact distance from points to a triangle mesh, for the benchmarks' Hausdorff measure.

MeshLab's Hausdorff filter finds each sample's nearest triangle with `vcg::face::PointDistanceBase`,
which, for a point projecting outside a triangle, returns its distance to the first edge (in the
triangle's vertex order) whose outside the projection lies on. Beyond an obtuse corner the
projection is outside two edges and the first is not always the nearer: where no other triangle
is nearer (along a border), the filter then reports the distance to the wrong edge
(docs/mesh_lod.md). `distances` gives the exact distance (Ericson, Real-Time Collision Detection,
5.1.5) from the same sample points.

Cost: the candidates of a point are the triangles whose bounding sphere reaches within its
nearest vertex's distance; triangles are bucketed by their spheres' radii (powers of two) so that a
few long ones do not widen every search.
"""
import numpy as np
from scipy.spatial import cKDTree

_CHUNK = 200_000  # point-triangle pairs evaluated at once


def _closest_sq(p, a, b, c):
    """Squared distance from each p to the triangle (a, b, c), row by row (Ericson's regions)."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = np.einsum("ij,ij->i", ab, ap), np.einsum("ij,ij->i", ac, ap)
    bp = p - b
    d3, d4 = np.einsum("ij,ij->i", ab, bp), np.einsum("ij,ij->i", ac, bp)
    cp = p - c
    d5, d6 = np.einsum("ij,ij->i", ab, cp), np.einsum("ij,ij->i", ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        den = va + vb + vc
        v_in, w_in = vb / den, vc / den
        q = a + ab * v_in[:, None] + ac * w_in[:, None]  # inside the face
        on_ab = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
        q = np.where(on_ab[:, None], a + ab * (d1 / (d1 - d3))[:, None], q)
        on_ac = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
        q = np.where(on_ac[:, None], a + ac * (d2 / (d2 - d6))[:, None], q)
        on_bc = (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        q = np.where(on_bc[:, None], b + (c - b) * w[:, None], q)
    q = np.where(((d1 <= 0) & (d2 <= 0))[:, None], a, q)
    q = np.where(((d3 >= 0) & (d4 <= d3))[:, None], b, q)
    q = np.where(((d6 >= 0) & (d5 <= d6))[:, None], c, q)
    # a degenerate triangle (den 0) falls to its edges and corners above, or to its nearest corner
    bad = ~np.isfinite(q).all(axis=1)
    if bad.any():
        corners = np.stack([a[bad], b[bad], c[bad]], axis=1)
        q[bad] = corners[np.arange(bad.sum()), np.argmin(((corners - p[bad, None]) ** 2).sum(-1), axis=1)]
    return ((p - q) ** 2).sum(axis=1)


def distances(points, vertices, faces):
    """Exact distance from each of `points` to the triangles `faces` over `vertices`."""
    points = np.asarray(points, dtype=np.float64)
    vertices = np.asarray(vertices, dtype=np.float64)
    faces = np.asarray(faces, dtype=np.int64)
    used = np.unique(faces)
    upper = cKDTree(vertices[used]).query(points)[0]  # a corner's distance bounds the surface's
    tri = vertices[faces]
    centre = tri.mean(axis=1)
    radius = np.sqrt(((tri - centre[:, None]) ** 2).sum(-1).max(axis=1))
    best = upper ** 2
    bucket = np.ceil(np.log2(np.maximum(radius, 1e-300) / radius.max() + 1e-300)).clip(-30, 0)
    for level in np.unique(bucket):
        ids = np.flatnonzero(bucket == level)
        reach = radius[ids].max()
        near = cKDTree(centre[ids]).query_ball_point(points, upper + reach)
        counts = np.fromiter((len(x) for x in near), dtype=np.int64, count=len(points))
        if counts.sum() == 0:
            continue
        pi = np.repeat(np.arange(len(points)), counts)
        ti = ids[np.concatenate([np.asarray(x, dtype=np.int64) for x in near if x])]
        for s in range(0, len(pi), _CHUNK):
            p, t = pi[s:s + _CHUNK], ti[s:s + _CHUNK]
            d = _closest_sq(points[p], tri[t, 0], tri[t, 1], tri[t, 2])
            np.minimum.at(best, p, d)
    return np.sqrt(best)
