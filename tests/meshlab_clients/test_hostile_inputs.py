"""Hostile inputs through pymeshlab, for every filter of the plugin: neighbour counts past a connected
part, collinear points, extreme aspect ratios, georeferenced coordinates, radii below the point
spacing, deleted vertices, bad face indices, out-of-range parameters, empty and non-finite layers,
absurd level lists, and checks of the results on disconnected, non-manifold and degenerate input.

Each case ends in a PyMeshLabException whose message names the problem, or in a result checked by a
property (never a number copied from a run); the input layer is bit-identical afterwards."""
import re

import numpy as np
import pymeshlab
import pytest
from scipy.spatial import cKDTree

from conftest import bumpy_points
from test_bad_inputs import (CURVATURE, DEVIATION, FITTED, FPS, GRAPH, MESH_MODE, ON_INPUT, POISSON, PYRAMID,
                             TRIANGLES, degenerate_faces, empty, grid, layer, non_manifold, snapshot)


# ---------------------------------------------------------------------------------------------- helpers

def fails(ms, flt, match, **params):
    """The filter raises a PyMeshLabException matching `match`, adds no layer and leaves the input as it was;
    returns the message."""
    before, layers = snapshot(ms), ms.mesh_number()
    with pytest.raises(pymeshlab.PyMeshLabException, match=match) as err:
        ms.apply_filter(flt, **params)
    assert ms.mesh_number() == layers  # no half-made layer
    for a, b in zip(before, snapshot(ms)):
        np.testing.assert_array_equal(a, b)
    return str(err.value)


def runs(ms, flt, layers_added=1, **params):
    """The filter succeeds, adds `layers_added` layers and leaves the input as it was; returns its values."""
    before, layers = snapshot(ms), ms.mesh_number()
    res = ms.apply_filter(flt, **params)
    assert ms.mesh_number() == layers + layers_added
    for a, b in zip(before, snapshot(ms)):
        np.testing.assert_array_equal(a, b)  # the input layer, bit for bit (NaN included)
    return res


def sample_index(ms, lod=None):
    """Indices in the input layer (mesh 0) of the LOD's vertices; asserts each is an input vertex, exactly."""
    lod = ms.current_mesh() if lod is None else lod
    dist, idx = cKDTree(ms.mesh(0).vertex_matrix()).query(lod.vertex_matrix())
    assert np.all(dist == 0), "an output vertex is not an input vertex"
    return idx


def assert_valid_lod(ms, lod=None):
    """Samples are distinct input vertices; each keeps its input normal where that was valid (finite, non-zero;
    pymeshlab's own normals of a layer with faces are angle-weighted sums, not unit) and has an estimated unit
    normal elsewhere. Returns their input indices."""
    lod = ms.current_mesh() if lod is None else lod
    idx = sample_index(ms, lod)
    assert lod.vertex_number() >= 1
    assert len(np.unique(idx)) == len(idx)
    nrm, given = lod.vertex_normal_matrix(), ms.mesh(0).vertex_normal_matrix()[idx]
    assert np.all(np.isfinite(nrm))
    valid = np.isfinite(given).all(axis=1) & (np.abs(given).sum(axis=1) > 0)
    np.testing.assert_array_equal(nrm[valid], given[valid])
    np.testing.assert_allclose(np.linalg.norm(nrm[~valid], axis=1), 1.0, atol=1e-6)
    return idx


def assert_valid_faces(ms, lod=None):
    """Every face corner is a vertex of the LOD, and every LOD vertex is an input vertex."""
    lod = ms.current_mesh() if lod is None else lod
    f = lod.face_matrix()
    assert len(f) > 0
    assert f.min() >= 0 and f.max() < lod.vertex_number()
    sample_index(ms, lod)


def assert_covers(points, samples, radius):
    """Every point is within `radius` (Euclidean) of a sample: the metric is never shorter than Euclidean."""
    reach, _ = cKDTree(samples).query(points)
    assert reach.max() <= radius * (1 + 1e-9)


