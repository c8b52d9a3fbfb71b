"""The plugin through the real pymeshlab 2025.7: listing, output properties, attributes, determinism."""

import numpy as np
import pymeshlab
import pytest
from scipy.spatial import cKDTree

from conftest import bumpy_points, mesh_set, parameter_defaults

FILTER = "generate_geodesic_poisson_lod"
PARAMS = ["radius", "metric", "curvatureexponent", "adaptivity", "normalneighbors",
          "graphneighbors", "recomputenormals", "seed"]


def snapshot(mesh):
    return (mesh.vertex_matrix().copy(), mesh.vertex_normal_matrix().copy(),
            mesh.vertex_color_matrix().copy(), mesh.face_number())


def assert_same(a, b):
    for x, y in zip(a[:3], b[:3]):
        np.testing.assert_array_equal(x, y)
    assert a[3] == b[3]


def check_lod(ms, input_id, result):
    """Subset of the input, coverage within the radius, unit normals, input unchanged."""
    src = ms.mesh(input_id)
    lod = ms.current_mesh()
    assert lod.id() != input_id
    assert lod.label() == src.label() + " LOD"
    pts, samples = src.vertex_matrix(), lod.vertex_matrix()
    assert result["sample_num"] == lod.vertex_number() > 0
    assert lod.vertex_number() < src.vertex_number()
    # Every sample is an input point, bit for bit, and no point is taken twice.
    dist, idx = cKDTree(pts).query(samples)
    assert np.all(dist == 0)
    np.testing.assert_array_equal(pts[idx], samples)
    assert len(np.unique(idx)) == len(idx)
    # Coverage: geodesic disks lie inside Euclidean balls of the same radius.
    reach, _ = cKDTree(samples).query(pts)
    assert reach.max() <= result["radius"] * (1 + 1e-9)
    # Normals present: the layer's own (kept as they are) or estimated (unit).
    norms = np.linalg.norm(lod.vertex_normal_matrix(), axis=1)
    assert np.all(np.isfinite(norms)) and np.all(norms > 0)
    return idx


def test_filter_is_listed_with_documented_parameters(plugin):
    assert FILTER in pymeshlab.filter_list()
    out = parameter_defaults(FILTER)
    for p in PARAMS:
        assert p in out, p


def test_synthetic_cloud(plugin):
    ms = mesh_set(bumpy_points())
    before = snapshot(ms.current_mesh())
    res = ms.apply_filter(FILTER, radius=pymeshlab.PureValue(0.05))
    assert set(res) >= {"sample_num", "radius"}
    assert res["radius"] == pytest.approx(0.05)
    check_lod(ms, 0, res)
    assert_same(before, snapshot(ms.mesh(0)))
    assert ms.mesh_number() == 2


def test_same_seed_same_output(plugin):
    runs = []
    for seed in (3, 3, 4):
        ms = mesh_set(bumpy_points(40))
        ms.apply_filter(FILTER, radius=pymeshlab.PercentageValue(4), seed=seed)
        runs.append(ms.current_mesh().vertex_matrix())
    np.testing.assert_array_equal(runs[0], runs[1])
    assert runs[0].shape != runs[2].shape or not np.array_equal(runs[0], runs[2])


def test_same_seed_same_bytes(plugin, tmp_path):
    """Saved LODs of two runs with the same seed are byte-identical files."""
    for flt, kw in [("generate_geodesic_poisson_lod", {"radius": pymeshlab.PureValue(0.05)}),
                    ("generate_geodesic_fps_lod", {"samplenum": 200})]:
        files = []
        for run in range(2):
            ms = mesh_set(bumpy_points(40))
            ms.apply_filter(flt, seed=7, **kw)
            files.append(tmp_path / f"{flt}_{run}.ply")
            ms.save_current_mesh(str(files[-1]), binary=True)
        assert files[0].read_bytes() == files[1].read_bytes()


