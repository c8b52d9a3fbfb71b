"""Farthest point LOD, mesh geodesics and triangle-mesh output through the real pymeshlab 2025.7."""

import numpy as np
import pymeshlab
import pytest
from scipy.spatial import cKDTree

from conftest import bumpy_points, mesh_set, parameter_defaults
from test_bad_inputs import FITTED, FPS, ON_INPUT, POISSON, TRIANGLES  # TRIANGLES: the default placement


def grid_mesh(n=40):
    pts = bumpy_points(n)
    idx = np.arange(n * n).reshape(n, n)
    a, b, c, d = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    faces = np.vstack([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=pts, face_matrix=faces), "grid")
    return ms


def assert_subset(src, lod):
    dist, idx = cKDTree(src.vertex_matrix()).query(lod.vertex_matrix())
    assert np.all(dist == 0)
    return idx


def assert_clean_faces(lod):
    f = lod.face_matrix()
    assert len(f) > 0
    assert np.all((f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2]))
    assert len(np.unique(np.sort(f, axis=1), axis=0)) == len(f)
    assert f.max() < lod.vertex_number()


def test_fps_filter_is_listed(plugin):
    assert FPS in pymeshlab.filter_list()
    out = parameter_defaults(FPS)
    for p in ["samplenum", "metric", "geodesicmode", "output", "seed"]:
        assert p in out, p


def test_fps_exact_count_order_and_prefixes(plugin):
    pts = bumpy_points(40)
    runs = {}
    for n in (20, 75):
        ms = mesh_set(pts)
        res = ms.apply_filter(FPS, samplenum=n, seed=11)
        lod = ms.current_mesh()
        assert res["sample_num"] == lod.vertex_number() == n
        np.testing.assert_array_equal(lod.vertex_custom_scalar_attribute_array("fps_order"), np.arange(n))
        assert_subset(ms.mesh(0), lod)
        runs[n] = (lod.vertex_matrix(), res["covering_radius"])
    np.testing.assert_array_equal(runs[75][0][:20], runs[20][0])  # a prefix is the smaller LOD
    assert 0 < runs[75][1] < runs[20][1]
    # The covering radius is a true bound on the distance to the nearest sample (Euclidean <= geodesic).
    reach, _ = cKDTree(runs[75][0]).query(pts)
    assert reach.max() <= runs[75][1] * (1 + 1e-9)


def test_mesh_geodesics_and_triangle_output(plugin):
    for flt, kwargs in [(POISSON, {"radius": pymeshlab.PureValue(0.08)}), (FPS, {"samplenum": 120})]:
        ms = grid_mesh()
        ms.apply_filter(flt, output=ON_INPUT, geodesicmode="Mesh (fast marching)", **kwargs)
        lod = ms.current_mesh()
        assert_subset(ms.mesh(0), lod)
        assert_clean_faces(lod)
        assert ms.mesh(0).face_number() == 2 * 39 * 39  # input untouched
        # Fitted per region: the same triangles, each vertex moved by less than the LOD's spacing; optimized
        # (the default): as many triangles, clean, each vertex moved by less than the spacing too.
        for output, same_faces in [(FITTED, True), (TRIANGLES, False)]:
            ms.set_current_mesh(0)
            ms.apply_filter(flt, output=output, geodesicmode="Mesh (fast marching)", **kwargs)
            placed = ms.current_mesh()
            assert placed.face_number() == lod.face_number()
            assert_clean_faces(placed)
            if same_faces:
                np.testing.assert_array_equal(placed.face_matrix(), lod.face_matrix())
            moved = np.linalg.norm(placed.vertex_matrix() - lod.vertex_matrix(), axis=1)
            assert 0 < moved.max() < np.sqrt(1 / lod.vertex_number())


def test_terrain_crop_both_modes(plugin, shared):
    for mode in ["Mesh (fast marching)", "Point graph (Dijkstra)"]:
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(shared("terrain_n44w072_crop301x301.ply"))
        res = ms.apply_filter(FPS, samplenum=2000, geodesicmode=mode, output=ON_INPUT)
        lod = ms.current_mesh()
        assert res["sample_num"] == lod.vertex_number() == 2000
        assert_subset(ms.mesh(0), lod)
        assert_clean_faces(lod)
        assert res["covering_radius"] > 0


def test_dragon_mesh_lod(plugin, shared):
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(shared("dragon_437k.ply"))
    before = ms.current_mesh().vertex_matrix().copy()
    res = ms.apply_filter(POISSON, output=ON_INPUT)
    lod = ms.current_mesh()
    assert res["sample_num"] == lod.vertex_number()
    idx = assert_subset(ms.mesh(0), lod)
    assert len(np.unique(idx)) == len(idx)  # repeated seam vertices never give two samples at one place
    assert_clean_faces(lod)
    np.testing.assert_array_equal(before, ms.mesh(0).vertex_matrix())


def test_dragon_100k_degenerate_mesh(plugin, shared):
    """Holes, duplicated edges and 43 unreferenced vertices: a result, and the left-out vertices reported."""
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(shared("dragon_100k.ply"))
    n = ms.current_mesh().vertex_number()
    res = ms.apply_filter(FPS, samplenum=3000, output=TRIANGLES)
    assert res["sample_num"] == 3000
    assert_clean_faces(ms.current_mesh())
    ms.set_current_mesh(0)
    res = ms.apply_filter(FPS, samplenum=n, geodesicmode="Point graph (Dijkstra)")
    assert res["sample_num"] == n  # the point graph keeps the unreferenced vertices
    with pytest.raises(pymeshlab.PyMeshLabException, match=rf"samplenum must be at most the {n - 43:,} points in "
                                                           r"triangles \(43 vertices in none are not sampled"):
        ms.set_current_mesh(0)
        ms.apply_filter(FPS, samplenum=n)  # mesh geodesics leave the 43 unreferenced vertices out