def grid_points(n, spacing=1.0, jitter=0.0, seed=0):
    """n x n points on z = 0 with the given spacing, optionally jittered in x and y."""
    x, y = np.meshgrid(np.arange(n) * spacing, np.arange(n) * spacing, indexing="ij")
    pts = np.column_stack([x.ravel(), y.ravel(), np.zeros(n * n)])
    if jitter:
        pts[:, :2] += np.random.default_rng(seed).uniform(-jitter, jitter, (n * n, 2))
    return pts


# ------------------------------------------------- 1. neighbour counts larger than a connected part

def two_clusters():
    """30 points (a 6 x 5 patch) and 300 points (a 20 x 15 patch) 100 units apart."""
    small = grid_points(6, spacing=0.1, jitter=0.01, seed=1)[:30]
    big = grid_points(20, spacing=0.1, jitter=0.01, seed=2)[:300] + [100.0, 0, 0]
    return np.vstack([small, big])


@pytest.mark.parametrize("flt,params", [
    (POISSON, {}),
    (FPS, {"samplenum": 2}),
    (FPS, {"samplenum": 40}),
    (PYRAMID, {"levels": "20%,2"}),
])
def test_neighbour_counts_past_a_connected_part(plugin, flt, params):
    """graphneighbors = normalneighbors = 50 with a part of 30 points (n = 330): not an error, a valid LOD
    (distinct input points with unit normals) in which each spatial part holds a sample."""
    ms = layer(two_clusters())
    runs(ms, flt, layers_added=2 if flt == PYRAMID else 1, graphneighbors=50, normalneighbors=50, **params)
    for k in range(1, ms.mesh_number()):
        idx = assert_valid_lod(ms, ms.mesh(k))
        assert (idx < 30).any() and (idx >= 30).any(), "a part of the input got no sample"


def test_neighbour_count_past_a_part_joins_the_parts(plugin):
    """A radius beyond the model gives one sample per connected part of the k-nearest graph: with
    graphneighbors = 10 the two clusters stay apart (one sample each); with graphneighbors = 50 the 30-point
    cluster's neighbour lists reach into the other one, the graph is one part, and one sample remains."""
    far = {"radius": pymeshlab.PureValue(1000.0)}
    ms = layer(two_clusters())
    runs(ms, POISSON, graphneighbors=10, **far)
    idx = assert_valid_lod(ms)
    assert len(idx) == 2 and (idx < 30).sum() == 1
    ms.set_current_mesh(0)
    runs(ms, POISSON, graphneighbors=50, normalneighbors=50, **far)
    assert len(assert_valid_lod(ms)) == 1


def test_curvature_with_normalneighbors_past_a_connected_part(plugin):
    ms = layer(two_clusters())
    ms.apply_filter(CURVATURE, normalneighbors=50)
    q = ms.current_mesh().vertex_scalar_array()
    assert len(q) == 330 and np.all(np.isfinite(q)) and np.all(q >= 0)


# ---------------------------------------------------------------------------------- 2. collinear points

def line(n=200):
    t = np.linspace(0, 10, n)
    return np.column_stack([t, 0.5 * t, -0.25 * t])


def line_but_one(n=200):
    return np.vstack([line(n), [[5.0, 5.0, 5.0]]])


@pytest.mark.parametrize("make", [line, line_but_one], ids=["all on a line", "all on a line but one"])
@pytest.mark.parametrize("flt,params", [
    (POISSON, {}),
    (POISSON, {"samplenum": 20}),
    (FPS, {"samplenum": 10}),
    (PYRAMID, {"levels": "50%,10%"}),
])
def test_collinear_points(plugin, make, flt, params):
    """Points on a line have no normal plane: no error; the LOD is valid (distinct input points, finite unit
    normals, perpendicular to the line when all points are on it), has the count asked for, and covers the
    line."""
    pts = make()
    ms = layer(pts)
    res = runs(ms, flt, layers_added=2 if flt == PYRAMID else 1, **params)
    for k in range(1, ms.mesh_number()):
        assert_valid_lod(ms, ms.mesh(k))
        if make is line:  # a normal of a line is perpendicular to it
            direction = np.array([1.0, 0.5, -0.25]) / np.linalg.norm([1.0, 0.5, -0.25])
            np.testing.assert_allclose(ms.mesh(k).vertex_normal_matrix() @ direction, 0.0, atol=1e-6)
    if flt == POISSON and "samplenum" not in params:
        assert_covers(pts, ms.current_mesh().vertex_matrix(), res["radius"])
    if "samplenum" in params:
        assert ms.current_mesh().vertex_number() == {FPS: 10, POISSON: 20}[flt]


