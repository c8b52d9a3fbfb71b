"""The array API and the MeshLab filters (through pymeshlab, with the plugin the package bundles) give the
same LOD for the same input, parameters and seed: the same rows, in the same order."""
import numpy as np
import pymeshlab
import pytest

import geodesic_lod as gl
import geodesic_lod.pymeshlab  # noqa: F401  (binds ms.generate_geodesic_*)
from common_inputs import layer
from conftest import bumpy_sphere, grid_mesh, rows_of

# The plugin's words for each metric (its dialog's), against the package's.
PLUGIN_METRIC = {"curvature-density": "Curvature-density geodesic", "eq3": "Weighted geodesic (eq. 3)",
                 "geodesic": "Geodesic (unweighted)", "euclidean": "Euclidean",
                 "surface-density": "Surface-density geodesic (airborne LiDAR)"}


def filter_rows(ms, points):
    return rows_of(points, ms.current_mesh().vertex_matrix())


@pytest.fixture(scope="module")
def cloud():
    return bumpy_sphere(3000, seed=7)


@pytest.mark.parametrize("metric", list(PLUGIN_METRIC))
def test_poisson_by_radius(cloud, metric):
    ms = layer(cloud)
    res = ms.generate_geodesic_poisson_lod(radius=pymeshlab.PureValue(0.1), metric=PLUGIN_METRIC[metric], seed=4)
    lod = gl.poisson_lod(cloud, radius=0.1, metric=metric, seed=4)
    np.testing.assert_array_equal(filter_rows(ms, cloud), lod.indices)
    assert res["sample_num"] == len(lod.indices)


@pytest.mark.parametrize("ask", [dict(samplenum=250), dict(samplerate=3.3), dict(samplenum=2999)])
def test_poisson_by_count_and_rate(cloud, ask):
    ms = layer(cloud)
    res = ms.generate_geodesic_poisson_lod(**ask, seed=1)
    lod = gl.poisson_lod(cloud, count=ask.get("samplenum"), rate=ask.get("samplerate"), seed=1)
    np.testing.assert_array_equal(filter_rows(ms, cloud), lod.indices)
    assert res["radius"] == lod.radius and res["covering_radius"] == lod.covering_radius
    assert res["iterations"] == lod.iterations


def test_poisson_with_normals_given(cloud):
    normals = cloud / np.linalg.norm(cloud, axis=1)[:, None]
    normals[::5] = 0  # missing: estimated by both
    ms = layer(cloud, normals=normals)
    ms.generate_geodesic_poisson_lod(samplenum=300, adaptivity=6.0, normalneighbors=12, graphneighbors=8)
    lod = gl.poisson_lod(cloud, normals, count=300, adaptivity=6.0, normal_neighbors=12, graph_neighbors=8)
    np.testing.assert_array_equal(filter_rows(ms, cloud), lod.indices)


def test_fps(cloud):
    ms = layer(cloud)
    res = ms.generate_geodesic_fps_lod(samplenum=150, seed=9)
    lod = gl.fps_lod(cloud, count=150, seed=9)
    np.testing.assert_array_equal(filter_rows(ms, cloud), lod.indices)
    assert res["covering_radius"] == lod.covering_radius


@pytest.mark.parametrize("order, choice", [("automatic", None), ("random", "Random"),
                                           ("prominence", "Prominent points first"), ("rims", "Rims first")])
def test_pyramid(cloud, order, choice):
    ms = layer(cloud)
    ms.generate_geodesic_lod_pyramid(levels="30%,10%,40", seed=3, **({"visitorder": choice} if choice else {}))
    pyr = gl.lod_pyramid(cloud, levels=["30%", "10%", 40], seed=3, visit_order=order)
    outputs = [ms.mesh(i) for i in range(1, ms.mesh_number())]
    assert len(outputs) == len(pyr.levels)
    for out, level in zip(outputs, pyr.levels):
        np.testing.assert_array_equal(rows_of(cloud, out.vertex_matrix()), level)


