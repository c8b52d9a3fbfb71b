"""geodesic_lod/height_field.py: height_field_lod on numpy arrays (vcg_ext/height_field_lod.h beneath)."""
import pathlib
import sys

import numpy as np
import pytest
from scipy.spatial import Delaunay

import geodesic_lod as gl

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "bench"))
from grid_tin_error import grid_tin_error  # noqa: E402  the height-field benchmark's measure


@pytest.fixture(scope="module")
def dem():
    """A 60 x 60 DEM at 30 m, a peak and ridges, with float32 noise."""
    y, x = np.mgrid[0:60, 0:60] * 30.0
    z = 300 * np.exp(-((x - 900) ** 2 + (y - 600) ** 2) / 2e5) + 50 * np.sin(x / 170) * np.cos(y / 230)
    z += np.random.default_rng(5).normal(0, 1, z.shape)
    return np.column_stack([x.ravel(), y.ravel(), z.ravel()])


def tin_error(points, idx):
    """|z - TIN(x, y)| of every point, the TIN being the Delaunay triangulation of points[idx] in x, y."""
    tri = Delaunay(points[idx, :2])
    simplex = tri.find_simplex(points[:, :2], tol=1e-9)
    assert (simplex >= 0).all()
    bary = np.einsum("ijk,ik->ij", tri.transform[simplex, :2], points[:, :2] - tri.transform[simplex, 2])
    w = np.column_stack([bary, 1 - bary.sum(1)])
    return np.abs(points[:, 2] - (w * points[idx][tri.simplices[simplex], 2]).sum(1))


def test_without_disks_each_sample_is_the_point_farthest_from_the_tin_before_it():
    # A grid as a DEM is: many points lie on the TIN's edges at some step, and heights in whole metres tie.
    y, x = np.mgrid[0:60, 0:60]
    z = np.round(80 * np.sin(x / 4.0) * np.cos(y / 5.0) + np.random.default_rng(1).integers(0, 6, x.shape))
    dem = np.column_stack([x.ravel() * 30.0, y.ravel() * 30.0, z.ravel()])
    lod = gl.height_field_lod(dem, count=900, separation=0)
    for k in range(lod.hull_size, 900, 5):
        error, uncovered = grid_tin_error(dem, 60, (0, 0), (30.0, 30.0), dem[lod.indices[:k]], lod.tin(k))
        assert uncovered == 0
        error[lod.indices[:k]] = -1
        assert error[lod.indices[k]] == pytest.approx(error.max(), abs=1e-9), k
        assert lod.errors[k] == pytest.approx(error.max(), abs=1e-9), k


def test_exact_counts_nested_and_separated(dem):
    before = dem.copy()
    big = gl.height_field_lod(dem, count=500)
    assert np.array_equal(dem, before)
    assert len(big.indices) == 500 == len(np.unique(big.indices))
    assert big.hull_size == 4 and big.separated_prefix == 500
    beta = gl.height_field.HEIGHT_FIELD_DEFAULTS.separation
    for k in (20, 180, 500):
        assert np.array_equal(gl.height_field_lod(dem, count=k).indices, big.indices[:k])
        xyz = dem[big.indices[:k]]  # the disks are in x, y, z by default
        d = np.linalg.norm(xyz[:, None] - xyz[None], axis=2) + np.eye(k) * 1e300
        assert d.min() >= beta * np.sqrt(big.area / k) * (1 - 1e-12)
    assert len(gl.height_field_lod(dem, rate=5).indices) == 180


def test_the_tin_of_a_prefix_covers_the_hull_and_uses_every_sample(dem):
    lod = gl.height_field_lod(dem, count=300)
    area = 59 * 30.0 * 59 * 30.0
    for k in (4, 57, 300):
        t = lod.tin(k)
        assert set(np.unique(t)) == set(range(k))
        p = dem[lod.indices[:k]]
        a, b, c = p[t[:, 0]], p[t[:, 1]], p[t[:, 2]]
        signed = ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1])) / 2
        assert (signed > 0).all() and np.isclose(signed.sum(), area)