@pytest.mark.parametrize("make", [line, line_but_one], ids=["all on a line", "all on a line but one"])
def test_collinear_points_curvature(plugin, make):
    ms = layer(make())
    ms.apply_filter(CURVATURE)
    q = ms.current_mesh().vertex_scalar_array()
    assert np.all(np.isfinite(q)) and np.all(q >= 0)


# ------------------------------------------------------------------- 3. a 1e6 x 1 x 1e-6 bounding box

def sliver(n=20000):
    rng = np.random.default_rng(3)
    return np.column_stack([rng.uniform(0, 1e6, n), rng.uniform(0, 1, n), rng.uniform(0, 1e-6, n)])


def test_extreme_aspect_ratio_poisson(plugin):
    """Poisson (default radius, 1% of the diagonal) on 20,000 points along 1e6 x 1 x 1e-6: valid samples,
    pairwise farther than the radius in the Euclidean metric, covering every point."""
    pts = sliver()
    ms = layer(pts)
    res = runs(ms, POISSON)
    assert_valid_lod(ms)
    assert_covers(pts, ms.current_mesh().vertex_matrix(), res["radius"])
    ms.set_current_mesh(0)
    res = runs(ms, POISSON, metric="Euclidean")
    s = ms.current_mesh().vertex_matrix()
    assert_valid_lod(ms)
    d, _ = cKDTree(s).query(s, k=2)
    assert d[:, 1].min() > res["radius"] * (1 - 1e-12)
    assert_covers(pts, s, res["radius"])


def test_extreme_aspect_ratio_fps_and_curvature(plugin):
    pts = sliver()
    ms = layer(pts)
    res = runs(ms, FPS, samplenum=50)
    assert_valid_lod(ms)
    assert ms.current_mesh().vertex_number() == 50
    assert_covers(pts, ms.current_mesh().vertex_matrix(), res["covering_radius"])
    ms.set_current_mesh(0)
    ms.apply_filter(CURVATURE)
    assert np.all(np.isfinite(ms.mesh(0).vertex_scalar_array()))


# ------------------------------------------------------------------------ 4. georeferenced coordinates

OFFSET = np.array([5e6, 5e6, 100.0])


def mm_grid():
    """100 x 100 points, 1 mm apart (jittered by up to 0.1 mm, so no two distances tie)."""
    return grid_points(100, spacing=1e-3, jitter=1e-4, seed=4)


@pytest.mark.parametrize("metric", ["Euclidean", None], ids=["Euclidean", "default metric"])
def test_georeferenced_coordinates(plugin, metric):
    """A 1 mm grid offset by (5e6, 5e6, 100) m: Poisson asked for 500 samples gives exactly 500, (Euclidean
    metric) pairwise farther than the returned radius, with normals +-z; and the same samples as the grid at
    the origin, up to double rounding of the coordinates (about 1e-9 m at 5e6 m)."""
    extra = {} if metric is None else {"metric": metric}
    out = {}
    for name, shift in (("origin", np.zeros(3)), ("offset", OFFSET)):
        pts = mm_grid() + shift
        ms = layer(pts)
        res = runs(ms, POISSON, samplenum=500, **extra)
        lod = ms.current_mesh()
        assert lod.vertex_number() == res["sample_num"] == 500
        assert_valid_lod(ms)
        np.testing.assert_allclose(np.abs(lod.vertex_normal_matrix()[:, 2]), 1.0, atol=1e-6)
        s = lod.vertex_matrix()
        if metric == "Euclidean":
            d, _ = cKDTree(s).query(s, k=2)
            assert d[:, 1].min() > res["radius"] * (1 - 1e-12)
        out[name] = (s - shift, res["radius"])
    (a, ra), (b, rb) = out["origin"], out["offset"]
    assert len(a) == len(b)
    assert rb == pytest.approx(ra, rel=1e-4)
    # Same samples in the same order, moved back by the offset (float64 spacing at 5e6 m: ~1e-9 m).
    np.testing.assert_allclose(b, a, rtol=0, atol=1e-8)


