"""The "Normal variation curvature" filter (eq. 1 in the vertex quality) through pymeshlab."""
import numpy as np
import pymeshlab

from conftest import bumpy_points, mesh_set, parameter_defaults

FILTER = "compute_scalar_by_normal_variation"


def test_listed_with_its_parameters(plugin):
    assert FILTER in pymeshlab.filter_list()
    out = parameter_defaults(FILTER)
    assert "normalneighbors" in out and "recomputenormals" in out


def test_quality_is_eq1_and_nothing_else_changes(plugin):
    pts = bumpy_points(40)
    ms = mesh_set(pts)
    m = ms.current_mesh()
    before = m.vertex_matrix().copy(), m.vertex_color_matrix().copy()
    res = ms.apply_filter(FILTER)
    assert ms.mesh_number() == 1  # in place: no new layer
    q = ms.current_mesh().vertex_scalar_array()
    assert np.all((q >= 0) & (q <= 1))
    x = pts[:, 0]
    assert q[x < 0.3].max() < 1e-6          # 0 where every neighbourhood is flat
    assert q[x > 0.6].mean() > 100 * (q[x < 0.3].mean() + 1e-9)
    assert res["max"] == q.max() and res["min"] == q.min()
    np.testing.assert_allclose(res["mean"], q.mean())
    np.testing.assert_array_equal(before[0], ms.current_mesh().vertex_matrix())
    np.testing.assert_array_equal(before[1], ms.current_mesh().vertex_color_matrix())


def test_grows_with_bending(plugin):
    means = []
    for r in (2.0, 1.0, 0.5):  # spheres of the same point density, smaller radius: more bending
        n = int(3000 * r * r)
        i = np.arange(n) + 0.5
        z = 1 - 2 * i / n
        t = np.pi * (1 + 5 ** 0.5) * i
        pts = r * np.column_stack([np.sqrt(1 - z * z) * np.cos(t), np.sqrt(1 - z * z) * np.sin(t), z])
        ms = mesh_set(pts)
        means.append(ms.apply_filter(FILTER)["mean"])
    assert means[0] < means[1] < means[2]