def test_more_samples_smaller_error_and_the_constraint_costs_little(dem):
    rms = {}
    for beta in (0.0, gl.height_field.HEIGHT_FIELD_DEFAULTS.separation):
        for k in (100, 400):
            lod = gl.height_field_lod(dem, count=k, separation=beta)
            rms[beta, k] = np.sqrt(np.mean(tin_error(dem, lod.indices) ** 2))
    for beta in (0.0, gl.height_field.HEIGHT_FIELD_DEFAULTS.separation):
        assert rms[beta, 400] < 0.5 * rms[beta, 100]
    # Against a random choice of the same count the error-driven LOD is far better.
    rand = np.r_[[0, 59, 3540, 3599], np.random.default_rng(0).choice(np.arange(1, 3540), 396, replace=False)]
    assert rms[gl.height_field.HEIGHT_FIELD_DEFAULTS.separation, 400] < 0.7 * np.sqrt(
        np.mean(tin_error(dem, np.unique(rand)) ** 2))


def test_progress_and_interrupt(dem):
    seen = []
    gl.height_field_lod(dem, count=200, progress=seen.append)
    assert seen and seen == sorted(seen) and seen[-1] == 1.0

    def interrupt(x):
        if x > 0.5:
            raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        gl.height_field_lod(dem, count=200, progress=interrupt)


@pytest.mark.parametrize("kwargs, words", [
    (dict(count=3), "count must be between the 4 points on the hull"),
    (dict(count=10, rate=5), "exactly one of count or rate"),
    (dict(), "exactly one of count or rate"),
    (dict(count=10, separation=-1), "separation must be a non-negative"),
    (dict(count=10**6), "count must be from 1 to 3,600"),
    (dict(rate="x"), "rate must be a percentage"),
    (dict(count=10, separation_in="z"), "separation_in must be 'xyz' or 'xy'"),
])
def test_bad_arguments_are_named(dem, kwargs, words):
    with pytest.raises(gl.InputError, match=words):
        gl.height_field_lod(dem, **kwargs)


def test_bad_points_are_named(dem):
    line = np.column_stack([np.arange(10.0), np.arange(10.0), np.zeros(10)])
    with pytest.raises(gl.InputError, match="points holds only points on one line in x, y"):
        gl.height_field_lod(line, count=5)
    bad = dem.copy()
    bad[7, 2] = np.nan
    with pytest.raises(gl.InputError, match="points: 1 row has NaN"):
        gl.height_field_lod(bad, count=10)
    twice = np.vstack([dem, dem + [0, 0, 5]])
    with pytest.raises(gl.InputError, match="3,600 distinct points in x, y"):
        gl.height_field_lod(twice, count=3601)
    with pytest.raises(gl.InputError, match="k must be from 4"):
        gl.height_field_lod(dem, count=10).tin(3)


@pytest.mark.parametrize("grid", [np.zeros((60, 60)), np.zeros((60, 80), np.float32), np.zeros((60, 60), np.int16)],
                         ids=["float64", "float32", "int16"])
def test_a_grid_of_heights_is_refused_saying_how_to_give_its_nodes(grid):
    """A raster as GIS tools hold a DEM (rows by columns of heights) is not the points: the message says so and
    how to make them; a NaN void then gets the rows' message."""
    with pytest.raises(gl.InputError) as e:
        gl.height_field_lod(grid, rate=5)
    message = str(e.value)
    assert message.startswith("points must ") and (f"{grid.shape}" in message or "int16" in message), message
    assert "grid of heights" in message and "np.column_stack([x.ravel(), y.ravel(), heights.ravel()])" in message
    y, x = np.mgrid[0:grid.shape[0], 0:grid.shape[1]] * 30.0
    points = np.column_stack([x.ravel(), y.ravel(), np.sin(x / 300).ravel() * 100])
    assert len(gl.height_field_lod(points, count=100).indices) == 100