# ----------------------------------------------------------------- 5. a radius below the point spacing

def test_radius_below_the_spacing_on_200k_points(plugin):
    """A radius of a tenth of the spacing on 202,500 points: every point becomes a sample."""
    pts = grid_points(450, spacing=1.0)
    pts[:, 2] = 0.3 * np.sin(pts[:, 0] / 7.0) * np.cos(pts[:, 1] / 11.0)
    ms = layer(pts)
    res = runs(ms, POISSON, radius=pymeshlab.PureValue(0.1))
    assert res["sample_num"] == ms.current_mesh().vertex_number() == len(pts)
    idx = sample_index(ms)
    assert np.array_equal(np.sort(idx), np.arange(len(pts)))


# --------------------------------------------------------------------------------- 6. deleted vertices

def test_deleted_vertices(plugin):
    """pymeshlab compacts the layer when vertices are removed (meshing_remove_selected_vertices leaves
    is_compact() true), so deleted-but-not-compacted vertices never reach the plugin through pymeshlab;
    the plugin's own skipping of them (PointSetFromMesh) is covered by the C++ tests. Here: the removed
    vertices are never sampled, and the counts are those of the remaining vertices."""
    pts = bumpy_points(20)
    ms = layer(pts)
    ms.compute_selection_by_condition_per_vertex(condselect="x < 0.3")
    removed = pts[:, 0] < 0.3
    ms.meshing_remove_selected_vertices()
    m = ms.current_mesh()
    assert m.is_compact()
    kept = int((~removed).sum())
    assert m.vertex_number() == kept
    res = runs(ms, POISSON, radius=pymeshlab.PureValue(1e-4))  # below the spacing: every remaining vertex
    assert res["sample_num"] == kept
    assert ms.current_mesh().vertex_matrix()[:, 0].min() >= 0.3
    ms.set_current_mesh(0)
    runs(ms, FPS, samplenum=kept)
    fails(ms, FPS, re.escape(f"samplenum must be between 1 and the number of points ({kept})"), samplenum=kept + 1)


# ------------------------------------------------------------------------------ 7. bad face indices

@pytest.mark.parametrize("bad", [400, 10**6, -1, -7, 2**31 - 1])
def test_out_of_range_face_index_is_refused_by_pymeshlab(plugin, bad):
    """pymeshlab.Mesh checks int32 face indices itself: an index < 0 or >= the vertex count is an error
    ("bad vertex index") before any filter runs."""
    pts, faces = grid(20)
    faces = faces.copy()
    faces[5, 1] = bad
    with pytest.raises(pymeshlab.PyMeshLabException, match=re.escape(f"bad vertex index {bad} in face 5")):
        pymeshlab.Mesh(vertex_matrix=pts, face_matrix=faces.astype(np.int32))


def test_int64_face_index_beyond_int32_wraps_in_pymeshlab(plugin):
    """int64 indices are narrowed to int32 by pymeshlab's conversion without a check: 2**32 + 3 becomes 3.
    The plugin only ever sees the wrapped (valid) index, and the LOD of that mesh is valid."""
    pts, faces = grid(20)
    faces = faces.astype(np.int64)
    faces[5, 1] = 2**32 + 3
    m = pymeshlab.Mesh(vertex_matrix=pts, face_matrix=faces)
    assert m.face_matrix()[5, 1] == 3
    ms = pymeshlab.MeshSet()
    ms.add_mesh(m, "input")
    runs(ms, FPS, samplenum=30, geodesicmode=MESH_MODE, output=ON_INPUT)
    assert_valid_faces(ms)


