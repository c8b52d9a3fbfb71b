"""Fixtures for the Python package's tests: synthetic clouds and meshes, the shared scans.

The package is imported from the build tree (build/python, which CTest puts on PYTHONPATH) or from
wherever it is installed."""
import numpy as np

from common_inputs import shared  # noqa: F401  (a fixture)


def bumpy_sphere(n=4000, seed=0):
    """n points on a unit sphere with bumps on one half: curvature varies over it."""
    rng = np.random.default_rng(seed)
    p = rng.normal(size=(n, 3))
    p /= np.linalg.norm(p, axis=1)[:, None]
    bump = np.where(p[:, 0] > 0, 0.08 * np.sin(9 * p[:, 1]) * np.sin(9 * p[:, 2]), 0.0)
    return p * (1 + bump)[:, None]


def grid_mesh(n=40):
    """A bumpy height field as n x n vertices and two triangles per cell."""
    x, y = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n), indexing="ij")
    z = np.where(x < 0.5, 0.0, 0.05 * (np.sin(8 * np.pi * x) * np.sin(8 * np.pi * y)) ** 2)
    pts = np.column_stack([x.ravel(), y.ravel(), z.ravel()])
    idx = np.arange(n * n).reshape(n, n)
    a, b, c, d = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    return pts, np.vstack([np.column_stack([a, b, c]), np.column_stack([a, c, d])])


def rows_of(points, subset):
    """The row of `points` each row of `subset` is an exact copy of (every subset row must be one)."""
    where = {row.tobytes(): i for i, row in enumerate(np.ascontiguousarray(points, dtype=np.float64))}
    rows = [where.get(r.tobytes(), -1) for r in np.ascontiguousarray(subset, dtype=np.float64)]
    assert -1 not in rows, "a sample is not an input point"
    return np.array(rows, dtype=np.int64)