def test_every_metric_runs_and_curvature_density_adapts(plugin):
    pts = bumpy_points()
    share = {}
    # The surface-density metric is about 1 + a / 3 = 2 times the Euclidean on a plane: a radius as long in it.
    # In the random order, the metric's doing alone (the prominent points first pack bumps in any metric).
    for metric, radius in [("Weighted geodesic (eq. 3)", 0.04), ("Curvature-density geodesic", 0.04),
                           ("Geodesic (unweighted)", 0.04), ("Euclidean", 0.04),
                           ("Surface-density geodesic (airborne LiDAR)", 0.08)]:
        ms = mesh_set(pts)
        res = ms.apply_filter(FILTER, radius=pymeshlab.PureValue(radius), metric=metric, visitorder="Random")
        idx = check_lod(ms, 0, res)
        share[metric] = np.mean(pts[idx, 0] >= 0.5)
    assert share["Curvature-density geodesic"] > share["Euclidean"]


def test_attributes_are_carried_to_the_lod(plugin):
    pts = bumpy_points(30)
    ms = mesh_set(pts)
    m = ms.current_mesh()
    ms.compute_color_by_function_per_vertex(x="x*255", y="y*255", z="128")
    ms.compute_scalar_by_function_per_vertex(q="x+2*y")
    m.add_vertex_custom_scalar_attribute(np.arange(len(pts), dtype=np.float64) / 3, "confidence")
    m.add_vertex_custom_point_attribute(pts[:, ::-1].copy(), "albedo")
    ms.apply_filter(FILTER, radius=pymeshlab.PureValue(0.1))
    src, lod = ms.mesh(0), ms.current_mesh()
    _, idx = cKDTree(src.vertex_matrix()).query(lod.vertex_matrix())
    np.testing.assert_array_equal(lod.vertex_color_matrix(), src.vertex_color_matrix()[idx])
    np.testing.assert_array_equal(lod.vertex_scalar_array(), src.vertex_scalar_array()[idx])
    np.testing.assert_array_equal(lod.vertex_custom_scalar_attribute_array("confidence"),
                                  src.vertex_custom_scalar_attribute_array("confidence")[idx])
    np.testing.assert_array_equal(lod.vertex_custom_point_attribute_matrix("albedo"),
                                  src.vertex_custom_point_attribute_matrix("albedo")[idx])


def test_given_normals_are_kept(plugin):
    pts = bumpy_points(30)
    normals = np.tile([0.0, 0.0, 1.0], (len(pts), 1))
    ms = mesh_set(pts, normals)
    ms.apply_filter(FILTER, radius=pymeshlab.PureValue(0.1))
    np.testing.assert_array_equal(ms.current_mesh().vertex_normal_matrix(),
                                  np.tile([0.0, 0.0, 1.0], (ms.current_mesh().vertex_number(), 1)))


def test_duplicate_points_give_distinct_samples(plugin):
    pts = bumpy_points(30)
    ms = mesh_set(np.vstack([pts, pts]))
    res = ms.apply_filter(FILTER, radius=pymeshlab.PureValue(0.1))
    samples = ms.current_mesh().vertex_matrix()
    assert len(np.unique(samples, axis=0)) == len(samples) == res["sample_num"]


def test_bunny_raw_scans(plugin, shared):
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(shared("bunny_scans_362k.ply"))
    before = snapshot(ms.current_mesh())
    res = ms.apply_filter(FILTER)
    check_lod(ms, 0, res)
    assert_same(before, snapshot(ms.mesh(0)))
    # The scans have no normals: the LOD's are estimated, unit length.
    np.testing.assert_allclose(np.linalg.norm(ms.current_mesh().vertex_normal_matrix(), axis=1), 1.0, atol=1e-6)


def test_dragon_vertices(plugin, shared):
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(shared("dragon_437k.ply"))
    before = snapshot(ms.current_mesh())
    res = ms.apply_filter(FILTER, metric="Curvature-density geodesic")
    check_lod(ms, 0, res)
    assert_same(before, snapshot(ms.mesh(0)))
    assert ms.current_mesh().face_number() == 0


def test_methods_bound_as_the_readme_shows(plugin):
    for name in ("generate_geodesic_poisson_lod", "generate_geodesic_fps_lod"):
        setattr(pymeshlab.MeshSet, name, pymeshlab.bind_function(name))
    ms = mesh_set(bumpy_points(30))
    assert ms.generate_geodesic_fps_lod(samplenum=12)["sample_num"] == 12
    ms.set_current_mesh(0)
    assert ms.generate_geodesic_poisson_lod(radius=pymeshlab.PureValue(0.2))["sample_num"] > 0