# ---------------------------------------------------------------------- 8. out-of-range parameters

@pytest.mark.parametrize("tol", [-1.0, -1e-9, -100.0])
def test_negative_tolerance(plugin, tol):
    fails(layer(bumpy_points(10)), POISSON, "tolerance must be at least 0", samplenum=10,
          tolerance=tol)


@pytest.mark.parametrize("maxdist", [pymeshlab.PureValue(0), pymeshlab.PureValue(-1.0), pymeshlab.PureValue(-1e-300),
                                     pymeshlab.PercentageValue(0)], ids=["0", "-1", "-1e-300", "0%"])
def test_maxdist_not_positive(plugin, maxdist):
    """(pymeshlab itself refuses a negative PercentageValue, before any filter runs.)"""
    fails(layer(*grid(), normals=np.tile([0, 0, 1.0], (144, 1))), DEVIATION, "maxdist must be a positive number",
          referencemesh=0, surfacemesh=0, maxdist=maxdist)


# ------------------------------------------------------- 9. empty and non-finite layers, pyramid and eq. 1

def nan_layer(bad):
    pts = bumpy_points(10)
    pts[[3, 40]] = bad
    return layer(pts)


@pytest.mark.parametrize("params", [{}, {"levels": "1"}, {"levels": "10"}], ids=["default levels", "1", "10"])
def test_pyramid_of_an_empty_layer(plugin, params):
    """An empty layer: the error says the layer has no vertices (as for the other filters), not that a level's
    count is out of range."""
    fails(empty(), PYRAMID, "the layer holds no points", **params)


def test_curvature_of_an_empty_layer(plugin):
    fails(empty(), CURVATURE, "the layer holds no points")


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf], ids=["NaN", "inf", "-inf"])
@pytest.mark.parametrize("flt", [PYRAMID, CURVATURE])
def test_non_finite_coordinates(plugin, flt, bad):
    fails(nan_layer([bad, 0, 0]), flt, re.escape("the layer holds 2 points with NaN or infinite coordinates"))


@pytest.mark.parametrize("flt", [PYRAMID, CURVATURE])
def test_all_coordinates_nan(plugin, flt):
    fails(layer(np.full((30, 3), np.nan)), flt, re.escape("the layer holds 30 points with NaN or infinite coordinates"))


# -------------------------------------------------------------------------- 10. absurd level counts

@pytest.mark.parametrize("levels", ["1e19", "1e19%", "99999999999999999999", "50%,1e19", "1e300", "1e19,10"])
def test_huge_levels(plugin, levels):
    """A level past any count: "levels: <item> ..." naming the item, with no overflowed (negative) count."""
    msg = fails(layer(bumpy_points(10)), PYRAMID, r"levels: \S*(1e19|1e300|99999999999999999999)", levels=levels)
    assert "-9223372036854775808" not in msg, msg
    assert not re.search(r"(?<![\w.])-\d", msg), f"a negative number in: {msg}"


# ------------------------------------------------------------------------------------ 11. result checks

def two_far_clouds():
    a = grid_points(15, spacing=0.1, jitter=0.01, seed=5)
    b = grid_points(15, spacing=0.1, jitter=0.01, seed=6) + [50.0, 20.0, 3.0]
    return np.vstack([a, b])


@pytest.mark.parametrize("metric", [None, "Geodesic (unweighted)", "Euclidean"])
def test_fps_first_samples_in_different_parts(plugin, metric):
    """Two far-apart point clouds: FPS with 2 samples puts one in each; with k samples the first two of the
    output (farthest-point order) are in different parts."""
    extra = {} if metric is None else {"metric": metric}
    for k in (2, 25):
        ms = layer(two_far_clouds())
        runs(ms, FPS, samplenum=k, **extra)
        idx = assert_valid_lod(ms)
        assert len(idx) == k
        np.testing.assert_array_equal(ms.current_mesh().vertex_custom_scalar_attribute_array("fps_order"),
                                      np.arange(k))
        assert (idx[0] < 225) != (idx[1] < 225)