def test_pyramid_within_a_tolerance(cloud):
    ms = layer(cloud)
    ms.generate_geodesic_lod_pyramid(levels="30%,10%,40", tolerance=8.0)
    pyr = gl.lod_pyramid(cloud, levels=["30%", "10%", 40], tolerance=8)
    outputs = [ms.mesh(i) for i in range(1, ms.mesh_number())]
    assert [o.vertex_number() for o in outputs] == pyr.counts
    for out, level in zip(outputs, pyr.levels):
        np.testing.assert_array_equal(rows_of(cloud, out.vertex_matrix()), level)


def test_mesh_geodesics_and_triangles():
    pts, faces = grid_mesh(35)
    ms = layer(pts, faces=faces)
    normals = ms.current_mesh().vertex_normal_matrix()  # the normals pymeshlab gives a mesh
    ms.generate_geodesic_poisson_lod(samplenum=90, output="Triangle mesh (geodesic Delaunay)")
    lod = gl.poisson_lod(pts, normals, faces=faces, count=90, mesh_output=True)
    out = ms.current_mesh()
    np.testing.assert_array_equal(out.vertex_matrix(), lod.positions)  # fitted alike
    np.testing.assert_array_equal(out.face_matrix(), lod.faces)
    ms.set_current_mesh(0)
    ms.generate_geodesic_poisson_lod(samplenum=90, output="Triangle mesh on input vertices")
    np.testing.assert_array_equal(filter_rows(ms, pts), lod.indices)


def test_pyramid_mesh_levels():
    pts, faces = grid_mesh(35)
    ms = layer(pts, faces=faces)
    normals = ms.current_mesh().vertex_normal_matrix()
    ms.generate_geodesic_lod_pyramid(levels="200,60,15", output="Triangle mesh (geodesic Delaunay)")
    pyr = gl.lod_pyramid(pts, normals, faces=faces, levels=[200, 60, 15], mesh_output=True)
    outputs = [ms.mesh(i) for i in range(1, ms.mesh_number())]
    assert len(outputs) == len(pyr.level_positions) == 3
    for out, positions, level_faces in zip(outputs, pyr.level_positions, pyr.level_faces):
        np.testing.assert_array_equal(out.vertex_matrix(), positions)  # each level fitted alike
        np.testing.assert_array_equal(out.face_matrix(), level_faces)
    kept = gl.lod_pyramid(pts, normals, faces=faces, levels=[200, 60, 15], mesh_output=True, placement="input")
    for positions, level in zip(kept.level_positions, kept.levels):
        np.testing.assert_array_equal(positions, pts[level])


def test_normal_variation(cloud):
    ms = layer(cloud)
    ms.compute_scalar_by_normal_variation(normalneighbors=15)
    nv = gl.normal_variation(cloud, normal_neighbors=15)
    np.testing.assert_array_equal(ms.current_mesh().vertex_scalar_array(), nv.curvature)


def test_shared_scan(shared):
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(shared("bunny_35k.ply"))
    m = ms.current_mesh()
    points, normals = m.vertex_matrix(), m.vertex_normal_matrix()
    faces = m.face_matrix() if m.face_number() else None
    ms.generate_geodesic_poisson_lod(samplenum=2000, seed=5)
    lod = gl.poisson_lod(points, normals, faces=faces, count=2000, seed=5)
    assert len(lod.indices) == 2000
    np.testing.assert_array_equal(filter_rows(ms, points), lod.indices)


def test_height_field():
    y, x = np.mgrid[0:40, 0:50] * 25.0
    dem = np.column_stack([x.ravel(), y.ravel(), (80 * np.sin(x / 200) * np.cos(y / 150) + x / 10).ravel()])
    ms = layer(dem)
    res = ms.generate_height_field_lod(levels="10%,2%")
    lod = gl.height_field_lod(dem, count=200)
    for layer_id, k in ((1, 200), (2, 40)):
        m = ms.mesh(layer_id)
        rows = rows_of(dem, m.vertex_matrix())
        np.testing.assert_array_equal(rows, lod.indices[:k])  # the layer in insertion order
        np.testing.assert_array_equal(m.face_matrix(), lod.tin(k))
    assert res["sample_num"] == 200 and res["max_error"] == lod.errors[-1]