@pytest.mark.parametrize("make", [non_manifold, degenerate_faces], ids=["non-manifold", "degenerate faces"])
@pytest.mark.parametrize("flt,params", [
    (POISSON, {"radius": pymeshlab.PureValue(0.15)}),
    (FPS, {"samplenum": 25}),
    (PYRAMID, {"levels": "40,12"}),
])
@pytest.mark.parametrize("mode", [MESH_MODE, GRAPH])
def test_triangle_output_on_bad_faces(plugin, make, flt, params, mode):
    """Triangle-mesh output of non-manifold or degenerate faces: every face corner indexes a vertex of the
    LOD, and every LOD vertex is an input vertex (on request); placed vertices are finite and near their
    input vertex, on as many triangles (the same ones when fitted per region)."""
    ms = make()
    layers = 2 if flt == PYRAMID else 1
    runs(ms, flt, layers_added=layers, output=ON_INPUT, geodesicmode=mode, **params)
    for k in range(1, ms.mesh_number()):
        assert_valid_faces(ms, ms.mesh(k))
        assert_valid_lod(ms, ms.mesh(k))
    on_input = [ms.mesh(k) for k in range(1, 1 + layers)]
    for output in (FITTED, TRIANGLES):  # fitted per region: on the same triangles; optimized (the default)
        ms.set_current_mesh(0)
        runs(ms, flt, layers_added=layers, output=output, geodesicmode=mode, **params)
        for kept, k in zip(on_input, range(ms.mesh_number() - layers, ms.mesh_number())):
            placed, f = ms.mesh(k), ms.mesh(k).face_matrix()
            assert len(f) == kept.face_number() and f.min() >= 0 and f.max() < placed.vertex_number()
            if output == FITTED:
                np.testing.assert_array_equal(placed.face_matrix(), kept.face_matrix())
            moved = np.linalg.norm(placed.vertex_matrix() - kept.vertex_matrix(), axis=1)
            assert np.isfinite(moved).all() and moved.max() < 0.5 * np.ptp(kept.vertex_matrix(), axis=0).max()


def broken_normal_plane():
    pts = grid_points(25, spacing=0.04, jitter=0.01, seed=7)
    nrm = np.tile([0, 0, 1.0], (len(pts), 1))
    nrm[0::3] = 0.0
    nrm[1::7] = np.nan
    nrm[2::11] = [np.inf, 0, 0]
    return pts, nrm


@pytest.mark.parametrize("flt,params", [
    (POISSON, {"radius": pymeshlab.PureValue(1e-4)}),  # every vertex a sample
    (POISSON, {}),
    (FPS, {"samplenum": 100}),
    (PYRAMID, {"levels": "100%,30%"}),
])
def test_repaired_normals_on_a_plane(plugin, flt, params):
    """A flat plane z = 0 whose normals are partly zero, NaN or infinite: the LOD's normals at those samples
    (and at all others) are +-(0, 0, 1) within 1e-6."""
    pts, nrm = broken_normal_plane()
    ms = layer(pts, normals=nrm)
    runs(ms, flt, layers_added=2 if flt == PYRAMID else 1, **params)
    broken = ~np.isfinite(nrm).all(axis=1) | (np.abs(nrm).sum(axis=1) == 0)
    hit = 0
    for k in range(1, ms.mesh_number()):
        lod = ms.mesh(k)
        idx = sample_index(ms, lod)
        n = lod.vertex_normal_matrix()
        assert np.all(np.isfinite(n))
        np.testing.assert_allclose(np.abs(n), np.tile([0, 0, 1.0], (len(n), 1)), atol=1e-6)
        hit += broken[idx].sum()
    assert hit > 0, "no sample at a vertex with a broken normal"


def test_repaired_normals_curvature_is_zero_on_a_plane(plugin):
    pts, nrm = broken_normal_plane()
    ms = layer(pts, normals=nrm)
    ms.apply_filter(CURVATURE)
    np.testing.assert_allclose(ms.current_mesh().vertex_scalar_array(), 0.0, atol=1e-6)
